// Gap, normal and constraint row of every candidate pair at the current displacement.
#include "signorini/contact/constraints.hpp"

#include "signorini/contact/contact_set.hpp"

namespace signorini {

void EvaluatePairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                   const std::vector<ContactPair> &pairs, const DofMap &dofs, const std::vector<char> &fixed,
                   bool large_deformation, const double *u_local, std::vector<PairState> &states,
                   std::vector<ConstraintRow> &rows, std::vector<std::array<double, 3>> &normals) {
  const int dim = mesh.Dim();
  states.resize(pairs.size());
  rows.resize(pairs.size());
  normals.resize(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const ContactPair &pair = pairs[p];
    const double *u = &u_local[pair.vertex * dim];
    // A mortar pair (MortarCoupling) has no facet: its slave part is evaluated here, the caller adds the master's.
    const bool mortar = pair.facet >= (PetscInt)obstacle.facets.size();
    states[p].entered = false;
    states[p].crossing = 0;
    if (mortar || !large_deformation) {
      // Linearised from where the pair was found: g0 + n0 . u, in a zone fixed there (a mortar row covers the master
      // side it overlaps).
      double g = pair.g0;
      for (int d = 0; d < dim; ++d) g += pair.n0[d] * u[d];
      states[p].gap = g;
      for (int d = 0; d < 3; ++d) normals[p][d] = pair.n0[d];
      states[p].inside = mortar || pair.zone0;
    } else {
      // svk: the current projection. The zone in which the gap counts: the node is over the facet now, or went
      // through it on the straight path X -> x (X: where the pair was found) from an open start (the gap, linear
      // along the path for a flat facet, changes sign at t = g0 / (g0 - g); the crossing point must lie on the
      // finite facet), or started behind it in its strip; a node touching at the start (|g0| <= -contact_touch_tol)
      // has only its current projection.
      const double *X = mesh.X(pair.vertex);
      double x[3] = {0, 0, 0};
      for (int d = 0; d < dim; ++d) x[d] = X[d] + u[d];
      const Facet &facet = *obstacle.facets[pair.facet];
      const Projection proj = facet.Project(x, opts.alpha_tol, opts.length);
      const double g = proj.gap;
      states[p].gap = g;
      for (int d = 0; d < 3; ++d) normals[p][d] = proj.normal[d];
      states[p].inside = proj.inside;
      if (pair.g0 > opts.touch_tol && g < 0) {
        const double t = pair.g0 / (pair.g0 - g);
        double c[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) c[d] = pair.x0[d] + t * (x[d] - pair.x0[d]);
        states[p].entered = facet.Project(c, opts.alpha_tol, opts.length).inside;
        states[p].crossing = t;
      } else {
        states[p].entered = pair.g0 < -opts.touch_tol && pair.inside0 && g < 0;
      }
    }
    ConstraintRow &row = rows[p];
    row.Clear();
    for (int k = 0; k < dim; ++k)
      if (!fixed[pair.vertex * dim + k]) row.Add(dofs.Row(pair.vertex, k), -normals[p][k]);
  }
  // svk: a node on the apex of a convex joint projects onto both facets only by the projection's tolerance, and it
  // is outside the obstacle when it is outside either: the nearer facet alone is its zone there (the first at a tie),
  // as for the linear material's reference zones (FindContactPairs). Both zones would hold it in the valley of the
  // two extended facets. The pairs of one node are adjacent.
  if (!large_deformation) return;
  for (std::size_t a = 0; a < pairs.size();) {
    std::size_t b = a;
    while (b < pairs.size() && pairs[b].vertex == pairs[a].vertex) ++b;
    const double *X = mesh.X(pairs[a].vertex), *u = &u_local[pairs[a].vertex * dim];
    double x[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) x[d] = X[d] + u[d];
    for (std::size_t p = a; p < b; ++p)
      for (std::size_t q = p + 1; q < b; ++q) {
        const auto nf = (PetscInt)obstacle.facets.size(); // a mortar pair (facet nf on) is no facet of a joint
        if (!states[p].inside || !states[q].inside || pairs[p].facet >= nf || pairs[q].facet >= nf ||
            !ConvexJoint(obstacle, {pairs[p].facet, normals[p].data(), states[p].gap},
                         {pairs[q].facet, normals[q].data(), states[q].gap}, x, dim, opts.search_radius))
          continue;
        const bool q_nearer = NearerFacet(obstacle.facets[pairs[q].facet]->Distance(x), pairs[q].facet,
                                          obstacle.facets[pairs[p].facet]->Distance(x), pairs[p].facet,
                                          opts.search_radius);
        states[q_nearer ? p : q].inside = false;
      }
    a = b;
  }
}

} // namespace signorini
