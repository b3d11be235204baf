// The load-step / active-set / Newton loop.
#include "signorini/solver/contact_solver.hpp"

#include "signorini/core/options.hpp"

#include <algorithm>
#include <cmath>

namespace signorini {

namespace {
PetscLogEvent EV_ASSEMBLY = 0, EV_ACTIVE_SET = 0, EV_SOLVE = 0;

/// Accumulates the wall time of a scope (maximum over ranks is taken when reported).
class ScopedTimer {
public:
  ScopedTimer(double &total) : total_(total), start_(MPI_Wtime()) {}
  ~ScopedTimer() { total_ += MPI_Wtime() - start_; }

private:
  double &total_;
  double start_;
};
} // namespace

PetscErrorCode ReadSolverOptions(MPI_Comm comm, SolverOptions &opts) {
  // Ranges (README): a relative residual above 1e-4 or an absolute one above 1e-6 (force units) would accept a
  // visibly unconverged state; the counts are bounded so that a typo cannot start a run that never ends.
  const RealRange rtol{0, SolverOptions::NEWTON_RTOL_MAX, true, false}, atol{0, SolverOptions::NEWTON_ATOL_MAX};
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Load stepping and Newton-Raphson", "signorini");
  PetscCall(OptionsInt(PetscOptionsObject, "-load_steps", "Number of load increments", 1, SolverOptions::LOAD_STEPS_MAX,
                       opts.load_steps));
  PetscCall(OptionsInt(PetscOptionsObject, "-load_max_cuts", "Halvings allowed for a failed load increment", 0,
                       SolverOptions::LOAD_MAX_CUTS_MAX, opts.max_cuts));
  PetscCall(OptionsInt(PetscOptionsObject, "-newton_max_it", "Newton/active-set iterations per load step (svk)", 1,
                       SolverOptions::NEWTON_MAX_IT_MAX, opts.newton_max_it));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_rtol", "Residual tolerance relative to the force scale", rtol,
                        opts.newton_rtol));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_atol", "Absolute residual tolerance (force units)", atol,
                        opts.newton_atol));
  PetscCall(PetscOptionsBool("-newton_linesearch", "Line search on du.R(u + s du) (det F <= 0 always halves the step)", "",
                             opts.line_search, &opts.line_search, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Setup() {
  MPI_Comm comm = mesh_.Comm();
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  if (!EV_ASSEMBLY) {
    PetscClassId id;
    PetscCall(PetscClassIdRegister("signorini", &id));
    PetscCall(PetscLogEventRegister("SigAssembly", id, &EV_ASSEMBLY));
    PetscCall(PetscLogEventRegister("SigActiveSet", id, &EV_ACTIVE_SET));
    PetscCall(PetscLogEventRegister("SigSolve", id, &EV_SOLVE));
  }
  PetscCall(BuildDirichlet(mesh_, bc_, dirichlet_));
  PetscCall(FindContactPairs(mesh_, obstacle_, contact_, dirichlet_.fixed, pairs_, candidate_));
  PetscCall(dofs_.Create(mesh_, (PetscInt)pairs_.size()));
  assembler_ = std::make_unique<Assembler>(mesh_, material_, dofs_, dirichlet_);
  PetscCall(assembler_->CheckCells());
  PetscCall(assembler_->StiffnessScale(kscale_));

  // Coordinates of the owned vertices in dof order, for the rigid-body modes.
  std::vector<double> coords(dofs_.OwnedU());
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) coords[dofs_.LocalOffset(v, k)] = mesh_.X(v)[k];
  u_local_.assign(mesh_.NumLocalVertices() * dim, 0.0);
  EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, false, u_local_.data(), states_, rows_,
                normals_);
  PetscCall(system_.Create(dofs_, rows_, coords, material_.model != MaterialModel::SVK, kscale_,
                           [&](Mat P) { return assembler_->InsertPattern(P); }));

  PetscCall(MatCreateVecs(system_.A(), u_.out(), nullptr));
  PetscCall(VecDuplicate(u_, du_.out()));
  PetscCall(VecDuplicate(u_, fext_.out()));
  PetscCall(VecDuplicate(u_, fint_.out()));
  PetscCall(VecDuplicate(u_, fdir_.out()));
  PetscCall(PetscObjectSetName((PetscObject)u_.get(), "displacement"));
  std::vector<PetscInt> from(mesh_.NumLocalVertices() * dim);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    for (int k = 0; k < dim; ++k) from[v * dim + k] = dofs_.Row(v, k);
  ISH is_from;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)from.size(), from.data(), PETSC_COPY_VALUES, is_from.out()));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)from.size(), u_seq_.out()));
  PetscCall(VecScatterCreate(u_, is_from, u_seq_, nullptr, &scatter_));
  lambda_.assign(pairs_.size(), 0.0);
  active_.assign(pairs_.size(), 0);
  (void)comm;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UpdateLocal() {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(scatter_, u_, u_seq_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter_, u_, u_seq_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar *a;
  PetscCall(VecGetArrayRead(u_seq_, &a));
  std::copy(a, a + u_local_.size(), u_local_.begin());
  PetscCall(VecRestoreArrayRead(u_seq_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SetDirichlet(double factor) {
  const int dim = mesh_.Dim();
  PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(u_, &u));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (dirichlet_.fixed[v * dim + k]) u[dofs_.LocalOffset(v, k)] = factor * dirichlet_.value[v * dim + k];
  PetscCall(VecRestoreArray(u_, &u));
  PetscCall(UpdateLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Residual(const std::vector<double> &lambda, double &norm, double &scale,
                                        const PetscScalar *direction, double *dot) {
  const int dim = mesh_.Dim();
  double min_J;
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(fint_));
  PetscCall(assembler_->Assemble(u_local_.data(), nullptr, 0, fint_, &min_J));
  const PetscScalar *fi, *fe;
  PetscCall(VecGetArrayRead(fint_, &fi));
  PetscCall(VecGetArrayRead(fext_, &fe));
  std::vector<double> r(dofs_.OwnedU(), 0.0);
  for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) r[i] = fi[i] - fe[i];
  double s[3] = {0, 0, 0};
  for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) s[1] += fi[i] * fi[i] + fe[i] * fe[i];
  PetscCall(VecRestoreArrayRead(fint_, &fi));
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  // Contact forces B^T lambda (all rows of the pair's node are local: pairs live with their owned node).
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    for (int k = 0; k < dim; ++k) r[dofs_.LocalOffset(pairs_[p].vertex, k)] -= lambda[p] * normals_[p][k];
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[v * dim + k]) {
          const PetscInt i = dofs_.LocalOffset(v, k);
          s[0] += r[i] * r[i];
          if (direction) s[2] += direction[i] * r[i];
        }
  double gs[3];
  PetscCallMPI(MPI_Allreduce(s, gs, 3, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  if (dot) *dot = gs[2];
  norm = std::isfinite(min_J) && min_J > 0 ? std::sqrt(gs[0]) : INFINITY;
  scale = std::sqrt(gs[1]);
  PetscFunctionReturn(0);
}

void ContactSolver::DropParallelPairs(std::vector<char> &next) const {
  // Two active pairs of one node with (nearly) the same normal, e.g. at the joint of collinear segments, are the
  // same constraint twice and would make the saddle-point matrix singular: the pair of the later facet is dropped.
  // Pairs are sorted by node, so a node's pairs are adjacent.
  const double cos_parallel = std::cos(M_PI / 180.0);
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    if (!next[p]) continue;
    for (std::size_t q = p + 1; q < pairs_.size() && pairs_[q].vertex == pairs_[p].vertex; ++q) {
      double dot = 0;
      for (int d = 0; d < 3; ++d) dot += normals_[p][d] * normals_[q][d];
      if (next[q] && dot > cos_parallel) next[q] = 0;
    }
  }
}

PetscErrorCode ContactSolver::ActiveSetHash(const std::vector<char> &active, unsigned long long &h) const {
  unsigned long long mine = 0;
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    if (active[p]) {
      unsigned long long z = (unsigned long long)mesh_.VertexOriginal(pairs_[p].vertex) * 1000003ULL +
                             (unsigned long long)pairs_[p].facet + 0x9E3779B97F4A7C15ULL;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
      mine += z ^ (z >> 31);
    }
  PetscCallMPI(MPI_Allreduce(&mine, &h, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, mesh_.Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Monitor(const IterationRecord &r) const {
  PetscFunctionBeginUser;
  if (contact_.monitor)
    PetscCall(PetscPrintf(mesh_.Comm(),
                          "  step %" PetscInt_FMT " (load %.4g) it %" PetscInt_FMT ": active %" PetscInt_FMT
                          " changed %" PetscInt_FMT " min lambda %.6e max penetration %.6e residual %.6e ksp its %"
                          PetscInt_FMT "\n",
                          r.step, r.load_factor, r.iteration, r.active, r.changed, r.min_lambda, r.max_penetration,
                          r.residual, r.krylov));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::LoadStep(PetscInt step, double factor, bool first, bool &ok) {
  MPI_Comm comm = mesh_.Comm();
  const bool large = material_.model == MaterialModel::SVK;
  const PetscInt max_it = large ? std::max(opts_.newton_max_it, contact_.max_it) : contact_.max_it;
  const double force_tol = contact_.c * contact_.gap_tol;
  std::vector<unsigned long long> seen;
  std::vector<char> next(pairs_.size());
  PetscInt krylov = 0;
  double last_solve_time = 0, solve_residual = 0;
  PetscFunctionBeginUser;
  ok = false;
  // The increment of the prescribed displacements enters through the first solve of the step (its Dirichlet rows
  // and the coupling K_fd du_d of the free rows), not by moving the boundary nodes alone, which could invert the
  // cells next to them under large prescribed displacements.
  const int dim = mesh_.Dim();
  std::vector<double> delta(u_local_.size(), 0.0), u_eval(u_local_.size());
  for (std::size_t i = 0; i < delta.size(); ++i)
    if (dirichlet_.fixed[i]) delta[i] = factor * dirichlet_.value[i] - u_local_[i];
  PetscCall(VecZeroEntries(fext_));
  PetscCall(assembler_->AssembleLoads(bc_, factor, fext_));
  for (PetscInt it = 0;; ++it) {
    double rnorm, rscale;
    bool moving = false;
    for (std::size_t i = 0; i < delta.size(); ++i) moving = moving || delta[i] != 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &moving, 1, MPI_CXX_BOOL, MPI_LOR, comm));
    {
      ScopedTimer t(stats_.time_assembly);
      PetscCall(PetscLogEventBegin(EV_ASSEMBLY, 0, 0, 0, 0));
      // Gaps with the prescribed displacements in place (the constraint rows hold only the free components).
      for (std::size_t i = 0; i < u_eval.size(); ++i) u_eval[i] = u_local_[i] + delta[i];
      EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_eval.data(), states_, rows_,
                    normals_);
      if (large || it == 0) {
        PetscCall(Residual(lambda_, rnorm, rscale));
      } else {
        // Linear material after a solve: K du was solved for exactly (to the solve's residual), so F_int = f + B^T
        // lambda on the free rows, without a pass over the cells; the monitor shows the solve's residual. The
        // final state gets a full residual evaluation (Solve).
        PetscScalar *fi;
        const PetscScalar *fe;
        PetscCall(VecGetArray(fint_, &fi));
        PetscCall(VecGetArrayRead(fext_, &fe));
        for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) fi[i] = fe[i];
        for (std::size_t p = 0; p < pairs_.size(); ++p)
          for (int k = 0; k < dim; ++k) fi[dofs_.LocalOffset(pairs_[p].vertex, k)] += lambda_[p] * normals_[p][k];
        PetscCall(VecRestoreArrayRead(fext_, &fe));
        PetscCall(VecRestoreArray(fint_, &fi));
        rnorm = solve_residual;
      }
      PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
    }
    // Active-set update (seed 4.1): first the pairs touching at the start, then the complementarity rule.
    PetscInt counts[2] = {0, 0};
    double mins[2] = {INFINITY, INFINITY};
    {
      ScopedTimer t(stats_.time_active_set);
      // Activation threshold: the deepest penetration of an inactive pair times -contact_activation_fraction.
      double deepest = 0, gdeepest;
      for (std::size_t p = 0; p < pairs_.size(); ++p)
        if (!active_[p] && states_[p].inside) deepest = std::max(deepest, -states_[p].gap);
      PetscCallMPI(MPI_Allreduce(&deepest, &gdeepest, 1, MPI_DOUBLE, MPI_MAX, comm));
      // It damps the first update of a load step only, the overshoot after the solve with the initial (touching or
      // previous) set; later updates activate every penetrating pair, so that the last pairs are not held back.
      const double frac = it == 1 ? contact_.activation_fraction : 0.0;
      const double activate_tol = std::max(force_tol, contact_.c * frac * gdeepest);
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        states_[p].lambda = lambda_[p];
        states_[p].active = active_[p];
        if (it == 0)
          next[p] = first ? (states_[p].inside && states_[p].gap <= contact_.touch_tol) : active_[p];
        else
          next[p] = NextActive(states_[p], contact_.c, force_tol, activate_tol);
      }
      DropParallelPairs(next);
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        counts[0] += next[p];
        counts[1] += next[p] != active_[p];
        if (active_[p]) mins[0] = std::min(mins[0], lambda_[p]);
        mins[1] = std::min(mins[1], states_[p].gap);
      }
    }
    PetscInt gcounts[2];
    double gmins[2];
    PetscCallMPI(MPI_Allreduce(counts, gcounts, 2, MPIU_INT, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(mins, gmins, 2, MPI_DOUBLE, MPI_MIN, comm));
    const bool residual_ok = !large || rnorm <= opts_.newton_rtol * rscale + opts_.newton_atol;
    IterationRecord rec{step,   it, gcounts[0], gcounts[1], krylov, factor, std::isfinite(gmins[0]) ? gmins[0] : 0.0,
                        std::max(0.0, std::isfinite(gmins[1]) ? -gmins[1] : 0.0), rnorm, last_solve_time};
    if (it > 0) {
      stats_.history.push_back(rec);
      PetscCall(Monitor(rec));
    }
    if (it > 0 && gcounts[1] == 0 && residual_ok && !moving) {
      stats_.reason = large ? "CONVERGED_ACTIVE_SET_AND_RESIDUAL" : "CONVERGED_ACTIVE_SET_UNCHANGED";
      ok = true;
      break;
    }
    if (!std::isfinite(rnorm)) {
      stats_.reason = "DIVERGED_NONINVERTIBLE_DEFORMATION";
      break;
    }
    if (it >= max_it) {
      stats_.reason = "DIVERGED_MAX_IT";
      break;
    }
    unsigned long long h;
    PetscCall(ActiveSetHash(next, h));
    if (gcounts[1] > 0 && it > 0) {
      const auto repeats = std::count(seen.begin(), seen.end(), h);
      if (repeats >= (large ? 3 : 1)) {
        stats_.reason = "DIVERGED_CYCLING";
        break;
      }
    }
    seen.push_back(h);
    active_ = next;

    {
      ScopedTimer t(stats_.time_assembly);
      PetscCall(PetscLogEventBegin(EV_ASSEMBLY, 0, 0, 0, 0));
      if (large || !k_assembled_) {
        PetscCall(MatZeroEntries(system_.A()));
        PetscCall(assembler_->Assemble(u_local_.data(), system_.A(), kscale_, nullptr, nullptr));
        PetscCall(MatAssemblyBegin(system_.A(), MAT_FLUSH_ASSEMBLY));
        PetscCall(MatAssemblyEnd(system_.A(), MAT_FLUSH_ASSEMBLY));
        if (system_.ReusesFactorization()) PetscCall(system_.AddAugmentation(rows_));
        k_assembled_ = true;
      }
      PetscCall(system_.SetConstraints(rows_, active_, -1.0 / kscale_));
      // Right-hand side: f - F_int on free rows, 0 on Dirichlet rows, the current gap on active multiplier rows.
      PetscScalar *b;
      const PetscScalar *fi, *fe;
      PetscCall(VecGetArray(system_.Rhs(), &b));
      PetscCall(VecGetArrayRead(fint_, &fi));
      PetscCall(VecGetArrayRead(fext_, &fe));
      for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) b[i] = fe[i] - fi[i];
      if (moving) {
        PetscCall(VecZeroEntries(fdir_));
        PetscCall(assembler_->AddStiffnessTimes(u_local_.data(), delta.data(), fdir_));
        const PetscScalar *fd;
        PetscCall(VecGetArrayRead(fdir_, &fd));
        for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) b[i] -= fd[i];
        PetscCall(VecRestoreArrayRead(fdir_, &fd));
      }
      for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
        if (mesh_.Owned(v))
          for (int k = 0; k < dim; ++k)
            if (dirichlet_.fixed[v * dim + k]) b[dofs_.LocalOffset(v, k)] = kscale_ * delta[v * dim + k];
      for (std::size_t p = 0; p < pairs_.size(); ++p) b[dofs_.OwnedU() + p] = active_[p] ? states_[p].gap : 0.0;
      PetscCall(VecRestoreArrayRead(fint_, &fi));
      PetscCall(VecRestoreArrayRead(fext_, &fe));
      PetscCall(VecRestoreArray(system_.Rhs(), &b));
      PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
    }
    {
      ScopedTimer t(stats_.time_solve);
      const double t0 = MPI_Wtime();
      PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
      PetscCall(system_.Solve(krylov, solve_residual));
      PetscCall(PetscLogEventEnd(EV_SOLVE, 0, 0, 0, 0));
      const double dt = MPI_Wtime() - t0;
      PetscCallMPI(MPI_Allreduce(&dt, &last_solve_time, 1, MPI_DOUBLE, MPI_MAX, comm));
    }
    stats_.solves++;
    stats_.active_set_iterations++;
    stats_.krylov_iterations += krylov;
    double step;
    PetscCall(UpdateSolution(rnorm, step));
    // What a shortened step left of the prescribed increment comes in the next solve; a full step lands exactly.
    for (double &d : delta) d *= 1.0 - step;
    if (step == 1.0) PetscCall(SetDirichlet(factor));
  }
  PetscFunctionReturn(0);
}

} // namespace signorini

namespace signorini {

PetscErrorCode ContactSolver::UpdateSolution(double r0, double &step) {
  const bool large = material_.model == MaterialModel::SVK;
  const PetscInt nu = dofs_.OwnedU();
  std::vector<double> new_lambda(pairs_.size());
  PetscFunctionBeginUser;
  const PetscScalar *x;
  PetscCall(VecGetArrayRead(system_.Solution(), &x));
  for (std::size_t p = 0; p < pairs_.size(); ++p) new_lambda[p] = x[nu + p];
  PetscCall(VecRestoreArrayRead(system_.Solution(), &x));
  PetscCall(VecCopy(u_, du_));
  // Step length: halved while det F <= 0 somewhere (always); with -newton_linesearch, the line search of Crisfield
  // along du on g(s) = du . R(u + s du, lambda): g(0) = -du.K du < 0, a full step is kept unless it overshoots
  // (g(1) > 0.8 |g(0)|), then the secant step; at most 8 trials.
  const PetscScalar *dx;
  PetscCall(VecGetArrayRead(system_.Solution(), &dx));
  std::vector<double> dir(dx, dx + nu);
  PetscCall(VecRestoreArrayRead(system_.Solution(), &dx));
  double g0 = 0;
  if (large && opts_.line_search) {
    double r, scale;
    EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_local_.data(), states_, rows_,
                  normals_);
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g0));
  }
  double s = 1.0;
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
    if (!large || k == 8) break;
    double r, scale, g;
    EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_local_.data(), states_, rows_,
                  normals_);
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g));
    PetscCall(PetscInfo(nullptr, "line search: step %g g(s)/g(0) %g residual %g (before %g)\n", s, g / g0, r, r0));
    if (!std::isfinite(r)) {
      // Safeguard, always on: det F <= 0 somewhere, halve the step.
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

PetscErrorCode ContactSolver::Solve(const std::function<PetscErrorCode(PetscInt, double)> &step_done) {
  MPI_Comm comm = mesh_.Comm();
  const bool large = material_.model == MaterialModel::SVK;
  PetscFunctionBeginUser;
  VecH u_saved;
  PetscCall(VecDuplicate(u_, u_saved.out()));
  PetscCall(VecCopy(u_, u_saved));
  std::vector<double> lambda_saved = lambda_;
  std::vector<char> active_saved = active_;
  double t = 0, dt = 1.0 / opts_.load_steps;
  PetscInt step = 0;
  while (t < 1.0 - 1e-12) {
    const double t_try = std::min(1.0, t + dt);
    bool ok;
    PetscCall(LoadStep(step + 1, t_try, step == 0, ok));
    if (contact_.converged_reason)
      PetscCall(PetscPrintf(comm, "Contact solve %s: %s at load factor %g after %" PetscInt_FMT " solve(s)\n",
                            ok ? "converged" : "diverged", stats_.reason.c_str(), t_try, stats_.solves));
    if (ok) {
      t = t_try;
      ++step;
      stats_.steps = step;
      PetscCall(VecCopy(u_, u_saved));
      lambda_saved = lambda_;
      active_saved = active_;
      PetscCall(step_done(step, t));
      continue;
    }
    const std::string &why = stats_.reason;
    const char *what = why == "DIVERGED_CYCLING" ? "the active set cycles (an earlier active set came back)"
                       : why == "DIVERGED_NONINVERTIBLE_DEFORMATION"
                           ? "the deformation became non-invertible (det F <= 0)"
                           : "the active-set/Newton loop reached its iteration limit (-contact_max_it, -newton_max_it)";
    PetscCheck(large && stats_.cuts < opts_.max_cuts, comm, PETSC_ERR_NOT_CONVERGED,
               "the contact solve did not converge at load factor %g: %s%s", t_try, what,
               large ? "; no more load-step cuts allowed (-load_max_cuts)" : "");
    stats_.cuts++;
    dt *= 0.5;
    PetscCall(PetscPrintf(comm, "Load step at factor %g failed (%s); cutting the increment to %g\n", t_try,
                          why.c_str(), dt));
    PetscCall(VecCopy(u_saved, u_));
    PetscCall(UpdateLocal());
    lambda_ = lambda_saved;
    active_ = active_saved;
  }
  // Final state of the pairs for the results.
  EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_local_.data(), states_, rows_,
                normals_);
  for (std::size_t p = 0; p < pairs_.size(); ++p) states_[p].lambda = lambda_[p], states_[p].active = active_[p];
  double rnorm, rscale;
  PetscCall(Residual(lambda_, rnorm, rscale));
  PetscFunctionReturn(0);
}

} // namespace signorini
