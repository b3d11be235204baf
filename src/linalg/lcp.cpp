// Lemke's method on a dense tableau; Lawson and Hanson's non-negative least squares.
#include "signorini/linalg/lcp.hpp"

#include <petscsys.h>
#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>

namespace signorini {

namespace {

/// Whether z >= 0 and w = q + M z solve the problem to tol (w is recomputed here): w_i >= -tol s_i and
/// |z_i w_i| <= tol s_i z_i, with s_i = max|q| + sum_j |M_ij z_j|, the size of the terms that w_i sums (its backward
/// error: a row whose terms cancel can only be that accurate).
bool IsSolution(int m, const std::vector<double> &M, const std::vector<double> &q, const std::vector<double> &z,
                std::vector<double> &w, double tol) {
  double qmax = 0;
  for (double v : q) qmax = std::max(qmax, std::abs(v));
  bool ok = true;
  for (int i = 0; i < m; ++i) {
    double wi = q[i], size = qmax;
    for (int j = 0; j < m; ++j) {
      const double term = M[i + (std::size_t)j * m] * z[j];
      wi += term, size += std::abs(term);
    }
    w[i] = wi;
    ok = ok && std::isfinite(wi) && z[i] >= 0 && wi >= -tol * size && std::abs(wi) * z[i] <= tol * size * z[i];
  }
  return ok;
}

/// The units of a run of Lemke's method (see Lemke): each row's largest |M_ij| (rowmax), the smallest and largest of
/// them (mref, mmax) and the largest |q_i| (qmax).
struct LcpUnits {
  double mref = INFINITY, mmax = 0, qmax = 0;
  std::vector<double> rowmax;
};

/// The tableau of w - M z - e z0 = q in a run's units: columns w (0..m-1), z (m..2m-1), z0 (2m), the right-hand side
/// (2m+1); row i holds basic variable Basis(i). equilibrate: each row divided by its largest M entry (at least 1).
class Tableau {
public:
  Tableau(int m, const std::vector<double> &M, const std::vector<double> &q, const LcpUnits &u, bool equilibrate)
      : m_(m), nc_(2 * m + 2), t_((std::size_t)m * nc_, 0.0), basis_(m) {
    for (int i = 0; i < m; ++i) {
      const double scale = equilibrate ? std::max(1.0, u.rowmax[i] / u.mref) : 1.0;
      At(i, i) = 1 / scale;
      for (int j = 0; j < m; ++j)
        At(i, m + j) = -M[i + (std::size_t)j * m] / u.mref / scale;
      At(i, Z0()) = -1 / scale;
      At(i, Rhs()) = q[i] / u.qmax / scale;
      basis_[i] = i;
    }
  }
  int Z0() const { return 2 * m_; }
  int Rhs() const { return 2 * m_ + 1; }
  double &At(int i, int j) { return t_[(std::size_t)i * nc_ + j]; }
  int Basis(int i) const { return basis_[i]; }
  /// Column c enters the basis at row r.
  void Pivot(int r, int c) {
    const double p = At(r, c);
    for (int j = 0; j < nc_; ++j)
      At(r, j) /= p;
    for (int i = 0; i < m_; ++i) {
      if (i == r) continue;
      const double f = At(i, c);
      if (f == 0) continue;
      for (int j = 0; j < nc_; ++j)
        At(i, j) -= f * At(r, j);
      At(i, c) = 0;
    }
    basis_[r] = c;
  }
  /// The row whose variable leaves when column entering enters (-1: none, a ray): the minimum ratio; at a tie z0
  /// leaves first (the solution), then the smallest variable index (no cycling in practice on these problems; the
  /// pivot limit bounds a degenerate one).
  int LeavingRow(int entering, bool equilibrate) {
    double column = 0;
    for (int i = 0; i < m_; ++i)
      column = std::max(column, std::abs(At(i, entering)));
    int r = -1;
    double best = INFINITY;
    for (int i = 0; i < m_; ++i) {
      const double d = At(i, entering);
      double row = column;
      if (!equilibrate) {
        row = 0;
        for (int j = 0; j < Rhs(); ++j)
          row = std::max(row, std::abs(At(i, j)));
      }
      if (d <= 1e-12 * row) continue;
      const double ratio = std::max(At(i, Rhs()), 0.0) / d;
      const bool tie = r >= 0 && std::abs(ratio - best) <= 1e-12 * std::max(equilibrate ? 1.0 : 0.0, std::abs(best));
      if (r < 0 || (!tie && ratio < best) ||
          (tie && (basis_[i] == Z0() || (basis_[r] != Z0() && basis_[i] < basis_[r]))))
        r = i, best = ratio;
    }
    return r;
  }

private:
  int m_, nc_;
  std::vector<double> t_;
  std::vector<int> basis_;
};

/// One run of Lemke's method (SolveLcp). equilibrate: in the units described there, with tolerances relative to a
/// column's largest entry; else M over its largest entry, rows as they are, pivots and ties relative to the row's
/// largest entry and to the larger ratio.
LcpStatus Lemke(int m, const std::vector<double> &M, const std::vector<double> &q, std::vector<double> &z,
                std::vector<double> &w, int *pivots, int max_pivots, bool equilibrate) {
  z.assign(m, 0.0);
  w = q;
  if (pivots) *pivots = 0;
  if (m == 0 || *std::min_element(q.begin(), q.end()) >= 0) return LcpStatus::SOLVED;
  // Units: the method runs on M / mref and q / |q|_max, mref the smallest of the rows' largest |M_ij| (z scales by
  // |q|_max / mref, w by |q|_max), and each row of the tableau is divided by its largest M entry, at least 1 there:
  // the same numbers, so the same pivots, in any units. Then an entry is round-off when it is within 1e-12 of the
  // largest in its column, and ratios tie within 1e-12 of the larger or of 1 (a right-hand side of order 1). M = 0:
  // w = q < 0 for every z.
  LcpUnits u;
  u.rowmax.assign(m, 0.0);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j)
      u.rowmax[i] = std::max(u.rowmax[i], std::abs(M[i + (std::size_t)j * m]));
    if (u.rowmax[i] > 0) u.mref = std::min(u.mref, u.rowmax[i]);
    u.mmax = std::max(u.mmax, u.rowmax[i]);
  }
  for (double v : q)
    u.qmax = std::max(u.qmax, std::abs(v));
  if (!std::isfinite(u.mref)) return LcpStatus::RAY;
  if (!equilibrate) u.mref = u.mmax;
  Tableau tab(m, M, q, u, equilibrate);
  const int z0 = tab.Z0(), rhs = tab.Rhs();
  if (max_pivots <= 0) max_pivots = 10 * m + 100;
  // z0 enters where q is most negative.
  int r = 0;
  for (int i = 1; i < m; ++i)
    if (tab.At(i, rhs) / -tab.At(i, z0) < tab.At(r, rhs) / -tab.At(r, z0)) r = i;
  int leaving = tab.Basis(r);
  tab.Pivot(r, z0);
  int count = 1;
  LcpStatus status = LcpStatus::PIVOT_LIMIT;
  for (; count < max_pivots; ++count) {
    const int entering = leaving < m ? leaving + m : leaving - m; // the complement of the variable that left
    r = tab.LeavingRow(entering, equilibrate);
    if (r < 0) {
      status = LcpStatus::RAY;
      break;
    }
    leaving = tab.Basis(r);
    tab.Pivot(r, entering);
    if (leaving == z0) {
      status = LcpStatus::SOLVED;
      ++count;
      break;
    }
  }
  if (pivots) *pivots = count;
  if (status != LcpStatus::SOLVED) return status;
  for (int i = 0; i < m; ++i)
    if (tab.Basis(i) >= m && tab.Basis(i) < z0) z[tab.Basis(i) - m] = std::max(tab.At(i, rhs), 0.0) * (u.qmax / u.mref);
  // A solution only if it is one: round-off in a degenerate or ill-conditioned tableau can end on a basis that is not
  // (INACCURATE, no verdict; z and w are what was found).
  if (!IsSolution(m, M, q, z, w, LCP_TOL)) return LcpStatus::INACCURATE;
  return status;
}

} // namespace

LcpStatus SolveLcp(int m, const std::vector<double> &M, const std::vector<double> &q, std::vector<double> &z,
                   std::vector<double> &w, int *pivots, int max_pivots) {
  // Each run's solution is checked, so a second run in the other units may stand for a first that ends on a ray or
  // a basis that is no solution through round-off (the 3D cube of test cycling_set_pivoted needs the second).
  const LcpStatus status = Lemke(m, M, q, z, w, pivots, max_pivots, true);
  if (status == LcpStatus::SOLVED) return status;
  std::vector<double> z2, w2;
  int pivots2 = 0;
  if (Lemke(m, M, q, z2, w2, &pivots2, max_pivots, false) != LcpStatus::SOLVED) return status;
  z = z2, w = w2;
  if (pivots) *pivots = pivots2;
  return LcpStatus::SOLVED;
}

} // namespace signorini

namespace signorini {

namespace {

/// The least-squares solution s of min |A_P s - b| (A_P: the columns cols of the k-row column-major A) by LAPACK's
/// gelss (SVD; singular values below 1e-13 of the largest count as 0, so dependent columns share the minimum-norm
/// solution); false if the SVD did not converge.
/// The Euclidean norm.
double Norm(const std::vector<double> &v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

bool LeastSquares(int k, const std::vector<double> &A, const std::vector<int> &cols, const std::vector<double> &b,
                  std::vector<double> &s) {
  const int n = (int)cols.size();
  const PetscBLASInt rows = k, ncols = n, nrhs = 1, ldb = std::max(k, n);
  std::vector<double> a((std::size_t)k * n), y(ldb, 0.0), sv(std::min(k, n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < k; ++i) a[i + (std::size_t)j * k] = A[i + (std::size_t)cols[j] * k];
  std::copy(b.begin(), b.end(), y.begin());
  const PetscReal rcond = 1e-13;
  PetscBLASInt rank, info, lwork = -1;
  double query;
  LAPACKgelss_(&rows, &ncols, &nrhs, a.data(), &rows, y.data(), &ldb, sv.data(), &rcond, &rank, &query, &lwork,
               &info);
  lwork = (PetscBLASInt)query;
  std::vector<double> work(std::max<PetscBLASInt>(lwork, 1));
  LAPACKgelss_(&rows, &ncols, &nrhs, a.data(), &rows, y.data(), &ldb, sv.data(), &rcond, &rank, work.data(), &lwork,
               &info);
  s.assign(y.begin(), y.begin() + n);
  return info == 0;
}

} // namespace

double NonNegativeLeastSquares(int k, int m, const std::vector<double> &A, const std::vector<double> &b,
                               std::vector<double> &x) {
  x.assign(m, 0.0);
  std::vector<char> passive(m, 0);
  std::vector<double> r(b), s;
  std::vector<int> cols;
  const auto residual = [&] {
    r = b;
    for (int j = 0; j < m; ++j)
      if (x[j] != 0)
        for (int i = 0; i < k; ++i) r[i] -= A[i + (std::size_t)j * k] * x[j];
  };
  const double bnorm = Norm(b);
  double amax = 0;
  for (int j = 0; j < m; ++j) {
    double c = 0;
    for (int i = 0; i < k; ++i) c += A[i + (std::size_t)j * k] * A[i + (std::size_t)j * k];
    amax = std::max(amax, std::sqrt(c));
  }
  // A column enters while it would reduce the residual by more than round-off: its gradient A_j^T r above 1e-12 of
  // |A_j| |b| (the scale of the terms).
  const double tol = 1e-12 * amax * bnorm;
  for (int outer = 0; outer < 3 * m + 30; ++outer) {
    int t = -1;
    double best = tol;
    for (int j = 0; j < m; ++j) {
      if (passive[j]) continue;
      double w = 0;
      for (int i = 0; i < k; ++i) w += A[i + (std::size_t)j * k] * r[i];
      if (w > best) best = w, t = j;
    }
    if (t < 0) break;
    passive[t] = 1;
    for (int inner = 0; inner <= m; ++inner) {
      cols.clear();
      for (int j = 0; j < m; ++j)
        if (passive[j]) cols.push_back(j);
      if (!LeastSquares(k, A, cols, b, s)) {
        residual(); // no verdict better than the current point's
        return Norm(r);
      }
      bool positive = true;
      for (double v : s) positive = positive && v > 0;
      if (positive) {
        for (std::size_t c = 0; c < cols.size(); ++c) x[cols[c]] = s[c];
        break;
      }
      // Back along the segment from x to s to where the first passive variable reaches 0; it leaves the set.
      double alpha = 1;
      std::size_t first = 0;
      for (std::size_t c = 0; c < cols.size(); ++c)
        if (s[c] <= 0 && x[cols[c]] / (x[cols[c]] - s[c]) <= alpha) alpha = x[cols[c]] / (x[cols[c]] - s[c]), first = c;
      for (std::size_t c = 0; c < cols.size(); ++c) {
        const int j = cols[c];
        x[j] += alpha * (s[c] - x[j]);
        if (c == first || x[j] <= 0) x[j] = 0, passive[j] = 0;
      }
    }
    residual();
  }
  residual();
  return Norm(r);
}

} // namespace signorini
