// Friction on the kept factorisation (docs/theory.md §9, docs/solver.md): the saddle-point matrix of friction has
// rows that turn with the slip (3D) and slip columns that differ from their rows, so it changes with the sets in more
// than its multiplier block. Per group of rows J (a pair's normal row and its tangential ones), the current rows are
// R_J = Q_J B_J and their columns C_J = P_J B_J in terms of fixed rows B_J (the normal row and the rows along the
// pair's fixed tangents). With the multipliers nu = P^T x of the fixed columns and mu = nu - w B du (w the
// augmentation weight), the current system [K C^T; R D] is the fixed, symmetric [K + w B^T B, B^T; B, X] with only
// the multiplier block X changed, per group X_J = G^-1 F P^-T and the right-hand side y_J = G^-1 b_J, where
// G = E + w F P^-T, E_J the rows' Q (0 on a row the system writes as zeros) and F_J the diagonal the system writes.
// The kept factorisation of the fixed matrix (its Schur complement on every multiplier) then solves every set by a
// dense LU of the multipliers' S0 + (X - D0) alone, and x_J = P^-T (mu + w (y_J - X_J mu_J)) gives the current
// system's multipliers back.
#pragma once

#include "signorini/linalg/sparse_row.hpp"

#include <petscsys.h>

#include <tuple>
#include <vector>

namespace signorini {

/// A group of owned multiplier rows (local indices) and, row-major |J| x |J|, their rows and columns in terms of
/// the group's fixed rows (KeptRows' head).
struct RowGroup {
  std::vector<PetscInt> rows;
  std::vector<double> q, p;
};

class KeptRows {
public:
  /// The fixed rows of every owned multiplier row and the groups (every owned row in at most one; a row in none is
  /// its own group with Q = P = 1).
  void Set(std::vector<SparseRow> fixed, std::vector<RowGroup> groups);
  const std::vector<SparseRow> &Fixed() const { return fixed_; }
  bool Empty() const { return fixed_.empty(); }
  /// The multiplier block X and the maps of the right-hand side and the solution, from what the system writes on
  /// each owned row: kept (the row's coefficients, else zeros) and d (its diagonal entry); w the augmentation weight
  /// of the fixed matrix. Not collective; an error names a group whose G is singular.
  [[nodiscard]] PetscErrorCode Update(const std::vector<char> &kept, const std::vector<double> &d, double w);
  /// X's diagonal (owned rows) and its entries off the diagonal (owned row, owned column, value).
  const std::vector<double> &Diagonal() const { return x_diag_; }
  const std::vector<std::tuple<PetscInt, PetscInt, double>> &Couplings() const { return x_off_; }
  /// The current system's multiplier right-hand side (owned rows) becomes the fixed system's, y = G^-1 b per group;
  /// y is kept for Back.
  void Forward(PetscScalar *bm);
  /// The fixed system's multipliers mu (owned rows) become the current system's, x = P^-T (mu + w (y - X mu)).
  void Back(PetscScalar *xm) const;

private:
  struct Group {
    std::vector<PetscInt> rows;
    std::vector<double> x, ginv, pinvt; ///< row-major: X_J, G^-1, P^-T
  };
  std::vector<SparseRow> fixed_;
  std::vector<RowGroup> given_;
  std::vector<Group> groups_;
  std::vector<double> x_diag_, y_;
  std::vector<std::tuple<PetscInt, PetscInt, double>> x_off_;
  double w_ = 0;
};

} // namespace signorini
