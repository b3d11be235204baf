// Global numbering of the saddle-point unknowns: on each rank its owned displacement rows, then its owned
// multiplier rows; ghost vertices learn their numbers from their owners. The displacement and multiplier blocks of a
// nested saddle-point matrix number their rows alone (block rows: the same order without the other block's rows).
#pragma once

#include "signorini/core/handle.hpp"
#include "signorini/mesh/mesh.hpp"

#include <vector>

namespace signorini {

class DofMap {
public:
  /// Numbers the dofs of `mesh` with `num_owned_multipliers` multiplier rows on this rank. Collective.
  [[nodiscard]] PetscErrorCode Create(const Mesh &mesh, PetscInt num_owned_multipliers);

  int Dim() const { return dim_; }
  PetscInt OwnedU() const { return nu_; }
  PetscInt OwnedLambda() const { return nl_; }
  PetscInt OwnedRows() const { return nu_ + nl_; }
  PetscInt RowStart() const { return row_start_; }
  PetscInt GlobalRows() const { return n_global_; }
  PetscInt GlobalU() const { return nu_global_; }
  PetscInt GlobalLambda() const { return n_global_ - nu_global_; }
  /// Global row of component k of local vertex v.
  PetscInt Row(PetscInt v, int k) const { return vertex_row_[v] + k; }
  /// Global row of owned multiplier p.
  PetscInt LambdaRow(PetscInt p) const { return row_start_ + nu_ + p; }
  /// Row of component k of local vertex v in the displacement block alone.
  PetscInt URow(PetscInt v, int k) const { return vertex_urow_[v] + k; }
  /// Per local vertex its first row (component k: + k), in the whole system's numbering (Row) or the displacement
  /// block's (URow).
  const std::vector<PetscInt> &FirstRows(bool block) const { return block ? vertex_urow_ : vertex_row_; }
  /// The displacement block's row of the global displacement row `row` (of any rank).
  PetscInt UBlockRow(PetscInt row) const;
  /// The multiplier block's row of owned multiplier p.
  PetscInt LambdaBlockRow(PetscInt p) const { return lambda_start_ + p; }
  /// Local offset (into this rank's part of a global vector) of component k of owned vertex v.
  PetscInt LocalOffset(PetscInt v, int k) const { return vertex_row_[v] + k - row_start_; }
  /// Index sets of the owned displacement rows (block size dim) and multiplier rows; named "u" and "lambda".
  IS IsU() const { return is_u_; }
  IS IsLambda() const { return is_lambda_; }

private:
  int dim_ = 2;
  PetscInt nu_ = 0, nl_ = 0, row_start_ = 0, n_global_ = 0, nu_global_ = 0, lambda_start_ = 0;
  std::vector<PetscInt> vertex_row_, vertex_urow_;
  std::vector<PetscInt> row_starts_, u_starts_; ///< per rank (and one past the last): first row, first block row
  ISH is_u_, is_lambda_;
};

} // namespace signorini
