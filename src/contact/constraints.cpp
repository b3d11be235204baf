// Gap, normal and constraint row of every candidate pair at the current displacement.
#include "signorini/contact/constraints.hpp"

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
    const double *X = mesh.X(pair.vertex), *u = &u_local[pair.vertex * dim];
    double x[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) x[d] = X[d] + u[d];
    const Projection proj = obstacle.facets[pair.facet]->Project(x, opts.alpha_tol);
    states[p].inside = proj.inside;
    if (large_deformation) {
      states[p].gap = proj.gap;
      for (int d = 0; d < 3; ++d) normals[p][d] = proj.normal[d];
    } else {
      double g = pair.g0;
      for (int d = 0; d < dim; ++d) g += pair.n0[d] * u[d];
      states[p].gap = g;
      for (int d = 0; d < 3; ++d) normals[p][d] = pair.n0[d];
    }
    ConstraintRow &row = rows[p];
    row.ncols = 0;
    for (int k = 0; k < dim; ++k) {
      if (fixed[pair.vertex * dim + k]) continue;
      row.cols[row.ncols] = dofs.Row(pair.vertex, k);
      row.coef[row.ncols] = -normals[p][k];
      ++row.ncols;
    }
  }
}

} // namespace signorini
