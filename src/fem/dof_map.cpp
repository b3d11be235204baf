// Numbering of the saddle-point unknowns.
#include "signorini/fem/dof_map.hpp"

#include <algorithm>

namespace signorini {

PetscErrorCode DofMap::Create(const Mesh &mesh, PetscInt num_owned_multipliers) {
  MPI_Comm comm = mesh.Comm();
  PetscFunctionBeginUser;
  dim_ = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  PetscInt owned = 0;
  for (PetscInt v = 0; v < nv; ++v) owned += mesh.Owned(v);
  nu_ = dim_ * owned;
  nl_ = num_owned_multipliers;
  const PetscInt local = nu_ + nl_;
  PetscCallMPI(MPI_Scan(&local, &row_start_, 1, MPIU_INT, MPI_SUM, comm));
  row_start_ -= local;
  PetscCallMPI(MPI_Allreduce(&local, &n_global_, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(&nu_, &nu_global_, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Scan(&nl_, &lambda_start_, 1, MPIU_INT, MPI_SUM, comm));
  lambda_start_ -= nl_;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  row_starts_.assign(size + 1, n_global_);
  u_starts_.assign(size + 1, nu_global_);
  const PetscInt u_start = row_start_ - lambda_start_;
  PetscCallMPI(MPI_Allgather(&row_start_, 1, MPIU_INT, row_starts_.data(), 1, MPIU_INT, comm));
  PetscCallMPI(MPI_Allgather(&u_start, 1, MPIU_INT, u_starts_.data(), 1, MPIU_INT, comm));

  // Owners number their vertices; the vertex SF carries the numbers to the ghosts.
  std::vector<PetscInt> root(nv, -1), leaf(nv, -1);
  PetscInt next = row_start_;
  for (PetscInt v = 0; v < nv; ++v)
    if (mesh.Owned(v)) root[v] = next, next += dim_;
  PetscCall(PetscSFBcastBegin(mesh.VertexSF(), MPIU_INT, root.data(), leaf.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(mesh.VertexSF(), MPIU_INT, root.data(), leaf.data(), MPI_REPLACE));
  vertex_row_.resize(nv);
  vertex_urow_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v) {
    vertex_row_[v] = mesh.Owned(v) ? root[v] : leaf[v];
    PetscCheck(vertex_row_[v] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "vertex %" PetscInt_FMT " has no dof number", v);
    vertex_urow_[v] = UBlockRow(vertex_row_[v]);
  }
  PetscCall(ISCreateStride(comm, nu_, row_start_, 1, is_u_.out()));
  PetscCall(ISSetBlockSize(is_u_, dim_));
  PetscCall(ISCreateStride(comm, nl_, row_start_ + nu_, 1, is_lambda_.out()));
  PetscCall(PetscObjectSetName((PetscObject)is_u_.get(), "u"));
  PetscCall(PetscObjectSetName((PetscObject)is_lambda_.get(), "lambda"));
  PetscFunctionReturn(0);
}

PetscInt DofMap::UBlockRow(PetscInt row) const {
  // The owner: the last rank whose first row is at most row (ranks without rows share their first row).
  const std::size_t r = std::upper_bound(row_starts_.begin(), row_starts_.end() - 1, row) - row_starts_.begin() - 1;
  return row - row_starts_[r] + u_starts_[r];
}

} // namespace signorini
