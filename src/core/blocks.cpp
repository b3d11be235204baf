// Contiguous blocks of a global index range, one per rank.
#include "signorini/core/blocks.hpp"

#include <cstdint>

namespace signorini {

PetscErrorCode BlockOf(MPI_Comm comm, PetscInt n, PetscInt &start, PetscInt &size) {
  PetscMPIInt rank, nranks;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &nranks));
  const PetscInt base = n / nranks, extra = n % nranks;
  size = base + (rank < extra ? 1 : 0);
  start = rank * base + PetscMin((PetscInt)rank, extra);
  PetscFunctionReturn(0);
}

PetscErrorCode ScatterBlocks(MPI_Comm comm, const std::vector<std::size_t> &root_values,
                             std::vector<std::size_t> &block) {
  static_assert(sizeof(std::size_t) == sizeof(std::uint64_t), "tags travel as MPI_UINT64_T");
  PetscMPIInt rank, nranks;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &nranks));
  PetscInt n = rank == 0 ? (PetscInt)root_values.size() : 0, start, size;
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCall(BlockOf(comm, n, start, size));
  std::vector<PetscMPIInt> counts(rank == 0 ? nranks : 0), displs(rank == 0 ? nranks : 0);
  PetscMPIInt count;
  PetscCall(PetscMPIIntCast(size, &count));
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  for (int r = 1; r < (int)displs.size(); ++r)
    displs[r] = displs[r - 1] + counts[r - 1];
  block.resize(size);
  PetscCallMPI(MPI_Scatterv(root_values.data(), counts.data(), displs.data(), MPI_UINT64_T, block.data(), count,
                            MPI_UINT64_T, 0, comm));
  PetscFunctionReturn(0);
}

} // namespace signorini
