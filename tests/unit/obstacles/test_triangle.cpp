// Triangle facets (gap, normal, barycentric alpha and inside flag, exact distance to the interior, edges and
// vertices) and meshed obstacles (facets from elements, orientation, manifold and degeneracy checks).
#include "signorini/obstacles/obstacle.hpp"
#include "signorini/obstacles/obstacle_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace signorini {
namespace {

/// The right triangle (0,0,0), (2,0,0), (0,2,0): normal +z by the right-hand rule.
Triangle Unit() {
  const double a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {0, 2, 0};
  return Triangle(a, b, c);
}

Projection At(const Facet &f, double x, double y, double z, double tol = 0) {
  const double p[3] = {x, y, z};
  return f.Project(p, tol, INFINITY);
}

double DistanceTo(const Facet &f, double x, double y, double z) {
  const double p[3] = {x, y, z};
  return f.Distance(p);
}

TEST(Triangle, NormalFollowsTheRightHandRuleOfTheNodeOrder) {
  const Triangle t = Unit();
  EXPECT_DOUBLE_EQ(t.Area(), 2.0);
  const Projection p = At(t, 0.5, 0.5, 1);
  EXPECT_NEAR(p.normal[0], 0, 1e-15);
  EXPECT_NEAR(p.normal[1], 0, 1e-15);
  EXPECT_NEAR(p.normal[2], 1, 1e-15);
  const double a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {0, 2, 0};
  const Triangle reversed(a, c, b);
  EXPECT_NEAR(At(reversed, 0.5, 0.5, 1).normal[2], -1, 1e-15);
  EXPECT_NEAR(At(reversed, 0.5, 0.5, 1).gap, -1, 1e-15);
}

TEST(Triangle, GapIsTheSignedDistanceToThePlaneOnAnInclinedTriangle) {
  // The plane x + y + z = 1 through its three axis points; unit normal (1,1,1)/sqrt(3).
  const double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1};
  const Triangle t(a, b, c);
  const double s = 1 / std::sqrt(3.0);
  const Projection p = At(t, 1, 1, 1);
  EXPECT_NEAR(p.gap, 2 * s, 1e-15);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(p.normal[i], s, 1e-15);
  EXPECT_NEAR(At(t, 0, 0, 0).gap, -s, 1e-15);
  // The centroid's foot has barycentric coordinates 1/3 each.
  EXPECT_NEAR(At(t, 1.0 / 3 + 0.1, 1.0 / 3 + 0.1, 1.0 / 3 + 0.1).alpha, 1.0 / 3, 1e-15);
  EXPECT_TRUE(At(t, 1.0 / 3, 1.0 / 3, 1.0 / 3).inside);
}

TEST(Triangle, AlphaIsTheSmallestBarycentricCoordinate) {
  const Triangle t = Unit();
  EXPECT_NEAR(At(t, 0, 0, 0.3).alpha, 0, 1e-15);      // vertex P0: (1, 0, 0)
  EXPECT_NEAR(At(t, 1, 0, -0.3).alpha, 0, 1e-15);     // edge P0-P1: (0.5, 0.5, 0)
  EXPECT_NEAR(At(t, 0.5, 0.5, 0).alpha, 0.25, 1e-15); // (0.5, 0.25, 0.25)
  EXPECT_NEAR(At(t, 3, 0, 0).alpha, -0.5, 1e-15);     // beyond P1: (-0.5, 1.5, 0)
}

TEST(Triangle, InsideFlagUsesTheAlphaToleranceOnEveryEdge) {
  const Triangle t = Unit();
  EXPECT_TRUE(At(t, 0.5, 0.5, 2).inside);
  EXPECT_TRUE(At(t, 1, 0, 0.1).inside); // on the edge P0-P1
  EXPECT_TRUE(At(t, 1, 1, 0.1).inside); // on the hypotenuse
  EXPECT_TRUE(At(t, 0, 2, 0.1).inside); // on the vertex P2
  EXPECT_FALSE(At(t, 1, -1e-6, 0.1).inside);
  EXPECT_FALSE(At(t, -1e-6, 1, 0.1).inside);
  EXPECT_FALSE(At(t, 1 + 1e-6, 1, 0.1).inside);
  // Barycentric -5e-7 (1e-6 over 2): inside with alpha_tol 1e-6, not with 1e-7.
  EXPECT_TRUE(At(t, 1, -1e-6, 0.1, 1e-6).inside);
  EXPECT_FALSE(At(t, 1, -1e-6, 0.1, 1e-7).inside);
  EXPECT_FALSE(At(t, 3, 3, 0).inside);
}

TEST(Triangle, EdgeToleranceIsCappedByTheBodyLength) {
  // A large triangle (legs 1000): relative to its heights alone, alpha_tol 1e-8 would reach 1e-5 past an edge;
  // capped by a tenth of a body of diagonal 2 it reaches 2e-9.
  const double a[3] = {0, 0, 0}, b[3] = {1000, 0, 0}, c[3] = {0, 1000, 0};
  const Triangle t(a, b, c);
  const double past[3] = {1, -1e-6, 0.1}, near[3] = {1, -1.5e-9, 0.1}, beyond[3] = {1, -2.5e-9, 0.1};
  EXPECT_TRUE(t.Project(past, 1e-8, INFINITY).inside);
  EXPECT_FALSE(t.Project(past, 1e-8, 2).inside);
  EXPECT_TRUE(t.Project(near, 1e-8, 2).inside);
  EXPECT_FALSE(t.Project(beyond, 1e-8, 2).inside);
  // A triangle smaller than a tenth of the body keeps the tolerance relative to its own heights (1e-6 x 2 past the
  // edge y = 0).
  const double inside[3] = {1, -1.5e-6, 0.1}, outside[3] = {1, -2.5e-6, 0.1};
  EXPECT_TRUE(Unit().Project(inside, 1e-6, 100).inside);
  EXPECT_FALSE(Unit().Project(outside, 1e-6, 100).inside);
}

TEST(Triangle, DistanceIsToTheInteriorEdgesAndVertices) {
  const Triangle t = Unit();
  EXPECT_NEAR(DistanceTo(t, 0.5, 0.5, -0.7), 0.7, 1e-15);      // over the interior: |gap|
  EXPECT_NEAR(DistanceTo(t, 1, -3, 4), 5, 1e-15);              // nearest the edge P0-P1 at (1, 0, 0)
  EXPECT_NEAR(DistanceTo(t, 2, 2, 0), std::sqrt(2.0), 1e-15);  // nearest the hypotenuse at (1, 1, 0)
  EXPECT_NEAR(DistanceTo(t, -3, -4, 0), 5, 1e-15);             // nearest the vertex P0
  EXPECT_NEAR(DistanceTo(t, 4, -1, 2), 3, 1e-15);              // nearest the vertex P1: (2, -1, 2)
  EXPECT_NEAR(DistanceTo(t, -1, 4, 0), std::sqrt(5.0), 1e-15); // nearest the vertex P2: (-1, 2, 0)
  EXPECT_NEAR(DistanceTo(t, 1, 1, 0), 0, 1e-15);
  double c[3];
  const double x[3] = {2, 1, 1};
  t.ClosestPoint(x, c);
  EXPECT_NEAR(c[0], 1.5, 1e-15); // foot (2, 1) onto the hypotenuse x + y = 2: (1.5, 0.5)
  EXPECT_NEAR(c[1], 0.5, 1e-15);
  EXPECT_NEAR(c[2], 0, 1e-15);
}

TEST(Triangle, BoundsAndSurface) {
  const double a[3] = {1, -2, 3}, b[3] = {4, 0, -1}, c[3] = {0, 5, 2};
  const Triangle t(a, b, c);
  double lo[3], hi[3];
  t.Bounds(lo, hi);
  EXPECT_EQ(lo[0], 0);
  EXPECT_EQ(lo[1], -2);
  EXPECT_EQ(lo[2], -1);
  EXPECT_EQ(hi[0], 4);
  EXPECT_EQ(hi[1], 5);
  EXPECT_EQ(hi[2], 3);
  const auto s = t.Surface(Box{});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1][0], 4);
  EXPECT_EQ(s[2][1], 5);
}

/// An element set of the given nodes (x, y, z each) and elements (node indices), tags 101, 102, ...
ElementSet Set(const std::vector<double> &xyz, const std::vector<std::vector<int>> &elements) {
  ElementSet set;
  set.coords = xyz;
  for (std::size_t i = 0; i < xyz.size() / 3; ++i)
    set.node_tags.push_back(i + 1);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    set.nodes.insert(set.nodes.end(), elements[e].begin(), elements[e].end());
    set.offsets.push_back((int)set.nodes.size());
    set.tags.push_back(101 + e);
  }
  return set;
}

/// The unit square z = 0 with its centre node 4: corners 0..3 counter-clockwise seen from +z.
const std::vector<double> SQUARE = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0.5, 0};

std::string Build(const ElementSet &set, int dim, std::vector<std::unique_ptr<Facet>> &out) {
  return BuildMeshFacets(set, dim, "test.msh", out);
}

TEST(ObstacleMesh, QuadrilateralsBecomeTwoTrianglesFacingTheRightHandNormal) {
  std::vector<std::unique_ptr<Facet>> out;
  ASSERT_EQ(Build(Set(SQUARE, {{0, 1, 2, 3}}), 3, out), "");
  ASSERT_EQ(out.size(), 2u);
  for (const auto &f : out) {
    EXPECT_NEAR(At(*f, 0.5, 0.5, 0.2).gap, 0.2, 1e-15);
    EXPECT_NEAR(At(*f, 0.5, 0.5, 0.2).normal[2], 1, 1e-15);
  }
  // Together the halves cover the square: every point of it is inside one of them.
  for (double x : {0.1, 0.5, 0.9})
    for (double y : {0.1, 0.5, 0.9})
      EXPECT_TRUE(At(*out[0], x, y, 0).inside || At(*out[1], x, y, 0).inside);
}

TEST(ObstacleMesh, ConsistentFanIsAccepted) {
  std::vector<std::unique_ptr<Facet>> out;
  EXPECT_EQ(Build(Set(SQUARE, {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}), 3, out), "");
  EXPECT_EQ(out.size(), 4u);
}

TEST(ObstacleMesh, InconsistentOrientationNamesTheElements) {
  std::vector<std::unique_ptr<Facet>> out;
  const std::string e = Build(Set(SQUARE, {{0, 1, 4}, {1, 2, 4}, {2, 4, 3}, {3, 0, 4}}), 3, out);
  EXPECT_NE(e.find("obstacle mesh 'test.msh'"), std::string::npos) << e;
  EXPECT_NE(e.find("element 102 and element 103 traverse their common edge (nodes 3, 5) in the same direction"),
            std::string::npos)
      << e;
  EXPECT_TRUE(out.empty());
}

TEST(ObstacleMesh, NonManifoldEdgeIsAnError) {
  std::vector<std::unique_ptr<Facet>> out;
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
  const std::string e = Build(Set(xyz, {{0, 1, 2}, {1, 0, 3}, {1, 0, 4}}), 3, out);
  EXPECT_NE(e.find("the edge (nodes 1, 2) is shared by 3 elements (element 101, element 102, element 103)"),
            std::string::npos)
      << e;
}

TEST(ObstacleMesh, DegenerateFacetsAreErrors) {
  std::vector<std::unique_ptr<Facet>> out;
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0};
  EXPECT_NE(Build(Set(xyz, {{0, 1, 2}}), 3, out).find("element 101 has zero area"), std::string::npos);
  EXPECT_NE(Build(Set(xyz, {{0, 1, 2, 3}}), 3, out).find("element 101 has zero area"), std::string::npos);
  // A bow tie: the halves of the split face opposite ways.
  const std::vector<double> bow = {0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_NE(Build(Set(bow, {{0, 1, 2, 3}}), 3, out).find("element 101 is a folded"), std::string::npos);
  EXPECT_NE(Build(Set(xyz, {{0, 0}}), 2, out).find("element 101 has zero length"), std::string::npos);
  EXPECT_TRUE(out.empty());
}

TEST(ObstacleMesh, PolylineSegmentsKeepTheirDirection) {
  std::vector<std::unique_ptr<Facet>> out;
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 2, 1, 0};
  ASSERT_EQ(Build(Set(xyz, {{0, 1}, {1, 2}}), 2, out), "");
  ASSERT_EQ(out.size(), 2u);
  EXPECT_NEAR(At(*out[0], 0.5, 1, 0).normal[1], 1, 1e-15); // left normal of (0,0) -> (1,0)
  EXPECT_NEAR(At(*out[0], 0.5, 1, 0).gap, 1, 1e-15);
  const auto line = out[1]->Polyline();
  EXPECT_EQ(line[0][0], 1);
  EXPECT_EQ(line[1][0], 2);
}

TEST(ObstacleMesh, PolylineChecks) {
  std::vector<std::unique_ptr<Facet>> out;
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 2, 1, 0, 1, -1, 0};
  EXPECT_NE(Build(Set(xyz, {{0, 1}, {2, 1}}), 2, out).find("element 101 and element 102 both end at node 2"),
            std::string::npos);
  EXPECT_NE(Build(Set(xyz, {{1, 0}, {1, 2}}), 2, out).find("element 101 and element 102 both start at node 2"),
            std::string::npos);
  EXPECT_NE(Build(Set(xyz, {{0, 1}, {1, 2}, {1, 3}}), 2, out).find("node 2 is shared by 3 line elements"),
            std::string::npos);
  const std::vector<double> skew = {0, 0, 0, 1, 0, 0.5};
  EXPECT_NE(Build(Set(skew, {{0, 1}}), 2, out).find("element 101 leaves the plane z = "), std::string::npos);
  EXPECT_TRUE(out.empty());
}

} // namespace
} // namespace signorini
