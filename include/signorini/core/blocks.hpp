// Contiguous blocks of a global index range, one per rank in rank order (PETSc's default split): how data kept in a
// file's order (node and cell tables) is spread over the ranks.
#pragma once

#include <petscsys.h>

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace signorini {

/// This rank's block of the indices 0 .. n-1: its first index and its size (n / size, one more on the first
/// n % size ranks, as PetscSplitOwnership). Collective (n must be the same on every rank).
[[nodiscard]] PetscErrorCode BlockOf(MPI_Comm comm, PetscInt n, PetscInt &start, PetscInt &size);

/// Spreads root_values, held on rank 0 (ignored elsewhere), over the ranks: block receives this rank's block
/// (BlockOf) of it. Collective.
[[nodiscard]] PetscErrorCode ScatterBlocks(MPI_Comm comm, const std::vector<std::size_t> &root_values,
                                           std::vector<std::size_t> &block);

/// Every rank's `mine` concatenated in rank order, into `all` on every rank (values of a trivially copyable type, sent
/// as bytes: for small data such as a contact interface or a list of labels). Collective.
template <typename T>
[[nodiscard]] PetscErrorCode AllGather(MPI_Comm comm, const std::vector<T> &mine, std::vector<T> &all) {
  static_assert(std::is_trivially_copyable<T>::value, "AllGather sends values as bytes");
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscMPIInt bytes = (PetscMPIInt)(mine.size() * sizeof(T));
  std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; ++r) displs[r + 1] = displs[r] + counts[r];
  all.resize(displs[size] / sizeof(T));
  PetscCallMPI(MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE, comm));
  PetscFunctionReturn(0);
}

/// AllGather, then sorted without repeats: the union of the ranks' values. Collective.
template <typename T>
[[nodiscard]] PetscErrorCode AllGatherUnion(MPI_Comm comm, const std::vector<T> &mine, std::vector<T> &all) {
  PetscFunctionBeginUser;
  PetscCall(AllGather(comm, mine, all));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  PetscFunctionReturn(0);
}

} // namespace signorini
