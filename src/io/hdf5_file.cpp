// An HDF5 file written collectively through MPI-IO, each rank one slab of rows per dataset.
#include "signorini/io/hdf5_file.hpp"

#include <hdf5.h>

#include <string>
#include <type_traits>

#ifndef H5_HAVE_PARALLEL
#error "signorini writes its HDF5 output in parallel: it needs HDF5 built with MPI (libhdf5-openmpi-dev)"
#endif

namespace signorini {

namespace {

/// Closes an HDF5 identifier when it goes out of scope; ok() says whether it was created.
class Id {
public:
  Id(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Id(const Id &) = delete;
  Id &operator=(const Id &) = delete;
  ~Id() {
    if (id_ >= 0) (void)close_(id_);
  }
  operator hid_t() const { return id_; }
  bool ok() const { return id_ >= 0; }

private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

} // namespace

Hdf5File::~Hdf5File() {
  if (file_ >= 0) (void)H5Fclose(file_);
}

/// The most specific description on HDF5's error stack (its innermost entry), or empty.
std::string InnermostError() {
  std::string reason;
  const auto visit = [](unsigned n, const H5E_error2_t *e, void *data) -> herr_t {
    if (n == 0 && e->desc) *static_cast<std::string *>(data) = e->desc;
    return 0;
  };
  (void)H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &reason);
  (void)H5Eclear2(H5E_DEFAULT);
  return reason;
}

PetscErrorCode Hdf5File::Agree(bool local_ok, const std::string &reason) {
  PetscFunctionBeginUser;
  if (!local_ok && ok_) failed_here_ = true, reason_ = reason.empty() ? InnermostError() : reason;
  ok_ = ok_ && local_ok;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok_, 1, MPI_C_BOOL, MPI_LAND, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode Hdf5File::Open(MPI_Comm comm, const std::string &path, bool create) {
  PetscFunctionBeginUser;
  comm_ = comm;
  path_ = path;
  // Failures become one message (OutputWriter, with Reason()), not HDF5's own printed error stack.
  (void)H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  bool ok = fapl.ok() && H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL) >= 0;
  if (ok)
    file_ =
        create ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl);
  PetscCall(Agree(ok && file_ >= 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Hdf5File::CreateGroup(const std::string &path) {
  PetscFunctionBeginUser;
  if (!ok_) PetscFunctionReturn(0);
  Id group(H5Gcreate2(file_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  PetscCall(Agree(group.ok()));
  PetscFunctionReturn(0);
}

template <typename T>
PetscErrorCode Hdf5File::WriteRows(const std::string &path, std::int64_t rows, int cols, std::int64_t first,
                                   const std::vector<T> &data) {
  static_assert(std::is_same<T, double>::value || std::is_same<T, long long>::value, "double or long long");
  PetscFunctionBeginUser;
  if (!ok_) PetscFunctionReturn(0);
  const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
  const int rank = cols == 1 ? 1 : 2;
  const hsize_t dims[2] = {(hsize_t)rows, (hsize_t)cols}, start[2] = {(hsize_t)first, 0},
                count[2] = {(hsize_t)(data.size() / cols), (hsize_t)cols};
  const hsize_t n = data.size();
  Id space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Id set(space.ok() ? H5Dcreate2(file_, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1,
         H5Dclose);
  // Every HDF5 call clears its error stack as it starts: the reason of a failed creation is taken now.
  const std::string failed_create = set.ok() ? "" : InnermostError();
  Id memory(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Id transfer(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  bool ok = set.ok() && memory.ok() && transfer.ok() && H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE) >= 0;
  // A rank without rows still takes part in the collective write, with empty selections.
  if (ok && n > 0) ok = H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr) >= 0;
  if (ok && n == 0) ok = H5Sselect_none(space) >= 0 && H5Sselect_none(memory) >= 0;
  PetscCall(Agree(ok, failed_create)); // no rank enters the collective write that another one skips
  if (!ok_) PetscFunctionReturn(0);
  const T none{};
  PetscCall(Agree(H5Dwrite(set, type, memory, space, transfer, n > 0 ? data.data() : &none) >= 0));
  PetscFunctionReturn(0);
}

template PetscErrorCode Hdf5File::WriteRows(const std::string &, std::int64_t, int, std::int64_t,
                                            const std::vector<double> &);
template PetscErrorCode Hdf5File::WriteRows(const std::string &, std::int64_t, int, std::int64_t,
                                            const std::vector<long long> &);

PetscErrorCode Hdf5File::Close() {
  PetscFunctionBeginUser;
  bool ok = true;
  if (file_ >= 0) ok = H5Fclose(file_) >= 0;
  file_ = -1;
  PetscCall(Agree(ok));
  PetscFunctionReturn(0);
}

} // namespace signorini
