// Error handler and collective error checks.
#include "signorini/core/errors.hpp"

#include <cstdio>
#include <cstring>
#include <vector>

namespace signorini {

namespace {

PetscErrorCode Handler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n,
                       PetscErrorType p, const char *mess, void *) {
  if (p != PETSC_ERROR_INITIAL) return n;
  int world_size = 1, comm_size = 1, rank = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &world_size);
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &comm_size);
  if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
  const bool collective = comm_size == world_size;
  const char *text = mess ? mess : "";
  const bool user = n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_READ ||
                    n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FILE_UNEXPECTED || n == PETSC_ERR_ARG_OUTOFRANGE ||
                    n == PETSC_ERR_NOT_CONVERGED || n == PETSC_ERR_CONV_FAILED || n == PETSC_ERR_ARG_WRONG;
  if (!collective || rank == 0) {
    if (n == PETSC_ERR_MEM)
      std::fprintf(stderr, "signorini: error: out of memory (%s)\n", text);
    else if (user)
      std::fprintf(stderr, "signorini: error: %s\n", text);
    else
      std::fprintf(stderr, "signorini: error: %s [PETSc error %d in %s() at %s:%d]\n", text, (int)n, func, file, line);
    std::fflush(stderr);
  }
  if (!collective && world_size > 1) MPI_Abort(PETSC_COMM_WORLD, 1);
  return n;
}

} // namespace

PetscErrorCode InstallErrorHandler() {
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(Handler, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckCollective(MPI_Comm comm, bool ok, const std::string &message) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscMPIInt mine = ok ? size : rank, first;
  PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm));
  if (first == size) PetscFunctionReturn(0);
  int len = rank == first ? (int)message.size() : 0;
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, first, comm));
  std::vector<char> buf(len + 1, '\0');
  if (rank == first) std::memcpy(buf.data(), message.data(), len);
  PetscCallMPI(MPI_Bcast(buf.data(), len, MPI_CHAR, first, comm));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", buf.data());
}

PetscErrorCode RaiseFromRoot(MPI_Comm comm, const std::string &message_on_root) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int len = rank == 0 ? (int)message_on_root.size() : 0;
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  if (len == 0) PetscFunctionReturn(0);
  std::vector<char> buf(len + 1, '\0');
  if (rank == 0) std::memcpy(buf.data(), message_on_root.data(), len);
  PetscCallMPI(MPI_Bcast(buf.data(), len, MPI_CHAR, 0, comm));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", buf.data());
}

} // namespace signorini
