// An HDF5 file written by every rank together through MPI-IO: each rank writes one contiguous slab of rows of each
// dataset (its block of the file's order), so that no rank holds a whole table.
#pragma once

#include <petscsys.h>

#include <cstdint>
#include <string>
#include <vector>

namespace signorini {

/// Every call is collective on the communicator given to Open. After an HDF5 failure on any rank, Ok() is false on
/// every rank and the later calls do nothing, so that the caller raises one error naming the file (Path()).
class Hdf5File {
public:
  Hdf5File() = default;
  Hdf5File(const Hdf5File &) = delete;
  Hdf5File &operator=(const Hdf5File &) = delete;
  /// Closes the file if Close was not called (on an error path, which every rank takes together).
  ~Hdf5File();

  /// Creates (truncating) or opens for writing the file at path.
  [[nodiscard]] PetscErrorCode Open(MPI_Comm comm, const std::string &path, bool create);
  /// Creates the group at an absolute path ("/mesh").
  [[nodiscard]] PetscErrorCode CreateGroup(const std::string &path);
  /// Creates the dataset at an absolute path, of rows x cols values (one dimension when cols is 1), and writes this
  /// rank's rows (rows.size() / cols of them) from row first on. T: double or long long.
  template <typename T>
  [[nodiscard]] PetscErrorCode WriteRows(const std::string &path, std::int64_t rows, int cols, std::int64_t first,
                                         const std::vector<T> &data);
  /// Closes the file (its last failure shows in Ok()).
  [[nodiscard]] PetscErrorCode Close();
  bool Ok() const { return ok_; }
  const std::string &Path() const { return path_; }
  /// Whether the first failure happened on this rank, and HDF5's most specific description of it.
  bool FailedHere() const { return failed_here_; }
  const std::string &Reason() const { return reason_; }

private:
  /// Turns a local success into one shared by every rank; a local failure keeps reason, or HDF5's innermost error.
  [[nodiscard]] PetscErrorCode Agree(bool local_ok, const std::string &reason = "");
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::string path_, reason_;
  std::int64_t file_ = -1;
  bool ok_ = true, failed_here_ = false;
};

} // namespace signorini
