// Lemke's method on a dense tableau.
#include "signorini/solver/lcp.hpp"

#include <algorithm>
#include <cmath>

namespace signorini {

LcpStatus SolveLcp(int m, const std::vector<double> &M, const std::vector<double> &q, std::vector<double> &z,
                   std::vector<double> &w, int *pivots, int max_pivots) {
  z.assign(m, 0.0);
  w = q;
  if (pivots) *pivots = 0;
  if (m == 0 || *std::min_element(q.begin(), q.end()) >= 0) return LcpStatus::SOLVED;
  // The tableau of w - M z - e z0 = q: columns w (0..m-1), z (m..2m-1), z0 (2m), the right-hand side (2m+1); row i
  // holds basic variable basis[i]. Rows are scaled to their largest entry so that one tolerance fits all.
  const int nc = 2 * m + 2, z0 = 2 * m, rhs = 2 * m + 1;
  std::vector<double> t((std::size_t)m * nc, 0.0);
  auto at = [&](int i, int j) -> double & { return t[(std::size_t)i * nc + j]; };
  std::vector<int> basis(m);
  for (int i = 0; i < m; ++i) {
    double scale = 1;
    for (int j = 0; j < m; ++j) scale = std::max(scale, std::abs(M[i + (std::size_t)j * m]));
    at(i, i) = 1 / scale;
    for (int j = 0; j < m; ++j) at(i, m + j) = -M[i + (std::size_t)j * m] / scale;
    at(i, z0) = -1 / scale;
    at(i, rhs) = q[i] / scale;
    basis[i] = i;
  }
  auto pivot = [&](int r, int c) {
    const double p = at(r, c);
    for (int j = 0; j < nc; ++j) at(r, j) /= p;
    for (int i = 0; i < m; ++i) {
      if (i == r) continue;
      const double f = at(i, c);
      if (f == 0) continue;
      for (int j = 0; j < nc; ++j) at(i, j) -= f * at(r, j);
      at(i, c) = 0;
    }
    basis[r] = c;
  };
  if (max_pivots <= 0) max_pivots = 10 * m + 100;
  // z0 enters where q is most negative (relative to the row's scale).
  int r = 0;
  for (int i = 1; i < m; ++i)
    if (at(i, rhs) / -at(i, z0) < at(r, rhs) / -at(r, z0)) r = i;
  int leaving = basis[r];
  pivot(r, z0);
  int count = 1;
  LcpStatus status = LcpStatus::PIVOT_LIMIT;
  for (; count < max_pivots; ++count) {
    const int entering = leaving < m ? leaving + m : leaving - m; // the complement of the variable that left
    double cmax = 0;
    for (int i = 0; i < m; ++i) cmax = std::max(cmax, std::abs(at(i, entering)));
    const double tol = 1e-12 * std::max(cmax, 1e-300);
    // Minimum ratio; at a tie z0 leaves first (the solution), then the smallest variable index (no cycling in
    // practice on these problems; the pivot limit bounds a degenerate one).
    r = -1;
    double best = INFINITY;
    for (int i = 0; i < m; ++i) {
      const double d = at(i, entering);
      if (d <= tol) continue;
      const double ratio = std::max(at(i, rhs), 0.0) / d;
      const bool tie = r >= 0 && std::abs(ratio - best) <= 1e-12 * std::max(1.0, std::abs(best));
      if (r < 0 || (!tie && ratio < best) ||
          (tie && (basis[i] == z0 || (basis[r] != z0 && basis[i] < basis[r]))))
        r = i, best = ratio;
    }
    if (r < 0) {
      status = LcpStatus::RAY;
      break;
    }
    leaving = basis[r];
    pivot(r, entering);
    if (leaving == z0) {
      status = LcpStatus::SOLVED;
      ++count;
      break;
    }
  }
  if (pivots) *pivots = count;
  if (status != LcpStatus::SOLVED) return status;
  for (int i = 0; i < m; ++i)
    if (basis[i] >= m && basis[i] < z0) z[basis[i] - m] = std::max(at(i, rhs), 0.0); // z basic; w from z below
  for (int i = 0; i < m; ++i) {
    double wi = q[i];
    for (int j = 0; j < m; ++j) wi += M[i + (std::size_t)j * m] * z[j];
    w[i] = wi;
  }
  return status;
}

} // namespace signorini
