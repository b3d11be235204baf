// The load-step / active-set / Newton loop.
#include "signorini/solver/contact_solver.hpp"

#include "signorini/core/progress.hpp"

#include "signorini/core/options.hpp"
#include "signorini/solver/solver_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace signorini {

namespace {

/// The smallest det F of an invertible deformation. A cell that a trial step squeezes to within round-off of zero
/// volume has a det F of about 1e-16 whose sign round-off decides: the same trial state was invertible on two ranks and
/// not on one, and the two took different paths (svk, seeds 4242 cases 101 and 163; test
/// rank_independence:svk_degenerate_cell). It counts as non-invertible on any number of ranks.
constexpr double MIN_DET_F = 1e-10;
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

PetscErrorCode ReadSolverOptions(MPI_Comm comm, MaterialModel model, SolverOptions &opts) {
  // Ranges (README): a relative residual above 1e-4 or an absolute one above 1e-6 (force units) would accept a
  // visibly unconverged state; the counts are bounded so that a typo cannot start a run that never ends.
  const RealRange rtol{0, SolverOptions::NEWTON_RTOL_MAX, true, false}, atol{0, SolverOptions::NEWTON_ATOL_MAX};
  PetscBool max_cuts_set = PETSC_FALSE, max_it_set = PETSC_FALSE, line_search_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Load stepping and Newton-Raphson", "signorini");
  PetscCall(OptionsInt(PetscOptionsObject, "-load_steps", "Number of load increments", 1, SolverOptions::LOAD_STEPS_MAX,
                       opts.load_steps));
  PetscCall(OptionsInt(PetscOptionsObject, "-load_max_cuts", "Halvings allowed for a failed load increment (svk)", 0,
                       SolverOptions::LOAD_MAX_CUTS_MAX, opts.max_cuts, &max_cuts_set));
  PetscCall(OptionsInt(PetscOptionsObject, "-newton_max_it", "Newton iterations per load step (svk; at most "
                       "-contact_max_it of them change the active set)", 1,
                       SolverOptions::NEWTON_MAX_IT_MAX, opts.newton_max_it, &max_it_set));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_rtol", "Residual tolerance relative to the force scale", rtol,
                        opts.newton_rtol));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_atol", "Absolute residual tolerance (force units)", atol,
                        opts.newton_atol));
  PetscCall(PetscOptionsBool("-newton_linesearch",
                             "svk: line search on du.R(u + s du) (det F <= 1e-10 always halves the step)", "",
                             opts.line_search, &opts.line_search, &line_search_set));
  PetscCall(PetscOptionsBool("-newton_lagged_search",
                             "svk with the kept factorisation (-contact_reuse_factorization): while the active set "
                             "changes and the residual halves per step, a Newton step searches the active set in the "
                             "multiplier space with the factored tangent (modified Newton: one forward and one "
                             "backward pass); once it settles, inexact Newton steps with the current tangent (FGMRES "
                             "to a residual of min(0.1, ||R||/scale) ||R||); false: exact Newton at every iteration",
                             "", opts.lagged_search, &opts.lagged_search, &opts.lagged_search_set));
  PetscOptionsEnd();
  // The linear material solves a load step by the active-set loop alone (-contact_max_it) and never cuts one: these
  // would be ignored.
  if (model != MaterialModel::SVK) {
    PetscCheck(!max_cuts_set, comm, PETSC_ERR_USER_INPUT,
               "-load_max_cuts %" PetscInt_FMT " applies to -material_model svk only (the linear material never cuts a "
               "load step)", opts.max_cuts);
    PetscCheck(!max_it_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_max_it %" PetscInt_FMT " applies to -material_model svk only (the linear material's "
               "iterations are bounded by -contact_max_it)", opts.newton_max_it);
    PetscCheck(!line_search_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_linesearch %s applies to -material_model svk only", opts.line_search ? "true" : "false");
    PetscCheck(!opts.lagged_search_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_lagged_search %s applies to -material_model svk only, with the kept factorisation "
               "(-contact_reuse_factorization with a MUMPS LU or Cholesky solver)",
               opts.lagged_search ? "true" : "false");
  }
  // The saddle-point solver's PETSc options, before its KSP reads them (and before the mesh is read).
  PetscCall(CheckSolverOptionValues(comm));
  PetscFunctionReturn(0);
}

namespace {

PairIndex IndexPairs(const std::vector<ContactPair> &pairs) {
  PairIndex index;
  for (std::size_t p = 0; p < pairs.size(); ++p) index[{pairs[p].vertex, pairs[p].facet}] = p;
  return index;
}

/// Linear material: a pair's zone is fixed in the reference configuration (EvaluatePairs: inside = zone0), so a pair
/// outside it can never be active. Dropping it keeps a fine obstacle mesh (a node within the search radius of many
/// facets) from adding a multiplier, an identity row and a stabilising spring per facet.
void DropOutOfZone(std::vector<ContactPair> &pairs) {
  pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [](const ContactPair &p) { return !p.zone0; }), pairs.end());
}

} // namespace

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
  PetscCall(FindContactPairs(mesh_, obstacle_, contact_, dirichlet_.fixed, pairs_, candidate_, nullptr, &held_));
  if (material_.model != MaterialModel::SVK) DropOutOfZone(pairs_);
  PetscCall(dofs_.Create(mesh_, (PetscInt)pairs_.size()));
  assembler_ = std::make_unique<Assembler>(mesh_, material_, dofs_, dirichlet_);
  PetscCall(assembler_->CheckCells());
  PetscCall(assembler_->StiffnessScale(kscale_));
  u_local_.assign(mesh_.NumLocalVertices() * dim, 0.0);
  paired_at_ = u_local_;
  PetscCall(CreateSystem());
  lambda_.assign(pairs_.size(), 0.0);
  mult_.assign(pairs_.size(), 0.0);
  active_set_.Reset(pairs_.size());
  PetscCall(rigid_.Setup(mesh_, dirichlet_.fixed));
  const bool kept = system_->ReusesFactorization() || dofs_.GlobalLambda() == 0;
  PetscCheck(!(opts_.lagged_search_set && opts_.lagged_search && !kept), comm, PETSC_ERR_USER_INPUT,
             "-newton_lagged_search needs -material_model svk and the kept factorisation (-contact_reuse_factorization "
             "with a MUMPS LU or Cholesky solver)");
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CreateSystem() {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  // Coordinates of the owned vertices in dof order, for the rigid-body modes.
  std::vector<double> coords(dofs_.OwnedU());
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) coords[dofs_.LocalOffset(v, k)] = mesh_.X(v)[k];
  EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, false, u_local_.data(), states_, rows_,
                normals_);
  std::vector<PetscInt> d_nnz, o_nnz;
  PetscCall(assembler_->PatternCounts(d_nnz, o_nnz));
  system_ = std::make_unique<SaddlePointSystem>();
  PetscCall(system_->Create(dofs_, rows_, coords, material_.model != MaterialModel::SVK, kscale_, d_nnz, o_nnz,
                            [&](Mat A) { return assembler_->InsertPattern(A); }));
  if (opts_.lagged_search_set && opts_.lagged_search) system_->KeepFactorization();
  k_assembled_ = false;
  PetscCall(MatCreateVecs(system_->A(), u_.out(), nullptr));
  PetscCall(VecDuplicate(u_, du_.out()));
  PetscCall(VecDuplicate(u_, fext_.out()));
  PetscCall(VecDuplicate(u_, fint_.out()));
  fint_at_.clear();
  fdir_.Reset(); // made by the first step that moves a Dirichlet value
  PetscCall(PetscObjectSetName((PetscObject)u_.get(), "displacement"));
  std::vector<PetscInt> from(mesh_.NumLocalVertices() * dim);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    for (int k = 0; k < dim; ++k) from[v * dim + k] = dofs_.Row(v, k);
  ISH is_from;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)from.size(), from.data(), PETSC_COPY_VALUES, is_from.out()));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)from.size(), u_seq_.out()));
  PetscCall(VecScatterDestroy(&scatter_));
  PetscCall(VecScatterCreate(u_, is_from, u_seq_, nullptr, &scatter_));
  keys_.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    keys_[p] = {pairs_[p].vertex, mesh_.VertexOriginal(pairs_[p].vertex), pairs_[p].facet};
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Repair(const std::vector<double> &u_eval, bool force, bool &rebuilt) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  rebuilt = false;
  // Search again when a candidate node has moved more than half the search radius since the last search (or at the
  // start of a load step): the pairs then cover every facet within half the radius of every node.
  double moved = 0;
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (candidate_[v]) {
      double d2 = 0;
      for (int k = 0; k < dim; ++k) d2 += std::pow(u_eval[v * dim + k] - paired_at_[v * dim + k], 2);
      moved = std::max(moved, std::sqrt(d2));
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
  if (!force && moved <= 0.5 * contact_.search_radius) PetscFunctionReturn(0);
  std::vector<ContactPair> pairs;
  std::vector<char> candidate;
  PetscCall(FindContactPairs(mesh_, obstacle_, contact_, dirichlet_.fixed, pairs, candidate, u_eval.data()));
  paired_at_ = u_eval;
  bool same = pairs.size() == pairs_.size();
  for (std::size_t p = 0; same && p < pairs.size(); ++p)
    same = pairs[p].vertex == pairs_[p].vertex && pairs[p].facet == pairs_[p].facet;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_CXX_BOOL, MPI_LAND, mesh_.Comm()));
  if (same) {
    // The same pairs: keep their multipliers and active flags; only the start of the path moves.
    for (std::size_t p = 0; p < pairs.size(); ++p) pairs_[p] = pairs[p];
    PetscFunctionReturn(0);
  }
  const PairIndex old = IndexPairs(pairs_);
  // Pairs that are new but farther than half the radius from their node are not needed before the next search (it
  // comes before any candidate has moved half the radius): if every new pair is such, the current pairs stay (those
  // found again move the start of their path), and so do the system and its factorisation. The contact zone growing
  // into the radius at the start of every svk load step rebuilt the system each time (2D Hertz at 1M dofs: two
  // orderings, analyses and factorisations of 7-9 s).
  bool needed = false;
  for (const auto &pair : pairs)
    if (!old.count({pair.vertex, pair.facet}) && pair.g0 <= 0.5 * contact_.search_radius) needed = true;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &needed, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  if (!needed) {
    for (const auto &pair : pairs) {
      const auto it = old.find({pair.vertex, pair.facet});
      if (it != old.end()) pairs_[it->second] = pair;
    }
    PetscCall(PetscInfo(nullptr, "pair search: the new pairs are all farther than half the search radius; the pairs "
                        "stay\n"));
    PetscFunctionReturn(0);
  }
  // New pairs: carry the multiplier and the active flag of every pair that persists, then a new pattern.
  PetscCall(AdoptPairsFrom(std::move(pairs), old, lambda_, mult_, active_set_.Flags()));
  stats_.repairings++;
  rebuilt = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AdoptPairs(std::vector<ContactPair> pairs, const std::vector<double> &lambda,
                                         const std::vector<double> &mult, const std::vector<char> &active) {
  PetscFunctionBeginUser;
  std::vector<double> u_owned;
  PetscCall(OwnedDisplacement(u_owned));
  pairs_ = std::move(pairs);
  PetscCall(dofs_.Create(mesh_, (PetscInt)pairs_.size()));
  PetscCall(CreateSystem());
  PetscCall(SetOwnedDisplacement(u_owned));
  lambda_ = lambda, mult_ = mult;
  active_set_.Reset(pairs_.size());
  active_set_.Set(active);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AdoptPairsFrom(std::vector<ContactPair> pairs, const PairIndex &old,
                                             const std::vector<double> &lambda, const std::vector<double> &mult,
                                             const std::vector<char> &active) {
  std::vector<double> l(pairs.size(), 0.0), m(pairs.size(), 0.0);
  std::vector<char> a(pairs.size(), 0);
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto it = old.find({pairs[p].vertex, pairs[p].facet});
    if (it != old.end()) l[p] = lambda[it->second], m[p] = mult[it->second], a[p] = active[it->second];
  }
  PetscCall(AdoptPairs(std::move(pairs), l, m, a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::OwnedDisplacement(std::vector<double> &u) const {
  const PetscScalar *a;
  PetscFunctionBeginUser;
  // The displacement rows come first on every rank, in an order that does not depend on the pairs.
  PetscCall(VecGetArrayRead(u_, &a));
  u.assign(a, a + dofs_.OwnedU());
  PetscCall(VecRestoreArrayRead(u_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SetOwnedDisplacement(const std::vector<double> &u) {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(u_, &a));
  std::copy(u.begin(), u.end(), a);
  PetscCall(VecRestoreArray(u_, &a));
  PetscCall(UpdateLocal());
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
  // F_int is assembled again only when the displacement changed since the last assembly (svk: the step length check
  // of UpdateSolution evaluates the residual at the new iterate, which the next iteration starts from).
  bool same = fint_at_ == u_local_;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_CXX_BOOL, MPI_LAND, mesh_.Comm()));
  if (same) {
    min_J = fint_min_J_;
  } else {
    PetscCall(VecZeroEntries(fint_));
    PetscCall(assembler_->Assemble(u_local_.data(), nullptr, 0, fint_, &min_J));
    fint_at_ = u_local_;
    fint_min_J_ = min_J;
  }
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
  norm = std::isfinite(min_J) && min_J > MIN_DET_F ? std::sqrt(gs[0]) : INFINITY;
  scale = std::sqrt(gs[1]);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Monitor(const IterationRecord &r) const {
  PetscFunctionBeginUser;
  ProgressNote("step %" PetscInt_FMT " iteration %" PetscInt_FMT ": %" PetscInt_FMT " active pairs, %" PetscInt_FMT
               " changed", r.step, r.iteration, r.active, r.changed);
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
  const bool large = material_.model == MaterialModel::SVK;
  StepState st{step, factor, first, large};
  PetscFunctionBeginUser;
  st.exact_newton = exact_newton_;
  ok = false;
  // The increment of the prescribed displacements enters through the first solve of the step (its Dirichlet rows
  // and the coupling K_fd du_d of the free rows), not by moving the boundary nodes alone, which could invert the
  // cells next to them under large prescribed displacements.
  st.delta.assign(u_local_.size(), 0.0);
  st.u_eval.resize(u_local_.size());
  st.next.assign(pairs_.size(), 0);
  for (std::size_t i = 0; i < st.delta.size(); ++i)
    if (dirichlet_.fixed[i]) st.delta[i] = factor * dirichlet_.value[i] - u_local_[i];
  PetscCall(VecZeroEntries(fext_));
  PetscCall(assembler_->AssembleLoads(bc_, factor, fext_));
  PetscReal load_scale;
  PetscCall(VecNorm(fext_, NORM_INFINITY, &load_scale));
  active_set_.BeginStep(load_scale);
  widen_to_ = 0;
  unheld_detail_.clear();
  PetscInt it = 0;
  for (;; ++it) {
    PetscInt changes = 0;
    PetscCall(EvaluateIterate(st, it));
    {
      // Active-set update: first the pairs touching at the start, then the complementarity rule (ActiveSet).
      ScopedTimer t(stats_.time_active_set);
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        states_[p].lambda = lambda_[p];
        states_[p].active = active_set_.Flags()[p];
      }
      if (it == 0) active_set_.First(states_, first, keys_, normals_, st.next);
      else PetscCall(active_set_.Next(states_, it, keys_, normals_, st.next, changes));
    }
    Outcome outcome;
    PetscCall(StepControl(st, it, changes, outcome));
    if (outcome == Outcome::STOP && !st.singular && st.pivoted < 2 &&
        (stats_.reason == "DIVERGED_CYCLING" || stats_.reason == "DIVERGED_NOT_HELD" ||
         stats_.reason == "DIVERGED_MAX_IT")) {
      // The rule's sets cycled, or the body seemed free: the linear material's last resort, a finite method (again
      // after a set that came back was pivoted: the sets from it may have cycled, or not held the body). Out of
      // iterations, only its verdict on the body counts.
      Pivot pivot;
      PetscCall(PivotedActiveSet(st, it, stats_.reason.c_str(), pivot));
      if (pivot == Pivot::UNHELD) stats_.reason = "DIVERGED_NOT_HELD";
      else if (pivot == Pivot::SET && stats_.reason != "DIVERGED_MAX_IT") {
        outcome = Outcome::SOLVE, changes = 1;
        stats_.reason.clear();
      }
    }
    st.searching = it == 0 || changes > 0;
    if (outcome == Outcome::CONVERGED) ok = true;
    if (outcome == Outcome::CONVERGED || outcome == Outcome::STOP) break;
    if (outcome == Outcome::EXTENDED) continue;
    active_set_.Set(st.next);
    bool held;
    PetscCall(rigid_.Held(keys_, normals_, st.next, held));
    st.stabilised = !held;
    PetscCall(AssembleSystem(st));
    PetscCall(SolveAndUpdate(st));
    if (st.singular) break;
  }
  // A factorisation found null pivots: the supports and the candidate pairs do not hold the body, or the MUMPS controls
  // call regular pivots null (the step may be repeated with the pairs of a wider radius, UnpairedAfterFailure).
  if (st.singular) stats_.reason = "DIVERGED_SINGULAR";
  if (!ok) PetscCall(UnpairedAfterFailure(st, it));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::PivotedActiveSet(StepState &st, PetscInt it, const char *why, Pivot &pivot) {
  PetscFunctionBeginUser;
  pivot = Pivot::NONE;
  if (st.large || st.moving || !system_->ExactFactorization() || dofs_.GlobalLambda() > LCP_MAX_ROWS)
    PetscFunctionReturn(0);
  st.pivoted++;
  // The problem from the current iterate: the gaps and F_int there (a condensed iterate is expanded first), the
  // right-hand side f - F_int with no active row, condensed onto the multipliers: the base of the condensed solves
  // that follow (the next solve's active set only changes the multiplier rows).
  if (st.condensed) PetscCall(Materialise(st, it));
  PetscCall(Residual(lambda_, st.rnorm, st.rscale));
  st.next.assign(pairs_.size(), 0);
  st.stabilised = false;
  st.base = false;
  PetscCall(AssembleSystem(st));
  LcpStatus status = LcpStatus::PIVOT_LIMIT;
  int pivots = 0;
  double unbalanced = 0;
  {
    ScopedTimer t(stats_.time_solve);
    PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
    PetscCall(CondenseBase(st));
    if (system_->ExactFactorization() && !st.singular) {
      std::vector<double> gap(pairs_.size()), key(pairs_.size());
      const double nf = (double)obstacle_.facets.size() + 1;
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        gap[p] = states_[p].gap;
        key[p] = (double)keys_[p].original * nf + (double)keys_[p].facet;
      }
      PetscCall(system_->ContactLcp(gap, key, st.next, status, pivots, unbalanced));
    }
    PetscCall(PetscLogEventEnd(EV_SOLVE, 0, 0, 0, 0));
  }
  if (st.singular) PetscFunctionReturn(0);
  PetscInt active = 0;
  for (char a : st.next) active += a;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &active, 1, MPIU_INT, MPI_SUM, mesh_.Comm()));
  PetscCall(PetscInfo(nullptr, "%s after %d iterations: the complementarity problem in the multipliers: %s after %d "
                      "pivots, %" PetscInt_FMT " active, %g of the load along rigid motions unbalanced\n", why,
                      (int)it, LcpStatusName(status), pivots, active, unbalanced));
  stats_.pivoted_sets++;
  if (status != LcpStatus::SOLVED) PetscFunctionReturn(0);
  if (unbalanced > LCP_UNHELD) {
    pivot = Pivot::UNHELD;
    st.pivoted = 2; // the verdict stands for this step
    char text[256];
    std::snprintf(text, sizeof(text),
                  "no contact forces on its %" PetscInt_FMT " candidate pairs balance the load (the complementarity "
                  "problem leaves %.2g of it along rigid-body motions unbalanced)",
                  dofs_.GlobalLambda(), unbalanced);
    unheld_detail_ = text;
    PetscFunctionReturn(0);
  }
  // The step goes on from that set with the usual rule, its earlier sets forgotten.
  pivot = Pivot::SET;
  active_set_.Restart();
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UnpairedAfterFailure(StepState &st, PetscInt it) {
  const bool large = material_.model == MaterialModel::SVK;
  PetscFunctionBeginUser;
  widen_to_ = 0;
  if (stats_.reason == "DIVERGED_NONINVERTIBLE_DEFORMATION" || stats_.search_widenings >= MAX_WIDENINGS)
    PetscFunctionReturn(0);
  // The displacement of the step's last iterate (a condensed search keeps it at its base until it is expanded; a
  // singular refactorisation left nothing to expand).
  if (st.condensed && !st.singular) PetscCall(Materialise(st, it));
  Penetration unpaired, prescribed;
  std::vector<std::array<PetscInt, 2>> found;
  double reach;
  PetscCall(DeepestUnpaired(mesh_, obstacle_, contact_, candidate_, held_, dirichlet_.fixed, pairs_, st.u_eval.data(),
                            unpaired, prescribed, &found, &reach));
  // A set that cycles or leaves the body free may lack the facets that would hold it, beyond the radius: such a step
  // is repeated once with a radius of at least the body's diagonal (a block pushed towards an inclined wall 0.1 away
  // cycled with the default radius and converged with 0.3; a body that nothing holds then says so,
  // DIVERGED_NOT_HELD, where it cycled before).
  // svk cuts the load step first (a smaller increment is the usual cure of a cycle, and its pairs within the whole
  // diagonal would be many: the svk punch cut once in 1.5 s, and took 14.6 s with such a radius).
  const bool can_cut = large && stats_.cuts < opts_.max_cuts && stats_.reason != "DIVERGED_NOT_HELD";
  const bool unheld = (stats_.reason == "DIVERGED_CYCLING" || stats_.reason == "DIVERGED_NOT_HELD") && !can_cut;
  const bool penetrates = unpaired.depth > contact_.gap_tol;
  // A singular system (null pivots) with pairs found within less than the body's diagonal: the facets that would
  // hold the body may be beyond the radius (a block 0.05 above the floor of its notch, searched within 0.01, had
  // pairs with its side wall alone). Only pairs within the whole diagonal that leave it singular say it is not held.
  const bool singular = stats_.reason == "DIVERGED_SINGULAR" && contact_.search_radius < contact_.length &&
                        !obstacle_.facets.empty();
  if (!penetrates && !(unheld && !widened_unheld_) && !singular) PetscFunctionReturn(0);
  // A node that went into the obstacle farther than the radius reaches, or started there deeper than it: the radius
  // must cover the candidates' displacements, with room for the repeated step to move them on. The linear material
  // also gets the pairs of the facets its nodes went into: a facet within the radius whose zone did not hold the
  // node in the reference configuration has no pair, however wide the radius (a block pushed 0.3 sideways by its
  // supports went 0.1 into a wall unseen while its corner was paired with the floor).
  // (Without a penetration the displacement of a cycling or free iterate is no measure of the travel.)
  const double radius =
      std::min(penetrates ? std::max({2 * contact_.search_radius, 2 * reach, 2 * unpaired.depth})
                          : std::max(2 * contact_.search_radius, contact_.length),
               SEARCH_RADIUS_MAX * contact_.length);
  bool more = !large && !found.empty();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &more, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  if (radius <= contact_.search_radius && !more) PetscFunctionReturn(0);
  if (!large) extra_pairs_.insert(found.begin(), found.end());
  widen_to_ = std::max(radius, contact_.search_radius);
  widen_node_ = penetrates ? unpaired.node : -1;
  widen_depth_ = unpaired.depth;
  // A repeat for a free or singular body is made once: the pairs within the diagonal that still leave it free say so.
  if (!penetrates && (unheld || singular)) widened_unheld_ = true, first_unheld_ = stats_.reason;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::WidenSearch(const std::vector<double> &lambda, const std::vector<double> &mult,
                                          const std::vector<char> &active) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  contact_.search_radius = widen_to_;
  stats_.search_widenings++;
  if (material_.model == MaterialModel::SVK) {
    // svk searches its pairs again at the start of every load step (Repair), now with the wider radius.
    PetscCall(AdoptPairs(pairs_, lambda, mult, active));
    PetscFunctionReturn(0);
  }
  std::vector<ContactPair> pairs;
  std::vector<char> candidate;
  PetscCall(FindContactPairs(mesh_, obstacle_, contact_, dirichlet_.fixed, pairs, candidate));
  DropOutOfZone(pairs);
  // The facets the nodes went into count in their zone from now on (the gap g0 + n0 u of the reference
  // configuration, exact for a flat facet).
  const PairIndex found = IndexPairs(pairs);
  for (const auto &[v, f] : extra_pairs_) {
    if (found.count({v, f})) continue;
    const double *X = mesh_.X(v);
    const Projection pr = obstacle_.facets[f]->Project(X, contact_.alpha_tol, contact_.length);
    ContactPair pair{v, f, {pr.normal[0], pr.normal[1], pr.normal[2]}, pr.gap, pr.inside, true, {0, 0, 0}};
    for (int k = 0; k < dim; ++k) pair.x0[k] = X[k];
    pairs.push_back(pair);
  }
  SortPairs(mesh_, pairs);
  PetscCall(AdoptPairsFrom(std::move(pairs), IndexPairs(pairs_), lambda, mult, active));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::EvaluateIterate(StepState &st, PetscInt it) {
  ScopedTimer t(stats_.time_assembly);
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(EV_ASSEMBLY, 0, 0, 0, 0));
  st.moving = false;
  for (double d : st.delta) st.moving = st.moving || d != 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &st.moving, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  // Gaps with the prescribed displacements in place (the constraint rows hold only the free components).
  for (std::size_t i = 0; i < st.u_eval.size(); ++i) st.u_eval[i] = u_local_[i] + st.delta[i];
  if (st.condensed) {
    // The gaps after a condensed solve: the base's plus the normal displacement of the increment (the zone, the
    // normals and the constraint rows of the linear material do not move).
    for (std::size_t p = 0; p < pairs_.size(); ++p) states_[p].gap = st.g_base[p] + st.shift[p];
    st.rnorm = st.solve_residual;
    st.rscale = 0;
    PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  if (st.large) {
    // svk: pairs from the current configuration (new pairs mean a new pattern and a new analysis).
    bool rebuilt;
    PetscCall(Repair(st.u_eval, it == 0, rebuilt));
    if (rebuilt) {
      // A new layout: no base of a condensed search survives it.
      st.base = false;
      st.u_base.Reset();
      st.next.assign(pairs_.size(), 0);
      st.measured = false;
      PetscCall(VecZeroEntries(fext_));
      PetscCall(assembler_->AssembleLoads(bc_, st.factor, fext_));
    }
  }
  EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, st.large, st.u_eval.data(), states_,
                rows_, normals_);
  if (st.large || it == 0 || st.stabilised) {
    PetscCall(Residual(lambda_, st.rnorm, st.rscale));
  } else {
    // Linear material after a solve: K du was solved for exactly (to the solve's residual), so F_int = f + B^T x on
    // the free rows (x: the solved multipliers), without a pass over the cells; the monitor shows the solve's
    // residual. A state that may be the solution gets a full residual evaluation (StepControl).
    PetscScalar *fi;
    const PetscScalar *fe;
    fint_at_.clear();
    PetscCall(VecGetArray(fint_, &fi));
    PetscCall(VecGetArrayRead(fext_, &fe));
    for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) fi[i] = fe[i];
    for (std::size_t p = 0; p < pairs_.size(); ++p)
      for (int k = 0; k < dim; ++k) fi[dofs_.LocalOffset(pairs_[p].vertex, k)] += mult_[p] * normals_[p][k];
    PetscCall(VecRestoreArrayRead(fext_, &fe));
    PetscCall(VecRestoreArray(fint_, &fi));
    st.rnorm = st.solve_residual;
    st.rscale = 0;
  }
  PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::StepControl(StepState &st, PetscInt it, PetscInt &changes, Outcome &outcome) {
  PetscFunctionBeginUser;
  outcome = Outcome::SOLVE;
  // Once the set has cycled (one switch per update), svk switches a pair only at an equilibrium of the current set:
  // the multipliers and gaps that choose it are then those of the set's solution, not of a Newton iterate on its way
  // there (svk's block in the notch toggled one pair between a tensile multiplier and a penetration while the
  // residual stayed at 4e-4).
  bool deferred = false; // svk: a switch put off until an equilibrium (below): not a state to judge the body by
  if (st.large && changes > 0 && active_set_.OneAtATime() && !(st.rnorm <= EquilibriumTol(st.rscale))) {
    st.next = active_set_.Flags();
    changes = 0;
    deferred = true;
  }
  // An active set that comes back would cycle. svk with lagged searches first drops them for the rest of the step
  // (their stale tangent can lead the set round); then, as the linear material does at once, the updates switch one
  // pair at a time (ActiveSet::SwitchOneAtATime). A set that comes back after that ends the step (DIVERGED_CYCLING).
  const bool lagging = st.large && opts_.lagged_search && system_->ReusesFactorization() && !st.exact_newton;
  if (it > 0 && changes > 0 && std::isfinite(st.rnorm) && (lagging || !active_set_.OneAtATime())) {
    bool back;
    PetscCall(active_set_.Seen(st.next, keys_, st.large ? 3 : 1, back, false));
    if (back && lagging) {
      st.exact_newton = true;
      active_set_.Forget();
      PetscCall(PetscInfo(nullptr, "the active set came back: exact Newton steps from now on in this load step\n"));
    } else if (back) {
      // The linear material solves its complementarity problem first (PivotedActiveSet, finite), the first time.
      bool found = false;
      if (!st.large && st.pivoted == 0) {
        const std::vector<char> current = active_set_.Flags(), next = st.next;
        Pivot pivot;
        PetscCall(PivotedActiveSet(st, it, "the active set came back", pivot));
        if (st.singular) {
          outcome = Outcome::STOP;
          PetscFunctionReturn(0);
        }
        if (pivot == Pivot::UNHELD) {
          // No contact forces on these pairs hold the body (the step may then be repeated with wider pairs).
          stats_.reason = "DIVERGED_NOT_HELD";
          outcome = Outcome::STOP;
          PetscFunctionReturn(0);
        }
        found = pivot == Pivot::SET;
        PetscInt differ = 0;
        for (std::size_t p = 0; p < current.size() && found; ++p) differ += current[p] != st.next[p];
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPIU_INT, MPI_SUM, mesh_.Comm()));
        // Its solution's set is the current one, which the rule would change: nothing new to go on from.
        found = found && differ > 0;
        if (found) changes = differ;
        else st.next = next;
      }
      if (!found) {
        PetscCall(active_set_.SwitchOneAtATime(states_, keys_, st.next, changes));
        PetscCall(
            PetscInfo(nullptr, "the active set came back: one switch per update from now on in this load step\n"));
      }
    }
  }
  if (changes > 0) st.candidate_rnorm = -1, st.stalled_corrections = 0; // a new active set: not a correction's
  if (it > 0) {
    PetscCall(RecordIteration(st.step, it, st.factor, st.next, changes, st.krylov, st.rnorm, st.last_solve_time));
    // A state that may be the solution: certified, or the loop goes on (svk: Newton; linear: one more solve corrects
    // an equilibrium residual left by an inexact solver) or stops with the violated condition.
    if (changes == 0 && !st.moving && !st.stabilised) {
      if (st.condensed) PetscCall(Materialise(st, it));
      if (!st.large) PetscCall(Residual(lambda_, st.rnorm, st.rscale));
      const double tol = EquilibriumTol(st.rscale);
      PetscCall(PetscInfo(nullptr, "candidate state: equilibrium residual %g (tolerance %g)\n", st.rnorm, tol));
      if (st.rnorm <= tol || !st.large) {
        Certificate cert;
        PetscCall(Certify(st.u_eval, st.rnorm, tol, cert));
        if (cert.Satisfied()) {
          certificate_ = cert;
          stats_.reason = st.large ? "CONVERGED_ACTIVE_SET_AND_RESIDUAL" : "CONVERGED_ACTIVE_SET_UNCHANGED";
          outcome = Outcome::CONVERGED;
          PetscFunctionReturn(0);
        }
        if (cert.equilibrium <= cert.equilibrium_tol) {
          stats_.reason = "DIVERGED_CERTIFICATE";
          stats_.violation = cert.Violation();
          outcome = Outcome::STOP;
          PetscFunctionReturn(0);
        }
      }
      // Linear material, the state certified but for its equilibrium residual (an iterative solver's): the next
      // solve keeps the active set and only has to bring the residual below the tolerance. It starts from this
      // state's multipliers, so its start's residual is about this one, and it may stop at a tenth of the tolerance
      // instead of -contact_ksp_rtol relative to that start (the certificate checks the result again). 2D Hertz,
      // fieldsplit_gamg, 1M dofs: 46 Krylov iterations of the correction solve before. A correction that did not
      // reach the tolerance (its start's residual was not this one) is followed by a solve to the KSP's tolerance.
      if (!st.large && st.rnorm > tol) {
        // Corrections that no longer halve the residual cannot reach the tolerance: the solves are as accurate as
        // the system's conditioning lets them be (e.g. a nearly incompressible material). A correction that started
        // from another residual is followed by a solve to the KSP's tolerance (below), so the loop stops only when
        // that one does not halve the residual either.
        const bool halved = st.candidate_rnorm <= 0 || st.rnorm <= 0.5 * st.candidate_rnorm;
        st.stalled_corrections = halved ? 0 : st.stalled_corrections + 1;
        if (st.stalled_corrections >= 2) {
          stats_.reason = "DIVERGED_EQUILIBRIUM_STALLED";
          char text[256];
          std::snprintf(text, sizeof(text), "%g after two correction solves, %g before them, tolerance %g", st.rnorm,
                        st.candidate_rnorm, tol);
          stats_.violation = text;
          outcome = Outcome::STOP;
          PetscFunctionReturn(0);
        }
        if (halved) st.candidate_rnorm = st.rnorm;
        st.correction_rtol = st.corrected ? 0.0 : 0.1 * tol / st.rnorm;
      }
    }
    if (st.stabilised && changes == 0 && !deferred && st.measured) {
      // The springs let the body move along the rigid motions its active set leaves free, and no pair closed. Where
      // the body goes is the free rigid part of the solve's displacement (RigidModes::FreeMotion), not the whole of
      // it: the elastic deformation of the step moves nodes by amounts unrelated to that, and a pair it brought a
      // little nearer used to stretch the step by a huge factor (a block pushed away from its only wall along a
      // frictionless floor then cycled instead of being reported free). If that motion brings some pair to close on
      // its facet, the body is moved along it past the point where the nearest such pair closes (once more the
      // motion beyond it), so that the next update activates it; if none, the load moves the body away from every
      // obstacle (a block on a disc held at two nodes rolls about the disc's centre, which closes no pair on it). A
      // pair closes on its facet: linear material, in its zone (fixed); svk, where the node's path meets the facet's
      // plane projects onto the facet (a node beside the foot of an inclined wall enters its zone as it slides
      // towards it). A touching pair (gap 0) that the motion drives in closes at once.
      const int dim = mesh_.Dim();
      std::vector<double> du(u_local_.size());
      for (std::size_t i = 0; i < du.size(); ++i) du[i] = u_local_[i] - st.u_before[i];
      std::array<double, 6> motion;
      PetscCall(rigid_.FreeMotion(keys_, normals_, active_set_.Flags(), du.data(), motion));
      const double size = rigid_.Magnitude(motion);
      double reach = INFINITY;
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        const double *X = mesh_.X(keys_[p].vertex);
        const double closing = -rigid_.Along(X, normals_[p].data(), motion);
        if (!(closing > CLOSING * size && states_[p].gap >= 0)) continue;
        const double t = states_[p].gap / closing;
        bool on_facet = states_[p].InZone();
        if (st.large) {
          double x[3] = {0, 0, 0};
          rigid_.Motion(X, motion, x);
          for (int k = 0; k < dim; ++k) x[k] = X[k] + u_local_[keys_[p].vertex * dim + k] + t * x[k];
          on_facet = obstacle_.facets[pairs_[p].facet]->Project(x, contact_.alpha_tol, contact_.length).inside;
        }
        if (on_facet) reach = std::min(reach, t);
      }
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &reach, 1, MPI_DOUBLE, MPI_MIN, mesh_.Comm()));
      PetscCall(PetscInfo(nullptr, "stabilised state: free rigid motion of size %g, nearest pair closes at %g of it\n",
                          size, reach));
      if (!std::isfinite(reach) || reach > 1e12) {
        stats_.reason = "DIVERGED_NOT_HELD";
        outcome = Outcome::STOP;
      } else {
        // The next check, when the move closes no pair, is made without a solve in between: it must see the same
        // solve's motion, so the move shifts the displacement it is measured from (u_before) as well.
        const std::vector<double> before = u_local_;
        PetscCall(MoveRigidly(motion, 1 + 2 * reach));
        for (std::size_t i = 0; i < u_local_.size(); ++i) st.u_before[i] += u_local_[i] - before[i];
        outcome = Outcome::EXTENDED;
      }
      PetscFunctionReturn(0);
    }
  }
  // Linear material: every iteration is an active-set iteration. svk: every iteration is a Newton step, at most
  // -newton_max_it of them, and at most -contact_max_it of them may change the active set.
  if (changes > 0) ++st.set_changes;
  const bool limit = st.large ? it >= opts_.newton_max_it || st.set_changes > contact_.max_it : it >= contact_.max_it;
  bool cycling = false;
  if (std::isfinite(st.rnorm) && !limit) PetscCall(active_set_.Seen(st.next, keys_, st.large ? 3 : 1, cycling));
  if (!std::isfinite(st.rnorm)) stats_.reason = "DIVERGED_NONINVERTIBLE_DEFORMATION";
  else if (limit) stats_.reason = "DIVERGED_MAX_IT";
  else if (cycling && changes > 0 && it > 0) stats_.reason = "DIVERGED_CYCLING";
  else PetscFunctionReturn(0);
  outcome = Outcome::STOP;
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
  // A lagged step is a condensed search (SolveAndUpdate): its later iterations (st.base) keep it.
  if (!(st.large && st.base)) {
    const bool contracting = st.lag_rnorm < 0 || st.rnorm <= LAGGED_CONTRACTION * st.lag_rnorm;
    const bool lag = st.large && opts_.lagged_search && st.searching && !st.stabilised &&
                     !st.exact_newton && !active_set_.OneAtATime() && system_->ReusesFactorization();
    st.lagged = lag && contracting;
    st.lag_rnorm = st.rnorm;
    // A lagged step that did not contract: the factored tangent has drifted too far to precondition the current one.
    if (lag && !contracting) system_->RefactorNext();
  } else if (st.stabilised || st.exact_newton) {
    st.lagged = false; // the search is left (Condensable): a full solve from the base with the current tangent
  }
  if ((st.large && !st.lagged) || !k_assembled_) {
    ProgressBegin("stiffness assembly");
    PetscCall(MatZeroEntries(system_->Stiffness()));
    PetscCall(assembler_->Assemble(u_local_.data(), system_->Stiffness(), kscale_, nullptr, nullptr));
    PetscCall(MatAssemblyBegin(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
    PetscCall(MatAssemblyEnd(system_->Stiffness(), MAT_FLUSH_ASSEMBLY));
    if (system_->Augmented()) PetscCall(system_->AddAugmentation(rows_));
    k_assembled_ = true;
    ProgressEnd();
  }
  PetscCall(system_->SetConstraints(rows_, st.next, -1.0 / kscale_, st.stabilised ? STABILISATION * kscale_ : 0.0));
  if (Condensable(st)) {
    // The base's right-hand side with the new active set: its displacement rows stay, the gaps are the base's.
    PetscScalar *b;
    PetscCall(VecGetArray(system_->Rhs(), &b));
    for (std::size_t p = 0; p < pairs_.size(); ++p) b[dofs_.OwnedU() + p] = st.next[p] ? st.g_base[p] : 0.0;
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
  PetscCall(VecRestoreArrayRead(fint_, &fi));
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  PetscCall(VecRestoreArray(system_->Rhs(), &b));
  PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::NewtonForcing(const StepState &st, double &rtol) const {
  PetscFunctionBeginUser;
  // svk with the kept factorisation and the lagged search: an inexact Newton step. A linear residual of
  // eta ||R||, eta = min(SEARCH_RTOL, ||R|| / scale), keeps Newton's quadratic convergence (Dembo, Eisenstat and
  // Steihaug 1982). None needs to go below half the equilibrium tolerance: so close to the solution the quadratic
  // term is far below it (2D Hertz, 195k dofs, svk: a quarter instead of a half took 4 more preconditioner
  // applications). The KSP's tolerance is relative to the right-hand side, which carries the whole contact force (the
  // solve is for the multipliers, not their increments).
  // Once the active set has cycled (ActiveSet::SwitchOneAtATime), every step is exact: one pair switches per step,
  // and the gaps and multipliers that choose it must be those of the current set's solution.
  rtol = 0;
  if (!(opts_.lagged_search && system_->ReusesFactorization()) || active_set_.OneAtATime() || !(st.rnorm > 0) ||
      !(st.rscale > 0))
    PetscFunctionReturn(0);
  const double eta = std::min(SEARCH_RTOL, std::max(0.5 * EquilibriumTol(st.rscale) / st.rnorm, st.rnorm / st.rscale));
  PetscReal bnorm;
  PetscCall(VecNorm(system_->Rhs(), NORM_2, &bnorm));
  if (bnorm > 0) rtol = std::min(SEARCH_RTOL, eta * st.rnorm / bnorm);
  PetscFunctionReturn(0);
}

bool ContactSolver::Condensable(const StepState &st) const {
  if (!st.base || st.stabilised || !system_->ReusesFactorization()) return false;
  return st.large ? st.lagged : system_->ExactFactorization();
}

PetscErrorCode ContactSolver::SolveAndUpdate(StepState &st) {
  PetscFunctionBeginUser;
  bool condensed;
  {
    ScopedTimer t(stats_.time_solve);
    const double t0 = MPI_Wtime();
    PetscCall(PetscLogEventBegin(EV_SOLVE, 0, 0, 0, 0));
    const bool search = st.large ? st.lagged && system_->ReusesFactorization() : system_->ExactFactorization();
    // Linear material, kept factorisation, no stabilisation and no prescribed displacement still to apply: the
    // right-hand side assembled now is the base of the solves after it, which run in the multiplier space (condensed)
    // until Materialise.
    if (!st.base && !st.stabilised && !st.moving && search) PetscCall(CondenseBase(st));
    condensed = Condensable(st);
    if (st.singular) {
      // The condensation found null pivots: nothing to solve (LoadStep ends the step).
    } else if (condensed) {
      std::vector<double> bm(pairs_.size());
      for (std::size_t p = 0; p < pairs_.size(); ++p) bm[p] = st.next[p] ? st.g_base[p] : 0.0;
      PetscCall(system_->SolveCondensed(bm, lambda_, st.shift, st.solve_residual));
      mult_ = lambda_;
      st.krylov = 1;
    } else {
      // A full solve moves the displacement away from any base.
      st.base = false;
      double rtol = st.lagged ? SEARCH_RTOL : st.correction_rtol;
      if (st.large && !st.lagged) PetscCall(NewtonForcing(st, rtol));
      PetscCall(system_->Solve(st.krylov, st.solve_residual, st.singular, rtol));
      st.corrected = st.correction_rtol > 0;
      st.correction_rtol = 0;
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
  st.condensed = condensed;
  if (condensed) PetscFunctionReturn(0);
  double step_length;
  PetscCall(UpdateSolution(st.rnorm, st.stabilised, step_length));
  // What a shortened step left of the prescribed increment comes in the next solve; a full step lands exactly.
  for (double &d : st.delta) d *= 1.0 - step_length;
  if (step_length == 1.0) PetscCall(SetDirichlet(st.factor));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CondenseBase(StepState &st) {
  PetscFunctionBeginUser;
  if (!st.u_base) PetscCall(VecDuplicate(u_, st.u_base.out()));
  PetscCall(VecCopy(u_, st.u_base));
  st.g_base.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p) st.g_base[p] = states_[p].gap;
  PetscCall(system_->Condense(st.singular));
  if (st.singular) PetscFunctionReturn(0);
  st.base = true;
  st.base_rnorm = st.rnorm;
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
  PetscCall(VecCopy(st.u_base, u_));
  double step_length;
  PetscCall(UpdateSolution(st.base_rnorm, false, step_length));
  st.condensed = false;
  // The expansion used up the condensed right-hand side: a solve after it (svk: the next Newton step; linear: a
  // correction of an equilibrium residual the certificate refused) condenses again or solves in full.
  st.base = false;
  PetscCall(EvaluateIterate(st, it));
  for (std::size_t p = 0; p < pairs_.size(); ++p) states_[p].lambda = lambda_[p];
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Certify(const std::vector<double> &u_eval, double rnorm, double tol, Certificate &cert) {
  PetscFunctionBeginUser;
  PetscCall(active_set_.Certify(states_, keys_, normals_, rnorm, tol, cert));
  // The pairs cover the nodes that were within the search radius: a node that was not and went through the obstacle
  // would otherwise pass unseen.
  Penetration unpaired, prescribed;
  PetscCall(DeepestUnpaired(mesh_, obstacle_, contact_, candidate_, held_, dirichlet_.fixed, pairs_, u_eval.data(),
                            unpaired, prescribed));
  cert.unpaired_penetration = unpaired.depth;
  cert.unpaired_node = unpaired.node;
  std::copy(unpaired.x, unpaired.x + 3, cert.unpaired_x);
  cert.search_radius = contact_.search_radius;
  // No solve can lift a node whose normal motion the supports prescribe: the input contradicts itself.
  PetscCheck(prescribed.depth <= cert.gap_tol, mesh_.Comm(), PETSC_ERR_USER_INPUT,
             "candidate node %" PetscInt_FMT " (at %g, %g, %g) is held by -bc_dirichlet inside the obstacle, by %g "
             "(gap tolerance %g); expected prescribed displacements that keep the contact candidates out of the "
             "obstacle",
             prescribed.node, prescribed.x[0], prescribed.x[1], prescribed.x[2], prescribed.depth, cert.gap_tol);
  PetscFunctionReturn(0);
}

double ContactSolver::EquilibriumTol(double scale) const {
  // The absolute part may not exceed 1e-6 of the force scale: an absolute tolerance as large as a small load would
  // otherwise accept any state.
  return opts_.newton_rtol * scale + std::min(opts_.newton_atol, 1e-6 * scale);
}

PetscErrorCode ContactSolver::MoveRigidly(const std::array<double, 6> &motion, double t) {
  const int dim = mesh_.Dim();
  PetscScalar *u;
  PetscFunctionBeginUser;
  // u += t m(x) a on the owned displacement rows; a free mode moves no fixed component (its Dirichlet rows are in
  // the Gram matrix whose null space it is), which are skipped all the same.
  PetscCall(VecGetArray(u_, &u));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) {
    if (!mesh_.Owned(v)) continue;
    double m[3];
    rigid_.Motion(mesh_.X(v), motion, m);
    for (int k = 0; k < dim; ++k)
      if (!dirichlet_.fixed[v * dim + k]) u[dofs_.LocalOffset(v, k)] += t * m[k];
  }
  PetscCall(VecRestoreArray(u_, &u));
  PetscCall(UpdateLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::RecordIteration(PetscInt step, PetscInt it, double factor, const std::vector<char> &next,
                                              PetscInt changes, PetscInt krylov, double rnorm, double solve_time) {
  // Active pairs of the next solve; min lambda over the current active set; deepest penetration in a pair's zone.
  PetscInt count = 0, gcount;
  double m[2] = {INFINITY, 0}, gm[2];
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    count += next[p];
    if (states_[p].active) m[0] = std::min(m[0], lambda_[p]);
    if (states_[p].InZone()) m[1] = std::max(m[1], -states_[p].gap);
  }
  m[0] = -m[0];
  PetscCallMPI(MPI_Allreduce(&count, &gcount, 1, MPIU_INT, MPI_SUM, mesh_.Comm()));
  PetscCallMPI(MPI_Allreduce(m, gm, 2, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
  const IterationRecord rec{step, it, gcount, changes, krylov, factor, std::isfinite(gm[0]) ? -gm[0] : 0.0,
                            gm[1], rnorm, solve_time};
  stats_.history.push_back(rec);
  PetscCall(Monitor(rec));
  PetscFunctionReturn(0);
}

} // namespace signorini

namespace signorini {

PetscErrorCode ContactSolver::UpdateSolution(double r0, bool stabilised, double &step) {
  const bool large = material_.model == MaterialModel::SVK;
  const PetscInt nu = dofs_.OwnedU();
  std::vector<double> new_lambda(pairs_.size());
  const std::vector<char> &active = active_set_.Flags();
  PetscFunctionBeginUser;
  const PetscScalar *x;
  PetscCall(VecGetArrayRead(system_->Solution(), &x));
  // The solved multipliers: contact forces on active rows, stabilisation springs on inactive ones.
  for (std::size_t p = 0; p < pairs_.size(); ++p) mult_[p] = x[nu + p], new_lambda[p] = active[p] ? x[nu + p] : 0.0;
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
  if (large && opts_.line_search) {
    double r, scale;
    EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_local_.data(), states_, rows_,
                  normals_);
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g0));
  }
  double s = 1.0;
  if (large && stabilised) {
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
    if (!large || k == 8) break;
    double r, scale, g;
    EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, large, u_local_.data(), states_, rows_,
                  normals_);
    PetscCall(Residual(new_lambda, r, scale, dir.data(), &g));
    PetscCall(PetscInfo(nullptr, "line search: step %g g(s)/g(0) %g residual %g (before %g)\n", s, g / g0, r, r0));
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

PetscErrorCode ContactSolver::Solve(const std::function<PetscErrorCode(PetscInt, double)> &step_done) {
  MPI_Comm comm = mesh_.Comm();
  const bool large = material_.model == MaterialModel::SVK;
  PetscFunctionBeginUser;
  std::vector<double> u_saved;
  PetscCall(OwnedDisplacement(u_saved));
  std::vector<ContactPair> pairs_saved = pairs_;
  std::vector<double> lambda_saved = lambda_, mult_saved = mult_;
  std::vector<char> active_saved = active_set_.Flags();
  double t = 0, dt = 1.0 / opts_.load_steps;
  PetscInt step = 0;
  bool exact_repeat = false; // svk: this attempt repeats a step found free after lagged searches (below)
  while (t < 1.0 - 1e-12) {
    const double t_try = std::min(1.0, t + dt);
    bool ok;
    PetscCall(LoadStep(step + 1, t_try, step == 0, ok));
    if (contact_.converged_reason)
      PetscCall(PetscPrintf(comm, "Contact solve %s: %s at load factor %g after %" PetscInt_FMT " solve(s)\n",
                            ok ? "converged" : "diverged", stats_.reason.c_str(), t_try, stats_.solves));
    if (ok) {
      exact_repeat = false;
      t = t_try;
      ++step;
      stats_.steps = step;
      PetscCall(OwnedDisplacement(u_saved));
      pairs_saved = pairs_;
      mult_saved = mult_;
      lambda_saved = lambda_;
      active_saved = active_set_.Flags();
      // After the last solve the factorisation or preconditioner goes before the last step's output (1M dofs in 2D:
      // MUMPS's factors 1.35 GB, fieldsplit_gamg's blocks and hierarchy 0.36 GB).
      if (t >= 1.0 - 1e-12) PetscCall(system_->Release());
      PetscCall(step_done(step, t));
      continue;
    }
    // The repeat with exact Newton steps (below) that fails otherwise leaves the finding it was to check: not held.
    if (exact_repeat) stats_.reason = "DIVERGED_NOT_HELD", widen_to_ = 0;
    if (widen_to_ > 0) {
      // A candidate went into a facet it has no pair with: the step is repeated, from the last converged state, with
      // pairs found within a wider radius (linear material: and that pair; not a cut: the increment stays).
      if (widen_node_ >= 0)
        PetscCall(PetscPrintf(comm, "Load step at factor %g failed (%s) with node %" PetscInt_FMT " %g inside the "
                              "obstacle, on a facet it has no contact pair with: searching the pairs again within %g "
                              "(was %g)\n", t_try, stats_.reason.c_str(), widen_node_, widen_depth_, widen_to_,
                              contact_.search_radius));
      else
        PetscCall(PetscPrintf(comm, "Load step at factor %g failed (%s): searching the pairs again within %g (was %g), "
                              "for facets beyond the radius that may hold the body\n", t_try, stats_.reason.c_str(),
                              widen_to_, contact_.search_radius));
      PetscCall(SetOwnedDisplacement(u_saved));
      k_assembled_ = false;
      pairs_ = pairs_saved;
      PetscCall(WidenSearch(lambda_saved, mult_saved, active_saved));
      pairs_saved = pairs_;
      lambda_saved = lambda_;
      mult_saved = mult_;
      active_saved = active_set_.Flags();
      continue;
    }
    // svk: a body found free at the end of the lagged searches' path may be held. Their stale tangent and the
    // stabilised moves along the free rigid motion can carry the iterate to where its free motion does lead away from
    // every obstacle: an svk block tipping on a disc towards a wall (seed 4242, case 270) was moved off the wall and
    // past its balance on the disc, from where the load rolls it off, while exact Newton steps converge without a
    // stabilised solve. Before that verdict, the step is repeated once, from the last converged state, with exact
    // Newton steps (as after a set that came back), and so are the load steps after it; a repeat that fails
    // otherwise ends the run with the first finding.
    const bool lagged = opts_.lagged_search && system_->ReusesFactorization();
    if (large && stats_.reason == "DIVERGED_NOT_HELD" && lagged && !exact_newton_) {
      exact_newton_ = true;
      exact_repeat = true;
      PetscCall(PetscPrintf(comm, "Load step at factor %g failed (%s) after lagged Newton searches: repeating it with "
                            "exact Newton steps\n", t_try, stats_.reason.c_str()));
      PetscCall(SetOwnedDisplacement(u_saved));
      k_assembled_ = false;
      PetscCall(AdoptPairs(pairs_saved, lambda_saved, mult_saved, active_saved));
      continue;
    }
    // A body found free, then repeated with the facets of a wider radius, stays free when the repeat fails otherwise
    // (it cycles or runs out of iterations): the first finding is the clearer report. Not when the repeat's
    // deformation became non-invertible before any verdict: the wider pairs may hold the body (an svk block on a disc
    // beside an inclined wall, found free with the pairs of the default radius, is held by the wall's: seed 777 case
    // 136) or not (seed 777 case 56), so the report is the deformation, with both facts.
    const bool fatal = !(large && stats_.cuts < opts_.max_cuts);
    const bool deformed = stats_.reason == "DIVERGED_NONINVERTIBLE_DEFORMATION";
    std::string context;
    if (first_unheld_ == "DIVERGED_NOT_HELD" && stats_.reason != first_unheld_ && fatal) {
      if (!deformed) stats_.reason = first_unheld_;
      else {
        char text[200];
        std::snprintf(text, sizeof(text), " (the body was found not held with the pairs of a narrower radius; "
                      "repeated with those within %g, it deformed so before it could be found held or not)",
                      contact_.search_radius);
        context = text;
      }
    }
    const std::string &why = stats_.reason;
    // A singular system is no matter of the increment: never cut.
    const bool singular = why == "DIVERGED_SINGULAR";
    char within[128] = "the supports (there is no obstacle)";
    if (!obstacle_.facets.empty())
      std::snprintf(within, sizeof(within), "the supports and the candidate pairs within -contact_search_radius %g",
                    contact_.search_radius);
    const std::string what =
        singular
            ? system_->SingularReport(std::string("the body is not held by ") + within +
                                      "; add Dirichlet conditions (e.g. on a symmetry line) or candidate contact "
                                      "nodes so that every rigid-body motion is removed")
        : why == "DIVERGED_CYCLING"
            ? "the active set cycles (an earlier set came back, also with one pair switched per update); a body held "
              "only by contact at a point it can rock about (e.g. a block on a disc) cycles so: check that the "
              "supports and obstacles hold every rigid-body motion"
        : why == "DIVERGED_NONINVERTIBLE_DEFORMATION" ? "the deformation became non-invertible (det F <= 1e-10)" + context
        : why == "DIVERGED_NOT_HELD"
            ? (unheld_detail_.empty()
                   ? std::string("the body is not held: along a rigid-body motion that the supports and the active "
                                 "contact leave free, the load moves it away from every obstacle")
                   : "the body is not held: " + unheld_detail_) +
                  " (add Dirichlet conditions, or check the obstacle's position and orientation and "
                  "-contact_search_radius)"
        : why == "DIVERGED_CERTIFICATE"
            ? "the state is not a contact solution (" + stats_.violation + ") and the active-set rule cannot change it"
        : why == "DIVERGED_EQUILIBRIUM_STALLED"
            ? "the equilibrium residual stalls above its tolerance (" + stats_.violation + "): the solver cannot "
              "resolve the system more accurately (ill-conditioned, e.g. -material_nu near 0.5; or an iterative "
              "solver's tolerance); loosen -newton_rtol or use a direct solver"
        : large ? "the Newton loop reached its iteration limit (-newton_max_it Newton iterations, of which at most "
                  "-contact_max_it change the active set)"
                : "the active-set loop reached its iteration limit (-contact_max_it)";
    PetscCheck(large && stats_.cuts < opts_.max_cuts && why != "DIVERGED_NOT_HELD" && !singular, comm,
               PETSC_ERR_NOT_CONVERGED, "the contact solve did not converge at load factor %g: %s: %s%s", t_try,
               why.c_str(), what.c_str(),
               large && !singular ? "; no more load-step cuts allowed (-load_max_cuts)" : "");
    stats_.cuts++;
    dt *= 0.5;
    PetscCall(PetscPrintf(comm, "Load step at factor %g failed (%s); cutting the increment to %g\n", t_try,
                          why.c_str(), dt));
    PetscCall(SetOwnedDisplacement(u_saved));
    // The tangent of the failed attempt is not lagged into the next one.
    k_assembled_ = false;
    bool differ = pairs_.size() != pairs_saved.size() ||
                  !std::equal(pairs_.begin(), pairs_.end(), pairs_saved.begin(),
                              [](const ContactPair &a, const ContactPair &b) {
                                return a.vertex == b.vertex && a.facet == b.facet;
                              });
    // Collective decision: the pairs may have changed on some ranks only.
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_CXX_BOOL, MPI_LOR, comm));
    if (differ) PetscCall(AdoptPairs(pairs_saved, lambda_saved, mult_saved, active_saved));
    pairs_ = pairs_saved;
    lambda_ = lambda_saved;
    mult_ = mult_saved;
    active_set_.Set(active_saved);
  }
  stats_.search_radius = contact_.search_radius;
  // The final state is the last converged step's, whose pairs (states_), internal force (fint_) and certificate
  // StepControl left as they are.
  PetscCheck(certificate_.Satisfied(), comm, PETSC_ERR_NOT_CONVERGED,
             "the final state is not a contact solution: %s", certificate_.Violation().c_str());
  PetscFunctionReturn(0);
}

} // namespace signorini
