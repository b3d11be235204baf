// The name table of the loop's stopping reasons.
#include "signorini/loop/reason.hpp"

namespace signorini {

const char *ReasonName(Reason reason) {
  switch (reason) {
  case Reason::NONE: return "";
  case Reason::CONVERGED_ACTIVE_SET_UNCHANGED: return "CONVERGED_ACTIVE_SET_UNCHANGED";
  case Reason::CONVERGED_ACTIVE_SET_AND_RESIDUAL: return "CONVERGED_ACTIVE_SET_AND_RESIDUAL";
  case Reason::DIVERGED_CYCLING: return "DIVERGED_CYCLING";
  case Reason::DIVERGED_NOT_HELD: return "DIVERGED_NOT_HELD";
  case Reason::DIVERGED_SINGULAR: return "DIVERGED_SINGULAR";
  case Reason::DIVERGED_MAX_IT: return "DIVERGED_MAX_IT";
  case Reason::DIVERGED_CERTIFICATE: return "DIVERGED_CERTIFICATE";
  case Reason::DIVERGED_EQUILIBRIUM_STALLED: return "DIVERGED_EQUILIBRIUM_STALLED";
  case Reason::DIVERGED_NONINVERTIBLE_DEFORMATION: return "DIVERGED_NONINVERTIBLE_DEFORMATION";
  }
  return "";
}

} // namespace signorini
