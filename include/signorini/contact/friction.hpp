// Coulomb friction at the pairs against rigid obstacles (docs/theory.md §9): per pair its coefficient mu, a tangent
// basis of its normal, the tangential constraint rows, the slip increment of the load step, and the three sets of the
// primal-dual active set of Hueber, Stadler and Wohlmuth (SIAM J. Sci. Comput. 30, 2008) per load step: open
// (inactive), stick and slip, with the tangential multipliers lambda_t.
//
// Conventions. A pair's tangential multiplier lambda_t (dim - 1 components in its tangent basis t_k) is the friction
// force the node exerts on the obstacle: the force on the body is n lambda_n - sum_k t_k lambda_t,k, and on a slip
// node lambda_t = mu lambda_n s / |s| for its slip increment s (s_k = t_k . (u - u at the start of the load step)).
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
#include "signorini/fem/dof_map.hpp"
#include "signorini/linalg/sparse_row.hpp"

#include <array>
#include <string>
#include <vector>

namespace signorini {

/// Friction state of a pair in a solve.
enum class Grip : char { OPEN = 0, SLIP = 1, STICK = 2 };
extern const char *const GRIP_NAMES[]; ///< "open", "slip", "stick"

/// The friction of a run's pairs. Pairs live on their node's rank; nothing here is collective unless said so.
class Friction {
public:
  /// The run's coefficient (-contact_friction; 0: frictionless, and nothing below is used).
  void SetCoefficient(double mu) { mu_ = mu; }
  bool On() const { return mu_ > 0; }
  double Coefficient() const { return mu_; }
  /// Binds to the pairs (linear material: their normals are fixed): tangent bases, tangential rows on the free
  /// components of each node (fixed marks the Dirichlet dofs per local vertex dof), every pair open. A pair of bodies
  /// (mortar: is_mortar[p]) has no friction. Not collective.
  void Bind(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
            const std::vector<ContactPair> &pairs, const std::vector<std::array<double, 3>> &normals,
            const std::vector<char> &is_mortar);
  /// Tangential rows per pair (dim - 1) and in all.
  int PerPair() const { return dim_ - 1; }
  std::size_t Rows() const { return rows_.size(); }
  /// Starts a load step: the tangential displacements at u_local (the converged state) are the slips' origin.
  void BeginStep(const std::vector<ContactPair> &pairs, const double *u_local);
  /// The slip increments at u_local (PerPair() per pair).
  void Slips(const std::vector<ContactPair> &pairs, const double *u_local, std::vector<double> &s) const;
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
  /// Flags for cycle detection: 0 open, 1 slip, 2 stick per pair (the proposed sets), normal set `active`.
  void SetKey(const std::vector<char> &active, std::vector<char> &key) const;
  /// The constraint rows of the system: the normal ones, then the tangential ones; the active flags (stick rows and
  /// 3D slip rows across the slip); per row the column coefficients where they differ from the row's (slip pairs'
  /// normal rows; empty otherwise) and D on the active rows (0, or the 3D slip rows' spring).
  void SystemRows(const std::vector<SparseRow> &normal_rows, const std::vector<char> &active,
                  std::vector<SparseRow> &rows, std::vector<char> &flags, std::vector<std::vector<double>> &columns,
                  std::vector<double> &diag) const;
  /// The directions (3 values each) of the tangential rows active in SystemRows for pair p: what they hold.
  void HeldDirections(std::size_t p, std::vector<std::array<double, 3>> &dirs) const;
  /// The right-hand side of the tangential rows at u_local: -s on stick rows, 0 elsewhere.
  void RowRhs(const std::vector<ContactPair> &pairs, const double *u_local, PetscScalar *b) const;
  /// Reads the tangential multipliers of a solution (x_t: the tangential rows; lambda_n, mult_n: the normal
  /// multipliers and solved values): lambda_t (stick: solved; slip: mu lambda_n d; open: 0) and the force the solve
  /// applies through them (mult_t: x_t, plus mu mult_n d on slip pairs).
  void Read(const PetscScalar *x_t, const std::vector<double> &lambda_n, const std::vector<double> &mult_n);
  /// Adds scale times the friction forces on the nodes, -sum t_k lambda_t,k (or the solve's, mult_t), to r at the
  /// owned displacement offsets of the pairs' nodes.
  void AddForces(const std::vector<ContactPair> &pairs, const DofMap &dofs, double scale, bool solved,
                 double *r) const;
  /// The friction certificate at u_local. lambda_tol: the normal part's tolerance on multipliers; slip_tol: the
  /// gap tolerance. Collective.
  [[nodiscard]] PetscErrorCode Certify(MPI_Comm comm, const Mesh &mesh, const std::vector<ContactPair> &pairs,
                                       const std::vector<PairState> &states, const double *u_local,
                                       double lambda_tol, double slip_tol, FrictionCertificate &cert) const;
  /// Per pair: its set, lambda_t (PerPair() values) and tangent basis (dim vectors of 3 values, PerPair() of them),
  /// for the output.
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
  double mu_ = 0;
  int dim_ = 2;
  std::vector<double> mu_pair_;                            ///< per pair (0: a pair of bodies)
  std::vector<std::array<std::array<double, 3>, 2>> tangents_; ///< per pair
  std::vector<SparseRow> rows_;                            ///< per pair and tangent (empty: no free component)
  std::vector<std::vector<int>> components_;               ///< per pair: the component of each of its row's columns
  std::vector<double> base_;                               ///< t_k . u at the start of the step
  std::vector<Grip> grip_, next_;
  std::vector<double> dir_, next_dir_;                     ///< slip directions (PerPair() per pair)
  /// 3D slip pairs: D of the row across the slip, -|s| / (mu lambda_n) (NaN: no such row, lambda_n = 0)
  std::vector<double> across_, next_across_;
  /// The row of pair p along the direction a t_1 + b t_2 (3D) on its free components (empty when they vanish).
  void TurnedRow(std::size_t p, double a, double b, SparseRow &row) const;
  /// The row of tangential multiplier i (pair p, tangent k) in the system: rows_[i], or a 3D slip pair's turned one.
  void SystemRow(std::size_t p, int k, SparseRow &row) const;
  std::vector<double> lambda_t_, mult_t_;
};

} // namespace signorini
