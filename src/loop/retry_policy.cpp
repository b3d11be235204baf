// The retry policy after a failed load step and the failure message of a run that stops (retry_policy.hpp).
#include "signorini/loop/retry_policy.hpp"

#include <cstdio>

namespace signorini {

RetryDecision DecideRetry(const StepFailure &failure, const RetryHistory &history) {
  RetryDecision d;
  d.reason = failure.reason;
  d.wider_search = failure.wider_search;
  d.exact_newton = history.exact_newton;
  // A repeat with exact Newton steps that fails leaves the finding it was to check: a body found free stays not held;
  // another failure keeps its reason, and the steps go back to the lagged searches (then a cut).
  if (failure.repeated != Reason::NONE) {
    d.reason = failure.repeated;
    d.wider_search = false;
    if (failure.repeated != Reason::DIVERGED_NOT_HELD) d.exact_newton = false;
  }
  if (d.wider_search) {
    d.action = Retry::WIDEN;
    return d;
  }
  // The stale tangent of the lagged searches and the stabilised moves along a free rigid motion can carry the iterate
  // where the step cannot converge, while exact Newton steps from the last converged state do; a singular system is
  // no matter of the path.
  if (history.svk && history.lagged && !d.exact_newton && !history.exact_tried &&
      d.reason != Reason::DIVERGED_SINGULAR) {
    d.action = Retry::EXACT_NEWTON;
    d.exact_newton = true;
    return d;
  }
  const bool can_cut = history.svk && history.cuts < history.max_cuts;
  // A body found free, then repeated with the facets of a wider radius, stays free when the repeat fails otherwise
  // (it cycles or runs out of iterations): the first finding is the clearer report. Not when the repeat deformed
  // non-invertibly before any verdict: the wider pairs may hold the body or not, so the report gives both facts.
  if (history.first_unheld == Reason::DIVERGED_NOT_HELD && d.reason != Reason::DIVERGED_NOT_HELD && !can_cut) {
    if (d.reason != Reason::DIVERGED_NONINVERTIBLE_DEFORMATION) d.reason = Reason::DIVERGED_NOT_HELD;
    else d.deformed_after_unheld = true;
  }
  // A body not held or a singular system is no matter of the increment: never cut.
  const bool cut = can_cut && d.reason != Reason::DIVERGED_NOT_HELD && d.reason != Reason::DIVERGED_SINGULAR;
  d.action = cut ? Retry::CUT : Retry::FAIL;
  return d;
}

namespace {

/// What happened, by reason, and what to check.
std::string WhatHappened(const FailureReport &r) {
  char text[256];
  switch (r.reason) {
  case Reason::DIVERGED_SINGULAR: {
    std::string within = "the supports (there is no obstacle)";
    if (r.has_obstacle) {
      std::snprintf(text, sizeof(text), "the supports and the candidate pairs within -contact_search_radius %.6g",
                    r.search_radius);
      within = text;
    }
    return r.singular_prefix + "the body is not held by " + within +
           "; add Dirichlet conditions (e.g. on a symmetry line) or candidate contact nodes so that every rigid-body "
           "motion is removed";
  }
  case Reason::DIVERGED_CYCLING:
    return "the active set cycles (an earlier set came back, also with one pair switched per update); a body held "
           "only by contact at a point it can rock about (e.g. a block on a disc) cycles so: check that the supports "
           "and obstacles hold every rigid-body motion";
  case Reason::DIVERGED_NONINVERTIBLE_DEFORMATION: {
    std::string what = "the deformation became non-invertible (det F <= 1e-10)";
    if (r.deformed_after_unheld) {
      std::snprintf(text, sizeof(text), " (the body was found not held with the pairs of a narrower radius; "
                    "repeated with those within %.6g, it deformed so before it could be found held or not)",
                    r.search_radius);
      what += text;
    }
    return what;
  }
  case Reason::DIVERGED_NOT_HELD:
    return (r.unheld_detail.empty() ? std::string("the body is not held: along a rigid-body motion that the supports "
                                                  "and the active contact leave free, the load moves it away from "
                                                  "every obstacle")
                                    : "the body is not held: " + r.unheld_detail) +
           " (add Dirichlet conditions, or check the obstacle's position and orientation and -contact_search_radius)";
  case Reason::DIVERGED_CERTIFICATE:
    return "the state is not a contact solution (" + r.violation + ") and the active-set rule cannot change it";
  case Reason::DIVERGED_EQUILIBRIUM_STALLED:
    return "the equilibrium residual stalls above its tolerance (" + r.violation + "): the solver cannot resolve the "
           "system more accurately (ill-conditioned, e.g. -material_nu near 0.5; or an iterative solver's "
           "tolerance); loosen -newton_rtol or use a direct solver";
  default:
    return r.svk ? "the Newton loop reached its iteration limit (-newton_max_it Newton iterations, of which at most "
                   "-contact_max_it change the active set)"
                 : "the active-set loop reached its iteration limit (-contact_max_it)";
  }
}

} // namespace

std::string FailureMessage(const FailureReport &r) {
  char head[96];
  std::snprintf(head, sizeof(head), "the contact solve did not converge at load factor %.6g: ", r.load_factor);
  std::string message = head + std::string(ReasonName(r.reason)) + ": " + WhatHappened(r);
  if (r.svk && r.reason != Reason::DIVERGED_SINGULAR) message += "; no more load-step cuts allowed (-load_max_cuts)";
  // svk out of iterations on a body that only contact can hold: where to look.
  if (r.svk && r.reason == Reason::DIVERGED_MAX_IT && r.free_without_contact)
    message += "; the supports leave a rigid-body motion free, so only contact holds the body: one that must travel "
               "far along that motion to be held, or that nothing holds, can end so (the same case with "
               "-material_model linear says whether contact holds it)";
  return message;
}

} // namespace signorini
