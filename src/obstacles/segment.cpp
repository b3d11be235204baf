// Oriented segments: gap, normal and projection parameter (docs/theory.md §1).
#include "signorini/obstacles/obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace signorini {

Segment::Segment(const double *p0, const double *p1) {
  p0_[0] = p0[0], p0_[1] = p0[1], p1_[0] = p1[0], p1_[1] = p1[1];
  length_ = std::hypot(p1[0] - p0[0], p1[1] - p0[1]);
  n_[0] = -(p1[1] - p0[1]) / length_;
  n_[1] = (p1[0] - p0[0]) / length_;
}

Projection Segment::Project(const double *x, double alpha_tol, double length) const {
  Projection p;
  const double d[2] = {p1_[0] - p0_[0], p1_[1] - p0_[1]};
  // Eq. 24: alpha = (B - A) . (R - A) / |B - A|^2; Eq. 25: gap = n . (R - R*) = n . (R - A).
  p.alpha = (d[0] * (x[0] - p0_[0]) + d[1] * (x[1] - p0_[1])) / (length_ * length_);
  p.gap = n_[0] * (x[0] - p0_[0]) + n_[1] * (x[1] - p0_[1]);
  p.normal[0] = n_[0], p.normal[1] = n_[1];
  const double tol = alpha_tol * std::min(1.0, EDGE_TOL_LENGTH * length / length_);
  p.inside = p.alpha >= -tol && p.alpha <= 1 + tol;
  return p;
}

double Segment::Distance(const double *x) const {
  const double d[2] = {p1_[0] - p0_[0], p1_[1] - p0_[1]};
  const double a = std::clamp((d[0] * (x[0] - p0_[0]) + d[1] * (x[1] - p0_[1])) / (length_ * length_), 0.0, 1.0);
  return std::hypot(x[0] - p0_[0] - a * d[0], x[1] - p0_[1] - a * d[1]);
}

void Segment::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 2; ++i) lo[i] = std::min(p0_[i], p1_[i]), hi[i] = std::max(p0_[i], p1_[i]);
}

std::string Segment::Describe() const {
  std::ostringstream s;
  s << "segment (" << p0_[0] << "," << p0_[1] << ")->(" << p1_[0] << "," << p1_[1] << ")";
  return s.str();
}

bool Segment::Centroid(double *c) const {
  c[0] = 0.5 * (p0_[0] + p1_[0]), c[1] = 0.5 * (p0_[1] + p1_[1]), c[2] = 0;
  return true;
}

std::vector<std::array<double, 2>> Segment::Polyline() const {
  return {{p0_[0], p0_[1]}, {p1_[0], p1_[1]}};
}

ShapeType SegmentsShape() {
  return {"-obstacle_segments", "Oriented segments X0,Y0,X1,Y1,... (normal: left of P0->P1, into the body)", 4,
          [](const double *v, std::vector<std::unique_ptr<Facet>> &out) -> std::string {
            if (std::hypot(v[2] - v[0], v[3] - v[1]) <= 0) return "has zero length";
            out.push_back(std::make_unique<Segment>(v, v + 2));
            return "";
          },
          2};
}

} // namespace signorini
