// Obstacle facets (gap, normal, projection parameter, distance, their drawing in 3D), the shape registry and the
// -obstacle_ options.
#include "signorini/obstacles/obstacle.hpp"

#include "petsc_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace signorini {
namespace {

using test::ErrorCapture;
using test::ScopedOptions;

Projection ProjectOn(const Facet &facet, double x, double y, double alpha_tol = 0.0) {
  const double p[2] = {x, y};
  return facet.Project(p, alpha_tol, INFINITY);
}

double DistanceTo(const Facet &facet, double x, double y) {
  const double p[2] = {x, y};
  return facet.Distance(p);
}

const ShapeType &Shape(const std::string &option) {
  for (const ShapeType &shape : ShapeRegistry())
    if (option == shape.option) return shape;
  ADD_FAILURE() << "no shape type " << option << " in the registry";
  static const ShapeType none{"", "", 0, nullptr, 0};
  return none;
}

TEST(Segment, NormalIsTheLeftNormalOfTheDirection) {
  const double p0[2] = {1, 1}, p1[2] = {4, 5};
  const Segment s(p0, p1);
  EXPECT_DOUBLE_EQ(s.Length(), 5.0);
  const Projection p = ProjectOn(s, 0, 0);
  EXPECT_NEAR(p.normal[0], -0.8, 1e-15);
  EXPECT_NEAR(p.normal[1], 0.6, 1e-15);
  const Segment reversed(p1, p0);
  const Projection q = ProjectOn(reversed, 0, 0);
  EXPECT_NEAR(q.normal[0], 0.8, 1e-15);
  EXPECT_NEAR(q.normal[1], -0.6, 1e-15);
}

TEST(Segment, GapIsPositiveAboveAndNegativeWhenPenetrating) {
  const double p0[2] = {0, 0}, p1[2] = {2, 0};
  const Segment s(p0, p1);
  const Projection above = ProjectOn(s, 0.5, 0.3);
  EXPECT_NEAR(above.gap, 0.3, 1e-15);
  EXPECT_NEAR(above.normal[0], 0.0, 1e-15);
  EXPECT_NEAR(above.normal[1], 1.0, 1e-15);
  EXPECT_NEAR(ProjectOn(s, 1.5, -0.2).gap, -0.2, 1e-15);
  EXPECT_NEAR(ProjectOn(s, 1.0, 0.0).gap, 0.0, 1e-15);
  // The same points seen from the reversed segment (normal pointing down) have the opposite gap.
  const Segment reversed(p1, p0);
  EXPECT_NEAR(ProjectOn(reversed, 0.5, 0.3).gap, -0.3, 1e-15);

  // A slanted segment: gap is the signed distance along its normal.
  const double a[2] = {1, 1}, b[2] = {4, 5};
  const Segment slanted(a, b);
  const double n[2] = {-0.8, 0.6};
  const Projection p = ProjectOn(slanted, 2.5 + 2 * n[0], 3 + 2 * n[1]);
  EXPECT_NEAR(p.gap, 2.0, 1e-14);
  EXPECT_NEAR(p.alpha, 0.5, 1e-14);
}

TEST(Segment, AlphaIsZeroAtP0OneAtP1AndLinearAlong) {
  const double p0[2] = {-1, 2}, p1[2] = {3, 0};
  const Segment s(p0, p1);
  EXPECT_NEAR(ProjectOn(s, -1, 2).alpha, 0.0, 1e-15);
  EXPECT_NEAR(ProjectOn(s, 3, 0).alpha, 1.0, 1e-15);
  // Eq. 24: alpha = (P1 - P0) . (x - P0) / |P1 - P0|^2, independent of the offset along the normal.
  const double x[2] = {0.5, 4.0};
  const double expected = (4 * (x[0] + 1) + (-2) * (x[1] - 2)) / 20.0;
  EXPECT_NEAR(ProjectOn(s, x[0], x[1]).alpha, expected, 1e-15);
  EXPECT_NEAR(ProjectOn(s, -1 - 0.4, 2 + 0.2).alpha, -0.1, 1e-15);
  EXPECT_NEAR(ProjectOn(s, 3 + 0.8, 0 - 0.4).alpha, 1.2, 1e-15);
}

TEST(Segment, InsideFlagUsesTheAlphaTolerance) {
  const double p0[2] = {0, 0}, p1[2] = {10, 0};
  const Segment s(p0, p1);
  EXPECT_TRUE(ProjectOn(s, 5, -1).inside);
  EXPECT_TRUE(ProjectOn(s, 0, -1).inside);
  EXPECT_TRUE(ProjectOn(s, 10, -1).inside);
  EXPECT_FALSE(ProjectOn(s, -0.1, -1).inside); // alpha = -0.01
  EXPECT_FALSE(ProjectOn(s, 10.1, -1).inside); // alpha = 1.01
  EXPECT_TRUE(ProjectOn(s, -0.1, -1, 0.02).inside);
  EXPECT_TRUE(ProjectOn(s, 10.1, -1, 0.02).inside);
  EXPECT_FALSE(ProjectOn(s, -0.3, -1, 0.02).inside);
  EXPECT_FALSE(ProjectOn(s, 10.3, -1, 0.02).inside);
}

TEST(Segment, EndToleranceIsCappedByTheBodyLength) {
  // A floor 1000 long ending at x = 1.5: relative to its length alone, alpha_tol 1e-8 reaches 1e-5 past its end;
  // capped by a tenth of a body of diagonal 2 it reaches 2e-9.
  const double a[2] = {-998.5, 0}, b[2] = {1.5, 0};
  const Segment floor(a, b);
  const double past[2] = {1.5 + 1e-6, 0.1}, near[2] = {1.5 + 1.5e-9, 0.1}, beyond[2] = {1.5 + 2.5e-9, 0.1};
  EXPECT_TRUE(floor.Project(past, 1e-8, INFINITY).inside);
  EXPECT_FALSE(floor.Project(past, 1e-8, 2).inside);
  EXPECT_TRUE(floor.Project(near, 1e-8, 2).inside);
  EXPECT_FALSE(floor.Project(beyond, 1e-8, 2).inside);
  // A segment shorter than a tenth of the body keeps the tolerance relative to its length (1e-2 x 1 past its end).
  const double p0[2] = {0, 0}, p1[2] = {1, 0}, inside[2] = {1.009, 0.1}, outside[2] = {1.011, 0.1};
  const Segment unit(p0, p1);
  EXPECT_TRUE(unit.Project(inside, 1e-2, 100).inside);
  EXPECT_FALSE(unit.Project(outside, 1e-2, 100).inside);
}

TEST(Segment, DistanceIsToTheFiniteSegment) {
  const double p0[2] = {0, 0}, p1[2] = {2, 0};
  const Segment s(p0, p1);
  EXPECT_NEAR(DistanceTo(s, 1, 0.5), 0.5, 1e-15);
  EXPECT_NEAR(DistanceTo(s, 1, -0.25), 0.25, 1e-15);
  EXPECT_NEAR(DistanceTo(s, 5, 4), 5.0, 1e-15);   // beyond P1: distance to P1
  EXPECT_NEAR(DistanceTo(s, -3, -4), 5.0, 1e-15); // before P0: distance to P0
  EXPECT_NEAR(DistanceTo(s, 2, 0), 0.0, 1e-15);
  double lo[2], hi[2];
  const double a[2] = {3, -1}, b[2] = {1, 2};
  Segment(a, b).Bounds(lo, hi);
  EXPECT_EQ(lo[0], 1.0);
  EXPECT_EQ(lo[1], -1.0);
  EXPECT_EQ(hi[0], 3.0);
  EXPECT_EQ(hi[1], 2.0);
}

TEST(Disc, GapAndNormalAreRadial) {
  const double c[2] = {1, 2};
  const Ball d(c, 0.5, 2);
  const Projection top = ProjectOn(d, 1, 3);
  EXPECT_NEAR(top.gap, 0.5, 1e-15);
  EXPECT_NEAR(top.normal[0], 0.0, 1e-15);
  EXPECT_NEAR(top.normal[1], 1.0, 1e-15);
  EXPECT_TRUE(top.inside);
  const Projection pen = ProjectOn(d, 1.3, 2.4); // distance 0.5 from the centre: on the surface
  EXPECT_NEAR(pen.gap, 0.0, 1e-15);
  EXPECT_NEAR(pen.normal[0], 0.6, 1e-15);
  EXPECT_NEAR(pen.normal[1], 0.8, 1e-15);
  const Projection inside = ProjectOn(d, 1.0 - 0.3 * 0.6, 2.0 - 0.3 * 0.8);
  EXPECT_NEAR(inside.gap, -0.2, 1e-15);
  EXPECT_NEAR(inside.normal[0], -0.6, 1e-15);
  EXPECT_NEAR(inside.normal[1], -0.8, 1e-15);
  EXPECT_NEAR(DistanceTo(d, 1.0 - 0.3 * 0.6, 2.0 - 0.3 * 0.8), 0.2, 1e-15);
  EXPECT_NEAR(DistanceTo(d, 4, 6), 4.5, 1e-15);
  double lo[2], hi[2];
  d.Bounds(lo, hi);
  EXPECT_EQ(lo[0], 0.5);
  EXPECT_EQ(lo[1], 1.5);
  EXPECT_EQ(hi[0], 1.5);
  EXPECT_EQ(hi[1], 2.5);
}

TEST(Segment, PolylineIsItsTwoEndsInOrder) {
  const double p0[2] = {1, 2}, p1[2] = {3, -1};
  const auto points = Segment(p0, p1).Polyline();
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0][0], 1.0);
  EXPECT_EQ(points[0][1], 2.0);
  EXPECT_EQ(points[1][0], 3.0);
  EXPECT_EQ(points[1][1], -1.0);
}

TEST(Ball, PolylineIsAClosedPolygonOnTheCircle) {
  const double c[2] = {1, 2};
  const auto points = Ball(c, 0.5, 2).Polyline();
  ASSERT_EQ(points.size(), (std::size_t)Ball::POLYGON_SIDES + 1);
  EXPECT_EQ(points.front(), points.back());
  for (const auto &p : points) EXPECT_NEAR(std::hypot(p[0] - 1, p[1] - 2), 0.5, 1e-15);
  // Equal sides: the polygon is regular, so no side hides a flat spot of the circle.
  const double side = std::hypot(points[1][0] - points[0][0], points[1][1] - points[0][1]);
  for (std::size_t k = 1; k + 1 < points.size(); ++k)
    EXPECT_NEAR(std::hypot(points[k + 1][0] - points[k][0], points[k + 1][1] - points[k][1]), side, 1e-14);
}

TEST(Plane, GapIsTheSignedDistanceAlongTheUnitNormalEverywhere) {
  const double p[3] = {1, 2, 3}, n[3] = {0, 3, 4}; // normalised to (0, 0.6, 0.8)
  const Plane plane(p, n);
  const double x[3] = {-50, 2 + 0.6 * 2, 3 + 0.8 * 2}, behind[3] = {7, 2 - 0.6, 3 - 0.8};
  const Projection a = plane.Project(x, 0, 0), b = plane.Project(behind, 0, 0);
  EXPECT_NEAR(a.gap, 2.0, 1e-14);
  EXPECT_NEAR(b.gap, -1.0, 1e-14);
  EXPECT_NEAR(plane.Distance(behind), 1.0, 1e-14);
  EXPECT_TRUE(a.inside && b.inside); // unbounded: every point projects onto it
  EXPECT_NEAR(a.normal[0], 0.0, 1e-15);
  EXPECT_NEAR(a.normal[1], 0.6, 1e-15);
  EXPECT_NEAR(a.normal[2], 0.8, 1e-15);
  double lo[3], hi[3];
  plane.Bounds(lo, hi);
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(std::isinf(lo[i]) && std::isinf(hi[i]) && lo[i] < 0 && hi[i] > 0);
}

TEST(Sphere, GapAndNormalAreRadialIn3D) {
  const double c[3] = {1, 2, -1};
  const Ball sphere(c, 2.0, 3);
  const double out[3] = {1 + 2, 2 + 4, -1 + 4}, in[3] = {1, 2, -1 + 1.5};
  const Projection a = sphere.Project(out, 0, 0), b = sphere.Project(in, 0, 0);
  EXPECT_NEAR(a.gap, 4.0, 1e-14); // |x - c| = 6
  EXPECT_NEAR(a.normal[0], 1.0 / 3, 1e-15);
  EXPECT_NEAR(a.normal[1], 2.0 / 3, 1e-15);
  EXPECT_NEAR(a.normal[2], 2.0 / 3, 1e-15);
  EXPECT_NEAR(b.gap, -0.5, 1e-14);
  EXPECT_NEAR(b.normal[2], 1.0, 1e-15);
  EXPECT_NEAR(sphere.Distance(in), 0.5, 1e-14);
  double lo[3], hi[3];
  sphere.Bounds(lo, hi);
  EXPECT_EQ(lo[2], -3.0);
  EXPECT_EQ(hi[1], 4.0);
}

TEST(Cylinder, GapIgnoresThePositionAlongTheAxis) {
  const double p[3] = {0, 0, 1}, axis[3] = {2, 0, 0}, r = 0.5;
  const Cylinder cylinder(p, axis, r);
  for (double along : {-100.0, 0.0, 3.0}) {
    const double x[3] = {along, 0.6, 1 + 0.8}, in[3] = {along, 0, 1 - 0.2};
    const Projection a = cylinder.Project(x, 0, 0), b = cylinder.Project(in, 0, 0);
    EXPECT_NEAR(a.gap, 0.5, 1e-14);
    EXPECT_NEAR(a.normal[0], 0.0, 1e-15);
    EXPECT_NEAR(a.normal[1], 0.6, 1e-15);
    EXPECT_NEAR(a.normal[2], 0.8, 1e-15);
    EXPECT_NEAR(b.gap, -0.3, 1e-14);
    EXPECT_NEAR(b.normal[2], -1.0, 1e-15);
    EXPECT_NEAR(cylinder.Distance(in), 0.3, 1e-14);
  }
}

/// Bounds of a drawn surface, and whether every triangle's right-hand normal points into the body: for a plane along
/// `into`, for a sphere or cylinder away from `centre` (its centroid's direction, minus the part along `axis`).
struct Drawn {
  std::size_t triangles = 0;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  bool oriented = true;
};

Drawn Draw(const TriangleSoup &soup, const double *into, const double *centre, const double *axis = nullptr) {
  Drawn d;
  EXPECT_EQ(soup.size() % 3, 0u);
  d.triangles = soup.size() / 3;
  for (std::size_t t = 0; t + 2 < soup.size(); t += 3) {
    const auto &a = soup[t], &b = soup[t + 1], &c = soup[t + 2];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double dir[3], along = 0;
    for (int i = 0; i < 3; ++i)
      dir[i] = into ? into[i] : (a[i] + b[i] + c[i]) / 3 - centre[i];
    for (int i = 0; axis && i < 3; ++i)
      along += dir[i] * axis[i];
    for (int i = 0; axis && i < 3; ++i)
      dir[i] -= along * axis[i];
    d.oriented = d.oriented && n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2] > 0;
    for (const auto *p : {&a, &b, &c})
      for (int i = 0; i < 3; ++i)
        d.lo[i] = std::min(d.lo[i], (*p)[i]), d.hi[i] = std::max(d.hi[i], (*p)[i]);
  }
  return d;
}

TEST(Surface, PlaneIsTheRectangleOverTheBodysProjection) {
  Box body;
  const double lo[3] = {-1, 2, 0.5}, hi[3] = {3, 4, 1.5};
  for (int i = 0; i < 3; ++i)
    body.lo[i] = lo[i], body.hi[i] = hi[i];
  // The plane z = 0.2 with its normal +z: the rectangle [-1, 3] x [2, 4] at z = 0.2.
  const double p[3] = {7, -5, 0.2}, n[3] = {0, 0, 1};
  const Drawn d = Draw(Plane(p, n).Surface(body), n, nullptr);
  EXPECT_EQ(d.triangles, 2u);
  EXPECT_TRUE(d.oriented);
  const double want_lo[3] = {-1, 2, 0.2}, want_hi[3] = {3, 4, 0.2};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.lo[i], want_lo[i], 1e-14) << i;
    EXPECT_NEAR(d.hi[i], want_hi[i], 1e-14) << i;
  }
  // An oblique plane through the box's centre: its rectangle holds the projection of every corner of the box, and
  // lies in the plane.
  const double q[3] = {1, 3, 1}, m[3] = {1, -2, 2};
  const TriangleSoup soup = Plane(q, m).Surface(body);
  const double unit[3] = {1.0 / 3, -2.0 / 3, 2.0 / 3};
  const Drawn oblique = Draw(soup, unit, nullptr);
  EXPECT_TRUE(oblique.oriented);
  for (const auto &x : soup)
    EXPECT_NEAR(unit[0] * (x[0] - q[0]) + unit[1] * (x[1] - q[1]) + unit[2] * (x[2] - q[2]), 0.0, 1e-14);
  double t1[3], t2[3];
  TangentFrame(unit, t1, t2);
  EXPECT_NEAR(t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2], 0.0, 1e-15);
  for (const double *t : {t1, t2}) {
    double s_lo, s_hi, c_lo = 1e300, c_hi = -1e300;
    BoxExtent(body, q, t, s_lo, s_hi);
    for (const auto &x : soup) {
      const double c = t[0] * (x[0] - q[0]) + t[1] * (x[1] - q[1]) + t[2] * (x[2] - q[2]);
      c_lo = std::min(c_lo, c), c_hi = std::max(c_hi, c);
    }
    EXPECT_NEAR(c_lo, s_lo, 1e-14);
    EXPECT_NEAR(c_hi, s_hi, 1e-14);
  }
}

TEST(Surface, SphereIsClosedAroundItsCentreWithItsBounds) {
  const double c[4] = {1, -2, 0.5, 3};
  const Ball sphere(c, c[3], 3);
  const TriangleSoup soup = sphere.Surface(Box{});
  const Drawn d = Draw(soup, nullptr, c);
  EXPECT_EQ(d.triangles, 2u * Ball::SPHERE_MERIDIANS * (Ball::SPHERE_MERIDIANS / 2 - 1));
  EXPECT_TRUE(d.oriented); // outwards: into the body
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.lo[i], c[i] - c[3], 1e-14) << i;
    EXPECT_NEAR(d.hi[i], c[i] + c[3], 1e-14) << i;
  }
  for (const auto &x : soup)
    EXPECT_NEAR(std::hypot(x[0] - c[0], x[1] - c[1], x[2] - c[2]), c[3], 1e-14);
  // Closed: the vector areas of its triangles cancel.
  double area[3] = {0, 0, 0};
  for (std::size_t t = 0; t < soup.size(); t += 3)
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const auto &a = soup[t], &b = soup[t + 1], &e = soup[t + 2];
      area[i] += 0.5 * ((b[j] - a[j]) * (e[k] - a[k]) - (b[k] - a[k]) * (e[j] - a[j]));
    }
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(area[i], 0.0, 1e-12) << i;
  const double disc[3] = {0, 0, 1};
  EXPECT_TRUE(Ball(disc, 1, 2).Surface(Box{}).empty()); // a disc is drawn as a polyline
}

TEST(Surface, CylinderSpansTheBodyAlongItsAxis) {
  Box body;
  const double lo[3] = {-1, 2, 0.5}, hi[3] = {3, 4, 1.5};
  for (int i = 0; i < 3; ++i)
    body.lo[i] = lo[i], body.hi[i] = hi[i];
  // Axis along y through (1, 0, -2), radius 0.5: x in [0.5, 1.5], z in [-2.5, -1.5], y over the body's [2, 4].
  const double p[3] = {1, 0, -2}, a[3] = {0, 1, 0};
  const Cylinder cylinder(p, a, 0.5);
  const Drawn d = Draw(cylinder.Surface(body), nullptr, p, a);
  EXPECT_EQ(d.triangles, 2u * Cylinder::CYLINDER_SEGMENTS);
  EXPECT_TRUE(d.oriented); // outwards: into the body
  const double want_lo[3] = {0.5, 2, -2.5}, want_hi[3] = {1.5, 4, -1.5};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.lo[i], want_lo[i], 1e-14) << i;
    EXPECT_NEAR(d.hi[i], want_hi[i], 1e-14) << i;
  }
}

TEST(ShapeRegistry, ListsThe2DAnd3DShapes) {
  EXPECT_EQ(ShapeRegistry().size(), 7u);
  EXPECT_EQ(Shape("-obstacle_rectangles").numbers, 11);
  EXPECT_EQ(Shape("-obstacle_segments").numbers, 4);
  EXPECT_EQ(Shape("-obstacle_arcs").numbers, 6);
  EXPECT_EQ(Shape("-obstacle_discs").numbers, 3);
  EXPECT_EQ(Shape("-obstacle_planes").numbers, 6);
  EXPECT_EQ(Shape("-obstacle_spheres").numbers, 4);
  EXPECT_EQ(Shape("-obstacle_cylinders").numbers, 7);
  for (const char *option : {"-obstacle_segments", "-obstacle_arcs", "-obstacle_discs"})
    EXPECT_EQ(Shape(option).dim, 2) << option;
  for (const char *option : {"-obstacle_planes", "-obstacle_spheres", "-obstacle_cylinders", "-obstacle_rectangles"})
    EXPECT_EQ(Shape(option).dim, 3) << option;
  for (const ShapeType &shape : ShapeRegistry()) {
    EXPECT_TRUE(shape.build) << shape.option;
    EXPECT_GT(std::string(shape.help).size(), 0u) << shape.option;
  }
}

TEST(ShapeRegistry, SegmentBuildsOneOrientedFacet) {
  std::vector<std::unique_ptr<Facet>> facets;
  const double v[4] = {0, 0, 0, 3}; // upwards: left normal is -x
  EXPECT_EQ(Shape("-obstacle_segments").build(v, facets), "");
  ASSERT_EQ(facets.size(), 1u);
  const Projection p = ProjectOn(*facets[0], -0.5, 1);
  EXPECT_NEAR(p.gap, 0.5, 1e-15);
  EXPECT_NEAR(p.normal[0], -1.0, 1e-15);
  EXPECT_NEAR(p.alpha, 1.0 / 3, 1e-15);
}

/// Builds an arc and checks its facets: NSEG chords with ends on the circle, contiguous, and normals pointing to
/// the centre (sign +1) or away from it (sign -1).
void CheckArc(double t0, double t1, int nseg, double sign) {
  const double cx = 1, cy = -2, r = 3;
  const double v[6] = {cx, cy, r, t0, t1, (double)nseg};
  std::vector<std::unique_ptr<Facet>> facets;
  ASSERT_EQ(Shape("-obstacle_arcs").build(v, facets), "");
  ASSERT_EQ((int)facets.size(), nseg);
  const double dt = (t1 - t0) * M_PI / 180 / nseg;
  for (int k = 0; k < nseg; ++k) {
    SCOPED_TRACE("facet " + std::to_string(k));
    const double a = t0 * M_PI / 180 + k * dt, b = a + dt, m = 0.5 * (a + b);
    const auto &s = dynamic_cast<const Segment &>(*facets[k]);
    EXPECT_NEAR(s.Length(), 2 * r * std::sin(std::abs(dt) / 2), 1e-13);
    // Ends on the circle, in order: the start of facet k is P0 (alpha 0), its end is P1 (alpha 1).
    EXPECT_NEAR(ProjectOn(s, cx + r * std::cos(a), cy + r * std::sin(a)).alpha, 0.0, 1e-12);
    EXPECT_NEAR(ProjectOn(s, cx + r * std::cos(b), cy + r * std::sin(b)).alpha, 1.0, 1e-12);
    // The chord's normal is radial (through the centre), pointing inwards for counter-clockwise arcs.
    const Projection p = ProjectOn(s, cx, cy);
    EXPECT_NEAR(p.normal[0], -sign * std::cos(m), 1e-12);
    EXPECT_NEAR(p.normal[1], -sign * std::sin(m), 1e-12);
    EXPECT_NEAR(p.gap, sign * r * std::cos(std::abs(dt) / 2), 1e-12);
  }
}

TEST(ShapeRegistry, CounterClockwiseArcNormalsPointToTheCentre) {
  CheckArc(180, 360, 8, +1.0);
}

TEST(ShapeRegistry, ClockwiseArcNormalsPointAwayFromTheCentre) {
  CheckArc(90, -45, 5, -1.0);
}

TEST(ShapeRegistry, DiscBuildsOneFacet) {
  std::vector<std::unique_ptr<Facet>> facets;
  const double v[3] = {0, 0, 2};
  EXPECT_EQ(Shape("-obstacle_discs").build(v, facets), "");
  ASSERT_EQ(facets.size(), 1u);
  EXPECT_NEAR(ProjectOn(*facets[0], 0, -3).gap, 1.0, 1e-15);
}

TEST(ShapeRegistry, DegenerateItemsAreRejectedWithAReason) {
  const struct {
    const char *option;
    std::vector<double> values;
  } cases[] = {
      {"-obstacle_segments", {1, 2, 1, 2}},
      {"-obstacle_arcs", {0, 0, 0, 0, 90, 4}},
      {"-obstacle_arcs", {0, 0, -1, 0, 90, 4}},
      {"-obstacle_arcs", {0, 0, 1, 0, 90, 0}},
      {"-obstacle_arcs", {0, 0, 1, 0, 90, -2}},
      {"-obstacle_arcs", {0, 0, 1, 0, 90, 2.5}},
      {"-obstacle_arcs", {0, 0, 1, 0, 90, NAN}},
      {"-obstacle_arcs", {0, 0, 1, 30, 30, 4}},
      {"-obstacle_discs", {0, 0, 0}},
      {"-obstacle_discs", {0, 0, -2}},
  };
  for (const auto &c : cases) {
    std::string item = c.option;
    for (double x : c.values)
      item += " " + std::to_string(x);
    SCOPED_TRACE(item);
    std::vector<std::unique_ptr<Facet>> facets;
    EXPECT_NE(Shape(c.option).build(c.values.data(), facets), "");
    EXPECT_TRUE(facets.empty());
  }
}

TEST(ObstacleOptions, EveryShapeOptionContributesItsFacets) {
  ScopedOptions options({{"-obstacle_segments", "0,0,1,0,1,0,2,1"},
                         {"-obstacle_arcs", "0,0,5,180,360,6"},
                         {"-obstacle_discs", "10,0,1"}});
  Obstacle obstacle;
  const double before = test::PetscMemoryInUse();
  ASSERT_EQ(ReadObstacle(PETSC_COMM_SELF, obstacle), 0);
  EXPECT_EQ(test::PetscMemoryInUse(), before);
  ASSERT_EQ(obstacle.facets.size(), 2u + 6u + 1u);
  EXPECT_NE(dynamic_cast<const Ball *>(obstacle.facets.back().get()), nullptr);
}

TEST(ObstacleOptions, BadItemsAreErrors) {
  const struct {
    const char *option, *value, *expected;
  } cases[] = {
      {"-obstacle_segments", "0,0,1", "multiple of 4"},  {"-obstacle_segments", "0,0,0,0", "zero length"},
      {"-obstacle_segments", "0,0,1,nan", "value 4 'nan'"}, {"-obstacle_arcs", "0,0,1,0,90,0.5", "segments"},
      {"-obstacle_discs", "0,0,1,5,5,-1", "item 2"},    {"-obstacle_discs", "0x10,0,1", "value 1 '0x10'"},
      {"-obstacle_segments", "", "no obstacle"},       {"-obstacle_planes", "0,0,0,0,0,0", "zero normal"},
      {"-obstacle_spheres", "0,0,0", "multiple of 4"}, {"-obstacle_cylinders", "0,0,0,0,0,1,-1", "radius -1"},
      {"-obstacle_cylinders", "0,0,0,0,0,0,1", "zero axis"},
  };
  for (const auto &c : cases) {
    SCOPED_TRACE(std::string(c.option) + " " + c.value);
    ScopedOptions options({{c.option, c.value}});
    ErrorCapture capture;
    Obstacle obstacle;
    EXPECT_NE(ReadObstacle(PETSC_COMM_SELF, obstacle), 0);
    EXPECT_NE(capture.Message().find(c.expected), std::string::npos) << capture.Message();
    EXPECT_NE(capture.Message().find(c.option), std::string::npos) << capture.Message();
  }
}

TEST(Rectangle, TwoTrianglesOrientedIntoTheBodyCoverIt) {
  // Centre (1, 2, 3), normal along -y (scaled), U given partly along the normal (projected away), half-sizes 2 and 0.5.
  const double v[11] = {1, 2, 3, 0, -3, 0, 1, 1, 0, 2, 0.5};
  std::vector<std::unique_ptr<Facet>> facets;
  EXPECT_EQ(Shape("-obstacle_rectangles").build(v, facets), "");
  ASSERT_EQ(facets.size(), 2u);
  double area = 0;
  for (const auto &f : facets) area += dynamic_cast<const Triangle &>(*f).Area();
  EXPECT_NEAR(area, 4 * 2 * 0.5, 1e-14);
  // A point 0.25 on the body's side, inside the rectangle (within 2 of the centre along x, 0.5 along z): gap 0.25,
  // normal (0, -1, 0), on exactly one or both triangles; beyond the half-size along x it is on neither.
  const double x[3] = {2.9, 1.75, 3.4}, out[3] = {3.1, 1.75, 3};
  int on = 0;
  for (const auto &f : facets) {
    const Projection p = f->Project(x, 1e-8, INFINITY);
    if (!p.inside) continue;
    ++on;
    EXPECT_NEAR(p.gap, 0.25, 1e-14);
    EXPECT_NEAR(p.normal[1], -1, 1e-14);
  }
  EXPECT_GE(on, 1);
  for (const auto &f : facets) EXPECT_FALSE(f->Project(out, 1e-8, INFINITY).inside);
  const double zero[11] = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1}, along[11] = {0, 0, 0, 0, 0, 1, 0, 0, 2, 1, 1};
  EXPECT_NE(Shape("-obstacle_rectangles").build(zero, facets), "");
  EXPECT_NE(Shape("-obstacle_rectangles").build(along, facets), "");
}

} // namespace
} // namespace signorini
