// An unbounded plane (3D) through a point with its unit normal pointing into the body: gap n . (x - P).
#include "signorini/obstacles/obstacle.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace signorini {

Plane::Plane(const double *point, const double *normal) {
  const double norm = std::hypot(normal[0], normal[1], normal[2]); // no overflow of the squares
  for (int i = 0; i < 3; ++i) p_[i] = point[i], n_[i] = normal[i] / norm;
}

Projection Plane::Project(const double *x, double, double) const {
  Projection p;
  p.gap = n_[0] * (x[0] - p_[0]) + n_[1] * (x[1] - p_[1]) + n_[2] * (x[2] - p_[2]);
  for (int i = 0; i < 3; ++i) p.normal[i] = n_[i];
  p.inside = true;
  return p;
}

double Plane::Distance(const double *x) const { return std::abs(Project(x, 0, 0).gap); }

void Plane::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 3; ++i) lo[i] = -std::numeric_limits<double>::infinity(), hi[i] = -lo[i];
}

std::string Plane::Describe() const {
  std::ostringstream s;
  s << "plane through (" << p_[0] << "," << p_[1] << "," << p_[2] << ") normal (" << n_[0] << "," << n_[1] << ","
    << n_[2] << ")";
  return s.str();
}

TriangleSoup Plane::Surface(const Box &body) const {
  double t1[3], t2[3], s[2], t[2];
  TangentFrame(n_, t1, t2);
  BoxExtent(body, p_, t1, s[0], s[1]);
  BoxExtent(body, p_, t2, t[0], t[1]);
  const auto corner = [&](int i, int j) {
    return std::array<double, 3>{p_[0] + s[i] * t1[0] + t[j] * t2[0], p_[1] + s[i] * t1[1] + t[j] * t2[1],
                                 p_[2] + s[i] * t1[2] + t[j] * t2[2]};
  };
  TriangleSoup out;
  AppendTriangle(out, corner(0, 0), corner(1, 0), corner(1, 1), n_);
  AppendTriangle(out, corner(0, 0), corner(1, 1), corner(0, 1), n_);
  return out;
}

ShapeType PlanesShape() {
  return {"-obstacle_planes", "Unbounded planes PX,PY,PZ,NX,NY,NZ,... (point and normal; the normal points into the "
          "body)", 6,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            if (!(std::hypot(v[3], v[4], v[5]) > 0)) return "has a zero normal";
            out.push_back(std::make_unique<Plane>(v, v + 3));
            return "";
          },
          3};
}

} // namespace signorini
