// An infinite rigid cylinder (3D) given by a point on its axis, the axis direction and the radius, with the body
// outside it: exact gap |r| - R with r the part of x - P normal to the axis, radial normal.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace signorini {

Cylinder::Cylinder(const double *point, const double *axis, double radius) : r_(radius) {
  const double norm = std::hypot(axis[0], axis[1], axis[2]); // no overflow of the squares
  for (int i = 0; i < 3; ++i) p_[i] = point[i], a_[i] = axis[i] / norm;
}

double Cylinder::Radial(const double *x, double *r) const {
  const double d[3] = {x[0] - p_[0], x[1] - p_[1], x[2] - p_[2]};
  const double along = d[0] * a_[0] + d[1] * a_[1] + d[2] * a_[2];
  for (int i = 0; i < 3; ++i) r[i] = d[i] - along * a_[i];
  return std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

Projection Cylinder::Project(const double *x, double, double) const {
  Projection p;
  double r[3];
  const double d = Radial(x, r);
  p.gap = d - r_;
  p.inside = d > 0;
  for (int i = 0; i < 3; ++i) p.normal[i] = d > 0 ? r[i] / d : 0;
  return p;
}

double Cylinder::Distance(const double *x) const {
  double r[3];
  return std::abs(Radial(x, r) - r_);
}

void Cylinder::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 3; ++i) lo[i] = -std::numeric_limits<double>::infinity(), hi[i] = -lo[i];
}

std::string Cylinder::Describe() const {
  std::ostringstream s;
  s << "cylinder through (" << p_[0] << "," << p_[1] << "," << p_[2] << ") axis (" << a_[0] << "," << a_[1] << ","
    << a_[2] << ") radius " << r_;
  return s.str();
}

TriangleSoup Cylinder::Surface(const Box &body) const {
  double t1[3], t2[3], lo, hi;
  TangentFrame(a_, t1, t2);
  BoxExtent(body, p_, a_, lo, hi);
  const auto point = [&](int k, double along, double *radial) {
    const double phi = 2 * M_PI * (k % CYLINDER_SEGMENTS) / CYLINDER_SEGMENTS, c = std::cos(phi), s = std::sin(phi);
    std::array<double, 3> x;
    for (int i = 0; i < 3; ++i) radial[i] = c * t1[i] + s * t2[i], x[i] = p_[i] + along * a_[i] + r_ * radial[i];
    return x;
  };
  TriangleSoup out;
  for (int k = 0; k < CYLINDER_SEGMENTS; ++k) {
    double radial[3], next[3], out_of[3];
    const auto a0 = point(k, lo, radial), a1 = point(k, hi, radial), b0 = point(k + 1, lo, next),
               b1 = point(k + 1, hi, next);
    for (int i = 0; i < 3; ++i) out_of[i] = radial[i] + next[i]; // the body is outside
    AppendTriangle(out, a0, b0, b1, out_of);
    AppendTriangle(out, a0, b1, a1, out_of);
  }
  return out;
}

ShapeType CylindersShape() {
  return {"-obstacle_cylinders", "Infinite rigid cylinders PX,PY,PZ,AX,AY,AZ,R,... (point on the axis, axis, radius; "
          "the body is outside)", 7,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            if (!(std::hypot(v[3], v[4], v[5]) > 0)) return "has a zero axis";
            if (v[6] <= 0) return "has radius " + FormatNumber(v[6]) + " (expected > 0)";
            out.push_back(std::make_unique<Cylinder>(v, v + 3, v[6]));
            return "";
          },
          3};
}

} // namespace signorini
