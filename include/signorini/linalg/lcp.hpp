// Lemke's complementary pivoting method for a dense linear complementarity problem: find z >= 0 with
// w = q + M z >= 0 and z . w = 0. For a positive semidefinite M it is finite: it ends with a solution, or on a ray,
// which proves that the problem has none (Cottle, Pang and Stone, The Linear Complementarity Problem, 4.4). The
// contact solver's last resort for the active set of the linear material (ContactSolver::PivotedActiveSet).
#pragma once

#include <vector>

namespace signorini {

/// INACCURATE: the method ended on a basis whose z, w fail the check of a solution (round-off), no verdict.
enum class LcpStatus { SOLVED, RAY, PIVOT_LIMIT, INACCURATE };
inline const char *LcpStatusName(LcpStatus s) {
  return s == LcpStatus::SOLVED        ? "solved"
         : s == LcpStatus::RAY         ? "ray (no solution)"
         : s == LcpStatus::PIVOT_LIMIT ? "pivot limit"
                                       : "inaccurate";
}

/// SOLVED's check: z >= 0, w >= -LCP_TOL s_i and |w_i| <= LCP_TOL s_i where z_i > 0, s_i = max|q| + sum_j |M_ij z_j|
/// (the size of the terms that w_i sums: its backward error).
constexpr double LCP_TOL = 1e-8;

/// Solves the m x m problem (M column major: M[i + j m]) by Lemke's method with the covering vector of ones, at most
/// max_pivots pivots (0: 10 m + 100). Scale invariant: the same pivots for (s M, t q), s, t > 0, with z scaled by t / s
/// and w by t. SOLVED only when z, w pass the check of LCP_TOL. z and w get the solution (zero where not basic);
/// pivots the count.
LcpStatus SolveLcp(int m, const std::vector<double> &M, const std::vector<double> &q, std::vector<double> &z,
                   std::vector<double> &w, int *pivots = nullptr, int max_pivots = 0);

/// min |A x - b| over x >= 0 for a k x m matrix A (column major: A[i + j k]) with few rows and any number of columns
/// (the rigid motions against the candidate pairs): Lawson and Hanson's active-set method (Solving Least Squares
/// Problems, 1974, ch. 23), finite; at most k columns are ever positive together, each step a k x (at most k) least
/// squares problem (LAPACK's gelss). x gets the solution; returns |A x - b|. No package of Debian's offers it for
/// C or C++ (PETSc's TAO has iterative bound-constrained solvers, which would give the verdict a tolerance of theirs).
double NonNegativeLeastSquares(int k, int m, const std::vector<double> &A, const std::vector<double> &b,
                               std::vector<double> &x);

} // namespace signorini
