// The active-set rule NextActive on hand-built pair states; the rigid modes a set of constraints leaves free.
#include "signorini/contact/active_set.hpp"
#include "signorini/contact/rigid_modes.hpp"
#include "signorini/mesh/mesh.hpp"

#include <cmath>

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

namespace signorini {
namespace {

std::vector<PairKey> Keys(std::initializer_list<PetscInt> vertices) {
  std::vector<PairKey> keys;
  PetscInt facet = 0;
  for (PetscInt v : vertices) keys.push_back({v, v, facet++});
  return keys;
}

TEST(ProposeSet, NodeThroughAFacetIsActivatedOnTheFacetItCrossedFirst) {
  // One node, three facets: it crossed facet 1 (t = 0.3) and facet 2 (t = 0.7) and lies in the strip of facet 0.
  std::vector<PairState> s(3);
  for (auto &x : s) x.gap = -1.0;
  s[0].inside = true;
  s[1].entered = true, s[1].crossing = 0.3;
  s[2].entered = true, s[2].crossing = 0.7;
  const std::vector<std::array<double, 3>> n = {{{0, 1, 0}}, {{0.1, 1, 0}}, {{-0.1, 1, 0}}};
  std::vector<char> next;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0, 0}), n, next);
  EXPECT_EQ(next, (std::vector<char>{0, 1, 0}));
}

TEST(ProposeSet, TieAtAJointKeepsTheDeeperPenetration) {
  std::vector<PairState> s(2);
  s[0].entered = s[1].entered = true;
  s[0].crossing = s[1].crossing = 0.5;
  s[0].gap = -0.1, s[1].gap = -0.2;
  const std::vector<std::array<double, 3>> n = {{{0.1, 1, 0}}, {{-0.1, 1, 0}}};
  std::vector<char> next;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next);
  EXPECT_EQ(next, (std::vector<char>{0, 1}));
}

TEST(ProposeSet, ConcaveCornerKeepsBothFacets) {
  // Both pairs of the corner node in their zone (no path crossing): both penetrating pairs are activated.
  std::vector<PairState> s(2);
  s[0].inside = s[1].inside = true;
  s[0].gap = s[1].gap = -1e-3;
  const std::vector<std::array<double, 3>> n = {{{1, 0, 0}}, {{0, 1, 0}}};
  std::vector<char> next;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next);
  EXPECT_EQ(next, (std::vector<char>{1, 1}));
}

TEST(ProposeSet, ParallelPairsOfOneNodeCountOnce) {
  std::vector<PairState> s(3);
  for (auto &x : s) x.inside = true, x.gap = -1e-3;
  const std::vector<std::array<double, 3>> n = {{{0, 1, 0}}, {{0, 1, 0}}, {{0, 1, 0}}};
  std::vector<char> next;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0, 1}), n, next);
  EXPECT_EQ(next, (std::vector<char>{1, 0, 1}));
}

TEST(ProposeSet, ParallelPairsKeepTheDeeperPenetration) {
  // One node, two facets 0.9 degrees apart: the active one (gap 0) and the next one, penetrated by 1e-4 after the
  // node slid over their concave joint. The deeper one stays; within gap_tol the active one does.
  const double a = 0.9 * M_PI / 180;
  const std::vector<std::array<double, 3>> n = {{{0, 1, 0}}, {{-std::sin(a), std::cos(a), 0}}};
  std::vector<PairState> s(2);
  s[0].inside = s[1].inside = true;
  s[0].active = true, s[0].lambda = 1, s[0].gap = 0;
  s[1].gap = -1e-4;
  std::vector<char> next;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next, 1e-9);
  EXPECT_EQ(next, (std::vector<char>{0, 1}));
  // Penetrations that activate a pair (C 1e-8 > TOL) but lie within gap_tol 1e-7 of the active pair's gap.
  s[1].gap = -1e-8;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next, 1e-7);
  EXPECT_EQ(next, (std::vector<char>{1, 0}));
  s[0].active = false, s[0].lambda = 0, s[0].gap = -1e-8;
  s[1].active = true, s[1].lambda = 1, s[1].gap = 0;
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next, 1e-7);
  EXPECT_EQ(next, (std::vector<char>{0, 1}));
  ProposeSet(s, C, TOL, TOL, Keys({0, 0}), n, next, 1e-9); // beyond gap_tol: the deeper one
  EXPECT_EQ(next, (std::vector<char>{1, 0}));
}

TEST(Certificate, NamesTheFirstViolatedCondition) {
  Certificate c;
  c.gap_tol = 1e-9, c.lambda_tol = 1e-6, c.complementarity_tol = 1e-9, c.equilibrium_tol = 1e-8;
  EXPECT_TRUE(c.Satisfied());
  c.max_penetration = 1e-3;
  EXPECT_NE(c.Violation().find("penetrates"), std::string::npos);
  c.max_penetration = 0, c.min_active_lambda = -1;
  EXPECT_NE(c.Violation().find("tensile"), std::string::npos);
  c.min_active_lambda = 0, c.equilibrium = 1;
  EXPECT_NE(c.Violation().find("equilibrium"), std::string::npos);
  c.equilibrium = 0, c.changes = 2;
  EXPECT_NE(c.Violation().find("switch"), std::string::npos);
  c.changes = 0, c.equilibrium = NAN;
  EXPECT_FALSE(c.Satisfied());
}

TEST(Certificate, ReportsTheViolationsInTheirOrder) {
  // Every condition violated at once; each message names the first that still fails once the ones before it hold:
  // penetration, penetration on an unpaired facet, tensile active multiplier, inactive multiplier, complementarity,
  // equilibrium, switches of the rule.
  Certificate c;
  c.gap_tol = 1e-9, c.lambda_tol = 1e-6, c.complementarity_tol = 1e-9, c.equilibrium_tol = 1e-8;
  c.max_penetration = 1e-3, c.unpaired_penetration = 2e-3, c.unpaired_node = 7, c.min_active_lambda = -1;
  c.max_inactive_lambda = 1, c.complementarity = 1, c.equilibrium = 1, c.changes = 2;
  const char *expected[] = {"a node penetrates the obstacle by 0.001", "node 7 (at 0, 0, 0) penetrates",
                            "tensile multiplier -1", "an inactive pair carries a multiplier 1",
                            "complementarity max |lambda g| = 1", "the equilibrium residual 1", "switch 2 pair(s)"};
  for (const char *phrase : expected) {
    EXPECT_NE(c.Violation().find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << c.Violation();
    EXPECT_FALSE(c.Satisfied());
    if (c.max_penetration > c.gap_tol)
      c.max_penetration = 0;
    else if (c.unpaired_penetration > c.gap_tol)
      c.unpaired_penetration = 0;
    else if (c.min_active_lambda < -c.lambda_tol)
      c.min_active_lambda = 0;
    else if (c.max_inactive_lambda > c.lambda_tol)
      c.max_inactive_lambda = 0;
    else if (c.complementarity > c.complementarity_tol)
      c.complementarity = 0;
    else if (c.equilibrium > c.equilibrium_tol)
      c.equilibrium = 0;
    else
      c.changes = 0;
  }
  EXPECT_TRUE(c.Satisfied()) << c.Violation();
}

TEST(RigidModes, FloorAloneLeavesTheHorizontalTranslationFree) {
  const double centre[2] = {0.5, 0.5}, up[2] = {0, 1}, right[2] = {1, 0};
  double g[9] = {0}, row[3];
  for (double x : {0.0, 0.5, 1.0}) {
    const double X[2] = {x, 0};
    ASSERT_EQ(RigidModeRow(2, X, centre, 1.0, up, row), 3);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) g[i * 3 + j] += row[i] * row[j];
  }
  EXPECT_LT(RelativeSmallestEigenvalue(3, g), 1e-12);
  const double X[2] = {0, 0.5};
  RigidModeRow(2, X, centre, 1.0, right, row);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g[i * 3 + j] += row[i] * row[j];
  EXPECT_GT(RelativeSmallestEigenvalue(3, g), 1e-3);
}

/// The beam mesh (2D) and its rigid modes without supports.
class BeamModes : public ::testing::Test {
protected:
  void SetUp() override {
    MeshOptions opts;
    opts.file = SIGNORINI_SOURCE_DIR "/meshes/beam.msh";
    ASSERT_EQ(mesh_.Create(PETSC_COMM_SELF, opts), 0);
    fixed_.assign(2 * mesh_.NumLocalVertices(), 0);
    ASSERT_EQ(modes_.Setup(mesh_, fixed_), 0);
    ylow_ = INFINITY;
    for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) ylow_ = std::min(ylow_, mesh_.X(v)[1]);
  }
  /// du[v*2+k]: the rigid motion (tx, ty, omega about the point (0.3, 0.1)) plus a stretch s (x - 0.3) along x.
  std::vector<double> Displacement(double tx, double ty, double omega, double s) const {
    std::vector<double> du(2 * mesh_.NumLocalVertices());
    for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) {
      const double x = mesh_.X(v)[0] - 0.3, y = mesh_.X(v)[1] - 0.1;
      du[2 * v] = tx - omega * y + s * x;
      du[2 * v + 1] = ty + omega * x;
    }
    return du;
  }
  /// Pairs with a floor under the bottom vertices (normal +y), all active.
  void Floor(std::vector<PairKey> &keys, std::vector<std::array<double, 3>> &normals) const {
    for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
      if (mesh_.X(v)[1] < ylow_ + 1e-12) {
        keys.push_back({v, v, 0});
        normals.push_back({0, 1, 0});
      }
  }
  /// The displacement of local vertex v along dir (2 values) under the rigid motion a.
  double Along(PetscInt v, const double *dir, const RigidMotion &a) const {
    double m[3];
    modes_.Motion(v, a, m);
    return m[0] * dir[0] + m[1] * dir[1];
  }
  Mesh mesh_;
  std::vector<char> fixed_;
  RigidModes modes_;
  double ylow_ = 0;
};

TEST_F(BeamModes, EveryModeFreeGivesTheRigidMotionBack) {
  const std::vector<double> du = Displacement(0.3, -0.2, 0.05, 0);
  RigidMotion a;
  ASSERT_EQ(modes_.FreeMotion({}, {}, {}, du.data(), a), 0);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    for (int k = 0; k < 2; ++k) {
      const double e[2] = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0};
      EXPECT_NEAR(Along(v, e, a), du[2 * v + k], 1e-12);
    }
}

TEST_F(BeamModes, AFloorLeavesOnlyTheSlideAndAStretchAddsItsMean) {
  std::vector<PairKey> keys;
  std::vector<std::array<double, 3>> normals;
  Floor(keys, normals);
  ASSERT_GT(keys.size(), 2u);
  const std::vector<char> active(keys.size(), 1);
  // A translation (0.3, -0.2): the floor holds y and the rotation, so the free motion is the slide by 0.3.
  const std::vector<double> du = Displacement(0.3, -0.2, 0, 0);
  RigidMotion a;
  ASSERT_EQ(modes_.FreeMotion(keys, normals, active, du.data(), a), 0);
  const double right[2] = {1, 0}, up[2] = {0, 1};
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); v += 7) {
    EXPECT_NEAR(Along(v, right, a), 0.3, 1e-12);
    EXPECT_NEAR(Along(v, up, a), 0.0, 1e-12);
  }
  EXPECT_NEAR(modes_.Magnitude(a), 0.3, 1e-12);
  // The stretch s (x - 0.3) adds its mean over the vertices to the slide, nothing across it.
  double mean = 0;
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) mean += 0.01 * (mesh_.X(v)[0] - 0.3);
  mean /= (double)mesh_.NumLocalVertices();
  const std::vector<double> stretched = Displacement(0.3, -0.2, 0, 0.01);
  ASSERT_EQ(modes_.FreeMotion(keys, normals, active, stretched.data(), a), 0);
  EXPECT_NEAR(Along(0, right, a), 0.3 + mean, 1e-12);
  EXPECT_NEAR(Along(0, up, a), 0.0, 1e-12);
  // Every mode held (a pair with normal +x at vertex 0 as well): no free motion.
  keys.push_back({0, 0, 1});
  normals.push_back({1, 0, 0});
  std::vector<char> all(keys.size(), 1);
  ASSERT_EQ(modes_.FreeMotion(keys, normals, all, du.data(), a), 0);
  EXPECT_EQ(modes_.Magnitude(a), 0.0);
}

TEST_F(BeamModes, OnePairLeavesTheRotationsAboutItsNode) {
  // One pair with normal +y at a bottom vertex X0: the free modes are the slide along x and the rotations about X0
  // (eigenvectors that mix a translation and the rotation). A rotation about X0 plus a slide is free: the fit gives
  // it back exactly; a lift along +y is not, and the fit leaves it out.
  std::vector<PairKey> keys;
  std::vector<std::array<double, 3>> normals;
  Floor(keys, normals);
  keys.resize(1), normals.resize(1);
  const double *X0 = mesh_.X(keys[0].vertex);
  std::vector<double> du(2 * mesh_.NumLocalVertices());
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) {
    const double x = mesh_.X(v)[0] - X0[0], y = mesh_.X(v)[1] - X0[1], omega = 0.02;
    du[2 * v] = 0.1 - omega * y;
    du[2 * v + 1] = omega * x;
  }
  RigidMotion a;
  ASSERT_EQ(modes_.FreeMotion(keys, normals, {1}, du.data(), a), 0);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    for (int k = 0; k < 2; ++k) {
      const double e[2] = {k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0};
      EXPECT_NEAR(Along(v, e, a), du[2 * v + k], 1e-12);
    }
  std::vector<double> lifted = du;
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) lifted[2 * v + 1] += 0.3;
  RigidMotion b;
  ASSERT_EQ(modes_.FreeMotion(keys, normals, {1}, lifted.data(), b), 0);
  const double up[2] = {0, 1};
  EXPECT_NEAR(Along(keys[0].vertex, up, b), 0.0, 1e-12); // the pair's node does not move along its normal
}

} // namespace
} // namespace signorini
