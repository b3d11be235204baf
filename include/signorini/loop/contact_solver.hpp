// The active-set loop (docs/theory.md §4), merged with Newton-Raphson for the nonlinear material (a semismooth
// Newton method, §5), inside load steps (§6) with step cutting. Options: -load_steps, -load_max_cuts, -newton_*.
#pragma once

#include "signorini/bc/boundary_conditions.hpp"
#include "signorini/contact/active_set.hpp"
#include "signorini/contact/constraints.hpp"
#include "signorini/contact/contact_set.hpp"
#include "signorini/contact/friction.hpp"
#include "signorini/contact/mortar.hpp"
#include "signorini/contact/rigid_modes.hpp"
#include "signorini/fem/assembly.hpp"
#include "signorini/linalg/saddle_point.hpp"
#include "signorini/loop/loop_options.hpp"
#include "signorini/loop/material_policy.hpp"
#include "signorini/loop/retry_policy.hpp"
#include "signorini/loop/solved_state.hpp"

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace signorini {

/// Index of pairs by (local vertex, facet).
using PairIndex = std::map<std::pair<PetscInt, PetscInt>, std::size_t>;

/// The contact loop over one run. Its data members (about 38) stay in one class: they are the run's state that the
/// steps of every iteration, in three files (contact_solver.cpp, active_set_step.cpp, newton_step.cpp), read and write
/// together: the problem (references to its inputs and the material policy), the pairs and their evaluation at the
/// iterate, the displacement and force vectors with their scales, and the saddle-point system. What belongs to one
/// concern is its own object or struct: the material model (MaterialPolicy), the retry policy (DecideRetry) and what
/// the failed steps left (Retries), one load step's state (StepState), where F_int was assembled (InternalForceAt).
class ContactSolver {
public:
  ContactSolver(const Mesh &mesh, const Material &material, const BoundaryConditions &bc, const Obstacle &obstacle,
                const ContactOptions &contact, const SolverOptions &solver)
      : mesh_(mesh), material_(material), model_(MakeMaterialPolicy(material.model)), bc_(bc), obstacle_(obstacle),
        contact_(contact), opts_(solver),
        active_set_(mesh.Comm(), {contact.c, contact.gap_tol, contact.touch_tol, contact.activation_fraction,
                                  contact.length, contact.activation_gap_factor}) {
    friction_.Configure(contact, obstacle);
  }

  /// Initial weight of the springs on the normals of the inactive pairs, relative to the stiffness scale, in the
  /// solves whose active set leaves a rigid-body motion free (RigidModes). They pull the increment towards the
  /// previous iterate, so they vanish at convergence, and the final solve of a load step is always made without
  /// them. When a stabilised solve closes no pair but its free rigid motion brings some nearer, the body is moved
  /// along that motion past the nearest.
  static constexpr double STABILISATION = 1e-4;
  /// A pair closes along a free rigid motion when its gap shrinks by more than this fraction of the motion's size (a
  /// pair along which the body slides, a floor under a block moving sideways, is round-off away from 0).
  static constexpr double CLOSING = 1e-9;
  /// Relative residual of a lagged (modified) Newton step of the active-set search (-newton_lagged_search) that cannot
  /// be condensed (a prescribed displacement still to apply): the step only has to find the next active set. Also
  /// the largest forcing term of the inexact Newton steps after it settles (NewtonForcing).
  static constexpr double SEARCH_RTOL = 0.1;
  /// The iterative path's solve held at a touching point (1 to TOUCHING_PAIRS pairs, first load step, linear
  /// material): its displacement only picks the first update's pairs, and the next solve usually restarts from the
  /// step's start (RestartFromStepStart), so it stops at this relative residual instead of -contact_active_set_rtol's.
  /// 0.03: at 0.1 GMRES (the iterative preset's method) stopped after 6 iterations in a state that activated 189
  /// pairs instead of 195 on the 16k octant on 2 ranks (5 active-set iterations against 4; BiCGStab's 0.1 did not).
  static constexpr double TOUCHING_RTOL = 0.03;
  /// The same with CG (the null-space preconditioner in 3D), which minimises the error's energy: at 0.1 the octant of
  /// options/hertz3d.yml at 290k dofs took 5 CG iterations instead of 7 in it and at 1.07M 7 instead of 8, the same
  /// first update and later path (1543 and 3675 pairs); at 0.2 the first update took 1457 pairs instead of 1543 at
  /// 290k, and the step 6 solves instead of 4.
  static constexpr double TOUCHING_RTOL_CG = 0.1;
  static constexpr PetscInt TOUCHING_PAIRS = 3;
  /// The residual's round-off, in units of DBL_EPSILON times ||u|| times the mean sum_j |K_ij| of a row (krow_,
  /// Residual): rigidly translated bodies leave 0.17 to 0.5 of that unit in 2D and 3D (the Lame ring at 192 to 14k
  /// dofs, hertz3d at 6k and 40k, hexahedral and tetrahedral cubes, punch_on_plate's first steps), a bent cantilever
  /// solved directly 0.27, so 10 leaves a margin of 20. It only counts where the forces are of round-off size: for the
  /// cantilever it is 4e-9 against the relative part's 1.1e-8.
  static constexpr double ROUNDOFF_FACTOR = 10;
  /// A lagged step follows only one that reduced the residual at least by this factor (else the current tangent).
  static constexpr double LAGGED_CONTRACTION = 0.5;

  /// Dirichlet data, candidate pairs, numbering, the saddle-point system and its KSP. Collective.
  [[nodiscard]] PetscErrorCode Setup();
  /// Runs the load steps; step_done(step, load factor) is called after each converged step. Collective.
  [[nodiscard]] PetscErrorCode Solve(const std::function<PetscErrorCode(PetscInt, double)> &step_done);

  const Mesh &GetMesh() const { return mesh_; }
  const DofMap &Dofs() const { return dofs_; }
  const Assembler &GetAssembler() const { return *assembler_; }
  const DirichletData &Dirichlet() const { return dirichlet_; }
  const std::vector<ContactPair> &Pairs() const { return pairs_; }
  const std::vector<PairState> &States() const { return states_; }
  const std::vector<std::array<double, 3>> &Normals() const { return normals_; }
  const std::vector<char> &Candidates() const { return candidate_; }
  const std::vector<double> &ULocal() const { return u_local_; }
  const SolveStats &Stats() const { return stats_; }
  /// The certificate of the final state (Solve).
  const Certificate &GetCertificate() const { return certificate_; }
  SaddlePointSystem &System() { return *system_; }
  /// A plain view of the final state for post-processing (valid while the solver lives).
  SolvedState State() const {
    return {mesh_,   dofs_,    dirichlet_, pairs_, states_,       normals_,      candidate_,
            u_local_, fext_,    fint_,      stats_, certificate_, &mortar_, friction_.On() ? &friction_ : nullptr};
  }
  /// External load and internal force at the converged state (displacement rows of the saddle-point layout).
  Vec Fext() const { return fext_; }
  Vec Fint() const { return fint_; }
  double StiffnessScale() const { return kscale_; }

private:
  /// The compliance of every body for the mortar rows' normals (MortarCoupling::SetCompliance). Collective.
  [[nodiscard]] PetscErrorCode SetBodyCompliance();
  /// The saddle-point system, its vectors and the pair keys for the current pairs. Collective.
  [[nodiscard]] PetscErrorCode CreateSystem();
  /// K's pattern for the system: the counts d_nnz, o_nnz (PatternCounts', on entry) and the function that inserts the
  /// pattern, with the couplings that the mortar rows' B_p^T B_p add between slave and master nodes. Collective.
  [[nodiscard]] PetscErrorCode SystemPattern(std::vector<PetscInt> &d_nnz, std::vector<PetscInt> &o_nnz,
                                             std::function<PetscErrorCode(Mat)> &insert) const;
  /// The pairs of the rigid obstacles (FindContactPairs, with u_local as there) and of the bodies' interfaces
  /// (mortar_), sorted; a case without an obstacle has no candidates but the slave nodes. Collective.
  [[nodiscard]] PetscErrorCode FindAllPairs(std::vector<ContactPair> &pairs, std::vector<char> &candidate,
                                            const double *u_local = nullptr, std::vector<char> *held = nullptr);
  /// The pairs' gaps, zones, constraint rows and normals at the displacement u (EvaluatePairs), with the master
  /// terms of the mortar pairs; current: in the current configuration. Collective.
  [[nodiscard]] PetscErrorCode EvaluateAt(const double *u, bool current);
  /// The solver path of the run (ChooseSolverPath), once, before the first system is created.
  [[nodiscard]] PetscErrorCode ChooseSolver();
  /// The certificate of the current state (states_ and the displacement u_eval, dim values per local vertex): the
  /// active-set conditions over the pairs, and no candidate node without a pair inside the obstacle. Collective.
  [[nodiscard]] PetscErrorCode Certify(const std::vector<double> &u_eval, double rnorm, double tol, Certificate &cert);
  /// The certificate's balance of the two sides' forces of the pairs of bodies (Certificate::pair_force_balance).
  /// Collective.
  [[nodiscard]] PetscErrorCode PairForceBalance(Certificate &cert) const;
  /// svk: the mortar rows of the pairs of bodies in the configuration of u_eval (MortarCoupling::Update); a new
  /// pattern rebuilds the system (rebuilt). Collective.
  [[nodiscard]] PetscErrorCode UpdateMortar(const std::vector<double> &u_eval, bool &rebuilt);
  /// svk: searches the pairs again at the current configuration u_eval (force, or when a candidate moved more than
  /// half the search radius since the last search); new pairs rebuild the system (rebuilt). Collective.
  [[nodiscard]] PetscErrorCode Repair(const std::vector<double> &u_eval, bool force, bool &rebuilt);
  /// Takes new pairs (with their multipliers and active flags), keeping the displacement. Collective.
  [[nodiscard]] PetscErrorCode AdoptPairs(std::vector<ContactPair> pairs, const std::vector<double> &lambda,
                                          const std::vector<double> &mult, const std::vector<char> &active);
  /// AdoptPairs, carrying from the current pairs (old: their index by vertex and facet) the multipliers and active
  /// flags lambda, mult, active of those that persist; new pairs start inactive at zero. Collective.
  [[nodiscard]] PetscErrorCode AdoptPairsFrom(std::vector<ContactPair> pairs, const PairIndex &old,
                                              const std::vector<double> &lambda, const std::vector<double> &mult,
                                              const std::vector<char> &active);
  /// The state of the last converged load step, to which a failed one goes back.
  struct Converged {
    std::vector<double> u; ///< owned displacement (OwnedDisplacement)
    std::vector<ContactPair> pairs;
    std::vector<double> lambda, mult;
    std::vector<char> active;
    Friction::Saved friction;
  };
  [[nodiscard]] PetscErrorCode SaveConverged(Converged &c) const;
  /// The automatic choice's direct path stopped (the analysis found it does not fit or is slower, or MUMPS ran out of
  /// memory: SaddlePointSystem::DirectRejected): the run goes on on the iterative path, the failed load step again
  /// from its start (saved). Collective.
  [[nodiscard]] PetscErrorCode LeaveDirectPath(const Converged &saved);
  /// Goes back to c after a failed attempt (the pairs adopted again where they changed on some rank). Collective.
  [[nodiscard]] PetscErrorCode RestoreConverged(const Converged &c);
  /// Prints why a failed load step is repeated with a wider pair search. Collective.
  [[nodiscard]] PetscErrorCode PrintWidening(double t_try) const;
  /// The message of a run that stops after a failed step at load factor t_try (FailureMessage). Collective.
  [[nodiscard]] PetscErrorCode Failure(double t_try, const RetryDecision &d, std::string &message);
  [[nodiscard]] PetscErrorCode OwnedDisplacement(std::vector<double> &u) const;
  [[nodiscard]] PetscErrorCode SetOwnedDisplacement(const std::vector<double> &u);
  [[nodiscard]] PetscErrorCode UpdateLocal();
  /// The equilibrium tolerance of Newton and of the certificate at a force scale ||F_int|| + ||f|| and the round-off
  /// of the residual itself (Residual's roundoff): -newton_rtol scale + min(-newton_atol, 1e-6 scale) + roundoff.
  double EquilibriumTol(double scale, double roundoff) const;
  /// Adds t times the rigid motion with mode coefficients motion (RigidModes) to u. Collective.
  [[nodiscard]] PetscErrorCode MoveRigidly(const RigidMotion &motion, double t);
  /// Norm of R(u, lambda) = F_int - f - B^T lambda on the free rows, a force scale, and optionally direction . R and
  /// the round-off below which the norm means nothing (ROUNDOFF_FACTOR eps times the stiffness scale times ||u||: a
  /// body that prescribed displacements move rigidly has F_int of round-off size and no load, so a tolerance relative
  /// to the forces alone would be about 1e-21 against a residual of 1e-16).
  /// product: F_int from AddStiffnessProduct serves (the iterates of loose solves); else only F_int from the cells
  /// (the certificate's).
  [[nodiscard]] PetscErrorCode Residual(const std::vector<double> &lambda, double &norm, double &scale,
                                        const PetscScalar *direction = nullptr, double *dot = nullptr,
                                        double *roundoff = nullptr, bool product = false);
  /// The linear material after a full step of a solve from a state whose F_int fint_ holds, the prescribed values
  /// unchanged: F_int at the new iterate as that plus K du (SaddlePointSystem::StiffnessTimes, du the solve's
  /// displacement rows), on the free rows, instead of a pass over the cells (0.3 s a pass on the octant Hertz at 1.07M
  /// dofs, one rank). Nothing where the system cannot give K du. Collective.
  [[nodiscard]] PetscErrorCode AddStiffnessProduct();
  /// -info: the difference between F_int of AddStiffnessProduct (by_product) and the cells' (fint_) at the same
  /// displacement, on the free rows. Collective.
  [[nodiscard]] PetscErrorCode CompareProduct(Vec by_product) const;
  [[nodiscard]] PetscErrorCode SetDirichlet(double factor);
  /// Multiplier rows per pair: 1, or dim with friction (the tangential rows after the normal ones).
  PetscInt RowsPerPair() const { return friction_.On() ? mesh_.Dim() : 1; }
  /// Whether the supports and the next solve's active rows (st.next, with friction the stick rows) hold every rigid
  /// mode (RigidModes::Held). Collective.
  [[nodiscard]] PetscErrorCode Held(const std::vector<char> &next, bool &held) const;
  /// The rows that hold the body for the check of its rigid modes: the active pairs' normals, and with friction a
  /// stick pair's tangents and a 3D slip pair's direction across its slip (pair_of: each row's pair).
  struct HoldingSet {
    std::vector<PairKey> keys;
    std::vector<std::array<double, 3>> normals;
    std::vector<char> flags;
    std::vector<std::size_t> pair_of;
  };
  void HoldingRows(const std::vector<char> &next, HoldingSet &h) const;
  [[nodiscard]] PetscErrorCode UpdateSolution(double residual_before, bool stabilised, double &step);
  /// What runs per load step (LoadStep) and per active-set/Newton iteration within it: EvaluateIterate (pairs at the
  /// current iterate, the residual), the active-set update (ActiveSet), StepControl (certificate, stabilisation
  /// step extension, stopping reasons), AssembleSystem (K when it changes, constraint rows, right-hand side) and
  /// SolveAndUpdate (the saddle-point solve, the Newton update with its step length).
  struct StepState {
    PetscInt step;
    double factor;
    bool first;
    std::vector<double> delta{}, u_eval{}; ///< prescribed-displacement increment still to apply; u + delta
    std::vector<char> next{};              ///< the active set of the next solve
    /// Friction (-contact_friction): pairs whose stick/slip set changes for the next solve, slip pairs whose
    /// direction turned (3D), and the sets as one key per pair for cycle detection (Friction::SetKey).
    PetscInt friction_changes = 0, friction_turns = 0;
    std::vector<char> key{};
    PetscInt krylov = 0;
    double last_solve_time = 0, solve_residual = 0;
    bool loose = false; ///< the last solve was loose (an inexact active-set iteration)
    /// The equilibrium residual at the iterate, its force scale and its round-off (Residual).
    struct ResidualNorms {
      double norm = 0, scale = 0, roundoff = 0;
    } r{};
    bool moving = false;     ///< some prescribed displacement is still to apply
    bool stabilised = false; ///< the last solve carried the stabilisation springs
    bool searching = true;   ///< the next solve's active set is a new one (the first, or a change)
    /// svk: the lagged searches (-newton_lagged_search) and the exact Newton steps after them.
    struct Newton {
      bool lagged = false;   ///< the next solve is a condensed search with the factored tangent
      double lag_rnorm = -1; ///< the residual before the last solve (none: -1), for LAGGED_CONTRACTION
      bool exact = false;    ///< the active set came back, no more lagged searches in this load step
    } newton{};
    /// Linear material: solves that only correct the equilibrium residual of a candidate state (JudgeCandidate).
    struct Corrections {
      double rtol = 0;             ///< the next solve only corrects the equilibrium residual, to this tolerance
      bool made = false;           ///< the last solve was such a correction
      double candidate_rnorm = -1; ///< the equilibrium residual of the last candidate state of this active set
      int stalled = 0;             ///< corrections in a row that did not halve candidate_rnorm
    } correction{};
    PetscInt set_changes = 0;       ///< iterations of this load step that changed the active set
    std::vector<double> u_before{}; ///< the displacement (local layout) before the last stabilised solve
    std::vector<double> u_start{};  ///< the owned displacement at the step's start (RestartFromStepStart)
    bool restartable = false;       ///< u_start is recorded (on every rank alike: a rank may own no vertex)
    bool touching = false; ///< the next solve is held at a touching point alone (TOUCHING_RTOL; every rank alike)
    /// svk: the gaps that the touching solve's whole increment gives, linearised (g + n . du), for the first update
    /// (empty: none)
    std::vector<double> touch_gaps{};
    bool measured = false; ///< u_before is that of the current pairs (the same on every rank: a rank may own none)
    int pivoted = 0;       ///< complementarity problems of this step (PivotedActiveSet), at most 2
    bool singular = false; ///< a factorisation found null pivots: nothing was solved, the step ends (DIVERGED_SINGULAR)
    /// Condensed solves (kept factorisation): from the first solve without stabilisation and without a prescribed
    /// displacement still to apply (svk: from each lagged one), the active-set iterations run in the multiplier space
    /// against that solve's right-hand side, condensed once (its base: the displacement u, the gaps g), the
    /// displacement staying at the base's until the active set settles (Materialise). svk: the factored matrix is an
    /// earlier tangent, so the search is a modified Newton step; the Newton steps after it are exact (FGMRES).
    struct CondensedBase {
      bool ready = false;     ///< the right-hand side of the base is condensed (reuse mode, not stabilised)
      bool condensed = false; ///< the last solve was condensed: states from g + shift, u not updated
      VecH u{};
      std::vector<double> g{}, shift{};
      double rnorm = 0; ///< the equilibrium residual at the base
    } base{};
  };
  enum class Outcome { SOLVE, EXTENDED, CONVERGED, STOP };
  /// Load step number step from the converged state at pseudo-time from to that at factor; ok: it converged.
  [[nodiscard]] PetscErrorCode LoadStep(PetscInt step, double from, double factor, bool &ok);
  /// A step over which no ramp moves: ok when the state it starts from is certified at its loads (no solve then).
  /// Collective.
  [[nodiscard]] PetscErrorCode CertifiedAtRest(StepState &st, bool &ok);
  /// After a failed load step: the search radius a repeated step needs (retry_.widen_to; 0: none), when a candidate
  /// node is inside a facet it has no pair with at the step's last iterate (linear material: that pair goes to
  /// retry_.extra_pairs), or, once per run, when the step cycled or left the body free (DIVERGED_CYCLING, _NOT_HELD;
  /// svk only when it can cut the step no more), or when its system was singular (DIVERGED_SINGULAR) with a radius
  /// below the body's diagonal. Collective.
  [[nodiscard]] PetscErrorCode UnpairedAfterFailure(StepState &st, PetscInt it);
  /// Linear material with the kept factorisation, at most twice per load step: when an active set first comes back
  /// (instead of one switch per update, which follows only when this finds nothing new), and when the step ends with
  /// DIVERGED_CYCLING, _NOT_HELD or _MAX_IT, the contact problem from the current iterate as a linear complementarity
  /// problem in the multipliers (SaddlePointSystem::ContactLcp), solved by Lemke's method, which is finite. pivot:
  /// SET, it has a solution, whose active set is now st.next, and the step goes on from it, its earlier sets
  /// forgotten (its solves and the certificate decide, as for any set); UNHELD, the solution leaves more than
  /// LCP_UNHELD of the load along rigid motions unbalanced, to the regularisation's spring however weak it is: no
  /// contact forces on these pairs hold the body (DIVERGED_NOT_HELD); NONE, no solution or no such problem. why: for
  /// -info. Collective.
  enum class Pivot { NONE, SET, UNHELD };
  [[nodiscard]] PetscErrorCode PivotedActiveSet(StepState &st, PetscInt it, const char *why, Pivot &pivot);
  /// The iterative path's verdict on a body that its pairs cannot hold (it has no Schur complement for
  /// PivotedActiveSet's problem, and its Krylov solves of such a step ran out of iterations, or svk's Newton iterates
  /// deformed the body until det F vanished, where the direct path ends DIVERGED_NOT_HELD): at the start of a load
  /// step without friction, the part of the load along the rigid motions that the supports leave free which no
  /// non-negative forces on the candidate pairs balance (RigidModes::Unbalanced: a necessary condition of any
  /// equilibrium, so never a body that some state holds). Above LCP_UNHELD: unheld, with retry_.unheld_detail.
  /// Collective.
  [[nodiscard]] PetscErrorCode UnbalancedLoad(bool &unheld);
  /// See PivotedActiveSet and SaddlePointSystem::ContactLcp: the unbalanced fraction does not depend on the spring's
  /// stiffness, so not on E / load or the mesh (the spring itself carried 0.004 of the load of a block held between a
  /// floor and a wall under a small load). A body that its pairs hold leaves round-off (3e-8 at most in the tests), one
  /// that rolls off a disc or a sphere, or slides away along a frictionless floor, 0.009 to 0.3 in the tests and
  /// surveys (docs/survey.md), and 1 when its load pulls it off every obstacle.
  static constexpr double LCP_UNHELD = 1e-3;
  /// PivotedActiveSet's problem size (multipliers) at most: its eigendecomposition and pivots cost O(m^3) on rank 0
  /// (Lemke on a dense m = 1000 problem with 500 pivots: 0.56 s).
  static constexpr PetscInt LCP_MAX_ROWS = 2000;
  /// Finds the pairs again with the radius retry_.widen_to (linear material: in the reference configuration, with the
  /// pairs of retry_.extra_pairs in their zone), carrying the multipliers and active flags of the pairs that persist.
  /// Collective.
  [[nodiscard]] PetscErrorCode WidenSearch(const std::vector<double> &lambda, const std::vector<double> &mult,
                                           const std::vector<char> &active);
  /// The active-set flags that identify a set for cycle detection: st.next, or with friction st.key.
  const std::vector<char> &SetKey(const StepState &st) const { return friction_.On() ? st.key : st.next; }
  [[nodiscard]] PetscErrorCode EvaluateIterate(StepState &st, PetscInt it);
  /// The iterative path, linear material, first load step: the first update's solve starts from the step's start
  /// (st.u_start, no multipliers) instead of the state of the solve held at the touching pairs when its right-hand
  /// side is smaller there (RhsNorm; why: in active_set_step.cpp). Evaluates the iterate again. Collective.
  [[nodiscard]] PetscErrorCode RestartFromStepStart(StepState &st, PetscInt it);
  /// ||b|| of the next solve at the evaluated iterate (AssembleSystem): f - F_int on the free rows, the gaps of the
  /// pairs of st.next. Collective.
  [[nodiscard]] PetscErrorCode RhsNorm(const StepState &st, double &norm) const;
  [[nodiscard]] PetscErrorCode StepControl(StepState &st, PetscInt it, PetscInt &changes, Outcome &outcome);
  /// StepControl's parts, in its order. svk, once the set cycled: a switch away from an equilibrium of the current set
  /// is put off (st.next back to the current set); returns whether it was.
  bool DeferSwitch(StepState &st, PetscInt &changes) const;
  /// An active set that comes back: svk drops the lagged searches, the linear material pivots once
  /// (PivotedActiveSet), then the updates switch one pair at a time; done: the step stops (outcome). Collective.
  [[nodiscard]] PetscErrorCode ActiveSetCameBack(StepState &st, PetscInt it, PetscInt &changes, Outcome &outcome,
                                                 bool &done);
  /// A state whose active set did not change: certified (CONVERGED), refused (STOP with the violated condition), or
  /// the next solve corrects its equilibrium residual (linear material); done: outcome decided. Collective.
  [[nodiscard]] PetscErrorCode JudgeCandidate(StepState &st, PetscInt it, Outcome &outcome, bool &done);
  /// A stabilised solve that closed no pair: the body moved along its free rigid motion past the nearest pair that
  /// closes (EXTENDED), or not held (STOP). Collective.
  [[nodiscard]] PetscErrorCode ExtendAlongFreeMotion(StepState &st, Outcome &outcome);
  /// The stop of a step that goes on no further: non-invertible, out of iterations, or cycling (STOP). Collective.
  [[nodiscard]] PetscErrorCode StopAtLimits(StepState &st, PetscInt it, PetscInt changes, Outcome &outcome);
  [[nodiscard]] PetscErrorCode AssembleSystem(StepState &st);
  [[nodiscard]] PetscErrorCode SolveAndUpdate(StepState &st);
  /// The relative tolerance of an svk solve that is not lagged: an inexact Newton step (0: the KSP's).
  [[nodiscard]] PetscErrorCode NewtonForcing(const StepState &st, double &rtol) const;
  /// Whether the next solve can be condensed (StepState::CondensedBase::ready).
  bool Condensable(const StepState &st) const;
  /// The right-hand side assembled for the current iterate as the base of the condensed solves
  /// (StepState::CondensedBase): its u, g and rnorm, and its condensation. Collective.
  [[nodiscard]] PetscErrorCode CondenseBase(StepState &st);
  /// After condensed solves: the expansion of the last one (the whole solution for the base's right-hand side with the
  /// current constraints), and the displacement base.u + du; the pairs evaluated there. Collective.
  [[nodiscard]] PetscErrorCode Materialise(StepState &st, PetscInt it);
  [[nodiscard]] PetscErrorCode Monitor(const IterationRecord &r) const;
  [[nodiscard]] PetscErrorCode RecordIteration(PetscInt step, PetscInt it, double factor, const std::vector<char> &next,
                                               PetscInt changes, PetscInt krylov, double rnorm, double solve_time);

  const Mesh &mesh_;
  const Material &material_;
  std::unique_ptr<const MaterialPolicy> model_; ///< how the loop iterates on the material
  const BoundaryConditions &bc_;
  const Obstacle &obstacle_;
  ContactOptions contact_; ///< a copy: a failed load step may widen its search radius (WidenSearch)
  const SolverOptions &opts_;
  /// -newton_lagged_search as it applies: off by default with pairs of bodies (Setup).
  bool lagged_search_ = true;
  DirichletData dirichlet_;
  std::vector<ContactPair> pairs_;
  MortarCoupling mortar_; ///< the master terms of the pairs of bodies (-contact_pairs)
  /// What the failed load steps of the run asked for and found (UnpairedAfterFailure, the retry policy in Solve).
  struct Retries {
    double widen_to = 0;      ///< the search radius a failed load step asks for (UnpairedAfterFailure), 0: none
    PetscInt widen_node = -1; ///< the deepest unpaired node then (file number, 1-based) and its depth
    double widen_depth = 0;
    /// Linear material: the local vertices and facets found inside each other without a pair after a failed step;
    /// the pair search adds them from then on (WidenSearch).
    std::set<std::array<PetscInt, 2>> extra_pairs;
    bool widened_unheld = false; ///< a step that cycled or left the body free was repeated with a wider radius (once)
    /// svk: a step found free along the lagged searches' path was repeated with exact Newton steps (once); every
    /// load step from then on takes them (StepState::Newton::exact from its start)
    bool exact_newton = false;
    Reason first_unheld = Reason::NONE; ///< the reason of that step's failure
    std::string unheld_detail; ///< PivotedActiveSet's finding that the pairs cannot hold the body (this load step)
  } retry_;
  /// Load steps repeated with a wider search radius in a run, at most (each at least doubles it).
  static constexpr PetscInt MAX_WIDENINGS = 8;
  std::vector<char> candidate_;
  std::vector<char> held_; ///< contact-group nodes whose every component is fixed (FindContactPairs)
  std::vector<PairKey> keys_;
  ActiveSet active_set_;
  RigidModes rigid_;
  Certificate certificate_;
  std::vector<PairState> states_;
  Friction friction_; ///< Coulomb friction at the pairs against rigid obstacles (-contact_friction)
  std::vector<ConstraintRow> rows_;
  std::vector<std::array<double, 3>> normals_;
  DofMap dofs_;
  std::unique_ptr<Assembler> assembler_;
  std::unique_ptr<SaddlePointSystem> system_;
  std::vector<double> paired_at_; ///< displacement (per local vertex dof) at the last pair search
  VecH u_, du_, fext_, fint_, fdir_, u_seq_;
  VecScatter scatter_ = nullptr;
  std::vector<double> u_local_, lambda_, mult_; ///< mult_: the solved multipliers (springs on inactive rows)
  double kscale_ = 1;
  double krow_ = 1; ///< mean sum_j |K_ij| of a global row (Assembler::StiffnessScale): the residual's round-off scale
  bool k_assembled_ = false;
  /// Where fint_ holds F_int: the displacement (u_local_; empty: none) and the min det F there; exact: from the
  /// cells, else from AddStiffnessProduct (the free rows only).
  struct InternalForceAt {
    std::vector<double> u;
    double min_J = 1;
    bool exact = true;
  } fint_at_;
  SolveStats stats_;
  SolverProblem solver_problem_; ///< ChooseSolver's (without the node graph): ConfirmDirect's

public:
  ~ContactSolver() { (void)VecScatterDestroy(&scatter_); }
};

} // namespace signorini
