// Evaluation of the candidate pairs at a displacement: current gap, normal and projection (the constraint
// g(u) >= 0 and its gradient, the row of B), for the linear model linearised about the reference configuration
// (g = g0 + n0 . u, docs/theory.md §2) and for large deformation from the current configuration x = X + u.
#pragma once

#include "signorini/contact/active_set.hpp"
#include "signorini/contact/contact_set.hpp"
#include "signorini/fem/dof_map.hpp"
#include "signorini/linalg/sparse_row.hpp"

#include <array>
#include <vector>

namespace signorini {

/// A contact constraint row: the row of B of one pair, -n on the free displacement dofs of its node (the saddle-point
/// system takes it as a plain sparse row).
using ConstraintRow = SparseRow;

/// Gap, inside flag (in states) and constraint rows (free dofs only, coefficients -n) of every owned pair at the
/// local displacement u_local. fixed marks the Dirichlet dofs per local vertex dof.
void EvaluatePairs(const Mesh &mesh, const Obstacle &obstacle, const ContactOptions &opts,
                   const std::vector<ContactPair> &pairs, const DofMap &dofs, const std::vector<char> &fixed,
                   bool large_deformation, const double *u_local, std::vector<PairState> &states,
                   std::vector<ConstraintRow> &rows, std::vector<std::array<double, 3>> &normals);

} // namespace signorini
