// Nested dissection of a distributed graph by METIS: each rank orders the nodes it owns, the partition's interfaces
// are the separators.
#pragma once

#include <metis.h>
#include <petscsys.h>

#include <vector>

namespace signorini {

/// A graph in compressed adjacency form (symmetric, no self loops): vertex v's neighbours are
/// adjncy[xadj[v] .. xadj[v + 1]).
struct Graph {
  std::vector<idx_t> xadj{0}, adjncy;
  idx_t Size() const { return (idx_t)xadj.size() - 1; }
};

/// Where each rank's part of a gather to rank 0 goes (MPI_Gatherv): on rank 0 counts[r] (each rank's count) and
/// displs[r] (where its part starts; displs[size] the total), empty elsewhere. A total beyond what an int counts raises
/// PETSC_ERR_SUP with the message too_large on every rank. Collective.
[[nodiscard]] PetscErrorCode GatherLayout(MPI_Comm comm, PetscMPIInt count, std::vector<PetscMPIInt> &counts,
                                          std::vector<PetscMPIInt> &displs, const char *too_large);
/// The lists of every rank on rank 0 of comm, in rank order: rank r's is all[displs[r] .. displs[r + 1]) (all and
/// displs are empty on the other ranks). Raises PETSC_ERR_SUP on every rank when they hold more entries than an int
/// counts. Collective.
[[nodiscard]] PetscErrorCode GatherOnRoot(MPI_Comm comm, const std::vector<idx_t> &list, std::vector<idx_t> &all,
                                          std::vector<PetscMPIInt> &displs);
/// The graph of n vertices with the edges (edges[2 k], edges[2 k + 1]), in either or both directions, repeated or not.
Graph BuildGraph(idx_t n, const std::vector<idx_t> &edges);

/// METIS_NodeND of g with a fixed seed (the same graph gets the same order): order[k] is the vertex eliminated k-th.
/// Returns METIS's status.
int MetisOrder(Graph &g, std::vector<idx_t> &order);

/// The nested dissection of a graph whose vertices are distributed over the ranks of comm: rank r owns the vertices
/// [first[r], first[r + 1]) and gives edges (pairs of global vertex numbers, edges[2 k] its own) that contain every
/// edge between two of its vertices and every edge to a vertex of a higher rank. The ranks are split in halves
/// recursively ([lo, hi) into [lo, mid) and [mid, hi), mid = lo + (hi - lo) / 2); a vertex of the first half with a
/// neighbour in the second is in that split's separator (the first half's side of the partition's interface); each
/// rank orders its vertices outside the separators by METIS_NodeND, all ranks at once; a split's separator is
/// eliminated after both halves. The order (order[k]: the vertex eliminated k-th) on rank 0. The ordering then costs
/// the METIS_NodeND of the largest part instead of the whole graph's, and its separators are as short as the
/// partition's interfaces. status: METIS_OK, or the error of a METIS call on some rank (every rank). Collective.
[[nodiscard]] PetscErrorCode PartitionNestedDissection(MPI_Comm comm, const std::vector<idx_t> &first,
                                                       const std::vector<idx_t> &edges, std::vector<idx_t> &order,
                                                       int &status);

} // namespace signorini
