// A text file of the ranks' pieces in rank order, written with MPI-IO at exclusive-scan offsets.
#include "signorini/io/ordered_text.hpp"

#include "signorini/core/errors.hpp"

#include <algorithm>
#include <cstdint>

namespace signorini {

/// The most bytes one MPI-IO call writes (its count is an int).
constexpr std::int64_t WRITE_CHUNK = std::int64_t(1) << 30;

PetscErrorCode WriteInRankOrder(MPI_Comm comm, const std::string &path, const std::string &text) {
  PetscFunctionBeginUser;
  const std::string error = "cannot write '" + path + "'";
  std::int64_t length = (std::int64_t)text.size(), offset = 0, total = 0, rounds = 0;
  PetscCallMPI(MPI_Exscan(&length, &offset, 1, MPI_INT64_T, MPI_SUM, comm));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) offset = 0; // MPI_Exscan leaves rank 0's result undefined
  PetscCallMPI(MPI_Allreduce(&length, &total, 1, MPI_INT64_T, MPI_SUM, comm));
  const std::int64_t own_rounds = (length + WRITE_CHUNK - 1) / WRITE_CHUNK;
  PetscCallMPI(MPI_Allreduce(&own_rounds, &rounds, 1, MPI_INT64_T, MPI_MAX, comm));
  // File errors return (MPI_ERRORS_RETURN is the default handler of files): each is agreed on before the next
  // collective call.
  MPI_File file;
  const int opened =
      MPI_File_open(comm, path.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file) == MPI_SUCCESS;
  PetscCall(CheckCollective(comm, opened, error));
  bool ok = MPI_File_set_size(file, total) == MPI_SUCCESS;
  for (std::int64_t r = 0; r < rounds; ++r) {
    const std::int64_t from = std::min(r * WRITE_CHUNK, length), n = std::min(WRITE_CHUNK, length - from);
    MPI_Status status;
    ok = MPI_File_write_at_all(file, offset + from, text.data() + from, (int)n, MPI_CHAR, &status) == MPI_SUCCESS && ok;
  }
  ok = MPI_File_close(&file) == MPI_SUCCESS && ok;
  PetscCall(CheckCollective(comm, ok, error));
  PetscFunctionReturn(0);
}

} // namespace signorini
