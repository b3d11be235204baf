// Nested dissection of a distributed graph: the partition's interfaces as separators, each rank's part by METIS.
#include "signorini/linalg/parallel_dissection.hpp"

#include "signorini/core/errors.hpp"

#include <algorithm>
#include <climits>

namespace signorini {

namespace {

const MPI_Datatype IDX_T_MPI = sizeof(idx_t) == 8 ? MPI_INT64_T : MPI_INT32_T;
constexpr idx_t METIS_ORDERING_SEED = 7;
constexpr int NOT_SEPARATOR = INT_MAX;

/// The depth of the split that separates ranks r < s among the ranks [0, size) halved recursively.
int SplitDepth(int r, int s, int size) {
  int lo = 0, hi = size, depth = 0;
  for (;; ++depth) {
    const int mid = lo + (hi - lo) / 2;
    if (r < mid && s >= mid) return depth;
    (s < mid ? hi : lo) = mid;
  }
}

/// Appends to order the elimination order of the ranks [lo, hi) (depth: of their split): the first half's, the
/// second half's, then the split's separator (the vertices of the first half's ranks with that depth).
void Compose(int lo, int hi, int depth, const std::vector<std::vector<idx_t>> &interior,
             const std::vector<std::vector<idx_t>> &separator, std::vector<idx_t> &order) {
  if (hi - lo == 1) {
    order.insert(order.end(), interior[lo].begin(), interior[lo].end());
    return;
  }
  const int mid = lo + (hi - lo) / 2;
  Compose(lo, mid, depth + 1, interior, separator, order);
  Compose(mid, hi, depth + 1, interior, separator, order);
  for (int r = lo; r < mid; ++r)
    for (std::size_t k = 0; k < separator[r].size(); k += 2)
      if (separator[r][k + 1] == depth) order.push_back(separator[r][k]);
}

} // namespace

PetscErrorCode GatherLayout(MPI_Comm comm, PetscMPIInt count, std::vector<PetscMPIInt> &counts,
                            std::vector<PetscMPIInt> &displs, const char *too_large) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  counts.assign(rank == 0 ? size : 0, 0);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  displs.assign(rank == 0 ? size + 1 : 0, 0);
  PetscCall(RunOnRoot(comm, [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (PetscMPIInt r = 0; r < size; ++r) {
      PetscCheck((std::size_t)displs[r] + counts[r] <= (std::size_t)INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s",
                 too_large);
      displs[r + 1] = displs[r] + counts[r];
    }
    PetscFunctionReturn(0);
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode GatherOnRoot(MPI_Comm comm, const std::vector<idx_t> &list, std::vector<idx_t> &all,
                            std::vector<PetscMPIInt> &displs) {
  PetscMPIInt rank, size, count;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMPIIntCast((PetscInt)list.size(), &count));
  std::vector<PetscMPIInt> counts;
  PetscCall(GatherLayout(comm, count, counts, displs,
                         "the matrix graph is too large for the nested-dissection ordering on one rank; choose one of "
                         "MUMPS's orderings with -contact_mat_mumps_icntl_7"));
  all.resize(rank == 0 ? displs[size] : 0);
  PetscCallMPI(
      MPI_Gatherv(list.data(), count, IDX_T_MPI, all.data(), counts.data(), displs.data(), IDX_T_MPI, 0, comm));
  PetscFunctionReturn(0);
}

Graph BuildGraph(idx_t n, const std::vector<idx_t> &edges) {
  Graph g;
  std::vector<idx_t> &xadj = g.xadj, &adjncy = g.adjncy;
  xadj.assign(n + 1, 0);
  for (std::size_t e = 0; e < edges.size(); e += 2)
    ++xadj[edges[e] + 1], ++xadj[edges[e + 1] + 1];
  for (idx_t i = 0; i < n; ++i)
    xadj[i + 1] += xadj[i];
  adjncy.resize(xadj[n]);
  {
    std::vector<idx_t> next(xadj.begin(), xadj.end() - 1);
    for (std::size_t e = 0; e < edges.size(); e += 2) {
      adjncy[next[edges[e]]++] = edges[e + 1];
      adjncy[next[edges[e + 1]]++] = edges[e];
    }
  }
  idx_t w = 0;
  for (idx_t i = 0; i < n; ++i) {
    const idx_t begin = w;
    std::sort(adjncy.begin() + xadj[i], adjncy.begin() + xadj[i + 1]);
    for (idx_t k = xadj[i]; k < xadj[i + 1]; ++k)
      if (k == xadj[i] || adjncy[k] != adjncy[k - 1]) adjncy[w++] = adjncy[k];
    xadj[i] = begin;
  }
  xadj[n] = w;
  adjncy.resize(w);
  return g;
}

int MetisOrder(Graph &g, std::vector<idx_t> &order) {
  idx_t n = g.Size(), options[METIS_NOPTIONS];
  order.resize(n);
  if (n == 0) return METIS_OK;
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = METIS_ORDERING_SEED;
  std::vector<idx_t> iperm(n);
  return METIS_NodeND(&n, g.xadj.data(), g.adjncy.data(), nullptr, options, order.data(), iperm.data());
}

PetscErrorCode PartitionNestedDissection(MPI_Comm comm, const std::vector<idx_t> &first,
                                         const std::vector<idx_t> &edges, std::vector<idx_t> &order, int &status) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const idx_t start = first[rank], n = first[rank + 1] - start;
  const auto owner = [&](idx_t w) {
    return (int)(std::upper_bound(first.begin(), first.end(), w) - first.begin()) - 1;
  };
  // Each own vertex's separator: the shallowest split between this rank and a higher one holding a neighbour.
  std::vector<int> depth(n, NOT_SEPARATOR);
  for (std::size_t e = 0; e < edges.size(); e += 2) {
    const idx_t w = edges[e + 1];
    if (w >= start + n) {
      int &d = depth[edges[e] - start];
      d = std::min(d, SplitDepth(rank, owner(w), size));
    }
  }
  // The rest, numbered locally, and the edges between them; METIS orders them.
  std::vector<idx_t> local(n, -1), global;
  for (idx_t v = 0; v < n; ++v)
    if (depth[v] == NOT_SEPARATOR) local[v] = (idx_t)global.size(), global.push_back(start + v);
  std::vector<idx_t> inner;
  for (std::size_t e = 0; e < edges.size(); e += 2) {
    const idx_t v = edges[e] - start, w = edges[e + 1] - start;
    if (w >= 0 && w < n && w != v && local[v] >= 0 && local[w] >= 0)
      inner.push_back(local[v]), inner.push_back(local[w]);
  }
  Graph g = BuildGraph((idx_t)global.size(), inner);
  inner.clear();
  inner.shrink_to_fit();
  std::vector<idx_t> mine;
  status = MetisOrder(g, mine);
  g = Graph();
  for (idx_t &v : mine)
    v = global[v];
  // This rank's separator vertices with their depths.
  std::vector<idx_t> separator;
  for (idx_t v = 0; v < n; ++v)
    if (depth[v] != NOT_SEPARATOR) separator.push_back(start + v), separator.push_back((idx_t)depth[v]);
  // Both lists to rank 0, which composes the order.
  std::vector<std::vector<idx_t>> interior(rank == 0 ? size : 0), separators(rank == 0 ? size : 0);
  for (const auto &[list, all] : {std::pair{&mine, &interior}, std::pair{&separator, &separators}}) {
    std::vector<idx_t> gathered;
    std::vector<PetscMPIInt> displs;
    PetscCall(GatherOnRoot(comm, *list, gathered, displs));
    if (rank == 0)
      for (PetscMPIInt r = 0; r < size; ++r)
        (*all)[r].assign(gathered.begin() + displs[r], gathered.begin() + displs[r + 1]);
  }
  order.clear();
  if (rank == 0) {
    order.reserve(first[size]);
    Compose(0, size, 0, interior, separators, order);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_INT, MPI_MIN, comm));
  PetscFunctionReturn(0);
}

} // namespace signorini
