// Lemke's method (SolveLcp) against brute force over every complementary basis, on random positive definite,
// positive semidefinite and ill-scaled problems in units from 1e-12 to 1e12, and its ray on problems without one.
#include "signorini/linalg/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// M = A A^T (column major) with A m x k random: positive definite for k >= m, semidefinite of rank k otherwise;
/// row/column i scaled by scale[i] (D M D stays semidefinite).
std::vector<double> RandomGram(int m, int k, std::mt19937 &gen, const std::vector<double> &scale) {
  std::normal_distribution<double> n(0, 1);
  std::vector<double> a((std::size_t)m * k), M((std::size_t)m * m, 0.0);
  for (double &v : a) v = n(gen);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      double s = 0;
      for (int l = 0; l < k; ++l) s += a[i + (std::size_t)l * m] * a[j + (std::size_t)l * m];
      M[i + (std::size_t)j * m] = s * scale[i] * scale[j];
    }
  return M;
}

/// The conditions of a solution, to tol relative to the size of the terms of w_i = q_i + sum_j M_ij z_j (the
/// backward error: a row whose terms are large can only be that accurate).
void ExpectSolution(int m, const std::vector<double> &M, const std::vector<double> &q, const std::vector<double> &z,
                    const std::vector<double> &w, double tol) {
  for (int i = 0; i < m; ++i) {
    double wi = q[i], size = std::abs(q[i]);
    for (int j = 0; j < m; ++j) {
      const double term = M[i + (std::size_t)j * m] * z[j];
      wi += term, size += std::abs(term);
    }
    EXPECT_NEAR(w[i], wi, tol * size);
    EXPECT_GE(z[i], 0.0);
    EXPECT_GE(w[i], -tol * size) << "row " << i;
    EXPECT_LE(std::abs(z[i] * w[i]), tol * size * std::abs(z[i])) << "row " << i;
  }
}

/// Whether some complementary set (z_i = 0 or w_i = 0 for each i) solves the problem: 2^m linear solves.
bool BruteForceSolvable(int m, const std::vector<double> &M, const std::vector<double> &q) {
  for (int mask = 0; mask < (1 << m); ++mask) {
    // Solve M_SS z_S = -q_S by Gaussian elimination with partial pivoting.
    std::vector<int> s;
    for (int i = 0; i < m; ++i)
      if (mask & (1 << i)) s.push_back(i);
    const int n = (int)s.size();
    std::vector<double> a((std::size_t)n * (n + 1));
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) a[r * (n + 1) + c] = M[s[r] + (std::size_t)s[c] * m];
      a[r * (n + 1) + n] = -q[s[r]];
    }
    bool singular = false;
    for (int c = 0; c < n && !singular; ++c) {
      int p = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(a[r * (n + 1) + c]) > std::abs(a[p * (n + 1) + c])) p = r;
      if (std::abs(a[p * (n + 1) + c]) < 1e-12) singular = true;
      for (int k = 0; k <= n && !singular; ++k) std::swap(a[c * (n + 1) + k], a[p * (n + 1) + k]);
      for (int r = 0; r < n && !singular; ++r) {
        if (r == c) continue;
        const double f = a[r * (n + 1) + c] / a[c * (n + 1) + c];
        for (int k = c; k <= n; ++k) a[r * (n + 1) + k] -= f * a[c * (n + 1) + k];
      }
    }
    if (singular) continue;
    std::vector<double> z(m, 0.0);
    bool ok = true;
    for (int r = 0; r < n; ++r) {
      z[s[r]] = a[r * (n + 1) + n] / a[r * (n + 1) + r];
      ok = ok && z[s[r]] >= -1e-9;
    }
    for (int i = 0; i < m && ok; ++i) {
      double wi = q[i];
      for (int j = 0; j < m; ++j) wi += M[i + (std::size_t)j * m] * z[j];
      ok = (mask & (1 << i)) || wi >= -1e-9;
    }
    if (ok) return true;
  }
  return false;
}

TEST(Lcp, NonNegativeQIsSolvedByZero) {
  std::vector<double> z, w;
  int pivots = -1;
  EXPECT_EQ(SolveLcp(2, {1, 0, 0, 1}, {1, 0}, z, w, &pivots), LcpStatus::SOLVED);
  EXPECT_EQ(pivots, 0);
  EXPECT_EQ(z, (std::vector<double>{0, 0}));
}

TEST(Lcp, PositiveDefiniteMatchesTheUniqueSolution) {
  std::mt19937 gen(7);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int m = 1 + trial % 9;
    const std::vector<double> M = RandomGram(m, m + 2, gen, std::vector<double>(m, 1.0));
    std::vector<double> q(m), z, w;
    for (double &v : q) v = n(gen);
    ASSERT_EQ(SolveLcp(m, M, q, z, w), LcpStatus::SOLVED) << "trial " << trial;
    ExpectSolution(m, M, q, z, w, 1e-9);
  }
}

TEST(Lcp, SemidefiniteSolvesOrProvesNoSolution) {
  // Rank-deficient M: some problems have no solution; Lemke's ray must coincide with brute force's verdict.
  std::mt19937 gen(11);
  std::normal_distribution<double> n(0, 1);
  int rays = 0, solved = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int m = 2 + trial % 7;
    const std::vector<double> M = RandomGram(m, 1 + trial % (m - 1), gen, std::vector<double>(m, 1.0));
    std::vector<double> q(m), z, w;
    for (double &v : q) v = n(gen);
    const LcpStatus status = SolveLcp(m, M, q, z, w);
    ASSERT_NE(status, LcpStatus::PIVOT_LIMIT) << "trial " << trial;
    EXPECT_EQ(status == LcpStatus::SOLVED, BruteForceSolvable(m, M, q)) << "trial " << trial;
    if (status == LcpStatus::SOLVED) ExpectSolution(m, M, q, z, w, 1e-8), ++solved;
    else ++rays;
  }
  EXPECT_GT(rays, 10);
  EXPECT_GT(solved, 10);
}

TEST(Lcp, IllScaledRowsAsInTheContactProblem) {
  // Entries spanning 1e8 (a weakly held rigid motion beside the elastic compliance, ContactLcp).
  std::mt19937 gen(3);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 100; ++trial) {
    const int m = 3 + trial % 6;
    std::vector<double> scale(m);
    for (int i = 0; i < m; ++i) scale[i] = std::pow(10.0, 4 * (i % 3) - 4);
    const std::vector<double> M = RandomGram(m, m, gen, scale);
    std::vector<double> q(m), z, w;
    for (double &v : q) v = n(gen);
    ASSERT_EQ(SolveLcp(m, M, q, z, w), LcpStatus::SOLVED) << "trial " << trial;
    ExpectSolution(m, M, q, z, w, 1e-7);
  }
}

TEST(Lcp, ScaleInvariantAgainstBruteForce) {
  // (s M, t q) for s, t from 1e-12 to 1e12: the verdict of brute force on (M, q), the pivots of (M, q) and its z
  // times t / s. Before, rows were scaled to max(1, max |M_ij|) and ties were absolute: with s = 1e-12 false rays,
  // with s = 1e12 "solutions" that were none.
  std::mt19937 gen(5);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 120; ++trial) {
    const int m = 2 + trial % 7;
    const int k = trial % 3 == 0 ? 1 + trial % (m - 1) : m + 2; // semidefinite or positive definite
    const std::vector<double> M = RandomGram(m, k, gen, std::vector<double>(m, 1.0));
    std::vector<double> q(m), z0, w0;
    for (int i = 0; i < m; ++i) q[i] = i % 2 == 0 && trial % 2 == 0 ? -0.5 : n(gen);
    int pivots0 = 0;
    const LcpStatus status0 = SolveLcp(m, M, q, z0, w0, &pivots0);
    ASSERT_EQ(status0 == LcpStatus::SOLVED, BruteForceSolvable(m, M, q)) << "trial " << trial;
    double zmax = 0;
    for (double v : z0) zmax = std::max(zmax, v);
    for (double s : {1e-12, 1e-8, 1e-4, 1.0, 1e4, 1e8, 1e12})
      for (double t : {1e-12, 1.0, 1e12}) {
        std::vector<double> Ms(M), qs(q), z, w;
        for (double &v : Ms) v *= s;
        for (double &v : qs) v *= t;
        int pivots = 0;
        ASSERT_EQ(SolveLcp(m, Ms, qs, z, w, &pivots), status0) << "trial " << trial << " s " << s << " t " << t;
        EXPECT_EQ(pivots, pivots0) << "trial " << trial << " s " << s << " t " << t;
        if (status0 != LcpStatus::SOLVED) continue;
        ExpectSolution(m, Ms, qs, z, w, 1e-9);
        for (int i = 0; i < m; ++i) EXPECT_NEAR(z[i] * s / t, z0[i], 1e-12 * zmax) << "trial " << trial;
      }
  }
}

TEST(Lcp, NoSolutionEndsOnARay) {
  // w = q + M z with M = 0 and q_0 < 0: w_0 < 0 whatever z.
  std::vector<double> z, w;
  EXPECT_EQ(SolveLcp(2, {0, 0, 0, 0}, {-1, 1}, z, w), LcpStatus::RAY);
}

/// The residual |A x - b| (A k x m column major).
double NnlsResidual(int k, int m, const std::vector<double> &A, const std::vector<double> &b,
                    const std::vector<double> &x) {
  double r2 = 0;
  for (int i = 0; i < k; ++i) {
    double r = -b[i];
    for (int j = 0; j < m; ++j) r += A[i + (std::size_t)j * k] * x[j];
    r2 += r * r;
  }
  return std::sqrt(r2);
}

/// Brute force: the least residual over every subset of columns whose unconstrained least-squares solution (normal
/// equations) is non-negative, and 0 columns.
double NnlsBruteForce(int k, int m, const std::vector<double> &A, const std::vector<double> &b) {
  double best = NnlsResidual(k, m, A, b, std::vector<double>(m, 0.0));
  for (int mask = 1; mask < (1 << m); ++mask) {
    std::vector<int> c;
    for (int j = 0; j < m; ++j)
      if (mask & (1 << j)) c.push_back(j);
    const int n = (int)c.size();
    if (n > k) continue;
    std::vector<double> G(n * n, 0.0), y(n, 0.0);
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < k; ++i) {
        y[a] += A[i + (std::size_t)c[a] * k] * b[i];
        for (int d = 0; d < n; ++d) G[a * n + d] += A[i + (std::size_t)c[a] * k] * A[i + (std::size_t)c[d] * k];
      }
    bool ok = true;
    for (int a = 0; a < n && ok; ++a) { // Gaussian elimination (G positive definite for independent columns)
      ok = G[a * n + a] > 1e-12;
      for (int r = a + 1; r < n && ok; ++r) {
        const double f = G[r * n + a] / G[a * n + a];
        for (int d = a; d < n; ++d) G[r * n + d] -= f * G[a * n + d];
        y[r] -= f * y[a];
      }
    }
    if (!ok) continue;
    std::vector<double> x(m, 0.0), s(n);
    for (int a = n - 1; a >= 0; --a) {
      double v = y[a];
      for (int d = a + 1; d < n; ++d) v -= G[a * n + d] * s[d];
      s[a] = v / G[a * n + a];
    }
    for (int a = 0; a < n; ++a) ok = ok && s[a] >= 0, x[c[a]] = s[a];
    if (ok) best = std::min(best, NnlsResidual(k, m, A, b, x));
  }
  return best;
}

TEST(Nnls, MatchesBruteForceAndKkt) {
  std::mt19937 gen(11);
  std::normal_distribution<double> n(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const int k = 1 + trial % 6, m = 1 + (trial / 6) % 10;
    std::vector<double> A((std::size_t)k * m), b(k), x;
    for (double &v : A) v = n(gen);
    for (double &v : b) v = n(gen);
    const double r = NonNegativeLeastSquares(k, m, A, b, x);
    EXPECT_NEAR(r, NnlsResidual(k, m, A, b, x), 1e-12 * (1 + r));
    EXPECT_NEAR(r, NnlsBruteForce(k, m, A, b), 1e-10 * (1 + r)) << "trial " << trial;
    // KKT: x >= 0, the gradient A^T (b - A x) <= 0 off the support and 0 on it.
    for (int j = 0; j < m; ++j) {
      double w = 0;
      for (int i = 0; i < k; ++i) {
        double ri = b[i];
        for (int l = 0; l < m; ++l) ri -= A[i + (std::size_t)l * k] * x[l];
        w += A[i + (std::size_t)j * k] * ri;
      }
      EXPECT_GE(x[j], 0);
      EXPECT_LE(w, 1e-9);
      if (x[j] > 0) {
        EXPECT_NEAR(w, 0, 1e-9);
      }
    }
  }
}

TEST(Nnls, ManyColumnsLoadInsideAndOutsideTheCone) {
  // Six rigid modes, 2000 contact columns of one sign pattern: a load inside their cone is balanced (residual
  // round-off), its opposite is not (the residual is the load's part that no column reaches).
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(0.1, 1);
  const int k = 6, m = 2000;
  std::vector<double> A((std::size_t)k * m), x;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < k; ++i) A[i + (std::size_t)j * k] = i == 0 ? u(gen) : u(gen) - 0.55;
  std::vector<double> inside(k, 0.0), outside(k);
  for (int j = 0; j < m; j += 7)
    for (int i = 0; i < k; ++i) inside[i] += 0.3 * A[i + (std::size_t)j * k];
  EXPECT_LT(NonNegativeLeastSquares(k, m, A, inside, x), 1e-10 * inside[0]);
  for (int i = 0; i < k; ++i) outside[i] = -inside[i];
  const double r = NonNegativeLeastSquares(k, m, A, outside, x);
  EXPECT_GT(r, 0.9 * std::abs(outside[0])); // the first mode's columns are all positive: its load stays unbalanced
}

} // namespace
} // namespace signorini
