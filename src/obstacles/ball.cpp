// A rigid ball with the body outside it, in the mesh's dimension: a disc in 2D, a sphere in 3D; exact gap |x - c| - r
// and radial normal.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>
#include <sstream>

namespace signorini {

Ball::Ball(const double *centre, double radius, int dim) : r_(radius), dim_(dim) {
  for (int i = 0; i < dim; ++i) c_[i] = centre[i];
}

double Ball::CentreDistance(const double *x) const {
  double d2 = 0;
  for (int i = 0; i < dim_; ++i) d2 += (x[i] - c_[i]) * (x[i] - c_[i]);
  return std::sqrt(d2);
}

Projection Ball::Project(const double *x, double, double) const {
  Projection p;
  const double d = CentreDistance(x);
  p.gap = d - r_;
  p.inside = d > 0;
  for (int i = 0; i < dim_; ++i) p.normal[i] = d > 0 ? (x[i] - c_[i]) / d : 0;
  p.alpha = dim_ == 2 ? std::atan2(x[1] - c_[1], x[0] - c_[0]) : 0;
  return p;
}

double Ball::Distance(const double *x) const { return std::abs(CentreDistance(x) - r_); }

void Ball::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < dim_; ++i) lo[i] = c_[i] - r_, hi[i] = c_[i] + r_;
}

std::string Ball::Describe() const {
  std::ostringstream s;
  s << (dim_ == 2 ? "disc" : "sphere") << " centre (" << c_[0] << "," << c_[1];
  if (dim_ == 3) s << "," << c_[2];
  s << ") radius " << r_;
  return s.str();
}

namespace {
/// Builds one ball of dimension dim from its centre (dim numbers) and radius.
std::function<std::string(const double *, std::vector<std::unique_ptr<Facet>> &)> BuildBall(int dim) {
  return [dim](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
    if (v[dim] <= 0) return "has radius " + FormatNumber(v[dim]) + " (expected > 0)";
    out.push_back(std::make_unique<Ball>(v, v[dim], dim));
    return "";
  };
}
} // namespace

std::vector<std::array<double, 2>> Ball::Polyline() const {
  std::vector<std::array<double, 2>> points;
  if (dim_ != 2) return points;
  for (int k = 0; k <= POLYGON_SIDES; ++k) {
    const double a = 2 * M_PI * (k % POLYGON_SIDES) / POLYGON_SIDES;
    points.push_back({c_[0] + r_ * std::cos(a), c_[1] + r_ * std::sin(a)});
  }
  return points;
}

TriangleSoup Ball::Surface(const Box &) const {
  TriangleSoup out;
  if (dim_ != 3) return out;
  const int meridians = SPHERE_MERIDIANS, bands = SPHERE_MERIDIANS / 2;
  // Point of latitude band boundary i (0: the north pole, bands: the south pole) on meridian j.
  const auto point = [&](int i, int j) {
    const double theta = M_PI * i / bands, phi = 2 * M_PI * (j % meridians) / meridians;
    const bool pole = i == 0 || i == bands;
    const double ct = pole ? (i == 0 ? 1.0 : -1.0) : std::cos(theta), st = pole ? 0.0 : std::sin(theta);
    return std::array<double, 3>{c_[0] + r_ * st * std::cos(phi), c_[1] + r_ * st * std::sin(phi), c_[2] + r_ * ct};
  };
  for (int i = 0; i < bands; ++i)
    for (int j = 0; j < meridians; ++j) {
      const auto a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      // Outwards (the body is outside): along the centroid's direction from the centre.
      double out_of[3];
      for (int k = 0; k < 3; ++k) out_of[k] = a[k] + b[k] + c[k] + d[k] - 4 * c_[k];
      if (i > 0) AppendTriangle(out, a, b, d, out_of);
      if (i < bands - 1) AppendTriangle(out, b, c, d, out_of);
    }
  return out;
}

ShapeType DiscsShape() { return {"-obstacle_discs", "Rigid discs CX,CY,R,... (the body is outside)", 3, BuildBall(2), 2}; }

ShapeType SpheresShape() {
  return {"-obstacle_spheres", "Rigid spheres CX,CY,CZ,R,... (the body is outside)", 4, BuildBall(3), 3};
}

} // namespace signorini
