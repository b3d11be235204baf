// Contiguous blocks of a global index range, one per rank in rank order (PETSc's default split): how data kept in a
// file's order (node and cell tables) is spread over the ranks.
#pragma once

#include <petscsys.h>

#include <cstddef>
#include <vector>

namespace signorini {

/// This rank's block of the indices 0 .. n-1: its first index and its size (n / size, one more on the first
/// n % size ranks, as PetscSplitOwnership). Collective (n must be the same on every rank).
[[nodiscard]] PetscErrorCode BlockOf(MPI_Comm comm, PetscInt n, PetscInt &start, PetscInt &size);

/// Spreads root_values, held on rank 0 (ignored elsewhere), over the ranks: block receives this rank's block
/// (BlockOf) of it. Collective.
[[nodiscard]] PetscErrorCode ScatterBlocks(MPI_Comm comm, const std::vector<std::size_t> &root_values,
                                           std::vector<std::size_t> &block);

} // namespace signorini
