// Eigenvalues and eigenvectors of a small dense symmetric matrix (cyclic Jacobi rotations), for rigid-mode checks and
// tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace signorini {

/// Eigenvalues of the symmetric n x n matrix a (row major), in the order of the columns of v (n x n, row major, the
/// orthonormal eigenvectors) when v is given; unsorted.
inline std::vector<double> SymmetricEigen(std::vector<double> a, int n, std::vector<double> *v = nullptr) {
  if (v) {
    v->assign(n * n, 0.0);
    for (int i = 0; i < n; ++i) (*v)[i * n + i] = 1.0;
  }
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0, total = 0;
    for (int p = 0; p < n; ++p)
      for (int q = 0; q < n; ++q) (p == q ? total : off) += a[p * n + q] * a[p * n + q];
    if (off <= 1e-30 * (total + off)) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = a[p * n + q];
        if (apq == 0.0) continue;
        const double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {
          const double akp = a[k * n + p], akq = a[k * n + q];
          a[k * n + p] = c * akp - s * akq;
          a[k * n + q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {
          const double apk = a[p * n + k], aqk = a[q * n + k];
          a[p * n + k] = c * apk - s * aqk;
          a[q * n + k] = s * apk + c * aqk;
        }
        if (v)
          for (int k = 0; k < n; ++k) {
            const double vkp = (*v)[k * n + p], vkq = (*v)[k * n + q];
            (*v)[k * n + p] = c * vkp - s * vkq;
            (*v)[k * n + q] = s * vkp + c * vkq;
          }
      }
  }
  std::vector<double> eig(n);
  for (int i = 0; i < n; ++i) eig[i] = a[i * n + i];
  return eig;
}

/// Eigenvalues, ascending, of the symmetric n x n matrix a (row major).
inline std::vector<double> SymmetricEigenvalues(const std::vector<double> &a, int n) {
  std::vector<double> eig = SymmetricEigen(a, n);
  std::sort(eig.begin(), eig.end());
  return eig;
}

} // namespace signorini
