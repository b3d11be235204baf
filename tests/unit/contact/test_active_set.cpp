// The active-set rule NextActive on hand-built pair states.
#include "signorini/contact/active_set.hpp"

#include <gtest/gtest.h>

namespace signorini {
namespace {

constexpr double C = 1e3;    // complementarity parameter (force per unit gap)
constexpr double TOL = 1e-6; // force tolerance

PairState State(bool active, bool inside, double gap, double lambda) {
  PairState s;
  s.active = active;
  s.inside = inside;
  s.gap = gap;
  s.lambda = lambda;
  return s;
}

TEST(ActiveSet, InactivePenetratingInsideBecomesActive) {
  EXPECT_TRUE(NextActive(State(false, true, -1e-3, 0.0), C, TOL));
}

TEST(ActiveSet, InactivePenetratingOutsideTheFacetStaysInactive) {
  EXPECT_FALSE(NextActive(State(false, false, -1e-3, 0.0), C, TOL));
  EXPECT_FALSE(NextActive(State(false, false, -1.0, 0.0), C, TOL));
}

TEST(ActiveSet, InactiveWithAnOpenGapStaysInactive) {
  EXPECT_FALSE(NextActive(State(false, true, 1e-3, 0.0), C, TOL));
  EXPECT_FALSE(NextActive(State(false, true, 0.0, 0.0), C, TOL));
}

TEST(ActiveSet, ActiveWithCompressiveMultiplierStaysActive) {
  EXPECT_TRUE(NextActive(State(true, true, 0.0, 5.0), C, TOL));
  // A small opening is outweighed by a large compressive force: lambda - c g = 5 - 1 > 0.
  EXPECT_TRUE(NextActive(State(true, true, 1e-3, 5.0), C, TOL));
}

TEST(ActiveSet, ActivePairWhoseNodeLeavesTheFacetIsReleased) {
  EXPECT_FALSE(NextActive(State(true, false, 0.0, 5.0), C, TOL));
  EXPECT_FALSE(NextActive(State(true, false, -1e-3, 5.0), C, TOL));
}

TEST(ActiveSet, ActiveWithTensileMultiplierIsReleased) {
  EXPECT_FALSE(NextActive(State(true, true, 0.0, -5.0), C, TOL));
  EXPECT_FALSE(NextActive(State(true, true, 1e-3, 0.0), C, TOL)); // opening with no force: lambda - c g = -1
}

TEST(ActiveSet, ToleranceSeparatesNoiseFromDecisions) {
  // Inactive: a score within the tolerance does not activate, beyond it does.
  EXPECT_FALSE(NextActive(State(false, true, -0.5 * TOL / C, 0.0), C, TOL));
  EXPECT_TRUE(NextActive(State(false, true, -2.0 * TOL / C, 0.0), C, TOL));
  // Active: a slightly tensile multiplier within the tolerance keeps the pair, beyond it releases it.
  EXPECT_TRUE(NextActive(State(true, true, 0.0, -0.5 * TOL), C, TOL));
  EXPECT_FALSE(NextActive(State(true, true, 0.0, -2.0 * TOL), C, TOL));
  // With zero tolerance any penetration inside the facet activates.
  EXPECT_TRUE(NextActive(State(false, true, -1e-12, 0.0), C, 0.0));
}

TEST(ActiveSet, ComplementarityParameterWeighsTheGapAgainstTheMultiplier) {
  const PairState s = State(false, true, -1e-6, 0.0);
  EXPECT_FALSE(NextActive(s, 1.0, 1e-3)); // score 1e-6 below the tolerance
  EXPECT_TRUE(NextActive(s, 1e6, 1e-3));  // score 1
  const PairState t = State(true, true, 1e-3, 0.5);
  EXPECT_TRUE(NextActive(t, 100.0, 1e-6));   // 0.5 - 0.1 > 0
  EXPECT_FALSE(NextActive(t, 1000.0, 1e-6)); // 0.5 - 1 < 0
}

TEST(ActiveSet, ActivationToleranceOnlyDelaysActivation) {
  const double activate_tol = 100 * TOL;
  // Inactive: a penetration whose score lies between tol and activate_tol waits; a deeper one is activated.
  EXPECT_FALSE(NextActive(State(false, true, -10 * TOL / C, 0.0), C, TOL, activate_tol));
  EXPECT_TRUE(NextActive(State(false, true, -10 * TOL / C, 0.0), C, TOL, TOL));
  EXPECT_TRUE(NextActive(State(false, true, -200 * TOL / C, 0.0), C, TOL, activate_tol));
  // Active: release still uses tol, whatever activate_tol is.
  EXPECT_TRUE(NextActive(State(true, true, 0.0, 10 * TOL), C, TOL, activate_tol));
  EXPECT_TRUE(NextActive(State(true, true, 0.0, -0.5 * TOL), C, TOL, activate_tol));
  EXPECT_FALSE(NextActive(State(true, true, 0.0, -2.0 * TOL), C, TOL, activate_tol));
  // The three-argument form uses one tolerance for both.
  const PairState s = State(false, true, -10 * TOL / C, 0.0);
  EXPECT_EQ(NextActive(s, C, TOL), NextActive(s, C, TOL, TOL));
}

} // namespace
} // namespace signorini
