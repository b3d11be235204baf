// What the loop does after a failed load step: repeat it with a wider pair search, repeat it with exact Newton steps,
// cut its increment, or fail; and the failure's message. Pure functions of the failure and the run's history.
#pragma once

#include "signorini/loop/reason.hpp"

#include <petscsys.h>

#include <string>

namespace signorini {

enum class Retry {
  WIDEN,        ///< repeat the step from the last converged state with the pairs of a wider radius
  EXACT_NEWTON, ///< svk: repeat the step from the last converged state with exact Newton steps
  CUT,          ///< svk: halve the increment and repeat from the last converged state
  FAIL,         ///< stop the run with the reported reason
};

/// A failed attempt at a load step.
struct StepFailure {
  Reason reason = Reason::NONE;
  bool wider_search = false;         ///< the attempt asks for a wider pair search (ContactSolver::UnpairedAfterFailure)
  Reason repeated = Reason::NONE;    ///< the failure this attempt repeated with exact Newton steps (NONE: no repeat)
};

/// What the run has done so far that the policy depends on.
struct RetryHistory {
  bool svk = false;          ///< the nonlinear material, whose load steps can be cut
  bool lagged = false;       ///< svk: lagged Newton searches on the kept factorisation (-newton_lagged_search)
  bool exact_newton = false; ///< the load steps take exact Newton steps already
  bool exact_tried = false;  ///< a step was repeated with exact Newton steps in this run (once per run)
  PetscInt cuts = 0, max_cuts = 0; ///< the cuts made and allowed (-load_max_cuts)
  Reason first_unheld = Reason::NONE; ///< the failure of a step repeated with a wider radius for a free body
};

struct RetryDecision {
  Retry action = Retry::FAIL;
  Reason reason = Reason::NONE; ///< the failure to report (an earlier attempt's where it is the clearer report)
  bool exact_newton = false;    ///< whether the load steps take exact Newton steps from now on
  bool wider_search = false;    ///< the wider search still stands (a repeat's outcome cancels it)
  /// FAIL: the body was found not held with the pairs of a narrower radius, and with the wider ones it deformed
  /// non-invertibly before it could be found held or not (the message says both).
  bool deformed_after_unheld = false;
};

/// The retry policy, in this order:
///  1. The repeat of a step with exact Newton steps reports the failure it repeated: a body found free that fails
///     otherwise stays not held; another failure keeps its reason and leaves the lagged searches on.
///  2. A wider pair search asked for: WIDEN (not a cut: the increment stays).
///  3. svk with lagged searches, a failure that is not a singular system: EXACT_NEWTON, once per run (a step that
///     fails at the end of the lagged searches' path may converge with exact Newton steps).
///  4. A body found not held with a narrower radius and failing otherwise with a wider one, when nothing is left to
///     try, is reported not held, unless it deformed non-invertibly first.
///  5. svk with cuts left, unless the body is not held or the system singular (no matter of the increment): CUT.
///  6. FAIL.
RetryDecision DecideRetry(const StepFailure &failure, const RetryHistory &history);

/// What the failure message of a run needs.
struct FailureReport {
  Reason reason = Reason::NONE;
  double load_factor = 0;
  bool svk = false;
  bool deformed_after_unheld = false; ///< RetryDecision::deformed_after_unheld
  bool has_obstacle = true;
  double search_radius = 0;
  bool free_without_contact = false;  ///< svk out of iterations: the supports alone leave a rigid-body motion free
  std::string singular_prefix;        ///< DIVERGED_SINGULAR: the system's report of what it found (SingularReport)
  std::string unheld_detail;          ///< DIVERGED_NOT_HELD: the complementarity problem's finding, if any
  std::string violation;              ///< _CERTIFICATE, _EQUILIBRIUM_STALLED: the failed condition
};

/// The one-line message of a run that stops: "the contact solve did not converge at load factor F: REASON: what
/// happened and what to check".
std::string FailureMessage(const FailureReport &report);

} // namespace signorini
