// Contact options, the spatial search for candidate pairs, initial gaps and tributary lengths.
#include "signorini/contact/contact_set.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/fem/element.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

namespace signorini {

PetscErrorCode CheckContactInputs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts) {
  MPI_Comm comm = mesh.Comm();
  // -contact_monitor and -contact_converged_reason still print the (single) iteration and its reason; the solver's
  // own -contact_ksp_, -contact_pc_ and -contact_mat_ options solve the elastic problem.
  static const char *const contact_only[] = {
      "-contact_search_radius", "-contact_touch_tol", "-contact_gap_tol", "-contact_alpha_tol",
      "-contact_complementarity_c", "-contact_activation_fraction", "-contact_activation_gap_factor",
      "-contact_max_it", "-contact_reuse_factorization", "-contact_reuse_max_it", "-contact_nested_dissection",
      "-contact_nested_dissection_parallel"};
  PetscFunctionBeginUser;
  const bool contact = !obstacle.facets.empty() || !opts.pairs.empty();
  for (const char *name : contact_only) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &set));
    PetscCheck(!set || contact, comm, PETSC_ERR_USER_INPUT,
               "%s is given, but the case has no obstacle (no -obstacle_* option) and no pair of bodies "
               "(-contact_pairs), so there is no contact for it to act on; expected an obstacle or a pair, or no "
               "contact options", name);
  }
  PetscBool groups_set;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-contact_groups", &groups_set));
  PetscCheck(!groups_set || !obstacle.facets.empty(), comm, PETSC_ERR_USER_INPUT,
             "-contact_groups is given, but the case has no obstacle (no -obstacle_* option): its groups are the "
             "candidates of a body against rigid obstacles; expected an obstacle, or -contact_pairs SLAVE:MASTER for "
             "contact between bodies");
  for (const auto &[slave, master] : opts.pairs) {
    const std::string item = "-contact_pairs " + slave + ":" + master;
    PetscCheck(slave != master, comm, PETSC_ERR_USER_INPUT,
               "%s: the same group on both sides; expected the facet groups of two different bodies (self-contact is "
               "not supported)", item.c_str());
    // Each side is a facet group on a body's boundary: a curve or surface inside a body would pair its faces with
    // the other body's from within.
    std::vector<Face> boundary, faces;
    PetscCall(mesh.BoundaryFaces(boundary));
    std::set<std::array<PetscInt, 4>> on_boundary;
    const auto key = [](const Face &f) {
      std::array<PetscInt, 4> k{-1, -1, -1, -1};
      std::copy(f.v.begin(), f.v.begin() + f.n, k.begin());
      std::sort(k.begin(), k.end()); // the whole array, padding first (of a variable length GCC 12 warns falsely)
      return k;
    };
    for (const Face &f : boundary) on_boundary.insert(key(f));
    for (const std::string &group : {slave, master}) {
      PetscCall(mesh.GroupFaces(group, faces, item));
      PetscInt inside = 0;
      for (const Face &f : faces) inside += !on_boundary.count(key(f));
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &inside, 1, MPIU_INT, MPI_SUM, comm));
      PetscCheck(inside == 0, comm, PETSC_ERR_USER_INPUT,
                 "%s: physical group '%s' has %" PetscInt_FMT " facet(s) inside a body, off its boundary; expected a "
                 "group on the boundary of a body (curves in 2D, surfaces in 3D)", item.c_str(), group.c_str(), inside);
    }
  }
  // A candidate is a node of the body's boundary: a group of the body's dimension (or one with interior nodes)
  // would make interior nodes candidates.
  std::vector<PetscInt> vertices;
  std::vector<char> boundary(mesh.NumLocalVertices(), 0);
  PetscCall(mesh.BoundaryVertices(vertices));
  for (PetscInt v : vertices) boundary[v] = 1;
  for (const auto &g : opts.groups) {
    PetscCall(mesh.GroupVertices(g, vertices, "-contact_groups " + g));
    PetscInt interior = 0;
    for (PetscInt v : vertices) interior += mesh.Owned(v) && !boundary[v];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &interior, 1, MPIU_INT, MPI_SUM, comm));
    PetscCheck(interior == 0, comm, PETSC_ERR_USER_INPUT,
               "-contact_groups %s: physical group '%s' has %" PetscInt_FMT " node(s) inside the body, off its "
               "boundary; expected a group on the boundary (curves in 2D, surfaces in 3D, or points on them)",
               g.c_str(), g.c_str(), interior);
  }
  PetscFunctionReturn(0);
}

double ActivationGapFactor(int dim) {
  return dim == 3 ? std::pow(3 * M_PI / 4, 2.0 / 3.0) : 2.0;
}

PetscErrorCode ReadContactOptions(MPI_Comm comm, int dim, double L, double k, ContactOptions &opts) {
  // Ranges (docs/options.md): a penetration or touching gap beyond 1e-3 of the body's size is a visibly wrong state,
  // alpha beyond 1e-2 projects a node off its facet, a radius beyond 1e5 diagonals pairs everything anyway (and keeps
  // the bin search finite), a gap factor beyond 1e6 holds nothing back, and c far from E t makes lambda - c g compare
  // numbers of unrelated magnitudes.
  const RealRange radius{0, SEARCH_RADIUS_MAX, true, false, L, "body diagonal"};
  const RealRange gap{0, 1e-3, false, false, L, "body diagonal"};
  const RealRange alpha{0, 1e-2}, fraction{0, 1, false, true}, gap_factor{0, 1e6}, friction{0, 1e3};
  const RealRange c{1e-6, 1e6, false, false, k, "E x thickness"};
  PetscFunctionBeginUser;
  opts.length = L;
  opts.search_radius = 0.1 * L;
  opts.touch_tol = 1e-8 * L;
  opts.gap_tol = 1e-9 * L;
  opts.c = k;
  opts.activation_gap_factor = ActivationGapFactor(dim);
  PetscOptionsBegin(comm, nullptr, "Contact options", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsStringList(PetscOptionsObject, "-contact_groups", "Physical groups of candidate nodes (default: "
                              "whole boundary)", "no candidate nodes", "physical group names", opts.groups));
  std::vector<std::string> items;
  PetscCall(OptionsStringList(PetscOptionsObject, "-contact_pairs", "Pairs of facet groups of two bodies in contact, "
                              "SLAVE:MASTER[:MU],... (the slave side carries the multipliers: make it the finer mesh; MU: "
                              "the pair's friction coefficient, default -contact_friction)",
                              "no pair of bodies", "SLAVE:MASTER[:MU] items of physical group names", items));
  opts.pairs.clear();
  opts.pair_friction.clear();
  for (std::string item : items) {
    // An optional third field is the pair's friction coefficient.
    const auto colon = item.find(':');
    auto third = colon == std::string::npos ? colon : item.find(':', colon + 1);
    double mu = -1;
    if (third != std::string::npos) {
      const std::string text = item.substr(third + 1);
      char *end = nullptr;
      mu = std::strtod(text.c_str(), &end);
      PetscCheck(!text.empty() && *end == '\0' && std::isfinite(mu) && mu >= 0, comm, PETSC_ERR_USER_INPUT,
                 "-contact_pairs: item '%s' has the friction coefficient '%s'; expected a number >= 0 after the two "
                 "groups (SLAVE:MASTER:MU)", item.c_str(), text.c_str());
      PetscCheck(mu <= 1e3, comm, PETSC_ERR_USER_INPUT,
                 "-contact_pairs: item '%s' has the friction coefficient %g; expected a number in [0, 1000]",
                 item.c_str(), mu);
      item = item.substr(0, third);
    }
    PetscCheck(colon != std::string::npos && colon > 0 && colon + 1 < item.size() &&
                   item.find(':', colon + 1) == std::string::npos,
               comm, PETSC_ERR_USER_INPUT,
               "-contact_pairs: item '%s' is not of the form SLAVE:MASTER[:MU]; expected two physical group names "
               "(curves in 2D, surfaces in 3D) joined by a colon, e.g. -contact_pairs top_bottom:base_top",
               item.c_str());
    opts.pairs.emplace_back(item.substr(0, colon), item.substr(colon + 1));
    opts.pair_friction.push_back(mu);
  }
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_friction", "Coulomb friction coefficient mu of every pair "
                        "(against rigid obstacles and between bodies; 0: frictionless; docs/theory.md section 9)", friction,
                        opts.friction));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_search_radius", "Pair a node with the facets within this "
                        "distance (default 0.1 x body diagonal); a load step that ends with a node inside a facet it "
                        "has no pair with, or that cycles or leaves the body free, is repeated with a wider radius",
                        radius, opts.search_radius));
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
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_activation_gap_factor",
                        "In the first update of a load step, "
                        "activate only pairs whose gap at the start of the step is at most this factor times that of "
                        "the deepest penetrating pair (0: off; otherwise at least 1; default 2 in 2D, (3 pi/4)^(2/3) = "
                        "1.77 in 3D)",
                        gap_factor, opts.activation_gap_factor));
  PetscCall(OptionsInt(PetscOptionsObject, "-contact_max_it", "Maximum active-set iterations per load step (svk: "
                       "Newton iterations that change the active set)", 1,
                       CONTACT_MAX_IT_LIMIT, opts.max_it));
  PetscCall(PetscOptionsBool("-contact_monitor", "Print one line per active-set iteration", "", opts.monitor,
                             &opts.monitor, nullptr));
  PetscCall(PetscOptionsBool("-contact_converged_reason", "Print why the active-set loop stopped", "",
                             opts.converged_reason, &opts.converged_reason, nullptr));
  PetscOptionsEnd();
  PetscCheck(opts.activation_gap_factor == 0 || opts.activation_gap_factor >= 1, comm, PETSC_ERR_USER_INPUT,
             "-contact_activation_gap_factor %.6g is out of range; expected 0 (off) or a number in [1, 1e+06]",
             opts.activation_gap_factor);
  PetscFunctionReturn(0);
}

namespace {

/// Uniform grid of bins (dim dimensions) over the bounded facets' bounding boxes inflated by the search radius;
/// unbounded facets (planes, cylinders) are candidates everywhere.
class FacetBins {
public:
  FacetBins(const Obstacle &obstacle, int dim, double radius) : dim_(dim) {
    double hi[3] = {-1e300, -1e300, -1e300}, total = 0;
    const auto &facets = obstacle.facets;
    std::vector<PetscInt> bounded;
    for (std::size_t k = 0; k < facets.size(); ++k) {
      double a[3], b[3];
      facets[k]->Bounds(a, b);
      bool finite = true;
      for (int i = 0; i < dim; ++i) finite = finite && std::isfinite(a[i]) && std::isfinite(b[i]);
      if (!finite) {
        everywhere_.push_back((PetscInt)k);
        continue;
      }
      bounded.push_back((PetscInt)k);
      double size = 0;
      for (int i = 0; i < dim; ++i) {
        lo_[i] = std::min(lo_[i], a[i] - radius), hi[i] = std::max(hi[i], b[i] + radius);
        size = std::max(size, b[i] - a[i]);
      }
      total += size;
    }
    if (bounded.empty()) return;
    h_ = std::max({radius, total / bounded.size(), 1e-300});
    // At most MAX_BINS bins per direction keep the bin keys (products of the counts) within a long.
    for (int i = 0; i < dim; ++i) n_[i] = std::clamp((long)std::ceil((hi[i] - lo_[i]) / h_), 1L, MAX_BINS);
    h_ = 0;
    for (int i = 0; i < dim; ++i) h_ = std::max(h_, (hi[i] - lo_[i]) / n_[i]);
    for (PetscInt k : bounded) {
      double a[3], b[3];
      facets[k]->Bounds(a, b);
      long first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
      for (int i = 0; i < dim; ++i) first[i] = Cell(a[i] - radius, i), last[i] = Cell(b[i] + radius, i);
      for (long i = first[0]; i <= last[0]; ++i)
        for (long j = first[1]; j <= last[1]; ++j)
          for (long l = first[2]; l <= last[2]; ++l) bins_[(i * n_[1] + j) * n_[2] + l].push_back(k);
    }
  }
  /// The facets that may lie within the search radius of x: those of x's bin, then the unbounded ones.
  void Find(const double *x, std::vector<PetscInt> &near) const {
    near.clear();
    long key = 0;
    bool in = !bins_.empty();
    for (int i = 0; i < dim_ && in; ++i) {
      const long c = (long)std::floor((x[i] - lo_[i]) / h_);
      in = c >= 0 && c < n_[i];
      key = key * n_[i] + c;
    }
    if (in) {
      const auto it = bins_.find(key);
      if (it != bins_.end()) near = it->second;
    }
    near.insert(near.end(), everywhere_.begin(), everywhere_.end());
  }

private:
  static constexpr long MAX_BINS = 4096;
  long Cell(double x, int d) const { return std::clamp((long)std::floor((x - lo_[d]) / h_), 0L, n_[d] - 1); }
  int dim_;
  double lo_[3] = {1e300, 1e300, 1e300}, h_ = 1;
  long n_[3] = {1, 1, 1};
  std::map<long, std::vector<PetscInt>> bins_;
  std::vector<PetscInt> everywhere_;
};

} // namespace

bool ConvexJoint(const Obstacle &obstacle, const FacetSide &a, const FacetSide &b, const double *x, int dim,
                 double length) {
  double ca[3], cb[3];
  if (!obstacle.facets[a.facet]->Centroid(ca) || !obstacle.facets[b.facet]->Centroid(cb)) return false;
  double behind_a = 0, behind_b = 0; // signed heights of each centre over the other facet's plane
  for (int k = 0; k < dim; ++k) {
    behind_a += a.normal[k] * (cb[k] - (x[k] - a.gap * a.normal[k]));
    behind_b += b.normal[k] * (ca[k] - (x[k] - b.gap * b.normal[k]));
  }
  const double tol = 1e-12 * length;
  return behind_a < -tol && behind_b < -tol;
}

namespace {

/// The candidate nodes (the boundary, or the -contact_groups) but those whose every component is fixed (seed section
/// 4.2.1), which held marks, when given. Collective.
PetscErrorCode MarkCandidates(const Mesh &mesh, const ContactOptions &opts, const std::vector<char> &fixed,
                              std::vector<char> &candidate, std::vector<char> *held) {
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
      PetscCall(mesh.GroupVertices(g, vertices, "-contact_groups " + g));
      for (PetscInt v : vertices) candidate[v] = 1;
    }
  }
  // Seed section 4.2.1: nodes with every component fixed cannot move and are no candidates.
  if (held) held->assign(nv, 0);
  for (PetscInt v = 0; v < nv; ++v) {
    bool all_fixed = true;
    for (int k = 0; k < dim; ++k) all_fixed = all_fixed && fixed[v * dim + k];
    if (all_fixed && held) (*held)[v] = candidate[v];
    if (all_fixed) candidate[v] = 0;
  }
  PetscFunctionReturn(0);
}

/// Appends the pairs of node v at x with the facets near (bins) within the search radius, and their distances.
void AddNodePairs(const Obstacle &obstacle, const ContactOptions &opts, const std::vector<char> &fixed, int dim,
                  PetscInt v, const double x[3], const std::vector<PetscInt> &near, std::vector<ContactPair> &pairs,
                  std::vector<double> &distance) {
  for (PetscInt f : near) {
    const Facet &facet = *obstacle.facets[f];
    if (facet.Distance(x) > opts.search_radius) continue;
    const Projection p = facet.Project(x, opts.alpha_tol, opts.length);
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
}

/// The zones (zone0) of the pairs of node v at x, pairs[first] on: where the node projects onto no facet, or onto
/// two at a convex joint, which facet is its own.
void AssignZones(const Obstacle &obstacle, const ContactOptions &opts, const std::vector<char> &fixed, int dim,
                 PetscInt v, const double x[3], std::size_t first, std::vector<ContactPair> &pairs,
                 const std::vector<double> &distance) {
  // A node over the wedge of a convex joint projects onto none of its facets: the nearest one (the first at a
  // tie, both meeting at the joint) is its own.
  const auto nearer = [&](std::size_t p, std::size_t q) {
    return NearerFacet(distance[p], pairs[p].facet, distance[q], pairs[q].facet, opts.search_radius);
  };
  bool any = false;
  for (std::size_t p = first; p < pairs.size(); ++p)
    any = any || pairs[p].inside0;
  std::size_t nearest = first;
  for (std::size_t p = first; p < pairs.size(); ++p)
    if (nearer(p, nearest)) nearest = p;
  // Only there, or on a symmetry plane where a quarter of a meshed surface ends (the punch): the node's support
  // fixes a component k, the facet reaches the node's plane x_k = X_k from one side (its mirror image continues it
  // beyond), and the node is nearly over the facet's edge (past it by at most its height over the facet's plane).
  // Beyond the free end of a facet (a floor that ends under a beam) the obstacle is not below the node: the
  // nearest-facet zone held the nodes there on the floor's extended line as far as -contact_search_radius reached,
  // so that the result depended on it (the beam beyond a floor's end: 1, 1 and 13 active nodes, max |u| 0.241,
  // 0.202 and 0.053 for radii 0.08, 0.3 and 3); and the nearly-over-the-edge rule alone, without the symmetry
  // plane, held a block's corner 0.1 past a floor's end on its extended line (test floor_end_beside_block). A node
  // that goes into a facet without a pair is found by the certificate, and its load step repeated with the pair.
  if (!any && nearest < pairs.size()) {
    const ContactPair &n = pairs[nearest];
    bool own = false;
    if (distance[nearest] * distance[nearest] <= 2 * n.g0 * n.g0) {
      double lo[3], hi[3];
      obstacle.facets[n.facet]->Bounds(lo, hi);
      const double tol = 1e-9 * opts.length;
      for (int k = 0; k < dim && !own; ++k)
        own = fixed[v * dim + k] && (std::abs(lo[k] - x[k]) <= tol || std::abs(hi[k] - x[k]) <= tol);
    }
    for (std::size_t q = first; q < pairs.size() && !own; ++q)
      own = q != nearest &&
            std::abs(distance[q] - distance[nearest]) <= 1e-9 * distance[nearest] + 1e-12 * opts.search_radius &&
            ConvexJoint(obstacle, {n.facet, n.n0, n.g0}, {pairs[q].facet, pairs[q].n0, pairs[q].g0}, x, dim,
                        opts.search_radius);
    pairs[nearest].zone0 = own;
  }
  // A node on the apex of a convex joint projects onto both facets only by the tolerance of the projection (the
  // edge of both), and the obstacle is outside it when it is outside either facet: the nearer facet alone is its
  // own, as over the wedge. Both zones would hold the node in the valley of the two extended facets, whose second
  // gap turns negative as soon as the node slides along the first one (a finely faceted arc with a vertex under a
  // node failed its certificate so). At a concave joint the node must clear both facets and keeps both zones.
  for (std::size_t p = first; p < pairs.size(); ++p)
    for (std::size_t q = p + 1; q < pairs.size(); ++q)
      if (pairs[p].zone0 && pairs[q].zone0 &&
          ConvexJoint(obstacle, {pairs[p].facet, pairs[p].n0, pairs[p].g0}, {pairs[q].facet, pairs[q].n0, pairs[q].g0},
                      x, dim, opts.search_radius))
        (nearer(p, q) ? pairs[q] : pairs[p]).zone0 = false;
}

} // namespace

PetscErrorCode FindContactPairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                                const std::vector<char> &fixed, std::vector<ContactPair> &pairs,
                                std::vector<char> &candidate, const double *u_local, std::vector<char> *held) {
  const int dim = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  PetscFunctionBeginUser;
  PetscCall(MarkCandidates(mesh, opts, fixed, candidate, held));
  pairs.clear();
  std::vector<double> distance;
  const FacetBins bins(obstacle, dim, opts.search_radius);
  std::vector<PetscInt> near;
  for (PetscInt v = 0; v < nv; ++v) {
    if (!candidate[v] || !mesh.Owned(v)) continue;
    double x[3] = {0, 0, 0};
    for (int k = 0; k < dim; ++k) x[k] = mesh.X(v)[k] + (u_local ? u_local[v * dim + k] : 0.0);
    bins.Find(x, near);
    const std::size_t first = pairs.size();
    AddNodePairs(obstacle, opts, fixed, dim, v, x, near, pairs, distance);
    AssignZones(obstacle, opts, fixed, dim, v, x, first, pairs, distance);
  }
  SortPairs(mesh, pairs);
  PetscFunctionReturn(0);
}

void SortPairs(const Mesh &mesh, std::vector<ContactPair> &pairs) {
  std::sort(pairs.begin(), pairs.end(), [&](const ContactPair &a, const ContactPair &b) {
    const PetscInt oa = mesh.VertexOriginal(a.vertex), ob = mesh.VertexOriginal(b.vertex);
    return oa != ob ? oa < ob : a.facet < b.facet;
  });
}

PetscErrorCode DeepestUnpaired(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                               const std::vector<char> &candidate, const std::vector<char> &held,
                               const std::vector<char> &fixed, const std::vector<ContactPair> &pairs,
                               const double *u_local, Penetration &unpaired, Penetration &prescribed,
                               std::vector<std::array<PetscInt, 2>> *found, double *reach_out) {
  const int dim = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  PetscFunctionBeginUser;
  std::vector<std::array<PetscInt, 2>> paired(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p) paired[p] = {pairs[p].vertex, pairs[p].facet};
  std::sort(paired.begin(), paired.end());
  const auto examined = [&](PetscInt v) { return (candidate[v] || held[v]) && mesh.Owned(v); };
  if (found) found->clear();
  double reach = 0;
  for (PetscInt v = 0; v < nv; ++v)
    if (examined(v)) {
      double u2 = 0;
      for (int k = 0; k < dim; ++k) u2 += u_local[v * dim + k] * u_local[v * dim + k];
      reach = std::max(reach, std::sqrt(u2));
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &reach, 1, MPI_DOUBLE, MPI_MAX, mesh.Comm()));
  if (reach_out) *reach_out = reach;
  // Each examined node's penetration of each kind (0: unpaired, 1: prescribed): the deepest facet.
  std::vector<double> depth[2];
  depth[0].assign(nv, 0.0), depth[1].assign(nv, 0.0);
  {
    // Also when nothing examined has moved: a held node fixed at zero may sit inside the obstacle from the start.
    const FacetBins bins(obstacle, dim, opts.search_radius + reach);
    std::vector<PetscInt> near;
    for (PetscInt v = 0; v < nv; ++v) {
      if (!examined(v)) continue;
      double x[3] = {0, 0, 0};
      for (int k = 0; k < dim; ++k) x[k] = mesh.X(v)[k] + u_local[v * dim + k];
      bins.Find(x, near);
      for (PetscInt f : near) {
        if (std::binary_search(paired.begin(), paired.end(), std::array<PetscInt, 2>{v, f})) continue;
        const Projection p = obstacle.facets[f]->Project(x, opts.alpha_tol, opts.length);
        if (!p.inside) continue;
        // As in FindContactPairs: a facet whose normal lies in the node's fixed components gets no pair.
        double free2 = 0;
        for (int k = 0; k < dim; ++k)
          if (!fixed[v * dim + k]) free2 += p.normal[k] * p.normal[k];
        double &d = depth[free2 < 1e-12 ? 1 : 0][v];
        d = std::max(d, -p.gap);
        if (found && free2 >= 1e-12 && -p.gap > opts.gap_tol) found->push_back({v, f});
      }
    }
  }
  for (int kind = 0; kind < 2; ++kind) {
    // The deepest, then among the nodes within round-off of it the smallest file number, then its position.
    double deepest = 0;
    for (PetscInt v = 0; v < nv; ++v) deepest = std::max(deepest, depth[kind][v]);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &deepest, 1, MPI_DOUBLE, MPI_MAX, mesh.Comm()));
    Penetration &out = kind ? prescribed : unpaired;
    out = Penetration();
    if (deepest <= 0) continue;
    struct {
      double node;
      int rank;
    } mine{INFINITY, 0}, first;
    PetscCallMPI(MPI_Comm_rank(mesh.Comm(), &mine.rank));
    PetscInt local = -1;
    for (PetscInt v = 0; v < nv; ++v)
      if (depth[kind][v] > 0 && depth[kind][v] >= deepest * (1 - 1e-12) && mesh.VertexOriginal(v) < mine.node)
        mine.node = (double)mesh.VertexOriginal(v), local = v;
    PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_DOUBLE_INT, MPI_MINLOC, mesh.Comm()));
    double where[4] = {0, 0, 0, 0}; // depth, reference position
    if (first.rank == mine.rank) {
      where[0] = depth[kind][local];
      for (int k = 0; k < dim; ++k) where[1 + k] = mesh.X(local)[k];
    }
    PetscCallMPI(MPI_Bcast(where, 4, MPI_DOUBLE, first.rank, mesh.Comm()));
    out.depth = where[0];
    out.node = (PetscInt)first.node + 1;
    for (int k = 0; k < 3; ++k) out.x[k] = where[1 + k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TributaryLengths(const Mesh &mesh, const std::vector<char> &candidate, std::vector<double> &length,
                                const std::vector<double> *face_thickness, std::vector<double> *area) {
  const int dim = mesh.Dim();
  std::vector<Face> faces;
  PetscFunctionBeginUser;
  PetscCall(mesh.BoundaryFaces(faces));
  length.assign(mesh.NumLocalVertices(), 0.0);
  if (area) area->assign(mesh.NumLocalVertices(), 0.0);
  for (const auto &f : faces) {
    bool all = true;
    for (int a = 0; a < f.n; ++a) all = all && candidate[f.v[a]];
    if (!all) continue;
    double X[4 * 3], w[4], an[4][3];
    for (int a = 0; a < f.n; ++a)
      for (int d = 0; d < dim; ++d) X[a * dim + d] = mesh.X(f.v[a])[d];
    FaceIntegrals(dim, f.n, X, w, an);
    for (int a = 0; a < f.n; ++a) length[f.v[a]] += w[a];
    if (area)
      for (int a = 0; a < f.n; ++a) (*area)[f.v[a]] += w[a] * (face_thickness ? (*face_thickness)[f.cell] : 1.0);
  }
  PetscCall(mesh.SumShared(length));
  if (area) PetscCall(mesh.SumShared(*area));
  PetscFunctionReturn(0);
}

} // namespace signorini
