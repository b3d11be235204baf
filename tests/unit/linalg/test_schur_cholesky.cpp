// The multifrontal Cholesky with a Schur complement (SchurCholesky) against dense elimination: the Schur complement,
// the reduced right-hand side and the solution, for random positive definite blocks in several pivot orders; and its
// refusal of singular and indefinite blocks.
#include "signorini/linalg/schur_cholesky.hpp"

#include "petsc_helpers.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

namespace signorini {
namespace {

/// A symmetric matrix [A11 A12; A21 A22] in one triangle (entries may repeat and are then summed), dense copy beside.
struct Problem {
  int n = 0, m = 0;
  std::vector<int> row, col;
  std::vector<double> value, dense; // dense: n x n column major, the matrix in the original row order
  std::vector<int> schur;           // the Schur rows (original numbers), in Schur order
  /// Entry (i, j) += v (0-based), kept 1-based as MUMPS takes them.
  void Add(int i, int j, double v) {
    row.push_back(std::min(i, j) + 1), col.push_back(std::max(i, j) + 1), value.push_back(v);
    dense[i + (std::size_t)j * n] += v;
    if (i != j) dense[j + (std::size_t)i * n] += v;
  }
};

/// A11: the stiffness of springs (random directions) between neighbours of an nx x ny grid, 2 rows per node, positive
/// definite by a diagonal shift > 0; m Schur rows coupling 2 to 4
/// random rows each, A22 diagonal (half of it zero), all rows interleaved at random.
Problem RandomProblem(int nx, int ny, int m, double shift, std::mt19937 &gen) {
  std::uniform_real_distribution<double> u(0.5, 2.0), sign(-1, 1);
  const int nodes = nx * ny, ns = 2 * nodes;
  Problem p;
  p.n = ns + m, p.m = m;
  p.dense.assign((std::size_t)p.n * p.n, 0.0);
  // Original row numbers: a random permutation of the displacement rows and the Schur rows.
  std::vector<int> number(p.n);
  std::iota(number.begin(), number.end(), 0);
  std::shuffle(number.begin(), number.end(), gen);
  const auto spring = [&](int a, int b) {
    const double k = u(gen), c = sign(gen), s = sign(gen), norm = std::hypot(c, s) + 1e-3;
    const double d[2] = {c / norm, s / norm};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        const double v = k * d[i] * d[j];
        const int ai = number[2 * a + i], aj = number[2 * a + j], bi = number[2 * b + i], bj = number[2 * b + j];
        if (ai <= aj) p.Add(ai, aj, v);
        if (bi <= bj) p.Add(bi, bj, v);
        p.Add(ai, bj, -v);
      }
  };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const int a = x + y * nx;
      if (x + 1 < nx) spring(a, a + 1);
      if (y + 1 < ny) spring(a, a + nx);
      if (x + 1 < nx && y + 1 < ny) spring(a, a + nx + 1);
    }
  // The springs leave the translations free: shift 0 keeps A11 singular, a negative one makes it indefinite.
  for (int i = 0; i < ns; ++i)
    p.Add(number[i], number[i], shift);
  std::uniform_int_distribution<int> pick(0, ns - 1), how_many(2, 4);
  for (int k = 0; k < m; ++k) {
    const int r = number[ns + k];
    p.schur.push_back(r);
    for (int c = how_many(gen); c > 0; --c)
      p.Add(r, number[pick(gen)], sign(gen));
    p.Add(r, r, k % 2 ? 0.0 : u(gen));
  }
  return p;
}

/// Dense solution of A11 X = B (n1 x k, column major) for the rows `rows` of the dense matrix: Gaussian elimination
/// with partial pivoting.
std::vector<double> DenseSolve(const Problem &p, const std::vector<int> &rows, std::vector<double> B, int k) {
  const int n1 = (int)rows.size();
  std::vector<double> A((std::size_t)n1 * n1);
  for (int j = 0; j < n1; ++j)
    for (int i = 0; i < n1; ++i)
      A[i + (std::size_t)j * n1] = p.dense[rows[i] + (std::size_t)rows[j] * p.n];
  for (int c = 0; c < n1; ++c) {
    int piv = c;
    for (int i = c + 1; i < n1; ++i)
      if (std::abs(A[i + (std::size_t)c * n1]) > std::abs(A[piv + (std::size_t)c * n1])) piv = i;
    for (int j = 0; j < n1; ++j)
      std::swap(A[c + (std::size_t)j * n1], A[piv + (std::size_t)j * n1]);
    for (int j = 0; j < k; ++j)
      std::swap(B[c + (std::size_t)j * n1], B[piv + (std::size_t)j * n1]);
    for (int i = c + 1; i < n1; ++i) {
      const double f = A[i + (std::size_t)c * n1] / A[c + (std::size_t)c * n1];
      for (int j = c; j < n1; ++j)
        A[i + (std::size_t)j * n1] -= f * A[c + (std::size_t)j * n1];
      for (int j = 0; j < k; ++j)
        B[i + (std::size_t)j * n1] -= f * B[c + (std::size_t)j * n1];
    }
  }
  for (int j = 0; j < k; ++j)
    for (int i = n1 - 1; i >= 0; --i) {
      double s = B[i + (std::size_t)j * n1];
      for (int l = i + 1; l < n1; ++l)
        s -= A[i + (std::size_t)l * n1] * B[l + (std::size_t)j * n1];
      B[i + (std::size_t)j * n1] = s / A[i + (std::size_t)i * n1];
    }
  return B;
}

/// Positions (1-based, as MUMPS's PERM_IN): the displacement rows in `order` (a permutation of them), then the Schur
/// rows.
std::vector<int> Positions(const Problem &p, const std::vector<int> &displacement_order) {
  std::vector<int> position(p.n, 0);
  int next = 0;
  for (int r : displacement_order)
    position[r] = ++next;
  for (int r : p.schur)
    position[r] = ++next;
  return position;
}

void ExpectMatchesDense(const Problem &p, const std::vector<int> &order, std::mt19937 &gen) {
  SchurCholesky chol;
  ASSERT_EQ(chol.Analyse(p.n, p.m, p.row, p.col, Positions(p, order), 1), 0);
  std::vector<double> S;
  bool positive = false;
  ASSERT_EQ(chol.Factor(p.value, S, positive), 0);
  ASSERT_TRUE(positive);
  EXPECT_GT(chol.Flops(), 0);
  // Dense reference: X = A11^-1 A12, S = A22 - A21 X.
  std::vector<int> rows1 = order;
  std::sort(rows1.begin(), rows1.end());
  const int n1 = (int)rows1.size(), m = p.m;
  std::vector<double> A12((std::size_t)n1 * m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n1; ++i)
      A12[i + (std::size_t)j * n1] = p.dense[rows1[i] + (std::size_t)p.schur[j] * p.n];
  const std::vector<double> X = DenseSolve(p, rows1, A12, m);
  double scale = 0;
  for (double v : p.dense)
    scale = std::max(scale, std::abs(v));
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      double s = p.dense[p.schur[i] + (std::size_t)p.schur[j] * p.n];
      for (int l = 0; l < n1; ++l)
        s -= A12[l + (std::size_t)i * n1] * X[l + (std::size_t)j * n1];
      EXPECT_NEAR(S[i + (std::size_t)j * m], s, 1e-10 * scale) << "S(" << i << ", " << j << ")";
    }
  // A right-hand side: the reduced one b2 - A21 A11^-1 b1, then with a chosen x2 the whole solution.
  std::normal_distribution<double> nd(0, 1);
  std::vector<double> b(p.n), b1(n1), reduced(m), x2(m), x(p.n);
  for (double &v : b)
    v = nd(gen);
  for (int i = 0; i < n1; ++i)
    b1[i] = b[rows1[i]];
  const std::vector<double> y = DenseSolve(p, rows1, b1, 1);
  ASSERT_EQ(chol.Forward(b.data(), reduced.data()), 0);
  for (int j = 0; j < m; ++j) {
    double r = b[p.schur[j]];
    for (int l = 0; l < n1; ++l)
      r -= A12[l + (std::size_t)j * n1] * y[l];
    EXPECT_NEAR(reduced[j], r, 1e-10 * scale);
  }
  for (double &v : x2)
    v = nd(gen);
  ASSERT_EQ(chol.Backward(x2.data(), x.data()), 0);
  // x1 = A11^-1 (b1 - A12 x2), x2 as given.
  std::vector<double> rhs = b1;
  for (int i = 0; i < n1; ++i)
    for (int j = 0; j < m; ++j)
      rhs[i] -= A12[i + (std::size_t)j * n1] * x2[j];
  const std::vector<double> x1 = DenseSolve(p, rows1, rhs, 1);
  for (int i = 0; i < n1; ++i)
    EXPECT_NEAR(x[rows1[i]], x1[i], 1e-9 * (1 + std::abs(x1[i])));
  for (int j = 0; j < m; ++j)
    EXPECT_EQ(x[p.schur[j]], x2[j]);
  // A Backward needs a new Forward.
  test::ErrorCapture capture;
  EXPECT_NE(chol.Backward(x2.data(), x.data()), 0);
  EXPECT_NE(capture.Message().find("no forward elimination"), std::string::npos);
}

/// The displacement rows of p in a random order, and in the order of their numbers.
std::vector<int> DisplacementRows(const Problem &p) {
  std::vector<int> rows;
  for (int r = 0; r < p.n; ++r)
    if (std::find(p.schur.begin(), p.schur.end(), r) == p.schur.end()) rows.push_back(r);
  return rows;
}

TEST(SchurCholesky, MatchesDenseEliminationInAnyOrder) {
  std::mt19937 gen(2026);
  for (int trial = 0; trial < 6; ++trial) {
    const Problem p = RandomProblem(3 + trial, 4 + trial % 3, 1 + 3 * trial, 1e-2, gen);
    std::vector<int> order = DisplacementRows(p);
    ExpectMatchesDense(p, order, gen); // the original numbering (random on the grid)
    std::shuffle(order.begin(), order.end(), gen);
    ExpectMatchesDense(p, order, gen);
  }
}

TEST(SchurCholesky, LargePanelsMatchDenseElimination) {
  // A random order of a 20 x 20 grid fills in: supernodes with panels beyond SMALL_PANEL, solved by BLAS.
  std::mt19937 gen(99);
  const Problem p = RandomProblem(20, 20, 30, 1e-2, gen);
  std::vector<int> order = DisplacementRows(p);
  std::shuffle(order.begin(), order.end(), gen);
  ExpectMatchesDense(p, order, gen);
}

TEST(SchurCholesky, NoSchurRowsAndOnlySchurRows) {
  std::mt19937 gen(7);
  const Problem p = RandomProblem(5, 5, 0, 1e-2, gen);
  ExpectMatchesDense(p, DisplacementRows(p), gen);
  // A11 empty: S = A22.
  Problem q;
  q.n = q.m = 3;
  q.dense.assign(9, 0.0);
  q.schur = {2, 0, 1};
  q.Add(0, 0, 1.0), q.Add(0, 2, 2.0), q.Add(1, 1, 3.0);
  SchurCholesky chol;
  ASSERT_EQ(chol.Analyse(3, 3, q.row, q.col, Positions(q, {}), 1), 0);
  std::vector<double> S;
  bool positive = false;
  ASSERT_EQ(chol.Factor(q.value, S, positive), 0);
  ASSERT_TRUE(positive);
  const std::vector<double> expected = {0, 2, 0, 2, 1, 0, 0, 0, 3}; // rows/columns in Schur order 2, 0, 1
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(S[k], expected[k]);
}

TEST(SchurCholesky, RefusesSingularAndIndefiniteBlocks) {
  std::mt19937 gen(11);
  for (double shift : {0.0, -0.5}) {
    const Problem p = RandomProblem(6, 5, 4, shift, gen);
    SchurCholesky chol;
    ASSERT_EQ(chol.Analyse(p.n, p.m, p.row, p.col, Positions(p, DisplacementRows(p)), 1), 0);
    std::vector<double> S;
    bool positive = true;
    ASSERT_EQ(chol.Factor(p.value, S, positive), 0);
    EXPECT_FALSE(positive) << "shift " << shift;
    std::vector<double> b(p.n, 1.0), reduced(p.m);
    test::ErrorCapture capture;
    EXPECT_NE(chol.Forward(b.data(), reduced.data()), 0);
    EXPECT_NE(capture.Message().find("no factors"), std::string::npos);
  }
}

} // namespace
} // namespace signorini
