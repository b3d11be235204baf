// Oriented triangles (3D), the facets of a meshed rigid surface: gap to the plane, right-hand normal, barycentric
// position, and the exact closest point.
#include "signorini/obstacles/obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace signorini {

namespace {

double Dot(const double *a, const double *b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void Cross(const double *a, const double *b, double *c) {
  c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
}

} // namespace

Triangle::Triangle(const double *p0, const double *p1, const double *p2) {
  for (int i = 0; i < 3; ++i)
    p_[0][i] = p0[i], p_[1][i] = p1[i], p_[2][i] = p2[i];
  double e1[3], e2[3], c[3];
  for (int i = 0; i < 3; ++i)
    e1[i] = p1[i] - p0[i], e2[i] = p2[i] - p0[i];
  Cross(e1, e2, c);
  const double twice_area = std::sqrt(Dot(c, c));
  area_ = 0.5 * twice_area;
  for (int i = 0; i < 3; ++i)
    n_[i] = c[i] / twice_area;
  // Gram matrix G = [e1.e1 e1.e2; e1.e2 e2.e2], det G = |e1 x e2|^2.
  const double a = Dot(e1, e1), b = Dot(e1, e2), d = Dot(e2, e2), det = twice_area * twice_area;
  gram_inv_[0] = d / det, gram_inv_[1] = -b / det, gram_inv_[2] = a / det;
  for (int k = 0; k < 3; ++k) {
    double e[3];
    for (int i = 0; i < 3; ++i) e[i] = p_[(k + 2) % 3][i] - p_[(k + 1) % 3][i];
    height_[k] = twice_area / std::sqrt(Dot(e, e));
  }
}

void Triangle::Barycentric(const double *x, double *b) const {
  double e1[3], e2[3], w[3];
  for (int i = 0; i < 3; ++i)
    e1[i] = p_[1][i] - p_[0][i], e2[i] = p_[2][i] - p_[0][i], w[i] = x[i] - p_[0][i];
  // The foot P0 + b1 e1 + b2 e2 of x on the plane solves G (b1, b2) = (w.e1, w.e2).
  const double r1 = Dot(w, e1), r2 = Dot(w, e2);
  b[1] = gram_inv_[0] * r1 + gram_inv_[1] * r2;
  b[2] = gram_inv_[1] * r1 + gram_inv_[2] * r2;
  b[0] = 1 - b[1] - b[2];
}

Projection Triangle::Project(const double *x, double alpha_tol, double length) const {
  Projection p;
  double b[3], w[3];
  Barycentric(x, b);
  for (int i = 0; i < 3; ++i)
    w[i] = x[i] - p_[0][i], p.normal[i] = n_[i];
  p.gap = Dot(n_, w);
  p.alpha = std::min({b[0], b[1], b[2]});
  p.inside = true;
  for (int k = 0; k < 3; ++k)
    p.inside = p.inside && b[k] >= -alpha_tol * std::min(1.0, EDGE_TOL_LENGTH * length / height_[k]);
  return p;
}

void Triangle::ClosestPoint(const double *x, double *c) const {
  double b[3];
  Barycentric(x, b);
  if (b[0] >= 0 && b[1] >= 0 && b[2] >= 0) {
    for (int i = 0; i < 3; ++i)
      c[i] = b[0] * p_[0][i] + b[1] * p_[1][i] + b[2] * p_[2][i];
    return;
  }
  // The foot lies outside: the closest point is on the boundary, the nearest of the three edges' closest points.
  double best = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const double *a = p_[k], *e = p_[(k + 1) % 3];
    double d[3], w[3];
    for (int i = 0; i < 3; ++i)
      d[i] = e[i] - a[i], w[i] = x[i] - a[i];
    const double t = std::clamp(Dot(w, d) / Dot(d, d), 0.0, 1.0);
    double q[3], r[3];
    for (int i = 0; i < 3; ++i)
      q[i] = a[i] + t * d[i], r[i] = x[i] - q[i];
    const double dist2 = Dot(r, r);
    if (dist2 < best) {
      best = dist2;
      for (int i = 0; i < 3; ++i)
        c[i] = q[i];
    }
  }
}

double Triangle::Distance(const double *x) const {
  double c[3], r[3];
  ClosestPoint(x, c);
  for (int i = 0; i < 3; ++i)
    r[i] = x[i] - c[i];
  return std::sqrt(Dot(r, r));
}

void Triangle::Bounds(double *lo, double *hi) const {
  for (int i = 0; i < 3; ++i) {
    lo[i] = std::min({p_[0][i], p_[1][i], p_[2][i]});
    hi[i] = std::max({p_[0][i], p_[1][i], p_[2][i]});
  }
}

std::string Triangle::Describe() const {
  std::ostringstream s;
  s << "triangle";
  for (int k = 0; k < 3; ++k)
    s << (k ? "->" : " ") << "(" << p_[k][0] << "," << p_[k][1] << "," << p_[k][2] << ")";
  return s.str();
}

bool Triangle::Centroid(double *c) const {
  for (int k = 0; k < 3; ++k) c[k] = (p_[0][k] + p_[1][k] + p_[2][k]) / 3;
  return true;
}

TriangleSoup Triangle::Surface(const Box &) const {
  return {{p_[0][0], p_[0][1], p_[0][2]}, {p_[1][0], p_[1][1], p_[1][2]}, {p_[2][0], p_[2][1], p_[2][2]}};
}

} // namespace signorini
