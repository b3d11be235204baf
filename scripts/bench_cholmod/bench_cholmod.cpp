// Benchmark of signorini's SchurCholesky against CHOLMOD on a saddle-point matrix: the analysis, the factorisation
// with the Schur complement on the multiplier rows, and the forward and backward solves of one right-hand side.
//
// The matrix is the one `signorini ... -mat_view binary:FILE` writes (the saddle-point matrix A = [A11 A12; A21 A22]
// of one rank, the last m rows the multipliers, A22 diagonal); -m gives m, -dim the rows per node.
//   -solver ours     SchurCholesky (as MumpsSchur calls it): S = A22 - A21 A11^-1 A12 from the update matrices of
//                    the multifrontal factorisation of A11 = L L^T.
//   -solver cholmod  CHOLMOD (cholmod_schur.cpp). -w solve2 (default): P A11 P^T = L L^T (supernodal), W = L^-1 P A12
//                    by cholmod_solve2 with a sparse right-hand side (Bset) per column, S = A22 - W^T W by one BLAS
//                    syrk on the rows where W has entries (-s ssmult: cholmod_ssmult); -w spsolve: W by
//                    cholmod_spsolve; -w blocks: W by cholmod_solve2 on dense blocks of -block columns; -w shift: the
//                    whole matrix with a shifted multiplier block, the multiplier rows last, S from the factor's last
//                    block (RunCholmodShifted).
// -order given (default): METIS_NodeND of the node graph (signorini::MetisOrder), MumpsSchur's order in 3D and in 2D
// from 50k rows, for both solvers; -order own: CHOLMOD's default choice (AMD, METIS when AMD fills much; with -w shift
// CAMD with the multiplier rows last). One line of key=value per run; -check runs ours and one CHOLMOD route in one
// process and compares S, the condensed right-hand side and the solution.
//
// Build: cmake -DSIGNORINI_BENCH_CHOLMOD=ON (target bench_cholmod; CHOLMOD from Debian's libsuitesparse-dev).
// scripts/bench_cholmod/run.sh writes the Hertz matrices and runs the alternating measurements (RESULTS.md).
#include "bench_cholmod.hpp"

#include "signorini/linalg/parallel_dissection.hpp"
#include "signorini/linalg/schur_cholesky.hpp"

#include <petscmat.h>
#include <petscviewer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace bench_cholmod {
namespace {

[[nodiscard]] PetscErrorCode Load(const char *file, PetscInt m, PetscInt dim, SaddleMatrix &a) {
  Mat A;
  PetscViewer viewer;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_SELF, file, FILE_MODE_READ, &viewer));
  PetscCall(MatCreate(PETSC_COMM_SELF, &A));
  PetscCall(MatSetType(A, MATSEQAIJ));
  PetscCall(MatLoad(A, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(MatGetSize(A, &a.n, nullptr));
  a.m = m, a.nu = a.n - m, a.dim = dim;
  PetscCheck(m > 0 && a.nu > 0 && a.nu % dim == 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
             "-m %" PetscInt_FMT ": expected the number of multiplier rows, with n - m = %" PetscInt_FMT
             " displacement rows a multiple of -dim %" PetscInt_FMT,
             m, a.nu, dim);
  for (PetscInt i = 0; i < a.n; ++i) {
    PetscInt ncols;
    const PetscInt *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(A, i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; ++k)
      if (cols[k] >= i) {
        PetscCheck(i < a.nu || cols[k] == i, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
                   "entry (%" PetscInt_FMT ", %" PetscInt_FMT ") couples two multiplier rows: expected a diagonal "
                   "A22 (is -m right?)",
                   i, cols[k]);
        a.row.push_back((int)i), a.col.push_back((int)cols[k]), a.value.push_back(vals[k]);
      }
    PetscCall(MatRestoreRow(A, i, &ncols, &cols, &vals));
  }
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

/// MumpsSchur's given order: METIS_NodeND of the node graph of A11 (dim rows per node). order[k]: the displacement
/// row eliminated k-th.
[[nodiscard]] PetscErrorCode NodeOrder(const SaddleMatrix &a, std::vector<Long> &order) {
  PetscFunctionBeginUser;
  const idx_t nodes = (idx_t)(a.nu / a.dim);
  std::vector<idx_t> edges;
  for (std::size_t k = 0; k < a.row.size(); ++k) {
    if (a.col[k] >= a.nu) continue;
    const idx_t u = a.row[k] / a.dim, v = a.col[k] / a.dim;
    if (u != v) edges.push_back(u), edges.push_back(v);
  }
  signorini::Graph g = signorini::BuildGraph(nodes, edges);
  std::vector<idx_t> node_order;
  PetscCheck(signorini::MetisOrder(g, node_order) == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS failed");
  order.clear();
  for (idx_t v : node_order)
    for (PetscInt c = 0; c < a.dim; ++c)
      order.push_back((Long)(v * a.dim + c));
  PetscFunctionReturn(0);
}

[[nodiscard]] PetscErrorCode RunOurs(const SaddleMatrix &a, const std::vector<Long> &order, Result &r) {
  signorini::SchurCholesky chol;
  PetscFunctionBeginUser;
  std::vector<int> position(a.n);
  for (std::size_t k = 0; k < order.size(); ++k)
    position[order[k]] = (int)k;
  for (PetscInt i = a.nu; i < a.n; ++i)
    position[i] = (int)i;
  double t = Now();
  PetscCall(chol.Analyse(a.n, a.m, a.row, a.col, position, 0));
  r.analyse = Now() - t;
  r.entries = chol.Entries(), r.flops = chol.Flops();
  bool positive = false;
  t = Now();
  PetscCall(chol.Factor(a.value, r.s, positive));
  r.factor = Now() - t;
  PetscCheck(positive, PETSC_COMM_SELF, PETSC_ERR_MAT_CH_ZRPVT, "SchurCholesky: A11 not positive definite");
  std::vector<double> b, x2;
  RightHandSide(a, b, x2);
  r.reduced.resize(a.m), r.x.resize(a.n);
  for (int pass = 0; pass < SOLVE_PASSES; ++pass) {
    t = Now();
    PetscCall(chol.Forward(b.data(), r.reduced.data()));
    r.forward = Now() - t;
    t = Now();
    PetscCall(chol.Backward(x2.data(), r.x.data()));
    r.backward = Now() - t;
  }
  r.peak = PeakRssMiB();
  r.note = "ordering=metis_nodes";
  PetscFunctionReturn(0);
}

double RelativeDifference(const std::vector<double> &u, const std::vector<double> &v) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < u.size(); ++i)
    diff = std::max(diff, std::fabs(u[i] - v[i])), scale = std::max(scale, std::fabs(u[i]));
  return scale > 0 ? diff / scale : diff;
}

/// ||A11 x1 + A12 x2 - b1|| / ||b1||: the backward substitution's x solves the displacement rows.
double DisplacementResidual(const SaddleMatrix &a, const std::vector<double> &x) {
  std::vector<double> b, x2, r;
  RightHandSide(a, b, x2);
  r.assign(b.begin(), b.begin() + a.nu);
  for (std::size_t k = 0; k < a.row.size(); ++k) {
    const int i = a.row[k], j = a.col[k];
    if (i < a.nu) r[i] -= a.value[k] * x[j];
    if (j < a.nu && j != i) r[j] -= a.value[k] * x[i];
  }
  double rn = 0, bn = 0;
  for (PetscInt i = 0; i < a.nu; ++i)
    rn += r[i] * r[i], bn += b[i] * b[i];
  return std::sqrt(rn / bn);
}

void Print(const char *solver, const SaddleMatrix &a, double order_time, double load_peak, const Result &r) {
  std::printf("solver=%s n=%d m=%d order=%.4f analyse=%.4f factor=%.4f schur=%.4f forward=%.5f backward=%.5f "
              "peak_mib=%.1f load_peak_mib=%.1f entries=%.6g flops=%.6g residual=%.3g %s\n",
              solver, (int)a.n, (int)a.m, order_time, r.analyse, r.factor, r.schur, r.forward, r.backward, r.peak,
              load_peak, r.entries, r.flops, DisplacementResidual(a, r.x), r.note.c_str());
}

[[nodiscard]] PetscErrorCode Main() {
  char file[PETSC_MAX_PATH_LEN] = "", solver[32] = "ours", ordering[32] = "given", w_method[32] = "solve2",
       s_method[32] = "syrk";
  PetscInt m = 0, dim = 2, block = 64;
  PetscBool check = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_SELF, nullptr, "SchurCholesky against CHOLMOD", nullptr);
  PetscCall(
      PetscOptionsString("-file", "saddle-point matrix (PETSc binary)", nullptr, file, file, sizeof(file), nullptr));
  PetscCall(PetscOptionsInt("-m", "multiplier rows (the last ones)", nullptr, m, &m, nullptr));
  PetscCall(PetscOptionsInt("-dim", "rows per node", nullptr, dim, &dim, nullptr));
  PetscCall(PetscOptionsString("-solver", "ours or cholmod", nullptr, solver, solver, sizeof(solver), nullptr));
  PetscCall(PetscOptionsString("-order", "given (METIS node ND) or own (CHOLMOD's)", nullptr, ordering, ordering,
                               sizeof(ordering), nullptr));
  PetscCall(
      PetscOptionsString("-w", "solve2, spsolve or blocks", nullptr, w_method, w_method, sizeof(w_method), nullptr));
  PetscCall(PetscOptionsString("-s", "W^T W by syrk (dense rows of W) or ssmult (sparse)", nullptr, s_method, s_method,
                               sizeof(s_method), nullptr));
  PetscCall(PetscOptionsInt("-block", "columns per block (-w blocks)", nullptr, block, &block, nullptr));
  PetscCall(PetscOptionsBool("-check", "run both and compare", nullptr, check, &check, nullptr));
  PetscOptionsEnd();
  const std::string s = solver, o = ordering;
  PetscCheck(s == "ours" || s == "cholmod", PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
             "-solver %s: expected ours or cholmod", solver);
  PetscCheck(o == "given" || o == "own", PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-order %s: expected given or own",
             ordering);
  PetscCheck(s == "cholmod" || o == "given" || check, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
             "-solver ours takes the given order only");
  SaddleMatrix a;
  PetscCall(Load(file, m, dim, a));
  const double load_peak = PeakRssMiB();
  std::vector<Long> order;
  double order_time = 0;
  if (o == "given" || check) {
    const double t = Now();
    PetscCall(NodeOrder(a, order));
    order_time = Now() - t;
  }
  if (check) {
    Result ours, lib;
    PetscCall(RunOurs(a, order, ours));
    if (std::string(w_method) == "shift")
      PetscCall(RunCholmodShifted(a, order, o == "given", lib));
    else
      PetscCall(RunCholmod(a, order, o == "given", w_method, s_method, block, lib));
    Print("ours", a, order_time, load_peak, ours);
    Print("cholmod", a, order_time, load_peak, lib);
    std::printf("check: S %.3g, reduced rhs %.3g, x %.3g (max |difference| / max |ours|)\n",
                RelativeDifference(ours.s, lib.s), RelativeDifference(ours.reduced, lib.reduced),
                RelativeDifference(ours.x, lib.x));
  } else {
    Result r;
    if (s == "ours")
      PetscCall(RunOurs(a, order, r));
    else if (std::string(w_method) == "shift")
      PetscCall(RunCholmodShifted(a, order, o == "given", r));
    else
      PetscCall(RunCholmod(a, order, o == "given", w_method, s_method, block, r));
    Print(s == "ours" ? "ours" : o == "given" ? "cholmod_given" : "cholmod_own", a, order_time, load_peak, r);
  }
  PetscFunctionReturn(0);
}

} // namespace
} // namespace bench_cholmod

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, "SchurCholesky against CHOLMOD (scripts/bench_cholmod)"));
  PetscCall(bench_cholmod::Main());
  PetscCall(PetscFinalize());
  return 0;
}
