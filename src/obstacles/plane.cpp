// An unbounded plane (3D) through a point with its unit normal pointing into the body: gap n . (x - P).
#include "signorini/obstacles/obstacle.hpp"

#include <cmath>
#include <limits>
#include <sstream>

namespace signorini {

Plane::Plane(const double *point, const double *normal) {
  const double norm = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  for (int i = 0; i < 3; ++i) p_[i] = point[i], n_[i] = normal[i] / norm;
}

Projection Plane::Project(const double *x, double) const {
  Projection p;
  p.gap = n_[0] * (x[0] - p_[0]) + n_[1] * (x[1] - p_[1]) + n_[2] * (x[2] - p_[2]);
  for (int i = 0; i < 3; ++i) p.normal[i] = n_[i];
  p.inside = true;
  return p;
}

double Plane::Distance(const double *x) const { return std::abs(Project(x, 0).gap); }

void Plane::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 3; ++i) lo[i] = -std::numeric_limits<double>::infinity(), hi[i] = -lo[i];
}

std::string Plane::Describe() const {
  std::ostringstream s;
  s << "plane through (" << p_[0] << "," << p_[1] << "," << p_[2] << ") normal (" << n_[0] << "," << n_[1] << ","
    << n_[2] << ")";
  return s.str();
}

ShapeType PlanesShape() {
  return {"-obstacle_planes", "Unbounded planes PX,PY,PZ,NX,NY,NZ,... (point and normal; the normal points into the "
          "body)", 6,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            if (std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]) <= 0) return "has a zero normal";
            out.push_back(std::make_unique<Plane>(v, v + 3));
            return "";
          },
          3};
}

} // namespace signorini
