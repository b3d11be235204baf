// Helpers shared by the element tests: deterministic random numbers and small dense linear algebra.
#pragma once

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

/// Eigenvalues of a small symmetric matrix by cyclic Jacobi rotations.
inline Vector SymmetricEigenvalues(Vector A, int n) {
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0, total = 0;
    for (int p = 0; p < n; ++p)
      for (int q = 0; q < n; ++q)
        (p == q ? total : off) += A[p * n + q] * A[p * n + q];
    if (off <= 1e-30 * (total + off)) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = A[p * n + q];
        if (apq == 0.0) continue;
        const double theta = (A[q * n + q] - A[p * n + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {
          const double akp = A[k * n + p], akq = A[k * n + q];
          A[k * n + p] = c * akp - s * akq;
          A[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {
          const double apk = A[p * n + k], aqk = A[q * n + k];
          A[p * n + k] = c * apk - s * aqk;
          A[q * n + k] = s * apk + c * aqk;
        }
      }
  }
  Vector eig(n);
  for (int i = 0; i < n; ++i)
    eig[i] = A[i * n + i];
  std::sort(eig.begin(), eig.end());
  return eig;
}

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
