// Pattern, constraint rows, KSP set-up and solve of the saddle-point system.
#include "signorini/solver/saddle_point.hpp"

#include <cmath>

namespace signorini {

PetscErrorCode SaddlePointSystem::CreatePattern(const std::vector<ConstraintRow> &rows, Mat P) const {
  const PetscScalar zeros[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const PetscInt r = dofs_->LambdaRow((PetscInt)p);
    PetscCall(MatSetValues(P, 1, &r, rows[p].ncols, rows[p].cols, zeros, ADD_VALUES));
    PetscCall(MatSetValues(P, rows[p].ncols, rows[p].cols, 1, &r, zeros, ADD_VALUES));
    PetscCall(MatSetValue(P, r, r, 0.0, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SetDefaultSolver(KSP ksp) {
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPSetOptionsPrefix(ksp, "contact_"));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetTolerances(ksp, 1e-10, 1e-50, PETSC_DEFAULT, 2000));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetupKsp(const std::vector<double> &coords) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(comm, ksp_.out()));
  PetscCall(SetDefaultSolver(ksp_));
  PetscCall(KSPSetOperators(ksp_, A_, A_));
  PetscCall(KSPGetPC(ksp_, &pc));
  // Rigid-body modes of the displacement block, offered to fieldsplit's "u" solver as its near-null space.
  VecH xyz;
  const int dim = dofs_->Dim();
  PetscCall(VecCreateMPI(comm, dofs_->OwnedU(), PETSC_DECIDE, xyz.out()));
  PetscCall(VecSetBlockSize(xyz, dim));
  PetscScalar *a;
  PetscCall(VecGetArray(xyz, &a));
  for (PetscInt i = 0; i < dofs_->OwnedU(); ++i) a[i] = coords[i];
  PetscCall(VecRestoreArray(xyz, &a));
  PetscCall(MatNullSpaceCreateRigidBody(xyz, near_null_.out()));
  PetscCall(PetscObjectCompose((PetscObject)dofs_->IsU(), "nearnullspace", (PetscObject)near_null_.get()));
  if (dofs_->GlobalLambda() == 0) PetscCall(MatSetNearNullSpace(A_, near_null_));
  PetscCall(KSPSetFromOptions(ksp_));
  PetscBool fieldsplit;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (fieldsplit) {
    PetscCall(PCFieldSplitSetIS(pc, "u", dofs_->IsU()));
    PetscCall(PCFieldSplitSetIS(pc, "lambda", dofs_->IsLambda()));
  }
  // A direct MUMPS factorisation detects null pivots (ICNTL(24)): a body that nothing holds yet is then an error
  // instead of a solution with an arbitrary rigid motion.
  PetscBool factor;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  if (factor) {
    MatSolverType type;
    PetscCall(PCFactorGetMatSolverType(pc, &type));
    PetscBool mumps = PETSC_FALSE;
    if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
    if (mumps) {
      PetscCall(PCFactorSetUpMatSolverType(pc));
      PetscCall(PCFactorGetMatrix(pc, &mumps_factor_));
      PetscCall(MatMumpsSetIcntl(mumps_factor_, 24, 1));
      // A pivot below 1e-12 ||A|| is null: MUMPS's default (1e-5 eps ||A||) misses the rigid modes of 2D
      // elasticity; -contact_mat_mumps_cntl_3 overrides.
      PetscCall(MatMumpsSetCntl(mumps_factor_, 3, 1e-12));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetConstraints(const std::vector<ConstraintRow> &rows,
                                                 const std::vector<char> &active, double inactive_diag) {
  const PetscScalar zeros[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const PetscInt r = dofs_->LambdaRow((PetscInt)p);
    const PetscScalar *v = active[p] ? rows[p].coef : zeros;
    PetscCall(MatSetValues(A_, 1, &r, rows[p].ncols, rows[p].cols, v, INSERT_VALUES));
    PetscCall(MatSetValues(A_, rows[p].ncols, rows[p].cols, 1, &r, v, INSERT_VALUES));
    PetscCall(MatSetValue(A_, r, r, active[p] ? 0.0 : inactive_diag, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Solve(PetscInt &krylov_iterations) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  KSPConvergedReason reason;
  PetscReal bnorm, rnorm;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(x_));
  PetscCall(KSPSolve(ksp_, b_, x_));
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PetscCall(KSPGetIterationNumber(ksp_, &krylov_iterations));
  if (mumps_factor_) {
    PetscInt null_pivots = 0;
    PetscCall(MatMumpsGetInfog(mumps_factor_, 28, &null_pivots));
    PetscCheck(null_pivots == 0, comm, PETSC_ERR_NOT_CONVERGED,
               "the saddle-point system is singular (MUMPS found %" PetscInt_FMT " null pivot(s)): the body is not "
               "held; add Dirichlet conditions (e.g. on a symmetry line) so that the initial contact and the supports "
               "remove every rigid-body motion", null_pivots);
  }
  PetscCheck(reason >= 0, comm, PETSC_ERR_NOT_CONVERGED,
             "the saddle-point solve failed (%s): the system is singular or the solver unsuitable; is the body held "
             "(Dirichlet conditions or enough active contact) and do the -contact_ solver options fit?",
             KSPConvergedReasons[reason]);
  // A factorisation of a singular matrix can "succeed" with garbage: check the residual.
  PetscCall(MatMult(A_, x_, r_));
  PetscCall(VecAYPX(r_, -1.0, b_));
  PetscCall(VecNorm(r_, NORM_2, &rnorm));
  PetscCall(VecNorm(b_, NORM_2, &bnorm));
  PetscBool finite = (PetscBool)std::isfinite(rnorm);
  PetscCheck(finite && rnorm <= 1e-6 * bnorm + 1e-300, comm, PETSC_ERR_NOT_CONVERGED,
             "the saddle-point system is singular (relative residual %g after the solve): the body is not held; add "
             "Dirichlet conditions or check that the obstacle touches it", finite ? (double)(rnorm / bnorm) : -1.0);
  PetscFunctionReturn(0);
}

} // namespace signorini
