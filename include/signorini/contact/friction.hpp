// Coulomb friction at the pairs (docs/theory.md §9), against rigid obstacles and between bodies: per pair its coefficient mu, a tangent
// basis of its normal, the tangential constraint rows, the slip increment of the load step, and the three sets of the
// primal-dual active set of Hueber, Stadler and Wohlmuth (SIAM J. Sci. Comput. 30, 2008) per load step: open
// (inactive), stick and slip, with the tangential multipliers lambda_t.
//
// Conventions. A pair's tangential multiplier lambda_t (dim - 1 components in its tangent basis t_k) is the friction
// force the node exerts on the obstacle (or the master side): the force on the body is n lambda_n - sum_k t_k
// lambda_t,k, and on a slip node lambda_t = mu lambda_n s / |s| for its slip increment s (s_k = t_k . (r - r at the
// start of the load step), r the node's displacement, less the mortar-weighted master displacement sum_l w_jl u_l for
// a pair of bodies; the master nodes carry - w_jl times the slave node's friction force).
// The system takes the tangential rows as more constraint rows after the normal ones (index set lambda_t): a stick
// row t_k . du = -s_k (the step's slip stays 0) with D = 0; an open or slip row is inactive (lambda_t = 0 in the
// solve), and a slip pair's friction force mu lambda_n d (d: its slip direction, fixed in the solve) enters through
// the column of its normal multiplier, which becomes -(n - mu sum_k d_k t_k): the matrix is nonsymmetric. In 3D a slip
// pair's rows turn with its direction: along d inactive, across it (d_perp) the linearisation of lambda_t =
// mu lambda_n s/|s|, lambda_perp = mu lambda_n / |s| d_perp . s (a spring across the slip: D = -|s| / (mu lambda_n),
// right-hand side -d_perp . s), so that the slip direction is Newton's unknown too and a body that slides is held
// across its slip (HSW's semismooth Newton step, with the derivative of lambda_n in it left out).
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/contact/contact_set.hpp"
#include "signorini/contact/mortar.hpp"
#include "signorini/fem/dof_map.hpp"
#include "signorini/linalg/kept_rows.hpp"
#include "signorini/linalg/sparse_row.hpp"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace signorini {

/// Friction state of a pair in a solve.
enum class Grip : char { OPEN = 0, SLIP = 1, STICK = 2 };
extern const char *const GRIP_NAMES[]; ///< "open", "slip", "stick"

/// The friction of a run's pairs. Pairs live on their node's rank; the methods that need the master side of a pair
/// of bodies are collective.
class Friction {
public:
  /// The run's coefficients: -contact_friction, the pairs of bodies' own (-contact_pairs SLAVE:MASTER:MU) and the
  /// obstacle kinds' (-obstacle_friction KIND:MU).
  void Configure(const ContactOptions &opts, const Obstacle &obstacle);
  /// Whether any pair has friction (else nothing below is used).
  bool On() const;
  double Coefficient() const { return mu_; }
  /// The option that asks for friction, for messages: "-contact_friction 0.3", "-obstacle_friction ..." or
  /// "-contact_pairs ...:MU".
  std::string Describe() const;
  /// Binds to the pairs (linear material: their normals are fixed): mu, tangent bases and tangential rows per pair,
  /// on the free components of its node (fixed marks the Dirichlet dofs per local vertex dof) and, for a pair of
  /// bodies, of its master nodes (mortar: Bind done); every pair open. Not collective.
  void Bind(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
            const std::vector<ContactPair> &pairs, const std::vector<std::array<double, 3>> &normals,
            const MortarCoupling &mortar);
  /// The tangent bases and rows again for new normals (svk: the current configuration's), the pairs' sets kept and
  /// what lives in the tangent plane (slip directions, multipliers) turned with it. Not collective.
  void Frame(const std::vector<ContactPair> &pairs, const std::vector<std::array<double, 3>> &normals);
  /// Each pair's friction state by (vertex, facet), to carry across a new set of pairs (Recall after Bind): the set,
  /// the slip's origin, and the slip direction and multipliers as vectors.
  struct PairMemory {
    Grip grip;
    double origin[3], dir[3], lambda_t[3], mult_t[3];
  };
  using Memory = std::map<std::pair<PetscInt, PetscInt>, PairMemory>;
  Memory Remember(const std::vector<ContactPair> &pairs) const;
  /// Gives the pairs that persist their remembered state; a new pair (against a rigid obstacle) slips from its node's
  /// displacement at the start of the step.
  void Recall(const Memory &mem, const std::vector<ContactPair> &pairs);
  /// Tangential rows per pair (dim - 1).
  int PerPair() const { return dim_ - 1; }
  /// Starts a load step: the relative tangential displacements at u_local (the converged state, whose gaps states
  /// hold) are the slips' origin; a pair that closes during the step moves its origin to where it touched (Next).
  /// Collective.
  [[nodiscard]] PetscErrorCode BeginStep(const std::vector<ContactPair> &pairs, const std::vector<PairState> &states,
                                         const double *u_local);
  /// The slip increments at u_local (PerPair() per pair). Collective.
  [[nodiscard]] PetscErrorCode Slips(const std::vector<ContactPair> &pairs, const double *u_local,
                                     std::vector<double> &s) const;
  /// The sets of the first solve of a load step: the pairs of `active` keep their previous state (an open one
  /// sticks); the others are open.
  void First(const std::vector<char> &active);
  /// The sets of the next solve after a solve (states: lambda_n and gaps; active: the normal set of the next solve;
  /// c: the complementarity weight): an active pair sticks where |lambda_t + c s| <= mu max(0, lambda_n - c g),
  /// else slips along lambda_t + c s. changes: pairs whose set changes; turns: slip pairs whose direction turned by
  /// more than DIRECTION_TOL (3D). Collective (the counts are global).
  [[nodiscard]] PetscErrorCode Next(MPI_Comm comm, const std::vector<ContactPair> &pairs,
                                    const std::vector<PairState> &states, const std::vector<char> &active,
                                    const double *u_local, double c, PetscInt &changes, PetscInt &turns);
  /// The proposed sets become the current ones (the next solve's).
  void Adopt() { grip_ = next_, dir_ = next_dir_, across_ = next_across_; }
  /// Flags for cycle detection: 0 open, 1 slip, 2 stick, 3 slip backwards (2D) per pair (the proposed sets).
  void SetKey(const std::vector<char> &active, std::vector<char> &key) const;
  /// SystemRows' kept_weight: KeptRows' map of a group with such a spring has a condition number of about
  /// 1/KEPT_SPRING_MARGIN.
  static constexpr double KEPT_SPRING_MARGIN = 1e-3;
  /// The constraint rows of the system: the normal ones, then the tangential ones; the active flags (stick rows and
  /// 3D slip rows across the slip); per row the column coefficients where they differ from the row's (slip pairs'
  /// normal rows; empty otherwise) and D on the active rows (0, or the 3D slip rows' spring). heavy (if given): the
  /// augmentation weight class of each row (SaddlePointSystem::SetConstraints): a normal row's is its active flag, a
  /// pair's tangential rows share one (full while it sticks, or when its spring is near light_weight, the system's
  /// light weight r_I). kept_weight (if > 0, the kept factorisation's fixed weight w): a 3D slip row's spring with
  /// |1 + w D| < KEPT_SPRING_MARGIN moves to that margin (KeptRows' map would be singular at 1 + w D = 0).
  void SystemRows(const std::vector<SparseRow> &normal_rows, const std::vector<char> &active,
                  std::vector<SparseRow> &rows, std::vector<char> &flags, std::vector<std::vector<double>> &columns,
                  std::vector<double> &diag, std::vector<char> *heavy = nullptr, double light_weight = 0,
                  double kept_weight = 0) const;
  /// The rows of SystemRows on the kept factorisation (SaddlePointSystem::SetRowGroups, KeptRows): the fixed rows
  /// (the normal ones, then each pair's along its fixed tangents t_k; zero where the supports fix a tangent) and per
  /// pair its rows and columns in them (the current sets).
  void KeptGroups(const std::vector<SparseRow> &normal_rows, std::vector<SparseRow> &fixed,
                  std::vector<RowGroup> &groups) const;
  /// The directions (3 values each) of the tangential rows active in SystemRows for pair p: what they hold.
  void HeldDirections(std::size_t p, std::vector<std::array<double, 3>> &dirs) const;
  /// The right-hand side of the tangential rows at u_local: -s on stick rows, the spring's on 3D slip rows, 0
  /// elsewhere. Collective.
  [[nodiscard]] PetscErrorCode RowRhs(const std::vector<ContactPair> &pairs, const double *u_local,
                                      PetscScalar *b) const;
  /// Reads the tangential multipliers of a solution (x_t: the tangential rows; lambda_n, mult_n: the normal
  /// multipliers and solved values): lambda_t (stick: solved; slip: mu lambda_n d; open: 0) and the force the solve
  /// applies through them (mult_t: x_t, plus mu mult_n d on slip pairs).
  void Read(const PetscScalar *x_t, const std::vector<double> &lambda_n, const std::vector<double> &mult_n);
  /// Adds scale times the friction forces, -sum t_k lambda_t,k on each pair's node and - w_jl times that on its master
  /// nodes (lambda_t, or the solve's mult_t: solved), to r (the owned displacement rows, local offsets, n of them).
  /// Collective.
  [[nodiscard]] PetscErrorCode AddForces(const std::vector<ContactPair> &pairs, double scale, bool solved, double *r,
                                         PetscInt n) const;
  /// Adds the master nodes' part of AddForces (lambda_t) alone, and its sums per component over this rank's rows to
  /// sum (dim values). Collective.
  [[nodiscard]] PetscErrorCode AddMasterForces(const std::vector<ContactPair> &pairs, double *r, PetscInt n,
                                               double *sum) const;
  /// The friction certificate at u_local. lambda_tol: the normal part's tolerance on multipliers; slip_tol: the
  /// gap tolerance. Collective.
  [[nodiscard]] PetscErrorCode Certify(MPI_Comm comm, const std::vector<ContactPair> &pairs,
                                       const std::vector<PairState> &states, const double *u_local,
                                       double lambda_tol, double slip_tol, FrictionCertificate &cert) const;
  /// Per pair: its set, lambda_t (PerPair() values), its tangent basis and its coefficient, for the output.
  Grip State(std::size_t p) const { return grip_[p]; }
  const double *LambdaT(std::size_t p) const { return &lambda_t_[p * PerPair()]; }
  const double *Tangent(std::size_t p, int k) const { return tangents_[p][k].data(); }
  double Mu(std::size_t p) const { return mu_pair_[p]; }
  /// Saves and restores the sets and multipliers (a failed load step goes back).
  struct Saved {
    std::vector<Grip> grip;
    std::vector<double> dir, lambda_t, mult_t;
  };
  Saved Save() const { return {grip_, dir_, lambda_t_, mult_t_}; }
  void Restore(const Saved &s) {
    grip_ = next_ = s.grip, dir_ = next_dir_ = s.dir, lambda_t_ = s.lambda_t, mult_t_ = s.mult_t;
  }
  /// A slip direction that turned by less than this (|d_new - d_old|) is the same.
  static constexpr double DIRECTION_TOL = 1e-9;

private:
  /// The relative displacement of each pair's node, u_j - sum_l w_jl u_l (dim values per pair). Collective.
  [[nodiscard]] PetscErrorCode Relative(const std::vector<ContactPair> &pairs, const double *u_local,
                                        std::vector<double> &r) const;
  /// The slip increments of the relative displacements r (Relative).
  void SlipsOf(const std::vector<double> &r, std::vector<double> &s) const;
  /// The row of pair p along the direction a t_1 + b t_2 (3D): the combination of its two rows.
  void TurnedRow(std::size_t p, double a, double b, SparseRow &row) const;
  /// The row of tangential multiplier k of pair p in the system: its own, or a 3D slip pair's turned one; empty when
  /// the pair has none there.
  void SystemRow(std::size_t p, int k, SparseRow &row) const;
  /// Whether a row holds anything: a free part of norm above 1e-6 (the supports fix the motion along it otherwise);
  /// judged on the pair's own node.
  static bool HasRow(const SparseRow &row);

  double mu_ = 0;
  std::vector<double> pair_mu_; ///< per -contact_pairs item, -1: mu_
  std::vector<double> facet_mu_; ///< per obstacle facet, its kind's coefficient (-obstacle_friction), -1: mu_
  std::string kind_option_;      ///< -obstacle_friction as given (empty: none)
  int dim_ = 2;
  const Mesh *mesh_ = nullptr;
  const DofMap *dofs_ = nullptr;
  const MortarCoupling *mortar_ = nullptr;
  std::vector<double> mu_pair_;                                ///< per pair
  std::vector<std::array<std::array<double, 3>, 2>> tangents_; ///< per pair
  std::vector<SparseRow> rows_;   ///< per pair and tangent, on all the free columns of its normal row
  std::vector<char> has_;         ///< per pair and tangent: HasRow of its slave part
  std::vector<PetscInt> pairs_vertex_; ///< per pair: its node (local vertex)
  const std::vector<char> *fixed_ = nullptr; ///< Bind's Dirichlet flags
  std::vector<double> origin_;    ///< per pair (dim values): r at the start of the step, or where the pair touched
  std::vector<double> start_r_, start_gap_; ///< r and the gap at the start of the step
  std::vector<double> start_u_;   ///< the displacement at the start of the step (dim values per local vertex)
  std::vector<double> last_start_u_; ///< the displacement at the start of the last step (empty in the first)
  std::vector<double> last_motion_;  ///< per pair: r at the step's start less r at the last step's start
  std::vector<Grip> grip_, next_;
  std::vector<double> dir_, next_dir_; ///< slip directions (PerPair() per pair)
  /// 3D slip pairs: D of the row across the slip, -|s| / (mu lambda_n) (NaN: no such row, lambda_n = 0)
  std::vector<double> across_, next_across_;
  std::vector<double> lambda_t_, mult_t_;
};

} // namespace signorini
