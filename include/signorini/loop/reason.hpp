// Why the contact loop stopped: its converged and diverged reasons, with one name table (as PETSc's
// KSPConvergedReason), printed and written to summary.json by name.
#pragma once

namespace signorini {

/// The loop's stopping reasons (docs/theory.md: convergence means a certified state). NONE: the loop has not stopped,
/// or a stop was taken back (the complementarity problem found a set to go on from).
enum class Reason {
  NONE,
  CONVERGED_ACTIVE_SET_UNCHANGED,     ///< linear: the active set came back unchanged, the state certified
  CONVERGED_ACTIVE_SET_AND_RESIDUAL,  ///< svk: the active set unchanged and the Newton residual below tolerance
  DIVERGED_CYCLING,                   ///< an earlier active set came back
  DIVERGED_NOT_HELD,                  ///< a rigid-body motion left free carries the body away from every obstacle
  DIVERGED_SINGULAR,                  ///< the factorisation found null pivots
  DIVERGED_MAX_IT,                    ///< the iteration limit (-contact_max_it, -newton_max_it)
  DIVERGED_CERTIFICATE,               ///< the state is not a contact solution and the rule cannot change it
  DIVERGED_EQUILIBRIUM_STALLED,       ///< the equilibrium residual stalls above its tolerance
  DIVERGED_NONINVERTIBLE_DEFORMATION, ///< svk: det F <= 1e-10 somewhere
};

/// The reason's name as printed and written ("" for NONE).
const char *ReasonName(Reason reason);

} // namespace signorini
