// The active-set policy in one place: the activation rule (docs/theory.md §4: the primal-dual
// complementarity test lambda - c g > 0, with the sign convention g >= 0, lambda >= 0, lambda g = 0), the zone in
// which a pair's gap counts, the damping of the first update (-contact_activation_fraction), the first (touching)
// set, the pruning of parallel pairs of one node, cycle detection, and the convergence certificate.
#pragma once

#include <petscsys.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace signorini {

/// State of one pair after a solve.
struct PairState {
  double lambda = 0;    ///< multiplier (normal contact force, >= 0 compressive)
  double gap = 0;       ///< current gap (< 0 penetration): linearised (linear material) or current (svk)
  bool inside = false;  ///< svk: the current position projects onto the facet (0 <= alpha <= 1, docs/theory.md §1);
                        ///< linear: the pair's reference zone (ContactPair::zone0)
  bool entered = false; ///< svk: the straight path X -> x crossed the finite facet from its open side
                        ///< (g0 > touch_tol, g < 0), or the node started behind the facet within its strip
                        ///< (g0 < -touch_tol, X projects onto it)
  bool active = false;  ///< active in the solve that produced lambda
  double crossing = 0;  ///< where the path X -> x crossed the facet (0..1), when entered
  /// The pair's gap counts: the node is over the facet now, or went (or started) through it.
  bool InZone() const { return inside || entered; }
};

/// Whether the pair is active in the next solve. Only a pair in its zone can be active. An active pair stays
/// active while lambda - c g > -tol (its multiplier is compressive); an inactive pair becomes active when it
/// penetrates, lambda - c g > activate_tol (>= tol). c > 0 converts a gap to a force; the tolerances are forces.
inline bool NextActive(const PairState &s, double c, double tol, double activate_tol) {
  const double score = s.lambda - c * s.gap;
  return s.InZone() && (s.active ? score > -tol : score > activate_tol);
}
inline bool NextActive(const PairState &s, double c, double tol) { return NextActive(s, c, tol, tol); }

/// Identity of a pair: its local vertex (pairs of one vertex are adjacent), the vertex's number in the mesh file
/// and the facet (both partition-independent).
struct PairKey {
  PetscInt vertex, original, facet;
};

/// Two active pairs of one node with normals within 1 degree, e.g. at the joint of collinear segments, are the same
/// constraint twice and would make the saddle-point matrix singular: the one the node penetrates less (by its gap in
/// states, by more than gap_tol) is dropped; within gap_tol the inactive one, else the later one. Keeping the earlier
/// one whatever the gaps held a node that slid over the concave joint of two facets 0.9 degrees apart on the facet it
/// left, while it penetrated the other.
void DropParallelPairs(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                       const std::vector<std::array<double, 3>> &normals, double gap_tol, std::vector<char> &next);

/// The set of the next solve: NextActive for each pair (activate_tol for the inactive ones), then, per node, among
/// the pairs it would newly activate: if the node went through a facet on its path X -> x, only the facet it
/// crossed first (at a tie, e.g. through the joint of two facets, the deeper penetration) is activated, not the
/// facets whose infinite strip the displaced node happens to lie in; a node at a concave corner gets its second
/// facet in a later iteration, once the first holds it. Then parallel pairs are pruned (DropParallelPairs, gap_tol).
/// keys: pairs of one node are adjacent.
void ProposeSet(const std::vector<PairState> &states, double c, double tol, double activate_tol,
                const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                std::vector<char> &next, double gap_tol = 0);

/// The friction part of the certificate (docs/theory.md §9), over the pairs with mu > 0.
struct FrictionCertificate {
  bool on = false;
  double cone = 0;        ///< max (|lambda_t| - mu lambda_n) over the active pairs
  double stick_slip = 0;  ///< max |s| over the stick pairs
  double slip_rule = 0;   ///< max |lambda_t - mu lambda_n s/|s|| over the slip pairs with |s| > slip_tol
  double open_force = 0;  ///< max |lambda_t| over the open pairs
  double force_tol = 0;   ///< FORCE_RTOL times the largest lambda_n (or the lambda tolerance when larger)
  double slip_tol = 0;    ///< -contact_gap_tol
  PetscInt node[4] = {-1, -1, -1, -1}; ///< the node (file numbering, from 1) of each of the four above
  PetscInt stick = 0, slip = 0;        ///< pairs in each set
  double tangential_force[3] = {0, 0, 0}; ///< total friction force on the body, sum -t lambda_t
  /// The condition that fails, as a phrase for an error message (naming the node); empty when satisfied.
  std::string Violation() const;
  static constexpr double FORCE_RTOL = 1e-8;
};

/// The discrete Signorini conditions at a state, checked over every candidate pair; the residuals and the
/// thresholds they are held to. Satisfied() is the only way the loop reports convergence.
struct Certificate {
  double max_penetration = 0;     ///< max -g over the pairs in their zone (0 when none penetrates)
  double unpaired_penetration = 0; ///< deepest penetration of the obstacle by a candidate node without any pair
                                   ///< (farther than the search radius when the pairs were found)
  PetscInt unpaired_node = -1;     ///< that node (file numbering, from 1), -1 when none penetrates
  double unpaired_x[3] = {0, 0, 0}; ///< its reference position
  double search_radius = 0;        ///< -contact_search_radius, for the message
  double gap_tol = 0;             ///< -contact_gap_tol
  double min_active_lambda = 0;   ///< min lambda over the active pairs (0 when none)
  double lambda_tol = 0;          ///< a multiplier above -lambda_tol counts as compressive (ActiveSet::TensileTol)
  double max_inactive_lambda = 0; ///< max |lambda| over the inactive pairs
  double complementarity = 0;     ///< max |lambda g| over the pairs
  double complementarity_tol = 0; ///< gap_tol max(lambda) (lambda_tol when no multiplier is larger)
  double equilibrium = 0;         ///< ||F_int - f - B^T lambda|| on the free rows
  double equilibrium_tol = 0;     ///< -newton_rtol (||F_int|| + ||f||) + -newton_atol
  PetscInt changes = 0;           ///< pairs the undamped rule would switch (the active set must be unchanged)
  bool bodies = false;            ///< pairs of bodies (-contact_pairs): the two sides' forces are checked
  double pair_force_balance = 0;  ///< |sum of the forces on the slave sides + on the master sides|
  double pair_force_tol = 0;      ///< PAIR_FORCE_RTOL sum |lambda| over the pairs of bodies
  /// The two sides' forces balance exactly in exact arithmetic (sum_l w_jl = 1 where the master covers the slave
  /// node's support): beyond round-off the rows are wrong.
  static constexpr double PAIR_FORCE_RTOL = 1e-10;
  PetscInt active = 0;            ///< active pairs
  FrictionCertificate friction;   ///< -contact_friction > 0 (friction.hpp)
  bool Satisfied() const;
  /// The first condition that fails, as a phrase for an error message; empty when satisfied.
  std::string Violation() const;
};

/// The policy's parameters (from the -contact_ options).
struct ActiveSetParams {
  double c = 1;                   ///< -contact_complementarity_c
  double gap_tol = 0;             ///< -contact_gap_tol
  double touch_tol = 0;           ///< -contact_touch_tol
  double activation_fraction = 0; ///< -contact_activation_fraction
  double length = 1;              ///< the body's diagonal
  double activation_gap_factor = 0; ///< -contact_activation_gap_factor (0: off)
  /// The gap tolerance, at least the round-off of gaps computed from coordinates of size `length` (1e-13 of it).
  double GapTol() const { return gap_tol > 1e-13 * length ? gap_tol : 1e-13 * length; }
  double ForceTol() const { return c * GapTol(); }
};

/// The active set of the owned pairs and its history within a load step. Collective methods take the
/// communicator given at construction.
class ActiveSet {
public:
  ActiveSet(MPI_Comm comm, const ActiveSetParams &params) : comm_(comm), params_(params) {}
  void Reset(std::size_t npairs) {
    active_.assign(npairs, 0), start_gap_.clear(), started_ = false, half_overlap_ = false;
  }
  const std::vector<char> &Flags() const { return active_; }
  void Set(const std::vector<char> &flags) { active_ = flags; }
  /// Starts a load step: forgets the sets seen in the previous one. load_scale: the largest nodal force of the
  /// step's loads (max |f_i|), the force scale of TensileTol with the multipliers.
  void BeginStep(double load_scale) { seen_.clear(), load_scale_ = load_scale, single_ = false; }

  /// The set of the first solve of a load step: in the first step the pairs in their zone whose gap is within
  /// -contact_touch_tol (with SetOverlapRule, of those that start inside the obstacle only the ones at least
  /// OVERLAP_FRACTION of the deepest in), later the converged set of the previous step. Records the gaps at the start
  /// of the step. Collective.
  [[nodiscard]] PetscErrorCode First(const std::vector<PairState> &states, bool first_step,
                                     const std::vector<PairKey> &keys,
                                     const std::vector<std::array<double, 3>> &normals, std::vector<char> &next);
  /// The set of the next solve after iteration `it` (>= 1) of a load step. In iteration 1 only the pairs
  /// penetrating deeper than -contact_activation_fraction times the deepest penetration of an inactive pair, and
  /// whose gap at the start of the step is at most -contact_activation_gap_factor times that of the deepest one, are
  /// activated (the deepest always is), later every penetrating pair; parallel pairs are pruned. The gap factor:
  /// after a solve held at a touching point, a smooth (locally parabolic) contact is penetrated deepest where the
  /// start gap is a fixed fraction of the gap at the contact's edge (at 1/sqrt(2) of the half-width in 2D, 0.75 of the
  /// radius in 3D: the point load's indentation against the parabola), whatever the mesh size; the factor
  /// ActivationGapFactor (2 in 2D, 1.77 in 3D) activates about the contact's final set. Neither damps the update
  /// after a first set that held the deeper half of an overlap (First): that solve did not overshoot, and the pairs
  /// it leaves penetrating are the ring just outside its set. loose: the states come from
  /// a loose solve of the linear material, where an active pair's gap is only its row's residual (the rule then reads
  /// an active pair's multiplier alone). changes: global number of switched pairs. Collective.
  [[nodiscard]] PetscErrorCode Next(const std::vector<PairState> &states, PetscInt it, bool loose,
                                    const std::vector<PairKey> &keys, const std::vector<std::array<double, 3>> &normals,
                                    std::vector<char> &next, PetscInt &changes) const;
  /// After the active set came back (Seen): from now on in this load step each update switches one pair only, the
  /// one that violates its condition most (|lambda - c g|: the deepest penetration or the most tensile multiplier;
  /// the smallest node and facet numbers at a tie), applied to `next` now (changes: 1). Updates that switch many pairs
  /// at once can cycle between two sets that each overshoot the other (svk's block in the notch alternated between
  /// 21 and 16 active pairs); one switch at a time walks from one to the other. The sets seen so far are forgotten:
  /// a set that comes back in this mode ends the step. Collective.
  [[nodiscard]] PetscErrorCode SwitchOneAtATime(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                                std::vector<char> &next, PetscInt &changes);
  bool OneAtATime() const { return single_; }
  /// Whether the first set of the first step holds only the deeper half of an overlap (First): the iterative path's
  /// linear material without friction, where each active-set iteration costs a Krylov solve (on the direct path a
  /// condensed solve; there the whole overlap stays the first set).
  void SetOverlapRule(bool on) { overlap_rule_ = on; }
  /// Forgets the sets seen so far in this load step (the step goes on another way).
  void Forget() { seen_.clear(); }
  /// Forgets them and the one-at-a-time mode: the step starts again from another set.
  void Restart() { seen_.clear(), single_ = false; }
  /// Records `next` (unless record is false; a flag above 1 is another state of an active pair) and tells whether
  /// it came back: an earlier set of this load step
  /// (`repeats` times before). Collective.
  [[nodiscard]] PetscErrorCode Seen(const std::vector<char> &next, const std::vector<PairKey> &keys, int repeats,
                                    bool &cycling, bool record = true);
  /// The certificate of a state: states hold the gaps, multipliers and active flags of the current set;
  /// equilibrium and its tolerance come from the caller's residual. Collective.
  [[nodiscard]] PetscErrorCode Certify(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                       const std::vector<std::array<double, 3>> &normals, double equilibrium,
                                       double equilibrium_tol, Certificate &cert) const;

  /// Relative size, against the largest nodal force of the step (loads or multipliers), below which a negative
  /// multiplier counts as zero.
  static constexpr double MULTIPLIER_RTOL = 1e-6;
  /// Of the pairs that start inside the obstacle, the first set holds those at least this fraction of the deepest in
  /// (a smooth indenter touches over half the area it overlaps: First).
  static constexpr double OVERLAP_FRACTION = 0.5;

private:
  /// How negative an active pair's multiplier may be and still count as compressive: c times the gap tolerance,
  /// but at most MULTIPLIER_RTOL times the force scale (max_lambda: the largest |lambda| of the pairs, global).
  /// c gap_tol alone scales with E t and the body's size, not with the load: for a stiff material or a small load
  /// it exceeded every multiplier, and a body pulled off its obstacle converged glued to it by tensile multipliers.
  double TensileTol(double max_lambda) const {
    return std::min(params_.ForceTol(), MULTIPLIER_RTOL * std::max(load_scale_, max_lambda));
  }

  /// Keeps in `next` one of the pairs it switches against the current set: the largest |lambda - c g|, then the
  /// smallest node and facet numbers (the same on every partition). Collective.
  [[nodiscard]] PetscErrorCode KeepOneSwitch(const std::vector<PairState> &states, const std::vector<PairKey> &keys,
                                             std::vector<char> &next) const;

  MPI_Comm comm_;
  ActiveSetParams params_;
  bool single_ = false; ///< SwitchOneAtATime
  double load_scale_ = 0; ///< BeginStep
  std::vector<char> active_;
  std::vector<unsigned long long> seen_;
  std::vector<double> start_gap_; ///< the pairs' gaps at the start of the load step (First)
  bool started_ = false;          ///< start_gap_ holds the current pairs' (First since the last Reset)
  bool overlap_rule_ = false;     ///< SetOverlapRule
  bool half_overlap_ = false;     ///< the first set held the deeper half of an overlap (First; global)
};

} // namespace signorini
