// The bodies of the mesh: connected components of its cells, found in parallel without gathering the mesh.
#include "signorini/mesh/mesh.hpp"

#include "signorini/core/blocks.hpp"

#include <algorithm>
#include <numeric>

namespace signorini {

namespace {

/// Union-find over the local vertices with path halving.
struct UnionFind {
  std::vector<PetscInt> parent;
  explicit UnionFind(PetscInt n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  PetscInt Find(PetscInt a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void Join(PetscInt a, PetscInt b) {
    a = Find(a), b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

} // namespace

PetscErrorCode Mesh::BuildBodies() {
  const PetscInt nv = NumLocalVertices(), nc = NumLocalCells();
  PetscFunctionBeginUser;
  // Local components first: the vertices of each cell are joined, and each component is labelled with the smallest
  // file index of its cells.
  UnionFind uf(nv);
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt n;
    const PetscInt *cv = CellVertices(c, n);
    for (PetscInt a = 1; a < n; ++a) uf.Join(cv[0], cv[a]);
  }
  std::vector<PetscInt> label(nv, PETSC_MAX_INT); // of each component, at its root
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt n;
    const PetscInt r = uf.Find(CellVertices(c, n)[0]);
    label[r] = std::min(label[r], cell_orig_[c]);
  }
  // A body split over ranks is one component on each: the smallest label crosses the shared vertices (minimum over
  // the ranks that hold a vertex) and spreads through each local component, until no label changes anywhere. The
  // rounds are bounded by the number of ranks a body crosses.
  std::vector<PetscInt> root(nv), leaf(nv);
  for (int changed = 1; changed;) {
    for (PetscInt v = 0; v < nv; ++v) root[v] = leaf[v] = label[uf.Find(v)];
    PetscCall(PetscSFReduceBegin(vertex_sf_, MPIU_INT, leaf.data(), root.data(), MPI_MIN));
    PetscCall(PetscSFReduceEnd(vertex_sf_, MPIU_INT, leaf.data(), root.data(), MPI_MIN));
    PetscCall(PetscSFBcastBegin(vertex_sf_, MPIU_INT, root.data(), leaf.data(), MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(vertex_sf_, MPIU_INT, root.data(), leaf.data(), MPI_REPLACE));
    changed = 0;
    for (PetscInt v = 0; v < nv; ++v) {
      const PetscInt r = uf.Find(v), got = Owned(v) ? root[v] : leaf[v];
      if (got < label[r]) label[r] = got, changed = 1;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_LOR, comm_));
  }
  // The bodies' labels, few, gathered on every rank and sorted: a body's index is its label's rank among them.
  std::vector<PetscInt> mine;
  for (PetscInt v = 0; v < nv; ++v)
    if (uf.Find(v) == v && label[v] != PETSC_MAX_INT) mine.push_back(label[v]);
  std::sort(mine.begin(), mine.end());
  mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  std::vector<PetscInt> all;
  PetscCall(AllGatherUnion(comm_, mine, all));
  num_bodies_ = (PetscInt)all.size();
  const auto body_of = [&](PetscInt v) {
    return (PetscInt)(std::lower_bound(all.begin(), all.end(), label[uf.Find(v)]) - all.begin());
  };
  vertex_body_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v) vertex_body_[v] = body_of(v);
  cell_body_.resize(nc);
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt n;
    cell_body_[c] = vertex_body_[CellVertices(c, n)[0]];
  }
  PetscFunctionReturn(0);
}

} // namespace signorini
