// Helpers shared by the element tests: deterministic random numbers and small dense linear algebra.
#pragma once

#include "signorini/core/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace signorini::test {

using Vector = std::vector<double>;

/// Deterministic uniform numbers in [-1, 1) (the same on every platform).
class Random {
public:
  double Next() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(state_ >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  }

private:
  std::uint64_t state_ = 20240601;
};

inline Vector MatVec(const Vector &K, const Vector &x) {
  const std::size_t n = x.size();
  Vector y(n, 0.0);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t c = 0; c < n; ++c)
      y[r] += K[r * n + c] * x[c];
  return y;
}

inline double Norm(const Vector &v) {
  double s = 0;
  for (double x : v)
    s += x * x;
  return std::sqrt(s);
}

inline double MaxAbs(const Vector &v) {
  double s = 0;
  for (double x : v)
    s = std::max(s, std::abs(x));
  return s;
}

inline Vector Difference(const Vector &a, const Vector &b) {
  Vector d(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    d[i] = a[i] - b[i];
  return d;
}

/// Eigenvalues of a small symmetric matrix, ascending.
inline Vector SymmetricEigenvalues(Vector A, int n) { return signorini::SymmetricEigenvalues(std::move(A), n); }

/// Largest |K_rc - K_cr| of an n x n row-major matrix.
inline double MaxAsymmetry(const Vector &K, int n) {
  double asym = 0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      asym = std::max(asym, std::abs(K[r * n + c] - K[c * n + r]));
  return asym;
}

/// Central finite-difference Jacobian (row-major) of force(u) at u with step h.
template <typename ForceFunction>
Vector CentralDifferenceJacobian(const Vector &u, double h, ForceFunction force) {
  const int n = (int)u.size();
  Vector J(n * n);
  for (int c = 0; c < n; ++c) {
    Vector up(u), um(u);
    up[c] += h;
    um[c] -= h;
    const Vector fp = force(up), fm = force(um);
    for (int r = 0; r < n; ++r)
      J[r * n + c] = (fp[r] - fm[r]) / (2 * h);
  }
  return J;
}

} // namespace signorini::test
