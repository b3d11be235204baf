// The loop's retry policy after a failed load step (DecideRetry) by each rule and their order, the failure message
// (FailureMessage) by reason, and the reasons' name table; pure functions, no MPI.
#include "signorini/loop/retry_policy.hpp"

#include <set>
#include <string>

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// svk with lagged searches, no exact Newton yet, cuts left.
RetryHistory SvkFresh() {
  RetryHistory h;
  h.svk = true;
  h.lagged = true;
  h.max_cuts = 5;
  return h;
}

RetryHistory Linear() {
  RetryHistory h;
  h.max_cuts = 5; // the linear material never cuts, whatever -load_max_cuts says
  return h;
}

TEST(RetryPolicy, WiderSearchComesFirst) {
  for (const RetryHistory &h : {Linear(), SvkFresh()}) {
    const RetryDecision d = DecideRetry({Reason::DIVERGED_CYCLING, true, Reason::NONE}, h);
    EXPECT_EQ(d.action, Retry::WIDEN);
    EXPECT_EQ(d.reason, Reason::DIVERGED_CYCLING);
    EXPECT_TRUE(d.wider_search);
    EXPECT_FALSE(d.exact_newton);
  }
}

TEST(RetryPolicy, LinearFailsWithoutWiderSearch) {
  for (Reason r : {Reason::DIVERGED_CYCLING, Reason::DIVERGED_MAX_IT, Reason::DIVERGED_NOT_HELD,
                   Reason::DIVERGED_SINGULAR, Reason::DIVERGED_CERTIFICATE}) {
    const RetryDecision d = DecideRetry({r, false, Reason::NONE}, Linear());
    EXPECT_EQ(d.action, Retry::FAIL) << ReasonName(r);
    EXPECT_EQ(d.reason, r);
  }
}

TEST(RetryPolicy, SvkRepeatsOnceWithExactNewtonBeforeCutting) {
  RetryHistory h = SvkFresh();
  RetryDecision d = DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h);
  EXPECT_EQ(d.action, Retry::EXACT_NEWTON);
  EXPECT_TRUE(d.exact_newton);
  // Once per run: after a repeat, the next failure is cut.
  h.exact_tried = true;
  d = DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h);
  EXPECT_EQ(d.action, Retry::CUT);
  // Not without lagged searches, nor when the steps are exact already.
  h = SvkFresh();
  h.lagged = false;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h).action, Retry::CUT);
  h = SvkFresh();
  h.exact_newton = true;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h).action, Retry::CUT);
}

TEST(RetryPolicy, SingularIsNeverRepeatedNorCut) {
  const RetryDecision d = DecideRetry({Reason::DIVERGED_SINGULAR, false, Reason::NONE}, SvkFresh());
  EXPECT_EQ(d.action, Retry::FAIL);
  EXPECT_EQ(d.reason, Reason::DIVERGED_SINGULAR);
  EXPECT_FALSE(d.exact_newton);
}

TEST(RetryPolicy, NotHeldIsNeverCut) {
  RetryHistory h = SvkFresh();
  h.exact_tried = true;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_NOT_HELD, false, Reason::NONE}, h).action, Retry::FAIL);
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_CYCLING, false, Reason::NONE}, h).action, Retry::CUT);
}

TEST(RetryPolicy, CutsRunOut) {
  RetryHistory h = SvkFresh();
  h.exact_tried = true;
  h.cuts = 4;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h).action, Retry::CUT);
  h.cuts = 5;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_MAX_IT, false, Reason::NONE}, h).action, Retry::FAIL);
}

TEST(RetryPolicy, FailedRepeatReportsWhatItRepeated) {
  RetryHistory h = SvkFresh();
  h.exact_newton = true; // the repeat runs with exact Newton steps
  h.exact_tried = true;
  // A body found free stays not held, whatever the repeat did, and the wider search it asked for is dropped.
  RetryDecision d = DecideRetry({Reason::DIVERGED_MAX_IT, true, Reason::DIVERGED_NOT_HELD}, h);
  EXPECT_EQ(d.action, Retry::FAIL);
  EXPECT_EQ(d.reason, Reason::DIVERGED_NOT_HELD);
  EXPECT_FALSE(d.wider_search);
  EXPECT_TRUE(d.exact_newton);
  // Another failure keeps its reason and goes back to the lagged searches, then is cut.
  d = DecideRetry({Reason::DIVERGED_NONINVERTIBLE_DEFORMATION, true, Reason::DIVERGED_CYCLING}, h);
  EXPECT_EQ(d.action, Retry::CUT);
  EXPECT_EQ(d.reason, Reason::DIVERGED_CYCLING);
  EXPECT_FALSE(d.wider_search);
  EXPECT_FALSE(d.exact_newton);
}

TEST(RetryPolicy, BodyFoundFreeStaysFreeWhenNothingIsLeft) {
  RetryHistory h = Linear();
  h.first_unheld = Reason::DIVERGED_NOT_HELD;
  RetryDecision d = DecideRetry({Reason::DIVERGED_CYCLING, false, Reason::NONE}, h);
  EXPECT_EQ(d.action, Retry::FAIL);
  EXPECT_EQ(d.reason, Reason::DIVERGED_NOT_HELD);
  EXPECT_FALSE(d.deformed_after_unheld);
  // A deformation that became non-invertible first is reported as such, with the earlier finding.
  d = DecideRetry({Reason::DIVERGED_NONINVERTIBLE_DEFORMATION, false, Reason::NONE}, h);
  EXPECT_EQ(d.reason, Reason::DIVERGED_NONINVERTIBLE_DEFORMATION);
  EXPECT_TRUE(d.deformed_after_unheld);
  // While svk can still cut, the failure is cut with its own reason.
  h = SvkFresh();
  h.exact_tried = true;
  h.first_unheld = Reason::DIVERGED_NOT_HELD;
  d = DecideRetry({Reason::DIVERGED_CYCLING, false, Reason::NONE}, h);
  EXPECT_EQ(d.action, Retry::CUT);
  EXPECT_EQ(d.reason, Reason::DIVERGED_CYCLING);
  // A first finding that was a singular system changes nothing.
  h = Linear();
  h.first_unheld = Reason::DIVERGED_SINGULAR;
  EXPECT_EQ(DecideRetry({Reason::DIVERGED_CYCLING, false, Reason::NONE}, h).reason, Reason::DIVERGED_CYCLING);
}

TEST(FailureMessage, ByReason) {
  FailureReport r;
  r.load_factor = 0.5;
  r.reason = Reason::DIVERGED_MAX_IT;
  EXPECT_EQ(FailureMessage(r), "the contact solve did not converge at load factor 0.5: DIVERGED_MAX_IT: the active-set "
                               "loop reached its iteration limit (-contact_max_it)");
  r.svk = true;
  EXPECT_EQ(FailureMessage(r), "the contact solve did not converge at load factor 0.5: DIVERGED_MAX_IT: the Newton loop "
                               "reached its iteration limit (-newton_max_it Newton iterations, of which at most "
                               "-contact_max_it change the active set); no more load-step cuts allowed "
                               "(-load_max_cuts)");
  r.free_without_contact = true;
  const std::string hinted = FailureMessage(r);
  EXPECT_NE(hinted.find("; no more load-step cuts allowed (-load_max_cuts); the supports leave a rigid-body motion "
                        "free, so only contact holds the body"),
            std::string::npos)
      << hinted;
  // The hint belongs to svk out of iterations only.
  r.reason = Reason::DIVERGED_CYCLING;
  EXPECT_EQ(FailureMessage(r).find("only contact holds"), std::string::npos);

  FailureReport s;
  s.load_factor = 1;
  s.reason = Reason::DIVERGED_SINGULAR;
  s.search_radius = 0.25;
  s.singular_prefix = "PREFIX: ";
  s.svk = true; // a singular system is never cut: no word of cuts
  EXPECT_EQ(FailureMessage(s), "the contact solve did not converge at load factor 1: DIVERGED_SINGULAR: PREFIX: the "
                               "body is not held by the supports and the candidate pairs within "
                               "-contact_search_radius 0.25; add Dirichlet conditions (e.g. on a symmetry line) or "
                               "candidate contact nodes so that every rigid-body motion is removed");
  s.has_obstacle = false;
  EXPECT_NE(FailureMessage(s).find("not held by the supports (there is no obstacle);"), std::string::npos);

  FailureReport n;
  n.load_factor = 1;
  n.reason = Reason::DIVERGED_NOT_HELD;
  n.unheld_detail = "DETAIL";
  EXPECT_EQ(FailureMessage(n), "the contact solve did not converge at load factor 1: DIVERGED_NOT_HELD: the body is "
                               "not held: DETAIL (add Dirichlet conditions, or check the obstacle's position and "
                               "orientation and -contact_search_radius)");
  n.reason = Reason::DIVERGED_CERTIFICATE;
  n.violation = "penetration 0.1 at node 7";
  EXPECT_NE(FailureMessage(n).find("DIVERGED_CERTIFICATE: the state is not a contact solution (penetration 0.1 at "
                                   "node 7) and the active-set rule cannot change it"),
            std::string::npos);
  n.reason = Reason::DIVERGED_NONINVERTIBLE_DEFORMATION;
  n.search_radius = 3;
  n.deformed_after_unheld = true;
  EXPECT_NE(FailureMessage(n).find("(det F <= 1e-10) (the body was found not held with the pairs of a narrower "
                                   "radius; repeated with those within 3,"),
            std::string::npos);
}

TEST(Reason, NamesAreDistinctAndSpelledAsPrinted) {
  const Reason all[] = {Reason::CONVERGED_ACTIVE_SET_UNCHANGED, Reason::CONVERGED_ACTIVE_SET_AND_RESIDUAL,
                        Reason::DIVERGED_CYCLING,             Reason::DIVERGED_NOT_HELD,
                        Reason::DIVERGED_SINGULAR,            Reason::DIVERGED_MAX_IT,
                        Reason::DIVERGED_CERTIFICATE,         Reason::DIVERGED_EQUILIBRIUM_STALLED,
                        Reason::DIVERGED_NONINVERTIBLE_DEFORMATION};
  std::set<std::string> names;
  for (Reason r : all) {
    const std::string name = ReasonName(r);
    EXPECT_TRUE(name.rfind("CONVERGED_", 0) == 0 || name.rfind("DIVERGED_", 0) == 0) << name;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), sizeof(all) / sizeof(all[0]));
  EXPECT_STREQ(ReasonName(Reason::NONE), "");
  EXPECT_STREQ(ReasonName(Reason::DIVERGED_NOT_HELD), "DIVERGED_NOT_HELD");
}

} // namespace
} // namespace signorini
