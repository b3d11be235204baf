// Meshed rigid obstacles: a gmsh file's lines (2D) or triangles and quadrilaterals (3D) as oriented facets, checked
// for orientation, manifoldness and degenerate elements.
#include "signorini/obstacles/obstacle_mesh.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/options/option_paths.hpp"
#include "signorini/core/parse.hpp"
#include "signorini/core/progress.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace signorini {

namespace {

/// Diagonal of the bounding box of the set's nodes: the length scale of "zero" length and area.
double Diagonal(const ElementSet &set) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d2 = 0;
  for (std::size_t i = 0; i < set.node_tags.size(); ++i)
    for (int d = 0; d < 3; ++d)
      lo[d] = std::min(lo[d], set.X(i)[d]), hi[d] = std::max(hi[d], set.X(i)[d]);
  for (int d = 0; d < 3; ++d)
    d2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  return std::sqrt(d2);
}

std::string Tag(const ElementSet &set, int e) {
  return "element " + std::to_string(set.tags[e]);
}

/// 2D: lines chained head to tail into polylines in the plane z = const.
std::string BuildSegments(const ElementSet &set, const std::string &where, double tol,
                          std::vector<std::unique_ptr<Facet>> &out) {
  const double z0 = set.X(0)[2];
  // Per node, the lines that start (role 0) and end (role 1) there.
  std::map<int, std::vector<std::pair<int, int>>> at;
  for (int e = 0; e < set.NumElements(); ++e) {
    const int *v = &set.nodes[set.offsets[e]];
    for (int k = 0; k < 2; ++k)
      if (std::abs(set.X(v[k])[2] - z0) > tol)
        return where + ": " + Tag(set, e) + " leaves the plane z = " + FormatNumber(z0) +
               "; expected a curve in the plane of the 2D body";
    const double *a = set.X(v[0]), *b = set.X(v[1]);
    if (std::hypot(b[0] - a[0], b[1] - a[1]) <= tol)
      return where + ": " + Tag(set, e) + " has zero length; expected non-degenerate line elements";
    at[v[0]].push_back({e, 0});
    at[v[1]].push_back({e, 1});
  }
  for (const auto &[node, lines] : at) {
    const std::string tag = "node " + std::to_string(set.node_tags[node]);
    if (lines.size() > 2)
      return where + ": " + tag + " is shared by " + std::to_string(lines.size()) + " line elements (" +
             Tag(set, lines[0].first) + ", " + Tag(set, lines[1].first) + ", " + Tag(set, lines[2].first) +
             "); expected a manifold polyline (at most two lines per node)";
    if (lines.size() == 2 && lines[0].second == lines[1].second)
      return where + ": " + Tag(set, lines[0].first) + " and " + Tag(set, lines[1].first) + " both " +
             (lines[0].second == 0 ? "start" : "end") + " at " + tag +
             "; expected consistently oriented lines, chained head to tail (each left normal pointing into the body)";
  }
  for (int e = 0; e < set.NumElements(); ++e) {
    const int *v = &set.nodes[set.offsets[e]];
    out.push_back(std::make_unique<Segment>(set.X(v[0]), set.X(v[1])));
  }
  return "";
}

/// Twice the area vector (P1 - P0) x (P2 - P0) of the triangle of nodes a, b, c.
void AreaVector(const ElementSet &set, int a, int b, int c, double *n) {
  double e1[3], e2[3];
  for (int d = 0; d < 3; ++d)
    e1[d] = set.X(b)[d] - set.X(a)[d], e2[d] = set.X(c)[d] - set.X(a)[d];
  n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

double Norm(const double *n) {
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// 3D: triangles and quadrilaterals, each edge shared by at most two facets traversing it in opposite directions.
std::string BuildTriangles(const ElementSet &set, const std::string &where, double tol,
                           std::vector<std::unique_ptr<Facet>> &out) {
  // Per undirected edge (lower node, higher node), the facets using it and whether they go from lower to higher.
  std::map<std::pair<int, int>, std::vector<std::pair<int, bool>>> edges;
  for (int e = 0; e < set.NumElements(); ++e) {
    const int n = set.Size(e), *v = &set.nodes[set.offsets[e]];
    // A quadrilateral is split along its diagonal 0-2: both halves must have an area and face the same way.
    double n0[3], n1[3];
    AreaVector(set, v[0], v[1], v[2], n0);
    if (n == 4) AreaVector(set, v[0], v[2], v[3], n1);
    const bool degenerate = Norm(n0) <= tol || (n == 4 && Norm(n1) <= tol);
    if (degenerate)
      return where + ": " + Tag(set, e) + " has zero area (or a degenerate corner); expected non-degenerate " +
             (n == 3 ? "triangles" : "quadrilaterals");
    if (n == 4 && n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] <= 0)
      return where + ": " + Tag(set, e) + " is a folded or self-intersecting quadrilateral; expected convex ones";
    for (int k = 0; k < n; ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      edges[{std::min(a, b), std::max(a, b)}].push_back({e, a < b});
    }
  }
  for (const auto &[edge, facets] : edges) {
    const std::string nodes =
        "(nodes " + std::to_string(set.node_tags[edge.first]) + ", " + std::to_string(set.node_tags[edge.second]) + ")";
    if (facets.size() > 2)
      return where + ": the edge " + nodes + " is shared by " + std::to_string(facets.size()) + " elements (" +
             Tag(set, facets[0].first) + ", " + Tag(set, facets[1].first) + ", " + Tag(set, facets[2].first) +
             "); expected a manifold surface (at most two facets per edge)";
    if (facets.size() == 2 && facets[0].second == facets[1].second)
      return where + ": " + Tag(set, facets[0].first) + " and " + Tag(set, facets[1].first) +
             " traverse their common edge " + nodes +
             " in the same direction; expected consistently oriented facets (each normal, by the right-hand rule of "
             "the node order, pointing into the body)";
  }
  // A quadrilateral becomes the two triangles (0, 1, 2) and (0, 2, 3) rather than one bilinear facet: the contact
  // rules assume flat facets (the linear material's gap linearised with a constant normal; svk's crossing test, the
  // gap linear along a straight path: constraints.cpp), which a warped bilinear quadrilateral is not. For a flat
  // quadrilateral the two triangles are the same surface; a node on the diagonal pairs with both, and their parallel
  // normals are one constraint (DropParallelPairs).
  for (int e = 0; e < set.NumElements(); ++e) {
    const int *v = &set.nodes[set.offsets[e]];
    out.push_back(std::make_unique<Triangle>(set.X(v[0]), set.X(v[1]), set.X(v[2])));
    if (set.Size(e) == 4) out.push_back(std::make_unique<Triangle>(set.X(v[0]), set.X(v[2]), set.X(v[3])));
  }
  return "";
}

static_assert(sizeof(std::size_t) == sizeof(unsigned long long), "tags are broadcast as MPI_UNSIGNED_LONG_LONG");

/// Broadcasts a vector from rank 0 (resized on the others).
template <typename T>
[[nodiscard]] PetscErrorCode BroadcastVector(MPI_Comm comm, MPI_Datatype type, std::vector<T> &v) {
  unsigned long long n = v.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  v.resize(n);
  PetscCallMPI(MPI_Bcast(v.data(), (PetscMPIInt)n, type, 0, comm));
  PetscFunctionReturn(0);
}

} // namespace

std::string BuildMeshFacets(const ElementSet &set, int dim, const std::string &name,
                            std::vector<std::unique_ptr<Facet>> &out) {
  const std::string where = "obstacle mesh '" + name + "'";
  if (set.NumElements() == 0) return where + " has no elements";
  // A length below 1e-12 of the mesh's diagonal, an area below 1e-12 of its square, is zero (round-off).
  const double L = Diagonal(set), tol = 1e-12 * (dim == 2 ? L : L * L);
  std::vector<std::unique_ptr<Facet>> facets;
  const std::string error = dim == 2 ? BuildSegments(set, where, tol, facets) : BuildTriangles(set, where, tol, facets);
  if (!error.empty()) return error;
  for (auto &f : facets)
    out.push_back(std::move(f));
  return "";
}

PetscErrorCode LoadObstacleMeshes(MPI_Comm comm, int dim, Obstacle &obstacle) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (const ObstacleMeshSource &source : obstacle.meshes) {
    ElementSet set;
    std::string error, path;
    ProgressBegin(("reading obstacle mesh " + source.file).c_str());
    if (rank == 0) {
      std::string looked;
      path = FirstExisting({source.paths, source.origins}, looked);
      if (path.empty())
        error = "cannot open obstacle mesh file '" + source.file + "' (-obstacle_mesh " + source.value +
                "): not found at " + looked + "; expected a readable gmsh .msh or .geo file";
      if (error.empty()) error = ReadGmshElements(path, dim - 1, source.group, set);
      std::vector<std::unique_ptr<Facet>> check;
      if (error.empty()) error = BuildMeshFacets(set, dim, path, check);
    }
    ProgressEnd();
    PetscCall(RaiseFromRoot(comm, error));
    PetscCall(BroadcastVector(comm, MPI_DOUBLE, set.coords));
    PetscCall(BroadcastVector(comm, MPI_UNSIGNED_LONG_LONG, set.node_tags));
    PetscCall(BroadcastVector(comm, MPI_INT, set.offsets));
    PetscCall(BroadcastVector(comm, MPI_INT, set.nodes));
    PetscCall(BroadcastVector(comm, MPI_UNSIGNED_LONG_LONG, set.tags));
    error = BuildMeshFacets(set, dim, source.file, obstacle.facets);
    PetscAssert(error.empty(), comm, PETSC_ERR_PLIB, "obstacle mesh checked on rank 0 fails on another: %s",
                error.c_str());
    obstacle.facet_kind.resize(obstacle.facets.size(), MeshKind());
  }
  PetscFunctionReturn(0);
}

} // namespace signorini
