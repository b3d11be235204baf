// Rows moved between their ranks and contiguous blocks of the file's order, through a PetscSF.
#include "signorini/io/file_rows.hpp"

#include "signorini/core/blocks.hpp"

#include <algorithm>

namespace signorini {

namespace {

template <typename T> MPI_Datatype MpiType();
template <> MPI_Datatype MpiType<double>() {
  return MPI_DOUBLE;
}
template <> MPI_Datatype MpiType<long long>() {
  return MPI_LONG_LONG;
}

/// A contiguous MPI datatype of ncomp values of T, freed when it goes out of scope.
template <typename T> class RowType {
public:
  [[nodiscard]] PetscErrorCode Create(int ncomp) {
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Type_contiguous(ncomp, MpiType<T>(), &type_));
    PetscCallMPI(MPI_Type_commit(&type_));
    PetscFunctionReturn(0);
  }
  RowType() = default;
  RowType(const RowType &) = delete;
  RowType &operator=(const RowType &) = delete;
  ~RowType() {
    if (type_ != MPI_DATATYPE_NULL) (void)MPI_Type_free(&type_);
  }
  operator MPI_Datatype() const { return type_; }

private:
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

} // namespace

PetscErrorCode FileRows::Create(MPI_Comm comm, PetscInt n, const std::vector<PetscInt> &local,
                                const std::vector<PetscInt> &file) {
  PetscLayout layout;
  PetscFunctionBeginUser;
  n_ = n;
  PetscCall(BlockOf(comm, n, start_, size_));
  PetscCall(PetscLayoutCreate(comm, &layout));
  PetscCall(PetscLayoutSetLocalSize(layout, size_));
  PetscCall(PetscLayoutSetSize(layout, n));
  PetscCall(PetscLayoutSetUp(layout));
  PetscCall(PetscSFCreate(comm, sf_.out()));
  const PetscInt nrows = (PetscInt)file.size();
  leaf_extent_ = local.empty() ? nrows : (nrows ? *std::max_element(local.begin(), local.end()) + 1 : 0);
  PetscCall(PetscSFSetGraphLayout(sf_, layout, nrows, local.empty() ? nullptr : const_cast<PetscInt *>(local.data()),
                                  PETSC_COPY_VALUES, file.data()));
  PetscCall(PetscLayoutDestroy(&layout));
  PetscCall(PetscSFSetUp(sf_));
  PetscFunctionReturn(0);
}

template <typename T>
PetscErrorCode FileRows::ToBlocks(const std::vector<T> &values, int ncomp, std::vector<T> &block) const {
  RowType<T> row;
  PetscFunctionBeginUser;
  PetscAssert((PetscInt)values.size() >= leaf_extent_ * ncomp, PETSC_COMM_SELF, PETSC_ERR_PLIB, "rows missing");
  PetscCall(row.Create(ncomp));
  block.assign(size_ * ncomp, T());
  PetscCall(PetscSFReduceBegin(sf_, row, values.data(), block.data(), MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(sf_, row, values.data(), block.data(), MPI_REPLACE));
  PetscFunctionReturn(0);
}

template <typename T>
PetscErrorCode FileRows::FromBlocks(const std::vector<T> &block, int ncomp, std::vector<T> &values) const {
  RowType<T> row;
  PetscFunctionBeginUser;
  PetscCall(row.Create(ncomp));
  if ((PetscInt)values.size() < leaf_extent_ * ncomp) values.resize(leaf_extent_ * ncomp);
  PetscCall(PetscSFBcastBegin(sf_, row, block.data(), values.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf_, row, block.data(), values.data(), MPI_REPLACE));
  PetscFunctionReturn(0);
}

template PetscErrorCode FileRows::ToBlocks(const std::vector<double> &, int, std::vector<double> &) const;
template PetscErrorCode FileRows::ToBlocks(const std::vector<long long> &, int, std::vector<long long> &) const;
template PetscErrorCode FileRows::FromBlocks(const std::vector<double> &, int, std::vector<double> &) const;
template PetscErrorCode FileRows::FromBlocks(const std::vector<long long> &, int, std::vector<long long> &) const;

} // namespace signorini
