// The saddle-point system's kept factorisation: MUMPS with the Schur complement on the multipliers (factor, refactor,
// solves through the Schur complement, condensed solves in the multiplier space and their expansion).
#include "signorini/linalg/saddle_point.hpp"

#include "signorini/core/progress.hpp"
#include "signorini/linalg/pc_kept.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace signorini {

PetscErrorCode SaddlePointSystem::Factor() {
  PetscFunctionBeginUser;
  if (factored_) PetscFunctionReturn(0);
  std::vector<PetscScalar> d;
  PetscCall(MultiplierDiagonal(d));
  ProgressBegin("analysis and factorisation (the Schur complement on the candidates)");
  FactorChoices how;
  how.symmetric = !lu_ || turned_; // friction's fixed matrix is symmetric
  how.ordering = kept_.ordering;
  how.controls = mumps_controls_;
  how.keep_values = !constant_k_;
  // Friction's kept factorisation is never declined: its alternative, MUMPS LU of the plain form refactored at every
  // change, stopped with INFOG(1) = -9 (workspace) at the second factorisation of a one-layer strip with 804
  // multipliers (meshes/strip.geo, -contact_friction 0.3: delayed pivots), where the dense LU costs 5 ms per change.
  how.may_decline = !kept_.forced && !turned_;
  how.solver = kept_.solver;
  how.confirm = confirm_direct_;
  if (turned_) PetscCall(FactorFixedRows(how));
  else PetscCall(mumps_schur_.Factor(A_, {schur_rows_, d, dofs_->OwnedU(), dofs_->Dim(), kept_.coords}, how));
  ProgressEnd();
  if (!mumps_schur_.Rejected().empty()) {
    // The automatic choice leaves the direct path: the caller solves again on the iterative one.
    direct_rejected_ = mumps_schur_.Rejected();
    PetscFunctionReturn(0);
  }
  if (mumps_schur_.Declined()) {
    // The dense Schur complement would cost more than it saves (many candidates on a body that factors cheaply, such
    // as a thin plate): the KSP's MUMPS factorises the matrix, which stays in the augmented form, at every change.
    // PETSc's interface takes no given pivot order, so an ordering the user asked for is said not to apply.
    reuse_ = turned_ = false;
    PetscCheck(mumps_controls_.Icntl(7, 7) != 1, PetscObjectComm((PetscObject)A_.get()), PETSC_ERR_USER_INPUT,
               "-contact_mat_mumps_icntl_7 1 (the given nested dissection) does not apply: the kept factorisation "
               "declined its dense Schur complement on the %" PetscInt_FMT " candidates, and PETSc's MUMPS, which "
               "refactorises instead, takes no given ordering; expected -contact_mat_mumps_icntl_7 0, 2, 4, 6 or 7",
               dofs_->GlobalLambda());
    if (!kept_.ordering_given.empty())
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)A_.get()),
                            "Note: %s does not apply: the kept factorisation declined its dense Schur complement on "
                            "the %" PetscInt_FMT " candidates (it would cost more than a refactorisation per "
                            "active-set change), and PETSc's MUMPS, which refactorises instead, orders by its own "
                            "choice (-contact_mat_mumps_icntl_7); -contact_reuse_factorization keeps the Schur "
                            "complement and the ordering\n",
                            kept_.ordering_given.c_str(), dofs_->GlobalLambda()));
    if (kept_.solver_set)
      PetscCall(PetscPrintf(PetscObjectComm((PetscObject)A_.get()),
                            "Note: -contact_kept_solver %s does not apply: the kept factorisation declined its dense "
                            "Schur complement on the %" PetscInt_FMT " candidates (it would cost more than a "
                            "refactorisation per active-set change), and PETSc's MUMPS refactorises instead; "
                            "-contact_reuse_factorization keeps the Schur complement\n",
                            KEPT_SOLVER_NAMES[(int)kept_.solver], dofs_->GlobalLambda()));
    PetscFunctionReturn(0);
  }
  null_pivots_ = mumps_schur_.NullPivots();
  factored_ = null_pivots_ == 0;
  PetscCall(UseKeptPc());
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::FactorFixedRows(const FactorChoices &how) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  const std::vector<SparseRow> &fixed = kept_rows_.Fixed();
  const double w = aug_;
  PetscFunctionBeginUser;
  PetscCheck(!nest_.on && (PetscInt)fixed.size() == dofs_->OwnedLambda(), comm, PETSC_ERR_ORDER,
             "friction's kept factorisation needs the fixed rows of every multiplier row (SetRowGroups)");
  // [K + w B^T B, B^T; B, 1/w] on A's pattern (B: the fixed rows; A holds K and the current rows, whose columns are
  // the fixed rows'): symmetric whatever the sets, and regular where the candidates hold the body, as the augmented
  // matrix of frictionless contact.
  MatH fixed_matrix;
  PetscCall(MatDuplicate(A_, MAT_COPY_VALUES, fixed_matrix.out()));
  for (std::size_t p = 0; p < fixed.size(); ++p) {
    const SparseRow &row = fixed[p];
    const PetscInt r = dofs_->LambdaRow((PetscInt)p);
    PetscCall(MatSetValues(fixed_matrix, 1, &r, row.ncols, row.cols.data(), row.coef.data(), INSERT_VALUES));
    PetscCall(MatSetValues(fixed_matrix, row.ncols, row.cols.data(), 1, &r, row.coef.data(), INSERT_VALUES));
    PetscCall(MatSetValue(fixed_matrix, r, r, 1.0 / w, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(fixed_matrix, MAT_FLUSH_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fixed_matrix, MAT_FLUSH_ASSEMBLY));
  for (const SparseRow &row : fixed) {
    std::vector<PetscScalar> v(row.ncols * row.ncols);
    for (PetscInt i = 0; i < row.ncols; ++i)
      for (PetscInt j = 0; j < row.ncols; ++j) v[i * row.ncols + j] = w * row.coef[i] * row.coef[j];
    PetscCall(MatSetValues(fixed_matrix, row.ncols, row.cols.data(), row.ncols, row.cols.data(), v.data(),
                           ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(fixed_matrix, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(fixed_matrix, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(fixed_matrix, MAT_SYMMETRIC, PETSC_TRUE));
  std::vector<PetscScalar> d0;
  PetscCall(ToRoot(std::vector<double>(fixed.size(), 1.0 / w), d0));
  PetscCall(mumps_schur_.Factor(fixed_matrix, {schur_rows_, d0, dofs_->OwnedU(), dofs_->Dim(), kept_.coords}, how));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::UseFixedRowBlock() {
  PC pc;
  PetscFunctionBeginUser;
  // X's diagonal to rank 0 in the Schur order, and its entries off the diagonal by the global rows of both ends
  // (each sent from its row's owner, at most MAX_ROW_COUPLINGS per row: a pair's other rows).
  std::vector<PetscScalar> d;
  PetscCall(ToRoot(kept_rows_.Diagonal(), d));
  const PetscInt nl = dofs_->OwnedLambda();
  std::vector<std::vector<double>> col(MAX_ROW_COUPLINGS, std::vector<double>(nl, -1.0)),
      val(MAX_ROW_COUPLINGS, std::vector<double>(nl, 0.0));
  std::vector<int> used(nl, 0);
  for (const auto &[i, j, v] : kept_rows_.Couplings()) {
    PetscCheck(used[i] < MAX_ROW_COUPLINGS, PETSC_COMM_SELF, PETSC_ERR_PLIB, "more than %d couplings of row %d",
               MAX_ROW_COUPLINGS, (int)i);
    col[used[i]][i] = (double)dofs_->LambdaRow(j), val[used[i]][i] = v;
    used[i]++;
  }
  std::vector<MumpsSchur::Coupling> off;
  for (int k = 0; k < MAX_ROW_COUPLINGS; ++k) {
    std::vector<PetscScalar> col_root, val_root;
    PetscCall(ToRoot(col[k], col_root));
    PetscCall(ToRoot(val[k], val_root));
    for (std::size_t i = 0; i < col_root.size(); ++i) {
      if (col_root[i] < 0) continue;
      const PetscInt g = (PetscInt)col_root[i];
      const auto it = std::lower_bound(schur_rows_.begin(), schur_rows_.end(), g);
      PetscCheck(it != schur_rows_.end() && *it == g, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "a coupling to row %" PetscInt_FMT ", not a multiplier row", g);
      off.push_back({(PetscInt)i, (PetscInt)(it - schur_rows_.begin()), val_root[i]});
    }
  }
  mumps_schur_.SetCoupling(std::move(off));
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PCKeptSetDiagonal(pc, d));
  PetscCall(PCKeptSetRows(pc, &kept_rows_, dofs_->OwnedU()));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Refactor() {
  std::vector<PetscScalar> d;
  PetscFunctionBeginUser;
  PetscCall(MultiplierDiagonal(d));
  ProgressBegin("numerical refactorisation (the Schur complement on the candidates)");
  PetscCall(mumps_schur_.Refactor(A_, d));
  ProgressEnd();
  direct_rejected_ = mumps_schur_.Rejected();
  null_pivots_ = mumps_schur_.NullPivots();
  PetscFunctionReturn(0);
}

std::string SaddlePointSystem::SingularReport(const std::string &cause) const {
  char found[160];
  if (unheld_)
    std::snprintf(found, sizeof(found), "the supports and every candidate pair together leave a rigid-body motion "
                  "free, so its displacement block is singular for every active set");
  else if (null_pivots_ == 0 && singular_residual_ > 0)
    std::snprintf(found, sizeof(found), "%s found no null pivot, but its solve left a relative residual of %.6g",
                  mumps_schur_.UsesCholesky() ? "the Cholesky factorisation" : "MUMPS", singular_residual_);
  else std::snprintf(found, sizeof(found), "MUMPS found %d null pivot(s)", (int)null_pivots_);
  std::string report = std::string("the saddle-point system is singular (") + found + "): ";
  const std::string controls = mumps_controls_.PivotControls();
  if (!controls.empty())
    report += "the MUMPS controls " + controls + " may count regular pivots as null (expected them unset), or ";
  return report + cause;
}

PetscErrorCode SaddlePointSystem::UseKeptPc() {
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PCKeptRegister());
  PetscCall(PCSetType(pc, PCKEPT));
  PetscCall(PCKeptSetFactorization(pc, &mumps_schur_, "the saddle-point matrix (augmented form)"));
  PetscCall(KSPSetUp(ksp_));
  mumps_factor_ = nullptr; // PETSc's MUMPS factor went with its PC
  kept_viewed_ = false;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::KeptFactorization(MumpsSchur *&kept) const {
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PCKeptGetFactorization(pc, &kept));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveWithKeptFactor(const std::vector<PetscScalar> &d, double rtol,
                                                      PetscInt &iterations, double &check_tol) {
  PetscFunctionBeginUser;
  iterations = 0;
  check_tol = ACCEPTED_RESIDUAL;
  if (kept_.max_it > 0 && !refactor_next_) {
    KSPConvergedReason reason;
    PetscReal default_rtol, abstol, dtol;
    PetscInt max_it;
    PetscCall(KSPGetTolerances(ksp_, &default_rtol, &abstol, &dtol, &max_it));
    PetscCall(KSPSetTolerances(ksp_kept_, rtol > 0 ? rtol : default_rtol, abstol, PETSC_DEFAULT, kept_.max_it));
    PC kept;
    PetscCall(KSPGetPC(ksp_kept_, &kept));
    PetscCall(PCKeptSetDiagonal(kept, d));
    PetscCall(KSPSolve(ksp_kept_, b_, x_));
    PetscCall(KSPGetConvergedReason(ksp_kept_, &reason));
    PetscCall(KSPGetIterationNumber(ksp_kept_, &iterations));
    // The mean contraction per iteration tells how far the factored tangent has drifted from the current one: worse
    // than KEPT_CONTRACTION, the next solve refactors.
    const PetscReal *history;
    PetscInt n;
    PetscCall(KSPGetResidualHistory(ksp_kept_, &history, &n));
    const double rate = n > 1 && history[0] > 0 ? std::pow(history[n - 1] / history[0], 1.0 / (n - 1)) : 0.0;
    refactor_next_ = rate > KEPT_CONTRACTION;
    PetscCall(PetscInfo(nullptr,
                        "FGMRES with the kept factorisation: %" PetscInt_FMT " iteration(s), contraction %.6g per "
                        "iteration%s\n", iterations, rate, refactor_next_ ? ": the next solve refactors" : ""));
    if (reason > 0) {
      check_tol = std::max(check_tol, 2.0 * rtol); // an inexact step (rtol > 0) is as inexact as asked
      PetscFunctionReturn(0);
    }
    PetscCall(PetscInfo(nullptr, "FGMRES with the kept factorisation: %s after %" PetscInt_FMT
                        " iterations; refactoring\n", KSPConvergedReasons[reason], iterations));
  }
  // The tangent has drifted too far from the factored one (or -contact_reuse_max_it 0): factor the current one.
  PetscCall(Refactor());
  // Singular, or out of memory on the automatic path: the caller reports it (Solve).
  if (FactorStopped()) PetscFunctionReturn(0);
  PetscCall(mumps_schur_.Solve(d, b_, x_));
  refactor_next_ = false;
  ++iterations;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Condense(bool &singular) {
  PetscFunctionBeginUser;
  PetscCheck(reuse_ && !released_, PetscObjectComm((PetscObject)A_.get()), PETSC_ERR_ORDER,
             "a condensation needs the kept factorisation");
  PetscCall(Factor());
  singular = FactorStopped();
  // Declined: the caller solves in full (ExactFactorization() is false now).
  if (!reuse_ || singular) PetscFunctionReturn(0);
  MumpsSchur *kept;
  PetscCall(KeptFactorization(kept));
  PetscCall(kept->Condense(b_));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveCondensed(const std::vector<double> &bm, std::vector<double> &lambda,
                                                 std::vector<double> &shift, double &residual) {
  const PetscInt nl = dofs_->OwnedLambda();
  PetscFunctionBeginUser;
  PetscCheck(reuse_ && factored_ && stab_ == 0, PetscObjectComm((PetscObject)A_.get()), PETSC_ERR_ORDER,
             "a condensed solve needs the kept factorisation and no stabilisation");
  std::vector<PetscScalar> d, y;
  std::vector<double> x;
  PetscCall(MultiplierDiagonal(d));
  // b_m to rank 0, the dense solve there, x_m back.
  PetscCall(ToRoot(bm, y));
  MumpsSchur *kept;
  PetscCall(KeptFactorization(kept));
  PetscCall(kept->SolveReduced(d, y, residual));
  PetscCall(FromRoot(y, x));
  // Row p: -B_p du + D_p x_p = b_p, so B_p du = D_p x_p - b_p; an active row's multiplier is x_p + r b_p.
  lambda.assign(nl, 0.0);
  shift.assign(nl, 0.0);
  for (PetscInt p = 0; p < nl; ++p) {
    const double dp = active_[p] ? 0.0 : InactiveDiagonal(0.0, aug_inactive_);
    shift[p] = dp * x[p] - bm[p];
    lambda[p] = active_[p] ? x[p] + aug_ * bm[p] : 0.0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Expand(double &residual) {
  PetscFunctionBeginUser;
  PetscCheck(reuse_ && factored_ && stab_ == 0, PetscObjectComm((PetscObject)A_.get()), PETSC_ERR_ORDER,
             "an expansion needs the kept factorisation and no stabilisation");
  MumpsSchur *kept;
  PetscCall(KeptFactorization(kept));
  PetscCall(kept->Expand(x_));
  // A changing K (svk): the factored matrix is an earlier tangent, so the residual against the current matrix
  // measures the modified Newton step, not the solve; the factorisation's null-pivot check and the Newton iteration
  // judge it (only a non-finite result is an error here).
  PetscCall(CheckAndConvert(KSP_CONVERGED_ITS, 1, residual, constant_k_ ? ACCEPTED_RESIDUAL : INFINITY));
  PetscFunctionReturn(0);
}

} // namespace signorini
