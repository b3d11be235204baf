// Contact options, the spatial search for candidate pairs, initial gaps and tributary lengths.
#include "signorini/contact/contact_set.hpp"

#include "signorini/core/options.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace signorini {

PetscErrorCode ReadContactOptions(MPI_Comm comm, double L, double k, ContactOptions &opts) {
  // Ranges (README): a penetration or touching gap beyond 1e-3 of the body's size is a visibly wrong state, alpha
  // beyond 1e-2 projects a node off its facet, a radius beyond 1e5 diagonals pairs everything anyway (and keeps the
  // bin search finite), and c far from E t makes lambda - c g compare numbers of unrelated magnitudes.
  const RealRange radius{0, 1e5, true, false, L, "body diagonal"}, gap{0, 1e-3, false, false, L, "body diagonal"};
  const RealRange alpha{0, 1e-2}, fraction{0, 1, false, true}, c{1e-6, 1e6, false, false, k, "E x thickness"};
  PetscFunctionBeginUser;
  opts.length = L;
  opts.search_radius = 0.1 * L;
  opts.touch_tol = 1e-8 * L;
  opts.gap_tol = 1e-9 * L;
  opts.c = k;
  PetscOptionsBegin(comm, nullptr, "Contact options", "signorini");
  PetscCall(OptionsStringList(PetscOptionsObject, "-contact_groups", "Physical groups of candidate nodes (default: "
                              "whole boundary)", "no candidate nodes", "physical group names", opts.groups));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_search_radius", "Pair a node with the facets within this "
                        "distance (default 0.1 x body diagonal)", radius, opts.search_radius));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_touch_tol", "Initial gap that counts as touching (default 1e-8 "
                        "x diagonal)", gap, opts.touch_tol));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_gap_tol", "Penetration tolerance of the active-set rule "
                        "(default 1e-9 x diagonal)", gap, opts.gap_tol));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_alpha_tol", "Tolerance on the projection parameter alpha in "
                        "[0,1]", alpha, opts.alpha_tol));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_complementarity_c", "Weight c of the gap in the rule lambda - "
                        "c g > 0 (default E x thickness)", c, opts.c));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_activation_fraction", "In the first update of a load step, "
                        "activate only pairs penetrating deeper than this fraction of the deepest penetration (0: all)",
                        fraction, opts.activation_fraction));
  PetscCall(OptionsInt(PetscOptionsObject, "-contact_max_it", "Maximum active-set iterations per load step", 1,
                       CONTACT_MAX_IT_LIMIT, opts.max_it));
  PetscCall(PetscOptionsBool("-contact_monitor", "Print one line per active-set iteration", "", opts.monitor,
                             &opts.monitor, nullptr));
  PetscCall(PetscOptionsBool("-contact_converged_reason", "Print why the active-set loop stopped", "",
                             opts.converged_reason, &opts.converged_reason, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

namespace {

/// Uniform grid of bins over the facets' bounding boxes inflated by the search radius.
class FacetBins {
public:
  FacetBins(const Obstacle &obstacle, double radius) {
    lo_[0] = lo_[1] = 1e300;
    double hi[2] = {-1e300, -1e300}, total = 0;
    const auto &facets = obstacle.facets;
    for (const auto &f : facets) {
      double a[2], b[2];
      f->Bounds(a, b);
      for (int i = 0; i < 2; ++i) lo_[i] = std::min(lo_[i], a[i] - radius), hi[i] = std::max(hi[i], b[i] + radius);
      total += std::max(b[0] - a[0], b[1] - a[1]);
    }
    if (facets.empty()) return;
    h_ = std::max({radius, total / facets.size(), 1e-300});
    for (int i = 0; i < 2; ++i) n_[i] = std::clamp((long)std::ceil((hi[i] - lo_[i]) / h_), 1L, 4096L);
    h_ = std::max((hi[0] - lo_[0]) / n_[0], (hi[1] - lo_[1]) / n_[1]);
    for (std::size_t k = 0; k < facets.size(); ++k) {
      double a[2], b[2];
      facets[k]->Bounds(a, b);
      const long i0 = Cell(a[0] - radius, 0), i1 = Cell(b[0] + radius, 0);
      const long j0 = Cell(a[1] - radius, 1), j1 = Cell(b[1] + radius, 1);
      for (long i = i0; i <= i1; ++i)
        for (long j = j0; j <= j1; ++j) bins_[i * n_[1] + j].push_back((PetscInt)k);
    }
  }
  const std::vector<PetscInt> *Find(const double *x) const {
    if (bins_.empty()) return nullptr;
    const long i = (long)std::floor((x[0] - lo_[0]) / h_), j = (long)std::floor((x[1] - lo_[1]) / h_);
    if (i < 0 || j < 0 || i >= n_[0] || j >= n_[1]) return nullptr;
    const auto it = bins_.find(i * n_[1] + j);
    return it == bins_.end() ? nullptr : &it->second;
  }

private:
  long Cell(double x, int d) const { return std::clamp((long)std::floor((x - lo_[d]) / h_), 0L, n_[d] - 1); }
  double lo_[2], h_ = 1;
  long n_[2] = {1, 1};
  std::map<long, std::vector<PetscInt>> bins_;
};

} // namespace

PetscErrorCode FindContactPairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                                const std::vector<char> &fixed, std::vector<ContactPair> &pairs,
                                std::vector<char> &candidate, const double *u_local) {
  const int dim = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  PetscFunctionBeginUser;
  candidate.assign(nv, 0);
  std::vector<PetscInt> vertices;
  if (opts.groups.empty()) {
    PetscCall(mesh.BoundaryVertices(vertices));
    for (PetscInt v : vertices) candidate[v] = 1;
  } else {
    for (const auto &g : opts.groups) {
      PetscCall(mesh.GroupVertices(g, vertices));
      for (PetscInt v : vertices) candidate[v] = 1;
    }
  }
  // Seed section 4.2.1: nodes with every component fixed cannot move and are no candidates.
  for (PetscInt v = 0; v < nv; ++v) {
    bool all_fixed = true;
    for (int k = 0; k < dim; ++k) all_fixed = all_fixed && fixed[v * dim + k];
    if (all_fixed) candidate[v] = 0;
  }
  pairs.clear();
  std::vector<double> distance;
  const FacetBins bins(obstacle, opts.search_radius);
  for (PetscInt v = 0; v < nv; ++v) {
    if (!candidate[v] || !mesh.Owned(v)) continue;
    double x[3] = {0, 0, 0};
    for (int k = 0; k < dim; ++k) x[k] = mesh.X(v)[k] + (u_local ? u_local[v * dim + k] : 0.0);
    const auto *near = bins.Find(x);
    if (!near) continue;
    const std::size_t first = pairs.size();
    for (PetscInt f : *near) {
      const Facet &facet = *obstacle.facets[f];
      if (facet.Distance(x) > opts.search_radius) continue;
      const Projection p = facet.Project(x, opts.alpha_tol);
      // A pair whose normal lies in the node's fixed components has an empty constraint row: the supports already
      // hold the node in that direction.
      double free2 = 0;
      for (int k = 0; k < dim; ++k)
        if (!fixed[v * dim + k]) free2 += p.normal[k] * p.normal[k];
      if (free2 < 1e-12) continue;
      ContactPair pair{v, f, {p.normal[0], p.normal[1], p.normal[2]}, p.gap, p.inside, p.inside, {x[0], x[1], x[2]}};
      pairs.push_back(pair);
      distance.push_back(facet.Distance(x));
    }
    // A node over the wedge of a convex joint projects onto none of its facets: the nearest one (the first at a
    // tie, both meeting at the joint) is its own.
    bool any = false;
    for (std::size_t p = first; p < pairs.size(); ++p) any = any || pairs[p].inside0;
    std::size_t nearest = first;
    for (std::size_t p = first; p < pairs.size(); ++p)
      if (distance[p] < distance[nearest] - 1e-12 * opts.search_radius ||
          (distance[p] <= distance[nearest] + 1e-12 * opts.search_radius && pairs[p].facet < pairs[nearest].facet))
        nearest = p;
    if (!any && nearest < pairs.size()) pairs[nearest].zone0 = true;
  }
  std::sort(pairs.begin(), pairs.end(), [&](const ContactPair &a, const ContactPair &b) {
    const PetscInt oa = mesh.VertexOriginal(a.vertex), ob = mesh.VertexOriginal(b.vertex);
    return oa != ob ? oa < ob : a.facet < b.facet;
  });
  PetscFunctionReturn(0);
}

PetscErrorCode TributaryLengths(const Mesh &mesh, const std::vector<char> &candidate, std::vector<double> &length) {
  std::vector<std::array<PetscInt, 2>> edges;
  PetscFunctionBeginUser;
  PetscCall(mesh.BoundaryEdges(edges));
  length.assign(mesh.NumLocalVertices(), 0.0);
  for (const auto &e : edges) {
    if (!candidate[e[0]] || !candidate[e[1]]) continue;
    const double *a = mesh.X(e[0]), *b = mesh.X(e[1]);
    double L2 = 0;
    for (int d = 0; d < mesh.Dim(); ++d) L2 += (b[d] - a[d]) * (b[d] - a[d]);
    length[e[0]] += 0.5 * std::sqrt(L2);
    length[e[1]] += 0.5 * std::sqrt(L2);
  }
  PetscCall(mesh.SumShared(length));
  PetscFunctionReturn(0);
}

} // namespace signorini
