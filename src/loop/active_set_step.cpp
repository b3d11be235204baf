// The contact solver per active-set iteration: the pairs and residual at the iterate (EvaluateIterate), the step's
// control (certificate, stabilisation, stopping reasons), the complementarity problem as a last resort
// (PivotedActiveSet) and the repeated steps with the pairs a failed one lacked (UnpairedAfterFailure, WidenSearch).
#include "signorini/loop/contact_solver.hpp"

#include "contact_solver_detail.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace signorini {

using namespace detail;


namespace {

/// The finding that the pairs cannot hold the body, for the DIVERGED_NOT_HELD message: format with the candidate pairs'
/// count and the unbalanced fraction.
std::string UnheldDetail(const char *format, PetscInt pairs, double unbalanced) {
  char text[256];
  std::snprintf(text, sizeof(text), format, pairs, unbalanced);
  return text;
}

} // namespace

PetscErrorCode ContactSolver::PivotedActiveSet(StepState &st, PetscInt it, const char *why, Pivot &pivot) {
  PetscFunctionBeginUser;
  pivot = Pivot::NONE;
  if (!model_->Pivots() || st.moving || !system_->ExactFactorization() || dofs_.GlobalLambda() > LCP_MAX_ROWS)
    PetscFunctionReturn(0);
  st.pivoted++;
  // The problem from the current iterate: the gaps and F_int there (a condensed iterate is expanded first), the
  // right-hand side f - F_int with no active row, condensed onto the multipliers: the base of the condensed solves
  // that follow (the next solve's active set only changes the multiplier rows).
  if (st.base.condensed) PetscCall(Materialise(st, it));
  PetscCall(Residual(lambda_, st.r.norm, st.r.scale, nullptr, nullptr, &st.r.roundoff));
  st.next.assign(pairs_.size(), 0);
  st.stabilised = false;
  st.base.ready = false;
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
      const double nf = (double)(obstacle_.facets.size() + mortar_.Interfaces()) + 1;
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
                      "pivots, %" PetscInt_FMT " active, %.6g of the load along rigid motions unbalanced\n", why,
                      (int)it, LcpStatusName(status), pivots, active, unbalanced));
  stats_.pivoted_sets++;
  if (status != LcpStatus::SOLVED) PetscFunctionReturn(0);
  if (unbalanced > LCP_UNHELD) {
    pivot = Pivot::UNHELD;
    st.pivoted = 2; // the verdict stands for this step
    retry_.unheld_detail = UnheldDetail("no contact forces on its %" PetscInt_FMT " candidate pairs balance the load (the "
                                        "complementarity problem leaves %.2g of it along rigid-body motions "
                                        "unbalanced)", dofs_.GlobalLambda(), unbalanced);
    PetscFunctionReturn(0);
  }
  // The step goes on from that set with the usual rule, its earlier sets forgotten.
  pivot = Pivot::SET;
  active_set_.Restart();
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UnbalancedLoad(bool &unheld) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  unheld = false;
  if (friction_.On() || !system_->Iterative() || dofs_.GlobalLambda() == 0) PetscFunctionReturn(0);
  // A rigid motion that the supports and every candidate pair leave free is the singular system's verdict, as on the
  // direct path (DIVERGED_SINGULAR, SolveAndUpdate's check).
  bool held;
  PetscCall(Held(std::vector<char>(pairs_.size(), 1), held));
  if (!held) PetscFunctionReturn(0);
  std::vector<double> f(u_local_.size(), 0.0);
  const PetscScalar *fe;
  PetscCall(VecGetArrayRead(fext_, &fe));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) f[v * dim + k] = fe[dofs_.LocalOffset(v, k)];
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  double unbalanced;
  PetscCall(rigid_.Unbalanced(keys_, normals_, f.data(), unbalanced));
  PetscCall(PetscInfo(nullptr, "load step start: %.6g of the load along the free rigid motions unbalanced by any "
                      "non-negative forces on the %" PetscInt_FMT " candidate pairs\n", unbalanced,
                      dofs_.GlobalLambda()));
  if (!(unbalanced > LCP_UNHELD)) PetscFunctionReturn(0);
  unheld = true;
  retry_.unheld_detail = UnheldDetail("no non-negative contact forces on its %" PetscInt_FMT " candidate pairs balance "
                                      "the load (%.2g of it along rigid-body motions that the supports leave free is "
                                      "left unbalanced)", dofs_.GlobalLambda(), unbalanced);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UnpairedAfterFailure(StepState &st, PetscInt it) {
  PetscFunctionBeginUser;
  retry_.widen_to = 0;
  if (stats_.reason == Reason::DIVERGED_NONINVERTIBLE_DEFORMATION || stats_.search_widenings >= MAX_WIDENINGS)
    PetscFunctionReturn(0);
  // The displacement of the step's last iterate (a condensed search keeps it at its base until it is expanded; a
  // singular refactorisation left nothing to expand).
  if (st.base.condensed && !st.singular) PetscCall(Materialise(st, it));
  Penetration unpaired, prescribed;
  std::vector<std::array<PetscInt, 2>> found;
  double reach;
  PetscCall(DeepestUnpaired(mesh_, obstacle_, contact_, candidate_, held_, dirichlet_.fixed, pairs_, st.u_eval.data(),
                            unpaired, prescribed, &found, &reach));
  // A set that cycles or leaves the body free may lack the facets that would hold it, beyond the radius: such a step
  // is repeated once with a radius of at least the body's diagonal (a block pushed towards an inclined wall beyond
  // the default radius cycles with it and converges with the wall's pairs; a body that nothing holds then says so,
  // DIVERGED_NOT_HELD, instead of cycling).
  // svk cuts the load step first (a smaller increment is the usual cure of a cycle, and its pairs within the whole
  // diagonal would be many and slow).
  const bool can_cut =
      model_->Nonlinear() && stats_.cuts < opts_.max_cuts && stats_.reason != Reason::DIVERGED_NOT_HELD;
  const bool unheld =
      (stats_.reason == Reason::DIVERGED_CYCLING || stats_.reason == Reason::DIVERGED_NOT_HELD) && !can_cut;
  const bool penetrates = unpaired.depth > contact_.gap_tol;
  // A singular system (null pivots) with pairs found within less than the body's diagonal: the facets that would
  // hold the body may be beyond the radius (a block 0.05 above the floor of its notch, searched within 0.01, had
  // pairs with its side wall alone). Only pairs within the whole diagonal that leave it singular say it is not held.
  const bool singular = stats_.reason == Reason::DIVERGED_SINGULAR && contact_.search_radius < contact_.length &&
                        !obstacle_.facets.empty();
  if (!penetrates && !(unheld && !retry_.widened_unheld) && !singular) PetscFunctionReturn(0);
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
  bool more = !model_->CurrentConfiguration() && !found.empty();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &more, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  if (radius <= contact_.search_radius && !more) PetscFunctionReturn(0);
  if (!model_->CurrentConfiguration()) retry_.extra_pairs.insert(found.begin(), found.end());
  retry_.widen_to = std::max(radius, contact_.search_radius);
  retry_.widen_node = penetrates ? unpaired.node : -1;
  retry_.widen_depth = unpaired.depth;
  // A repeat for a free or singular body is made once: the pairs within the diagonal that still leave it free say so.
  if (!penetrates && (unheld || singular)) retry_.widened_unheld = true, retry_.first_unheld = stats_.reason;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::WidenSearch(const std::vector<double> &lambda, const std::vector<double> &mult,
                                          const std::vector<char> &active) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  contact_.search_radius = retry_.widen_to;
  stats_.search_widenings++;
  if (model_->CurrentConfiguration()) {
    // svk searches its pairs again at the start of every load step (Repair), now with the wider radius.
    PetscCall(AdoptPairs(pairs_, lambda, mult, active));
    PetscFunctionReturn(0);
  }
  std::vector<ContactPair> pairs;
  std::vector<char> candidate;
  PetscCall(FindAllPairs(pairs, candidate));
  DropOutOfZone(pairs);
  // The facets the nodes went into count in their zone from now on (the gap g0 + n0 u of the reference
  // configuration, exact for a flat facet).
  const PairIndex found = IndexPairs(pairs);
  for (const auto &[v, f] : retry_.extra_pairs) {
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
  if (st.base.condensed) {
    // The gaps after a condensed solve: the base's plus the normal displacement of the increment (the zone, the
    // normals and the constraint rows of the linear material do not move).
    for (std::size_t p = 0; p < pairs_.size(); ++p)
      states_[p].gap = st.base.g[p] + st.base.shift[p];
    st.r.norm = st.solve_residual;
    st.r.scale = 0, st.r.roundoff = 0;
    PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  if (model_->CurrentConfiguration()) {
    // svk: pairs from the current configuration (new pairs mean a new pattern and a new analysis), the mortar rows
    // of the pairs of bodies computed again there.
    bool rebuilt, repaired;
    PetscCall(UpdateMortar(st.u_eval, rebuilt));
    PetscCall(Repair(st.u_eval, it == 0, repaired));
    rebuilt = rebuilt || repaired;
    if (rebuilt) {
      // A new layout: no base of a condensed search survives it.
      st.base.ready = false;
      st.base.u.Reset();
      st.next.assign(pairs_.size(), 0);
      st.measured = false;
      PetscCall(VecZeroEntries(fext_));
      PetscCall(assembler_->AssembleLoads(bc_, st.factor, fext_));
    }
  }
  PetscCall(EvaluateAt(st.u_eval.data(), model_->CurrentConfiguration()));
  // After a loose solve the residual is evaluated in full: its equilibrium error goes into the next solve's
  // right-hand side instead of adding up over the iterations (octant Hertz at 290k dofs: 1e-3 loose solves decided
  // the set on a state wrong by their sum and converged to 1257 pairs before the correction solve showed 1528).
  if (model_->Nonlinear() || it == 0 || st.stabilised || st.loose) {
    PetscCall(Residual(lambda_, st.r.norm, st.r.scale, nullptr, nullptr, &st.r.roundoff, st.loose));
  } else {
    // Linear material after a solve: K du was solved for exactly (to the solve's residual), so F_int = f + B^T x on
    // the free rows (x: the solved multipliers), without a pass over the cells; the monitor shows the solve's
    // residual. A state that may be the solution gets a full residual evaluation (StepControl).
    PetscScalar *fi;
    const PetscScalar *fe;
    fint_at_.u.clear();
    PetscCall(VecGetArray(fint_, &fi));
    PetscCall(VecGetArrayRead(fext_, &fe));
    for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) fi[i] = fe[i];
    for (std::size_t p = 0; p < pairs_.size(); ++p)
      for (int k = 0; k < dim; ++k) fi[dofs_.LocalOffset(pairs_[p].vertex, k)] += mult_[p] * normals_[p][k];
    if (!mortar_.Empty()) {
      std::vector<double> master(dofs_.OwnedU(), 0.0);
      PetscCall(mortar_.AddMasterForces(mult_, 1, master));
      for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) fi[i] += master[i];
    }
    if (friction_.On()) PetscCall(friction_.AddForces(pairs_, 1, true, fi, dofs_.OwnedU()));
    PetscCall(VecRestoreArrayRead(fext_, &fe));
    PetscCall(VecRestoreArray(fint_, &fi));
    st.r.norm = st.solve_residual;
    st.r.scale = 0, st.r.roundoff = 0;
  }
  PetscCall(PetscLogEventEnd(EV_ASSEMBLY, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::RhsNorm(const StepState &st, double &norm) const {
  const int dim = mesh_.Dim();
  const PetscScalar *fi, *fe;
  PetscFunctionBeginUser;
  double s = 0;
  PetscCall(VecGetArrayRead(fint_, &fi));
  PetscCall(VecGetArrayRead(fext_, &fe));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[v * dim + k]) {
          const PetscInt i = dofs_.LocalOffset(v, k);
          s += (fe[i] - fi[i]) * (fe[i] - fi[i]);
        }
  PetscCall(VecRestoreArrayRead(fext_, &fe));
  PetscCall(VecRestoreArrayRead(fint_, &fi));
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    if (st.next[p]) s += states_[p].gap * states_[p].gap;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  norm = std::sqrt(s);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::RestartFromStepStart(StepState &st, PetscInt it) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  // The first solve of the first load step is held at the touching pairs alone; its displacement shows which pairs
  // go in (the first update activates them), but it is far from the answer where one pair held a body that only
  // contact holds: the octant Hertz turned about its touching node and went 4 units into the plane (a = 0.8), and
  // the next solve, from there, started from the gaps of the 1738 pairs activated, ||b|| = 165 against 0.45 for the
  // loads, and spent 19 Krylov iterations undoing it. A direct solve does not care where it starts (the linear
  // material's solution of a set is one); an iterative one starts from the step's start instead (no multipliers)
  // when the right-hand side of the next solve is smaller there: the octant at 290k dofs 0.98 against 165, 86 -> 73
  // Krylov iterations, 8 -> 7 active-set iterations; at 1.07M 99 Krylov iterations instead of 103. A cube pressed
  // by a sphere (108k dofs) restarts too (0.032 against 0.35), at the same cost (22 Krylov iterations).
  double here, there;
  PetscCall(RhsNorm(st, here));
  std::vector<double> u_here, lambda_here = lambda_, mult_here = mult_;
  PetscCall(OwnedDisplacement(u_here));
  VecH x_here;
  PetscCall(VecDuplicate(system_->Solution(), x_here.out()));
  PetscCall(VecCopy(system_->Solution(), x_here));
  std::vector<double> u = u_here;
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[v * dim + k]) {
          const PetscInt i = dofs_.LocalOffset(v, k);
          u[i] = st.u_start[i];
        }
  PetscCall(SetOwnedDisplacement(u));
  std::fill(lambda_.begin(), lambda_.end(), 0.0);
  std::fill(mult_.begin(), mult_.end(), 0.0);
  PetscCall(VecZeroEntries(system_->Solution()));
  // The full residual at the new iterate (EvaluateIterate's short form holds only after a solve from it).
  st.loose = true;
  PetscCall(EvaluateIterate(st, it));
  PetscCall(RhsNorm(st, there));
  PetscCall(PetscInfo(nullptr,
                      "first update: the next solve's ||b|| %.6g from the step's start, %.6g from the touching "
                      "pairs' solve: %s\n",
                      there, here, there < here ? "restarts from the start" : "goes on"));
  if (there < here) PetscFunctionReturn(0);
  PetscCall(SetOwnedDisplacement(u_here));
  lambda_ = lambda_here, mult_ = mult_here;
  PetscCall(VecCopy(x_here, system_->Solution()));
  PetscCall(EvaluateIterate(st, it));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::StepControl(StepState &st, PetscInt it, PetscInt &changes, Outcome &outcome) {
  bool done;
  PetscFunctionBeginUser;
  outcome = Outcome::SOLVE;
  const bool deferred = DeferSwitch(st, changes); // svk: not a state to judge the body by
  PetscCall(ActiveSetCameBack(st, it, changes, outcome, done));
  if (done) PetscFunctionReturn(0);
  if (changes > 0)
    st.correction.candidate_rnorm = -1, st.correction.stalled = 0; // a new active set: not a correction's
  if (it > 0) {
    PetscCall(RecordIteration(st.step, it, st.factor, st.next, changes, st.krylov, st.r.norm, st.last_solve_time));
    // A state that may be the solution: certified, or the loop goes on (svk: Newton; linear: one more solve corrects
    // an equilibrium residual left by an inexact solver) or stops with the violated condition.
    if (changes == 0 && st.friction_changes == 0 && st.friction_turns == 0 && !st.moving && !st.stabilised) {
      PetscCall(JudgeCandidate(st, it, outcome, done));
      if (done) PetscFunctionReturn(0);
    }
    if (st.stabilised && changes == 0 && !deferred && st.measured) {
      PetscCall(ExtendAlongFreeMotion(st, outcome));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(StopAtLimits(st, it, changes, outcome));
  PetscFunctionReturn(0);
}

bool ContactSolver::DeferSwitch(StepState &st, PetscInt &changes) const {
  // Once the set has cycled (one switch per update), svk switches a pair only at an equilibrium of the current set:
  // the multipliers and gaps that choose it are then those of the set's solution, not of a Newton iterate on its way
  // there (svk's block in the notch toggled one pair between a tensile multiplier and a penetration while the
  // residual stayed at 4e-4).
  if (model_->Nonlinear() && changes > 0 && active_set_.OneAtATime() &&
      !(st.r.norm <= EquilibriumTol(st.r.scale, st.r.roundoff))) {
    st.next = active_set_.Flags();
    changes = 0;
    return true;
  }
  return false;
}

PetscErrorCode ContactSolver::ActiveSetCameBack(StepState &st, PetscInt it, PetscInt &changes, Outcome &outcome,
                                               bool &done) {
  PetscFunctionBeginUser;
  done = false;
  // An active set that comes back would cycle. svk with lagged searches first drops them for the rest of the step
  // (their stale tangent can lead the set round); then, as the linear material does at once, the updates switch one
  // pair at a time (ActiveSet::SwitchOneAtATime). A set that comes back after that ends the step (DIVERGED_CYCLING).
  const bool lagging = model_->Nonlinear() && lagged_search_ && system_->ReusesFactorization() && !st.newton.exact;
  if (it > 0 && changes > 0 && std::isfinite(st.r.norm) && (lagging || !active_set_.OneAtATime())) {
    bool back;
    PetscCall(active_set_.Seen(SetKey(st), keys_, model_->CycleRepeats(), back, false));
    if (back && lagging) {
      st.newton.exact = true;
      active_set_.Forget();
      PetscCall(PetscInfo(nullptr, "the active set came back: exact Newton steps from now on in this load step\n"));
    } else if (back) {
      // The linear material solves its complementarity problem first (PivotedActiveSet, finite), the first time.
      bool found = false;
      if (model_->Pivots() && st.pivoted == 0) {
        const std::vector<char> current = active_set_.Flags(), next = st.next;
        Pivot pivot;
        PetscCall(PivotedActiveSet(st, it, "the active set came back", pivot));
        if (st.singular) {
          outcome = Outcome::STOP;
          done = true;
          PetscFunctionReturn(0);
        }
        if (pivot == Pivot::UNHELD) {
          // No contact forces on these pairs hold the body (the step may then be repeated with wider pairs).
          stats_.reason = Reason::DIVERGED_NOT_HELD;
          outcome = Outcome::STOP;
          done = true;
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
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::JudgeCandidate(StepState &st, PetscInt it, Outcome &outcome, bool &done) {
  PetscFunctionBeginUser;
  done = false;
  if (st.base.condensed) PetscCall(Materialise(st, it));
  if (!model_->Nonlinear()) PetscCall(Residual(lambda_, st.r.norm, st.r.scale, nullptr, nullptr, &st.r.roundoff));
  const double tol = EquilibriumTol(st.r.scale, st.r.roundoff);
  PetscCall(PetscInfo(nullptr, "candidate state: equilibrium residual %.6g (tolerance %.6g, of which round-off %.6g)\n",
                      st.r.norm, tol, st.r.roundoff));
  if (st.r.norm <= tol || !model_->Nonlinear()) {
    Certificate cert;
    PetscCall(Certify(st.u_eval, st.r.norm, tol, cert));
    if (cert.Satisfied()) {
      certificate_ = cert;
      stats_.reason = model_->ConvergedReason();
      outcome = Outcome::CONVERGED;
      done = true;
      PetscFunctionReturn(0);
    }
    if (cert.equilibrium <= cert.equilibrium_tol) {
      stats_.reason = Reason::DIVERGED_CERTIFICATE;
      stats_.violation = cert.Violation();
      outcome = Outcome::STOP;
      done = true;
      PetscFunctionReturn(0);
    }
  }
  // Linear material, the state certified but for its equilibrium residual (an iterative solver's): the next
  // solve keeps the active set and only has to bring the residual below the tolerance. It starts from this
  // state's multipliers, so its start's residual is about this one, and it may stop at a tenth of the tolerance
  // instead of -contact_ksp_rtol relative to that start (the certificate checks the result again). 2D Hertz,
  // fieldsplit_gamg, 1M dofs: 46 Krylov iterations of the correction solve before. A correction that did not
  // reach the tolerance (its start's residual was not this one) is followed by a solve to the KSP's tolerance.
  if (!model_->Nonlinear() && st.r.norm > tol) {
    // Corrections that no longer halve the residual cannot reach the tolerance: the solves are as accurate as
    // the system's conditioning lets them be (e.g. a nearly incompressible material). A correction that started
    // from another residual is followed by a solve to the KSP's tolerance (below), so the loop stops only when
    // that one does not halve the residual either.
    const bool halved = st.correction.candidate_rnorm <= 0 || st.r.norm <= 0.5 * st.correction.candidate_rnorm;
    st.correction.stalled = halved ? 0 : st.correction.stalled + 1;
    if (st.correction.stalled >= 2) {
      stats_.reason = Reason::DIVERGED_EQUILIBRIUM_STALLED;
      char text[256];
      std::snprintf(text, sizeof(text), "%.6g after two correction solves, %.6g before them, tolerance %.6g", st.r.norm,
                    st.correction.candidate_rnorm, tol);
      stats_.violation = text;
      outcome = Outcome::STOP;
      done = true;
      PetscFunctionReturn(0);
    }
    if (halved) st.correction.candidate_rnorm = st.r.norm;
    st.correction.rtol = st.correction.made ? 0.0 : 0.1 * tol / st.r.norm;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::ExtendAlongFreeMotion(StepState &st, Outcome &outcome) {
  PetscFunctionBeginUser;
  // The springs let the body move along the rigid motions its active set leaves free, and no pair closed. Where
  // the body goes is the free rigid part of the solve's displacement (RigidModes::FreeMotion), not the whole of
  // it: the elastic deformation of the step moves nodes by amounts unrelated to that, and a pair it brought a
  // little nearer would stretch the step by a huge factor (a block pushed away from its only wall along a
  // frictionless floor would cycle instead of being reported free). If that motion brings some pair to close on
  // its facet, the body is moved along it past the point where the nearest such pair closes (once more the
  // motion beyond it), so that the next update activates it; if none, the load moves the body away from every
  // obstacle (a block on a disc held at two nodes rolls about the disc's centre, which closes no pair on it). A
  // pair closes on its facet: linear material, in its zone (fixed); svk, where the node's path meets the facet's
  // plane projects onto the facet (a node beside the foot of an inclined wall enters its zone as it slides
  // towards it). A touching pair (gap 0) that the motion drives in closes at once.
  const int dim = mesh_.Dim();
  std::vector<double> du(u_local_.size());
  for (std::size_t i = 0; i < du.size(); ++i) du[i] = u_local_[i] - st.u_before[i];
  RigidMotion motion;
  // The motions the active set leaves free: with friction, its stick and slip rows hold too (as in Held, so that
  // the motion is one that the check found free, not one that friction's rows hold).
  HoldingSet holding;
  HoldingRows(active_set_.Flags(), holding);
  PetscCall(rigid_.FreeMotion(holding.keys, holding.normals, holding.flags, du.data(), motion, &holding.pair_of));
  const double size = rigid_.Magnitude(motion);
  double reach = INFINITY;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const double *X = mesh_.X(keys_[p].vertex);
    const double closing = -rigid_.PairRate(p, keys_, normals_, motion);
    if (!(closing > CLOSING * size && states_[p].gap >= 0)) continue;
    const double t = states_[p].gap / closing;
    bool on_facet = states_[p].InZone();
    // A mortar pair (a pair of bodies) has no facet to project on: its row covers the master side it overlaps.
    if (model_->CurrentConfiguration() && !mortar_.IsMortar(pairs_[p])) {
      double x[3] = {0, 0, 0};
      rigid_.Motion(keys_[p].vertex, motion, x);
      for (int k = 0; k < dim; ++k) x[k] = X[k] + u_local_[keys_[p].vertex * dim + k] + t * x[k];
      on_facet = obstacle_.facets[pairs_[p].facet]->Project(x, contact_.alpha_tol, contact_.length).inside;
    }
    if (on_facet) reach = std::min(reach, t);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &reach, 1, MPI_DOUBLE, MPI_MIN, mesh_.Comm()));
  PetscCall(PetscInfo(nullptr, "stabilised state: free rigid motion of size %.6g, nearest pair closes at %.6g of it\n",
                      size, reach));
  if (!std::isfinite(reach) || reach > 1e12) {
    stats_.reason = Reason::DIVERGED_NOT_HELD;
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

PetscErrorCode ContactSolver::StopAtLimits(StepState &st, PetscInt it, PetscInt changes, Outcome &outcome) {
  PetscFunctionBeginUser;
  // Linear material: every iteration is an active-set iteration. svk: every iteration is a Newton step, at most
  // -newton_max_it of them, and at most -contact_max_it of them may change the active set.
  if (changes > 0) ++st.set_changes;
  const bool limit =
      model_->Nonlinear() ? it >= opts_.newton_max_it || st.set_changes > contact_.max_it : it >= contact_.max_it;
  bool cycling = false;
  if (std::isfinite(st.r.norm) && !limit)
    PetscCall(active_set_.Seen(SetKey(st), keys_, model_->CycleRepeats(), cycling));
  if (!std::isfinite(st.r.norm))
    stats_.reason = Reason::DIVERGED_NONINVERTIBLE_DEFORMATION;
  else if (limit) stats_.reason = Reason::DIVERGED_MAX_IT;
  else if (cycling && changes + st.friction_changes > 0 && it > 0) stats_.reason = Reason::DIVERGED_CYCLING;
  else PetscFunctionReturn(0);
  outcome = Outcome::STOP;
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
  if (!mortar_.Empty()) PetscCall(PairForceBalance(cert));
  if (friction_.On())
    PetscCall(friction_.Certify(mesh_.Comm(), pairs_, states_, u_eval.data(), cert.lambda_tol, cert.gap_tol,
                                cert.friction));
  // No solve can lift a node whose normal motion the supports prescribe: the input contradicts itself.
  PetscCheck(prescribed.depth <= cert.gap_tol, mesh_.Comm(), PETSC_ERR_USER_INPUT,
             "candidate node %" PetscInt_FMT " (at %.6g, %.6g, %.6g) is held by -bc_dirichlet inside the obstacle, by %.6g "
             "(gap tolerance %.6g); expected prescribed displacements that keep the contact candidates out of the "
             "obstacle",
             prescribed.node, prescribed.x[0], prescribed.x[1], prescribed.x[2], prescribed.depth, cert.gap_tol);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::PairForceBalance(Certificate &cert) const {
  const int dim = mesh_.Dim();
  std::vector<double> lambda(pairs_.size(), 0.0), master;
  double sums[4] = {0, 0, 0, 0}; // slave + master force, sum |lambda|
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    if (mortar_.IsMortar(pairs_[p])) {
      lambda[p] = states_[p].lambda;
      for (int k = 0; k < dim; ++k) sums[k] += lambda[p] * normals_[p][k];
      sums[3] += std::abs(lambda[p]);
    }
  PetscCall(mortar_.MasterForces(mesh_, dofs_, lambda, master, sums));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  cert.bodies = true;
  cert.pair_force_balance = std::sqrt(sums[0] * sums[0] + sums[1] * sums[1] + sums[2] * sums[2]);
  cert.pair_force_tol = Certificate::PAIR_FORCE_RTOL * sums[3];
  PetscFunctionReturn(0);
}

double ContactSolver::EquilibriumTol(double scale, double roundoff) const {
  // The absolute part may not exceed 1e-6 of the force scale: an absolute tolerance as large as a small load would
  // otherwise accept any state. The round-off part only counts where the forces themselves are of round-off size.
  return opts_.newton_rtol * scale + std::min(opts_.newton_atol, 1e-6 * scale) + roundoff;
}

} // namespace signorini
