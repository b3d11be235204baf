// The saddle-point system [K -B^T; -B D] [du; lambda] = [f - F_int; g] in one parallel AIJ matrix with a fixed
// nonzero pattern, and its KSP (options prefix -contact_). B holds the contact normals of the active pairs
// (B = -C in the seed's notation, so that lambda >= 0 is a compressive force); an inactive pair has a zero row in B
// and a nonzero D entry, which gives lambda = 0 without changing the pattern. Knows nothing about geometry.
#pragma once

#include "signorini/core/handle.hpp"
#include "signorini/fem/dof_map.hpp"

#include <vector>

namespace signorini {

/// A constraint row: the global displacement rows it touches and their coefficients (free dofs only).
struct ConstraintRow {
  PetscInt ncols = 0;
  PetscInt cols[3] = {-1, -1, -1};
  double coef[3] = {0, 0, 0};
};

/// The default saddle-point solver (MUMPS LDL^T of the whole matrix, options prefix -contact_, iterative
/// tolerances rtol 1e-10); options given by the user override it at KSPSetFromOptions.
[[nodiscard]] PetscErrorCode SetDefaultSolver(KSP ksp);

class SaddlePointSystem {
public:
  /// Creates the matrix with the pattern of K (inserted by insert_k), the constraint rows and the multiplier diagonal,
  /// the vectors and the KSP. coords: dim values per owned vertex, in dof order (for the rigid-body near-null space
  /// of the "u" block). Collective.
  template <typename InsertK>
  [[nodiscard]] PetscErrorCode Create(const DofMap &dofs, const std::vector<ConstraintRow> &rows,
                                      const std::vector<double> &coords, InsertK insert_k);
  Mat A() const { return A_; }
  Vec Solution() const { return x_; }
  Vec Rhs() const { return b_; }
  KSP Ksp() const { return ksp_; }

  /// Writes the constraint rows: active rows get their coefficients (in both B and B^T) and D = 0, inactive rows
  /// zeros and D = inactive_diag. Ends with a final assembly of A. Collective.
  [[nodiscard]] PetscErrorCode SetConstraints(const std::vector<ConstraintRow> &rows, const std::vector<char> &active,
                                              double inactive_diag);
  /// Solves A x = b; a failed or inaccurate solve is an error naming the likely cause. Collective.
  [[nodiscard]] PetscErrorCode Solve(PetscInt &krylov_iterations);

private:
  [[nodiscard]] PetscErrorCode CreatePattern(const std::vector<ConstraintRow> &rows, Mat P) const;
  [[nodiscard]] PetscErrorCode SetupKsp(const std::vector<double> &coords);
  const DofMap *dofs_ = nullptr;
  MatH A_;
  VecH x_, b_, r_;
  KSPH ksp_;
  NullSpaceH near_null_;
  Mat mumps_factor_ = nullptr; ///< the MUMPS factor of a direct solve (owned by the PC), for the null-pivot check
};

template <typename InsertK>
PetscErrorCode SaddlePointSystem::Create(const DofMap &dofs, const std::vector<ConstraintRow> &rows,
                                         const std::vector<double> &coords, InsertK insert_k) {
  MPI_Comm comm = PetscObjectComm((PetscObject)dofs.IsU());
  PetscFunctionBeginUser;
  dofs_ = &dofs;
  MatH P;
  PetscCall(MatCreate(comm, P.out()));
  PetscCall(MatSetType(P, MATPREALLOCATOR));
  PetscCall(MatSetSizes(P, dofs.OwnedRows(), dofs.OwnedRows(), dofs.GlobalRows(), dofs.GlobalRows()));
  PetscCall(MatSetUp(P));
  PetscCall(insert_k(P.get()));
  PetscCall(CreatePattern(rows, P));
  PetscCall(MatCreate(comm, A_.out()));
  PetscCall(MatSetType(A_, MATAIJ));
  PetscCall(MatSetSizes(A_, dofs.OwnedRows(), dofs.OwnedRows(), dofs.GlobalRows(), dofs.GlobalRows()));
  // Without multipliers the matrix is K alone: blocked by node, so that AMG on the whole matrix sees the blocks.
  if (dofs.GlobalLambda() == 0) PetscCall(MatSetBlockSize(A_, dofs.Dim()));
  PetscCall(MatPreallocatorPreallocate(P, PETSC_TRUE, A_));
  PetscCall(MatSetOption(A_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatSetOption(A_, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(A_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscCall(PetscObjectSetName((PetscObject)A_.get(), "saddle_point"));
  PetscCall(MatCreateVecs(A_, x_.out(), b_.out()));
  PetscCall(VecDuplicate(b_, r_.out()));
  PetscCall(SetupKsp(coords));
  PetscFunctionReturn(0);
}

} // namespace signorini
