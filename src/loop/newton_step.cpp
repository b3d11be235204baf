// The contact solver per Newton iteration (for the linear material, per solve): the residual, the assembly of the
// saddle-point system, the solve (full or condensed in the multiplier space) and the update with its step length.
#include "signorini/loop/contact_solver.hpp"

#include "contact_solver_detail.hpp"
#include "signorini/core/progress.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace signorini {

using namespace detail;

PetscErrorCode ContactSolver::Residual(const std::vector<double> &lambda, double &norm, double &scale,
                                       const PetscScalar *direction, double *dot, double *roundoff, bool product) {
  const int dim = mesh_.Dim();
  double min_J;
  PetscFunctionBeginUser;
  // F_int is assembled again only when the displacement changed since the last assembly (svk: the step length check
  // of UpdateSolution evaluates the residual at the new iterate, which the next iteration starts from).
  bool same = fint_at_.u == u_local_ && (fint_at_.exact || product);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_CXX_BOOL, MPI_LAND, mesh_.Comm()));
  if (same) {
    min_J = fint_at_.min_J;
  } else {
    // F_int of the stiffness product at this displacement (AddStiffnessProduct) against the cells', with -info
    // (PetscInfo's class of a null object; test stiffness_product).
    VecH by_product;
    PetscBool info;
    PetscCall(PetscInfoEnabled(PETSC_SMALLEST_CLASSID, &info));
    const bool compare = info && fint_at_.u == u_local_ && !fint_at_.exact;
    if (compare) {
      PetscCall(VecDuplicate(fint_, by_product.out()));
      PetscCall(VecCopy(fint_, by_product));
    }
    PetscCall(PetscLogEventBegin(EV_FINT, 0, 0, 0, 0));
    PetscCall(VecZeroEntries(fint_));
    PetscCall(assembler_->Assemble(u_local_.data(), nullptr, 0, fint_, &min_J));
    PetscCall(PetscLogEventEnd(EV_FINT, 0, 0, 0, 0));
    if (compare) PetscCall(CompareProduct(by_product));
    fint_at_.u = u_local_;
    fint_at_.min_J = min_J;
    fint_at_.exact = true;
  }
  const PetscScalar *fi, *fe;
  PetscCall(VecGetArrayRead(fint_, &fi));
  PetscCall(VecGetArrayRead(fext_, &fe));
  std::vector<double> r(dofs_.OwnedU(), 0.0);
  for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) r[i] = fi[i] - fe[i];
  double s[4] = {0, 0, 0, 0};
  for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) s[1] += fi[i] * fi[i] + fe[i] * fe[i];
  PetscCall(VecRestoreArrayRead(fint_, &fi));
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  // Contact forces B^T lambda (all rows of the pair's node are local: pairs live with their owned node).
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    for (int k = 0; k < dim; ++k) r[dofs_.LocalOffset(pairs_[p].vertex, k)] -= lambda[p] * normals_[p][k];
  // The mortar pairs' forces on their master nodes (of any rank).
  if (!mortar_.Empty()) PetscCall(mortar_.AddMasterForces(lambda, -1, r));
  if (friction_.On()) PetscCall(friction_.AddForces(pairs_, -1, false, r.data(), dofs_.OwnedU()));
  // s[3]: ||u||^2 over the owned rows (prescribed values included), for the round-off of F_int (roundoff).
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) {
        s[3] += u_local_[v * dim + k] * u_local_[v * dim + k];
        if (!dirichlet_.fixed[v * dim + k]) {
          const PetscInt i = dofs_.LocalOffset(v, k);
          s[0] += r[i] * r[i];
          if (direction) s[2] += direction[i] * r[i];
        }
      }
  double gs[4];
  PetscCallMPI(MPI_Allreduce(s, gs, 4, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  if (dot) *dot = gs[2];
  if (roundoff) *roundoff = ROUNDOFF_FACTOR * DBL_EPSILON * krow_ * std::sqrt(gs[3]);
  norm = std::isfinite(min_J) && min_J > MIN_DET_F ? std::sqrt(gs[0]) : INFINITY;
  scale = std::sqrt(gs[1]);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AssembleSystem(StepState &st) {
  ScopedTimer t(stats_.time_assembly);
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(EV_ASSEMBLY, 0, 0, 0, 0));
  // svk with the kept factorisation, while the active set changes (-newton_lagged_search): the tangent of the last
  // assembly stays (a modified Newton step), solved to SEARCH_RTOL, as long as the residual contracts by
  // LAGGED_CONTRACTION per step; the exact tangent once the active set settles.
  // A lagged step is a condensed search (SolveAndUpdate): its later iterations (st.base.ready) keep it.
  if (!(model_->Nonlinear() && st.base.ready)) {
    const bool contracting = st.newton.lag_rnorm < 0 || st.r.norm <= LAGGED_CONTRACTION * st.newton.lag_rnorm;
    const bool lag = model_->Nonlinear() && lagged_search_ && st.searching && !st.stabilised && !st.newton.exact &&
                     !active_set_.OneAtATime() && system_->ReusesFactorization();
    st.newton.lagged = lag && contracting;
    st.newton.lag_rnorm = st.r.norm;
    // A lagged step that did not contract: the factored tangent has drifted too far to precondition the current one.
    if (lag && !contracting) system_->RefactorNext();
  } else if (st.stabilised || st.newton.exact) {
    st.newton.lagged = false; // the search is left (Condensable): a full solve from the base with the current tangent
  }
  // With friction, the tangential rows after the normal ones: stick rows active, slip pairs' normal columns with their
  // friction.
  std::vector<ConstraintRow> rows;
  std::vector<char> flags, heavy;
  std::vector<std::vector<double>> columns;
  std::vector<double> diag;
  if (friction_.On()) {
    friction_.SystemRows(rows_, st.next, rows, flags, columns, diag, &heavy, system_->AugmentationWeight(false),
                         system_->FixedRowWeight());
    // On the kept factorisation: the fixed rows and this system's rows and columns in them.
    if (system_->TurnsRows()) {
      std::vector<ConstraintRow> fixed;
      std::vector<RowGroup> groups;
      friction_.KeptGroups(rows_, fixed, groups);
      system_->SetRowGroups(std::move(fixed), std::move(groups));
    }
  }
  // svk between bodies (MortarCoupling::UseConsistentTangent): the mortar rows' variation in the tangent, with the
  // stiffness that it is added to; the active rows linearise the weighted gaps, their columns keep the forces' rows.
  // Once the active set stays (st.searching false): while it changes, the multipliers of the last iterate may be far
  // from any state, and their term lambda dc/du turned the first Newton steps of the 3D sphere on a block
  // (options/sphere_on_block.yml, svk, one load step) away from it: the step was cut twice, where the frozen
  // tangent's search converged.
  const bool consistent = mortar_.ConsistentTangent() && model_->Nonlinear() && !st.newton.lagged && !st.searching;
  std::vector<ConstraintRow> linearised;
  std::vector<std::vector<double>> frozen;
  if (consistent) linearised = rows_;
  const std::vector<ConstraintRow> &normal_rows = consistent ? linearised : rows_;
  if ((model_->Nonlinear() && !st.newton.lagged) || !k_assembled_) {
    ProgressBegin("stiffness assembly");
    PetscCall(PetscLogEventBegin(EV_STIFFNESS, 0, 0, 0, 0));
    PetscCall(MatZeroEntries(system_->Stiffness()));
    PetscCall(assembler_->Assemble(u_local_.data(), system_->Stiffness(), kscale_, nullptr, nullptr));
    PetscCall(MatAssemblyBegin(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
    PetscCall(MatAssemblyEnd(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
    if (consistent) {
      PetscCall(mortar_.Linearise(mesh_, dofs_, dirichlet_.fixed, lambda_, st.next, system_->Stiffness(),
                                  system_->Nested(), linearised, frozen));
      PetscCall(MatAssemblyBegin(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
      PetscCall(MatAssemblyEnd(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
    }
    if (system_->Augmented()) PetscCall(system_->AddAugmentation(friction_.On() ? rows : normal_rows));
    k_assembled_ = true;
    PetscCall(PetscLogEventEnd(EV_STIFFNESS, 0, 0, 0, 0));
    ProgressEnd();
  }
  if (friction_.On()) {
    PetscCall(system_->SetConstraints(rows, flags, -1.0 / kscale_, st.stabilised ? STABILISATION * kscale_ : 0.0,
                                      &columns, &diag, &heavy));
  } else {
    PetscCall(system_->SetConstraints(normal_rows, st.next, -1.0 / kscale_,
                                      st.stabilised ? STABILISATION * kscale_ : 0.0, frozen.empty() ? nullptr : &frozen));
  }
  if (Condensable(st)) {
    // The base's right-hand side with the new active set: its displacement rows stay, the gaps are the base's.
    PetscScalar *b;
    PetscCall(VecGetArray(system_->Rhs(), &b));
    for (std::size_t p = 0; p < pairs_.size(); ++p)
      b[dofs_.OwnedU() + p] = st.next[p] ? st.base.g[p] : 0.0;
    PetscCall(VecRestoreArray(system_->Rhs(), &b));
    PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  if (st.stabilised) st.u_before = u_local_, st.measured = true;
  // Right-hand side: f - F_int on free rows, 0 on Dirichlet rows, the current gap on active multiplier rows.
  PetscScalar *b;
  const PetscScalar *fi, *fe;
  PetscCall(VecGetArray(system_->Rhs(), &b));
  PetscCall(VecGetArrayRead(fint_, &fi));
  PetscCall(VecGetArrayRead(fext_, &fe));
  for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) b[i] = fe[i] - fi[i];
  if (st.moving) {
    if (!fdir_) PetscCall(VecDuplicate(u_, fdir_.out()));
    PetscCall(VecZeroEntries(fdir_));
    PetscCall(assembler_->AddStiffnessTimes(u_local_.data(), st.delta.data(), fdir_));
    const PetscScalar *fd;
    PetscCall(VecGetArrayRead(fdir_, &fd));
    for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) b[i] -= fd[i];
    PetscCall(VecRestoreArrayRead(fdir_, &fd));
  }
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (dirichlet_.fixed[v * dim + k]) b[dofs_.LocalOffset(v, k)] = kscale_ * st.delta[v * dim + k];
  for (std::size_t p = 0; p < pairs_.size(); ++p) b[dofs_.OwnedU() + p] = st.next[p] ? states_[p].gap : 0.0;
  if (friction_.On()) PetscCall(friction_.RowRhs(pairs_, st.u_eval.data(), b + dofs_.OwnedU() + pairs_.size()));
  PetscCall(VecRestoreArrayRead(fint_, &fi));
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  PetscCall(VecRestoreArray(system_->Rhs(), &b));
  PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::NewtonForcing(const StepState &st, double &rtol) const {
  PetscFunctionBeginUser;
  // svk with the kept factorisation and the lagged search, or on the iterative path without friction: an inexact
  // Newton step. A linear residual of eta ||R||, eta = min(SEARCH_RTOL, ||R|| / scale), keeps Newton's quadratic
  // convergence (Dembo, Eisenstat and Steihaug 1982). None needs to go below half the equilibrium tolerance: so close
  // to the solution the quadratic term is far below it (2D Hertz, 195k dofs, svk: a quarter instead of a half took 4
  // more preconditioner applications). The tolerance is relative to the right-hand side, which carries the whole
  // contact force (the solve is for the multipliers, not their increments); an iterative solve tests it against its
  // start's residual, which the last multipliers make smaller: stricter still. On the iterative path (the octant of
  // options/hertz3d.yml at 290k dofs, svk, one rank): 338 Krylov iterations instead of 481, 57.8 s instead of 71.0 s,
  // the same 14 iterations and state.
  // Once the active set has cycled (ActiveSet::SwitchOneAtATime), every step is exact: one pair switches per step,
  // and the gaps and multipliers that choose it must be those of the current set's solution.
  rtol = 0;
  const bool inexact = (lagged_search_ && system_->ReusesFactorization()) || (system_->Iterative() && !friction_.On());
  if (!inexact || active_set_.OneAtATime() || !(st.r.norm > 0) || !(st.r.scale > 0)) PetscFunctionReturn(0);
  const double eta = std::min(
      SEARCH_RTOL, std::max(0.5 * EquilibriumTol(st.r.scale, st.r.roundoff) / st.r.norm, st.r.norm / st.r.scale));
  PetscReal bnorm;
  PetscCall(VecNorm(system_->Rhs(), NORM_2, &bnorm));
  if (bnorm > 0) rtol = std::min(SEARCH_RTOL, eta * st.r.norm / bnorm);
  PetscFunctionReturn(0);
}

bool ContactSolver::Condensable(const StepState &st) const {
  if (!st.base.ready || st.stabilised || !system_->ReusesFactorization()) return false;
  return model_->Nonlinear() ? st.newton.lagged : system_->ExactFactorization();
}

PetscErrorCode ContactSolver::SolveAndUpdate(StepState &st) {
  PetscFunctionBeginUser;
  bool condensed;
  {
    ScopedTimer t(stats_.time_solve);
    const double t0 = MPI_Wtime();
    PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
    const bool search =
        model_->Nonlinear() ? st.newton.lagged && system_->ReusesFactorization() : system_->ExactFactorization();
    // Linear material, kept factorisation, no stabilisation and no prescribed displacement still to apply: the
    // right-hand side assembled now is the base of the solves after it, which run in the multiplier space (condensed)
    // until Materialise.
    if (!st.base.ready && !st.stabilised && !st.moving && search) PetscCall(CondenseBase(st));
    condensed = Condensable(st);
    st.loose = false;
    // An iterative solver cannot tell a singular system by its pivots: without friction (whose stick pairs hold
    // along their tangents too) a body that the supports and every candidate pair together leave free is singular
    // for every active set, and the step ends as a direct solver's would (DIVERGED_SINGULAR, after the search within
    // a wider radius), instead of a Krylov failure after many active-set iterations (the 3D robustness survey, seed
    // 777: 39 cases singular on the direct path; on the iterative one 12 Krylov breakdowns, 15 DIVERGED_MAX_IT and
    // others).
    if (!st.singular && !condensed && system_->Iterative() && !friction_.On()) {
      bool held;
      PetscCall(Held(std::vector<char>(pairs_.size(), 1), held));
      system_->SetUnheld(!held);
      st.singular = !held;
    }
    if (st.singular) {
      // The condensation found null pivots, or the supports and the candidates leave the body free: nothing to solve
      // (LoadStep ends the step).
    } else if (condensed) {
      std::vector<double> bm(pairs_.size());
      for (std::size_t p = 0; p < pairs_.size(); ++p)
        bm[p] = st.next[p] ? st.base.g[p] : 0.0;
      PetscCall(system_->SolveCondensed(bm, lambda_, st.base.shift, st.solve_residual));
      mult_ = lambda_;
      st.krylov = 1;
    } else {
      // A full solve moves the displacement away from any base.
      st.base.ready = false;
      double rtol = st.newton.lagged ? SEARCH_RTOL : st.correction.rtol;
      if (model_->Nonlinear() && !st.newton.lagged) PetscCall(NewtonForcing(st, rtol));
      // Inexact active set (linear material, iterative solver): while the set changes a solve only has to show
      // where it goes (to -contact_active_set_rtol of the load step's first residual, SaddlePointSystem::Solve); the
      // next iterate's residual is evaluated in full (EvaluateIterate), so that each solve also corrects what the
      // earlier ones left; the solve after which the set stays is corrected to the certificate's tolerance
      // (JudgeCandidate).
      // Without multipliers nothing can change: one solve to the KSP's tolerance. Friction's sets follow the slips
      // and the springs across them (3D) from every solve: loose solves made a cube dragged over a plane cycle.
      const bool loose = !model_->Nonlinear() && st.correction.rtol == 0 && opts_.active_set_rtol > 0 &&
                         system_->Iterative() && dofs_.GlobalLambda() > 0 && !friction_.On();
      if (loose) rtol = opts_.active_set_rtol;
      // Held at a touching point: this solve's displacement only picks the first update's pairs, and the next solve
      // usually restarts from the step's start. The octant Hertz at 1.07M dofs: 10 Krylov iterations instead of 15
      // here, the same later path (docs/performance.md, nineteenth session); where the first set is larger (an indenter
      // placed into the body, a patch test) its errors read as changes (the sixteenth session: 6 active-set iterations
      // instead of 4 on the 824k cube, 7 instead of 2 on the 3D patch test), so a few pairs at most.
      if (loose && st.touching) {
        bool cg;
        PetscCall(system_->KrylovIsCg(cg));
        rtol = std::max(rtol, cg ? TOUCHING_RTOL_CG : TOUCHING_RTOL);
      }
      // svk held at a touching point: like the linear material's, this solve only shows the first update's pairs
      // (from its whole increment, touch_gaps), and the next one restarts from the step's start.
      const bool touch_svk = model_->Nonlinear() && st.touching && st.restartable;
      if (touch_svk) rtol = TOUCHING_RTOL;
      st.loose = loose;
      const PetscInt fallbacks = system_->KrylovFallbacks();
      const bool inexact = model_->Nonlinear() && !st.newton.lagged && rtol > 0;
      PetscCall(system_->Solve(st.krylov, st.solve_residual, st.singular, rtol, loose, inexact));
      stats_.krylov_fallbacks += system_->KrylovFallbacks() - fallbacks;
      if (touch_svk && !st.singular) {
        const PetscScalar *x;
        PetscCall(VecGetArrayRead(system_->Solution(), &x));
        st.touch_gaps.resize(pairs_.size());
        for (std::size_t p = 0; p < pairs_.size(); ++p) {
          double g = states_[p].gap;
          for (int k = 0; k < mesh_.Dim(); ++k)
            g += normals_[p][k] * x[dofs_.LocalOffset(pairs_[p].vertex, k)];
          st.touch_gaps[p] = g;
        }
        PetscCall(VecRestoreArrayRead(system_->Solution(), &x));
        // The increment itself is not applied: its iterate would be cut by the step length (or not made invertible
        // by it: the octant at 1.07M dofs failed its full load step so and was cut in two), and the next solve
        // starts from the step's start, without multipliers.
        PetscCall(VecZeroEntries(system_->Solution()));
      }
      st.correction.made = st.correction.rtol > 0;
      st.correction.rtol = 0;
    }
    PetscCall(PetscLogEventEnd(EV_SOLVE, 0, 0, 0, 0));
    const double dt = MPI_Wtime() - t0;
    PetscCallMPI(MPI_Allreduce(&dt, &st.last_solve_time, 1, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
  }
  if (st.singular) PetscFunctionReturn(0);
  stats_.solves++;
  stats_.active_set_iterations++;
  stats_.krylov_iterations += st.krylov;
  stats_.stabilised_solves += st.stabilised;
  st.base.condensed = condensed;
  if (condensed || !st.touch_gaps.empty()) PetscFunctionReturn(0); // svk's touching solve: its increment not applied
  // A loose solve's iterate gets its residual in full (EvaluateIterate): for the linear material F_int there is the
  // last one's plus K du, where the prescribed values stay (Residual's certificate evaluation takes the cells).
  bool product = st.loose && !model_->Nonlinear() && !st.stabilised && !st.moving && fint_at_.u == u_local_;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &product, 1, MPI_CXX_BOOL, MPI_LAND, mesh_.Comm()));
  double step_length;
  PetscCall(UpdateSolution(st.r.norm, st.stabilised, step_length));
  // What a shortened step left of the prescribed increment comes in the next solve; a full step lands exactly.
  for (double &d : st.delta) d *= 1.0 - step_length;
  if (step_length == 1.0) PetscCall(SetDirichlet(st.factor));
  if (product && step_length == 1.0) PetscCall(AddStiffnessProduct());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CompareProduct(Vec by_product) const {
  const int dim = mesh_.Dim();
  const PetscScalar *a, *b;
  PetscFunctionBeginUser;
  double s[2] = {0, 0}; // ||F_int(product) - F_int(cells)||^2, ||F_int(cells)||^2 on the free rows
  PetscCall(VecGetArrayRead(by_product, &a));
  PetscCall(VecGetArrayRead(fint_, &b));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[v * dim + k]) {
          const PetscInt i = dofs_.LocalOffset(v, k);
          s[0] += (a[i] - b[i]) * (a[i] - b[i]), s[1] += b[i] * b[i];
        }
  PetscCall(VecRestoreArrayRead(fint_, &b));
  PetscCall(VecRestoreArrayRead(by_product, &a));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 2, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  PetscCall(PetscInfo(nullptr,
                      "F_int from the stiffness product: ||difference|| %.6g against the cells' ||F_int|| %.6g on "
                      "the free rows\n",
                      std::sqrt(s[0]), std::sqrt(s[1])));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AddStiffnessProduct() {
  const int dim = mesh_.Dim();
  const PetscInt nu = dofs_.OwnedU();
  PetscFunctionBeginUser;
  bool possible;
  PetscCall(system_->StiffnessTimesApplies(rows_, possible));
  if (!possible) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(EV_PRODUCT, 0, 0, 0, 0));
  // The step moved the free rows by du; the Dirichlet rows keep their values (SetDirichlet).
  const PetscScalar *x;
  PetscCall(VecGetArrayRead(system_->Solution(), &x));
  std::vector<PetscScalar> du(x, x + nu);
  PetscCall(VecRestoreArrayRead(system_->Solution(), &x));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (dirichlet_.fixed[v * dim + k]) du[dofs_.LocalOffset(v, k)] = 0;
  std::vector<double> kdu;
  PetscCall(system_->StiffnessTimes(rows_, du.data(), kdu));
  PetscScalar *fi;
  PetscCall(VecGetArray(fint_, &fi));
  for (PetscInt i = 0; i < nu; ++i)
    fi[i] += kdu[i];
  PetscCall(VecRestoreArray(fint_, &fi));
  fint_at_.u = u_local_;
  fint_at_.exact = false;
  PetscCall(PetscLogEventEnd(EV_PRODUCT, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CondenseBase(StepState &st) {
  PetscFunctionBeginUser;
  if (!st.base.u) PetscCall(VecDuplicate(u_, st.base.u.out()));
  PetscCall(VecCopy(u_, st.base.u));
  st.base.g.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    st.base.g[p] = states_[p].gap;
  PetscCall(system_->Condense(st.singular));
  if (st.singular) PetscFunctionReturn(0);
  st.base.ready = true;
  st.base.rnorm = st.r.norm;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Materialise(StepState &st, PetscInt it) {
  PetscFunctionBeginUser;
  {
    ScopedTimer t(stats_.time_solve);
    PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
    // The whole solution of the last condensed solve (the right-hand side is the base's with the gaps of the current
    // active set, AssembleSystem of that solve; the constraints are the current ones): the displacement increment
    // from the base.
    PetscCall(system_->Expand(st.solve_residual));
    st.krylov = 1;
    PetscCall(PetscLogEventEnd(EV_SOLVE, 0, 0, 0, 0));
  }
  stats_.solves++;
  PetscCall(VecCopy(st.base.u, u_));
  double step_length;
  PetscCall(UpdateSolution(st.base.rnorm, false, step_length));
  st.base.condensed = false;
  // The expansion used up the condensed right-hand side: a solve after it (svk: the next Newton step; linear: a
  // correction of an equilibrium residual the certificate refused) condenses again or solves in full.
  st.base.ready = false;
  PetscCall(EvaluateIterate(st, it));
  for (std::size_t p = 0; p < pairs_.size(); ++p) states_[p].lambda = lambda_[p];
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UpdateSolution(double r0, bool stabilised, double &step) {
  const bool newton = model_->Nonlinear(), current = model_->CurrentConfiguration();
  const PetscInt nu = dofs_.OwnedU();
  std::vector<double> new_lambda(pairs_.size());
  const std::vector<char> &active = active_set_.Flags();
  PetscFunctionBeginUser;
  const PetscScalar *x;
  PetscCall(VecGetArrayRead(system_->Solution(), &x));
  // The solved multipliers: contact forces on active rows, stabilisation springs on inactive ones.
  for (std::size_t p = 0; p < pairs_.size(); ++p) mult_[p] = x[nu + p], new_lambda[p] = active[p] ? x[nu + p] : 0.0;
  if (friction_.On()) friction_.Read(x + nu + pairs_.size(), new_lambda, mult_);
  PetscCall(VecRestoreArrayRead(system_->Solution(), &x));
  PetscCall(VecCopy(u_, du_));
  // Step length: halved while det F <= MIN_DET_F somewhere (always); with -newton_linesearch, the line search of Crisfield
  // along du on g(s) = du . R(u + s du, lambda): g(0) = -du.K du < 0, a full step is kept unless it overshoots
  // (g(1) > 0.8 |g(0)|), then the secant step; at most 8 trials.
  const PetscScalar *dx;
  PetscCall(VecGetArrayRead(system_->Solution(), &dx));
  std::vector<double> dir(dx, dx + nu);
  PetscCall(VecRestoreArrayRead(system_->Solution(), &dx));
  double g0 = 0;
  if (newton && opts_.line_search) {
    double r, scale;
    PetscCall(EvaluateAt(u_local_.data(), current));
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g0));
  }
  double s = 1.0;
  if (newton && stabilised) {
    // svk: a stabilised step moves the body along its free motions; it is cut to a quarter of the search radius,
    // so that the pairs searched again at the new position still see the obstacle it approaches (StepControl then
    // moves the body along its free rigid motion from there).
    double m = 0;
    for (PetscInt i = 0; i < nu; ++i) m = std::max(m, std::abs(dir[i]));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
    if (m > 0.25 * contact_.search_radius) s = 0.25 * contact_.search_radius / m;
  }
  for (int k = 0;; ++k) {
    // u = u_old + s du on the displacement rows (du_ holds u_old while trying).
    PetscScalar *u;
    const PetscScalar *u_old;
    PetscCall(VecGetArray(u_, &u));
    PetscCall(VecGetArrayRead(du_, &u_old));
    for (PetscInt i = 0; i < nu; ++i) u[i] = u_old[i] + s * dir[i];
    PetscCall(VecRestoreArrayRead(du_, &u_old));
    PetscCall(VecRestoreArray(u_, &u));
    PetscCall(UpdateLocal());
    if (!newton || k == 8) break;
    double r, scale, g;
    PetscCall(EvaluateAt(u_local_.data(), current));
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g));
    PetscCall(PetscInfo(nullptr, "line search: step %.6g g(s)/g(0) %.6g residual %.6g (before %.6g)\n", s, g / g0, r, r0));
    if (!std::isfinite(r)) {
      // Safeguard, always on: det F <= MIN_DET_F somewhere, halve the step.
      s *= 0.5;
      continue;
    }
    if (!opts_.line_search || g0 >= 0 || g <= 0.8 * std::abs(g0)) break;
    s = std::max(0.1 * s, s * g0 / (g0 - g));
  }
  lambda_ = new_lambda;
  step = s;
  PetscFunctionReturn(0);
}

} // namespace signorini
