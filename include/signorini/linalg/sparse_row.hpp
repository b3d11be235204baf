// A sparse row of the constraint block B of the saddle-point system: the global displacement rows it touches and
// their coefficients (a node against a rigid obstacle: at most one per spatial direction; a mortar row of a pair of
// bodies: its slave node's and the master nodes' components).
#pragma once

#include <petscsys.h>

#include <vector>

namespace signorini {

/// A row of B: ncols global displacement columns and their coefficients.
struct SparseRow {
  PetscInt ncols = 0;
  std::vector<PetscInt> cols;
  std::vector<double> coef;
  void Clear() { ncols = 0, cols.clear(), coef.clear(); }
  void Add(PetscInt col, double value) { cols.push_back(col), coef.push_back(value), ++ncols; }
};

} // namespace signorini
