// A rigid disc with the body outside it: exact gap |x - c| - r and radial normal.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>
#include <sstream>

namespace signorini {

Disc::Disc(const double *centre, double radius) : c_{centre[0], centre[1]}, r_(radius) {}

Projection Disc::Project(const double *x, double) const {
  Projection p;
  const double d = std::hypot(x[0] - c_[0], x[1] - c_[1]);
  p.gap = d - r_;
  p.inside = d > 0;
  p.normal[0] = d > 0 ? (x[0] - c_[0]) / d : 0;
  p.normal[1] = d > 0 ? (x[1] - c_[1]) / d : 0;
  p.alpha = std::atan2(x[1] - c_[1], x[0] - c_[0]);
  return p;
}

double Disc::Distance(const double *x) const { return std::abs(std::hypot(x[0] - c_[0], x[1] - c_[1]) - r_); }

void Disc::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 2; ++i) lo[i] = c_[i] - r_, hi[i] = c_[i] + r_;
}

std::string Disc::Describe() const {
  std::ostringstream s;
  s << "disc centre (" << c_[0] << "," << c_[1] << ") radius " << r_;
  return s.str();
}

std::vector<std::array<double, 2>> Disc::Polyline() const {
  std::vector<std::array<double, 2>> points;
  for (int k = 0; k <= POLYGON_SIDES; ++k) {
    const double a = 2 * M_PI * (k % POLYGON_SIDES) / POLYGON_SIDES;
    points.push_back({c_[0] + r_ * std::cos(a), c_[1] + r_ * std::sin(a)});
  }
  return points;
}

ShapeType DiscsShape() {
  return {"-obstacle_discs", "Rigid discs CX,CY,R,... (the body is outside)", 3,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            if (v[2] <= 0) return "has radius " + FormatNumber(v[2]) + " (expected > 0)";
            out.push_back(std::make_unique<Disc>(v, v[2]));
            return "";
          }};
}

} // namespace signorini
