// Lemke's complementary pivoting method for a dense linear complementarity problem: find z >= 0 with
// w = q + M z >= 0 and z . w = 0. For a positive semidefinite M it is finite: it ends with a solution, or on a ray,
// which proves that the problem has none (Cottle, Pang and Stone, The Linear Complementarity Problem, 4.4). The
// contact solver's last resort for the active set of the linear material (ContactSolver::PivotedActiveSet).
#pragma once

#include <vector>

namespace signorini {

enum class LcpStatus { SOLVED, RAY, PIVOT_LIMIT };
inline const char *LcpStatusName(LcpStatus s) {
  return s == LcpStatus::SOLVED ? "solved" : s == LcpStatus::RAY ? "ray (no solution)" : "pivot limit";
}

/// Solves the m x m problem (M column major: M[i + j m]) by Lemke's method with the covering vector of ones, at most
/// max_pivots pivots (0: 10 m + 100). z and w get the solution (zero where not basic); pivots the count.
LcpStatus SolveLcp(int m, const std::vector<double> &M, const std::vector<double> &q, std::vector<double> &z,
                   std::vector<double> &w, int *pivots = nullptr, int max_pivots = 0);

} // namespace signorini
