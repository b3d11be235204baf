// Lemke's method (SolveLcp) against brute force over every complementary basis, on random positive definite,
// positive semidefinite and ill-scaled problems, and its ray on problems without a solution.
#include "signorini/solver/lcp.hpp"

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

TEST(Lcp, NoSolutionEndsOnARay) {
  // w = q + M z with M = 0 and q_0 < 0: w_0 < 0 whatever z.
  std::vector<double> z, w;
  EXPECT_EQ(SolveLcp(2, {0, 0, 0, 0}, {-1, 1}, z, w), LcpStatus::RAY);
}

} // namespace
} // namespace signorini
