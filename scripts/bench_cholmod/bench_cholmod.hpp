// What the benchmark of SchurCholesky against CHOLMOD shares between its two files: the matrix, a run's result, the
// clock, the right-hand side, and the CHOLMOD routes (cholmod_schur.cpp).
#pragma once

#include <SuiteSparse_config.h>
#include <petscsys.h>
#include <petsctime.h>
#include <sys/resource.h>

#include <cmath>
#include <string>
#include <vector>

namespace bench_cholmod {

using Long = SuiteSparse_long;

/// The saddle-point matrix as the benchmark takes it: the upper triangle (row <= col, 0-based) and the split.
struct SaddleMatrix {
  PetscInt n = 0, m = 0, nu = 0, dim = 2;
  std::vector<int> row, col;
  std::vector<double> value;
};

/// What one solver produced, for the comparison and the report.
struct Result {
  double analyse = 0, factor = 0, schur = 0, forward = 0, backward = 0, peak = 0;
  double entries = 0, flops = 0;
  std::string note;
  std::vector<double> s, reduced, x;
};

/// Peak resident memory of the process so far (MiB).
inline double PeakRssMiB() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

inline double Now() {
  PetscLogDouble t;
  PetscTime(&t);
  return t;
}

/// The solves run this many times with the same right-hand side; the last one is timed (the application solves
/// many times per factorisation: the first one's allocations and page faults are not what it pays per solve).
constexpr int SOLVE_PASSES = 2;

/// A deterministic right-hand side and multiplier part x2 for the solves.
inline void RightHandSide(const SaddleMatrix &a, std::vector<double> &b, std::vector<double> &x2) {
  b.resize(a.n), x2.resize(a.m);
  for (PetscInt i = 0; i < a.n; ++i)
    b[i] = std::sin(0.37 * (double)i + 1.0);
  for (PetscInt i = 0; i < a.m; ++i)
    x2[i] = 1e-3 * std::cos(0.71 * (double)i);
}

/// CHOLMOD factors A11 (P A11 P^T = L L^T, supernodal; given: with order, else CHOLMOD's default choice), then
/// W = L^-1 P A12 by w_method (solve2, spsolve or blocks of `block` columns) and S = A22 - W^T W by s_method (syrk
/// or ssmult).
[[nodiscard]] PetscErrorCode RunCholmod(const SaddleMatrix &a, const std::vector<Long> &order, bool given,
                                        const std::string &w_method, const std::string &s_method, PetscInt block,
                                        Result &r);
/// CHOLMOD factors the whole matrix with a shifted multiplier block, the multiplier rows last (given: order, else
/// CAMD), and S comes from the factor's last block.
[[nodiscard]] PetscErrorCode RunCholmodShifted(const SaddleMatrix &a, const std::vector<Long> &order, bool given,
                                               Result &r);

} // namespace bench_cholmod
