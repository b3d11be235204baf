// What the contact loop asks of the material model (linear, svk): one object chosen once from -material_model, so
// that a new model answers these questions instead of adding a branch to the loop.
#pragma once

#include "signorini/fem/material.hpp"
#include "signorini/loop/reason.hpp"

#include <memory>

namespace signorini {

/// The material model as the loop sees it. The element kernels (fem) compute its stiffness and internal force; this
/// says how the loop must iterate on them.
class MaterialPolicy {
public:
  virtual ~MaterialPolicy() = default;
  /// The internal force is nonlinear in u (docs/theory.md §5): every iteration is a Newton step whose tangent is
  /// assembled again at the iterate, the residual is evaluated at every iterate (no shortcut from an exact linear
  /// solve), the step length is searched, a failed load step may be cut (-load_max_cuts), and the kept factorisation
  /// may serve as a lagged tangent (-newton_lagged_search). Otherwise K is constant: one solve per active set, and an
  /// iterative solve's equilibrium residual is corrected by a further solve.
  virtual bool Nonlinear() const = 0;
  /// Gaps, normals and pair zones are evaluated in the current configuration, so the pairs are searched again as the
  /// body moves (ContactSolver::Repair). Otherwise they are those of the reference configuration (g0 + n0 u, the
  /// zones fixed): pairs outside their zone are dropped and a failed step adds the facets its nodes went into.
  virtual bool CurrentConfiguration() const = 0;
  /// How many times an active set must come back before it counts as cycling (ActiveSet::Seen): Newton iterates pass
  /// through a set more than once on their way to its equilibrium.
  virtual int CycleRepeats() const = 0;
  /// Whether the contact problem from an iterate may be solved as a linear complementarity problem in the multipliers
  /// (Lemke, ContactSolver::PivotedActiveSet): exact only when the kept factorisation is the stiffness itself.
  virtual bool Pivots() const = 0;
  /// The reason a certified load step converged with.
  virtual Reason ConvergedReason() const = 0;
};

/// The policy of a model (-material_model).
std::unique_ptr<const MaterialPolicy> MakeMaterialPolicy(MaterialModel model);

} // namespace signorini
