// A short sparse row of the constraint block B of the saddle-point system: the global displacement rows it touches
// (at most one per spatial direction) and their coefficients.
#pragma once

#include <petscsys.h>

namespace signorini {

/// A row of B with at most three entries: ncols global displacement columns and their coefficients.
struct SparseRow {
  PetscInt ncols = 0;
  PetscInt cols[3] = {-1, -1, -1};
  double coef[3] = {0, 0, 0};
};

} // namespace signorini
