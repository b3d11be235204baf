// The CHOLMOD routes of the benchmark (bench_cholmod.cpp): A11 factored and the Schur complement from the sparse
// forward solve of the multiplier columns, or the whole matrix factored with a shifted multiplier block.
#include "bench_cholmod.hpp"

#include <cholmod.h>
#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace bench_cholmod {

namespace {

const char *OrderingName(int ordering) {
  switch (ordering) {
  case CHOLMOD_NATURAL:
    return "natural";
  case CHOLMOD_GIVEN:
    return "given";
  case CHOLMOD_AMD:
    return "amd";
  case CHOLMOD_METIS:
    return "metis";
  case CHOLMOD_NESDIS:
    return "nesdis";
  default:
    return "other";
  }
}

/// A12 (nu x m) in compressed columns, its rows permuted by pinv (pinv[i]: the position of row i) when given.
cholmod_sparse *OffDiagonal(const SaddleMatrix &a, const Long *pinv, cholmod_common *c) {
  std::vector<Long> count(a.m + 1, 0);
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.col[k] >= a.nu && a.row[k] < a.nu) ++count[a.col[k] - a.nu + 1];
  for (PetscInt j = 0; j < a.m; ++j)
    count[j + 1] += count[j];
  cholmod_sparse *B = cholmod_l_allocate_sparse(a.nu, a.m, count[a.m], 0, 1, 0, CHOLMOD_REAL, c);
  Long *p = (Long *)B->p, *i = (Long *)B->i;
  double *x = (double *)B->x;
  std::copy(count.begin(), count.end(), p);
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.col[k] >= a.nu && a.row[k] < a.nu) {
      const Long dst = count[a.col[k] - a.nu]++;
      i[dst] = pinv ? pinv[a.row[k]] : a.row[k], x[dst] = a.value[k];
    }
  cholmod_l_sort(B, c);
  return B;
}

/// A11 in compressed columns, lower triangle (the upper triangle by rows).
cholmod_sparse *Leading(const SaddleMatrix &a, cholmod_common *c) {
  std::vector<Long> count(a.nu + 1, 0);
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.col[k] < a.nu) ++count[a.row[k] + 1];
  for (PetscInt j = 0; j < a.nu; ++j)
    count[j + 1] += count[j];
  cholmod_sparse *A = cholmod_l_allocate_sparse(a.nu, a.nu, count[a.nu], 0, 1, -1, CHOLMOD_REAL, c);
  std::copy(count.begin(), count.end(), (Long *)A->p);
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.col[k] < a.nu) {
      const Long dst = count[a.row[k]]++;
      ((Long *)A->i)[dst] = a.col[k], ((double *)A->x)[dst] = a.value[k];
    }
  cholmod_l_sort(A, c);
  return A;
}

/// W = L^-1 P A12, column by column with a sparse right-hand side (cholmod_solve2's Bset).
cholmod_sparse *ForwardColumnsSparse(const SaddleMatrix &a, cholmod_factor *L, cholmod_common *c) {
  std::vector<Long> pinv(a.nu);
  for (Long k = 0; k < (Long)a.nu; ++k)
    pinv[((Long *)L->Perm)[k]] = k;
  cholmod_sparse *PB = OffDiagonal(a, pinv.data(), c);
  cholmod_dense *b = cholmod_l_zeros(a.nu, 1, CHOLMOD_REAL, c), *X = nullptr, *Y = nullptr, *E = nullptr;
  cholmod_sparse *bset = cholmod_l_allocate_sparse(a.nu, 1, a.nu, 1, 1, 0, CHOLMOD_PATTERN, c), *xset = nullptr;
  std::vector<Long> wp(1, 0), wi;
  std::vector<double> wx;
  const Long *bp = (Long *)PB->p, *bi = (Long *)PB->i;
  const double *bx = (double *)PB->x;
  double *bd = (double *)b->x;
  for (PetscInt j = 0; j < a.m; ++j) {
    Long *sp = (Long *)bset->p, *si = (Long *)bset->i;
    sp[0] = 0, sp[1] = bp[j + 1] - bp[j];
    for (Long k = bp[j]; k < bp[j + 1]; ++k)
      si[k - bp[j]] = bi[k], bd[bi[k]] = bx[k];
    if (!cholmod_l_solve2(CHOLMOD_L, L, b, bset, &X, &xset, &Y, &E, c)) break;
    for (Long k = bp[j]; k < bp[j + 1]; ++k)
      bd[bi[k]] = 0;
    const Long *xp = (Long *)xset->p, *xi = (Long *)xset->i;
    const double *xx = (double *)X->x;
    for (Long k = xp[0]; k < xp[1]; ++k)
      if (xx[xi[k]] != 0) wi.push_back(xi[k]), wx.push_back(xx[xi[k]]);
    wp.push_back((Long)wi.size());
  }
  cholmod_l_free_dense(&b, c), cholmod_l_free_dense(&X, c), cholmod_l_free_dense(&Y, c), cholmod_l_free_dense(&E, c);
  cholmod_l_free_sparse(&bset, c), cholmod_l_free_sparse(&xset, c), cholmod_l_free_sparse(&PB, c);
  cholmod_sparse *W = cholmod_l_allocate_sparse(a.nu, a.m, wi.size(), 0, 1, 0, CHOLMOD_REAL, c);
  std::copy(wp.begin(), wp.end(), (Long *)W->p);
  std::copy(wi.begin(), wi.end(), (Long *)W->i);
  std::copy(wx.begin(), wx.end(), (double *)W->x);
  return W;
}

/// W = L^-1 P A12 on dense blocks of nb columns (cholmod_solve2), kept sparse.
cholmod_sparse *ForwardColumnsBlocks(const SaddleMatrix &a, cholmod_factor *L, PetscInt nb, cholmod_common *c) {
  std::vector<Long> pinv(a.nu);
  for (Long k = 0; k < (Long)a.nu; ++k)
    pinv[((Long *)L->Perm)[k]] = k;
  cholmod_sparse *PB = OffDiagonal(a, pinv.data(), c);
  std::vector<Long> wp(1, 0), wi;
  std::vector<double> wx;
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  const Long *bp = (Long *)PB->p, *bi = (Long *)PB->i;
  for (PetscInt j0 = 0; j0 < a.m; j0 += nb) {
    const PetscInt cols = std::min(nb, a.m - j0);
    cholmod_dense *b = cholmod_l_zeros(a.nu, cols, CHOLMOD_REAL, c);
    for (PetscInt j = 0; j < cols; ++j)
      for (Long k = bp[j0 + j]; k < bp[j0 + j + 1]; ++k)
        ((double *)b->x)[j * a.nu + bi[k]] = ((double *)PB->x)[k];
    if (!cholmod_l_solve2(CHOLMOD_L, L, b, nullptr, &X, nullptr, &Y, &E, c)) break;
    for (PetscInt j = 0; j < cols; ++j) {
      const double *xx = (double *)X->x + (std::size_t)j * a.nu;
      for (Long i = 0; i < (Long)a.nu; ++i)
        if (xx[i] != 0) wi.push_back(i), wx.push_back(xx[i]);
      wp.push_back((Long)wi.size());
    }
    cholmod_l_free_dense(&b, c);
  }
  cholmod_l_free_dense(&X, c), cholmod_l_free_dense(&Y, c), cholmod_l_free_dense(&E, c);
  cholmod_l_free_sparse(&PB, c);
  cholmod_sparse *W = cholmod_l_allocate_sparse(a.nu, a.m, wi.size(), 0, 1, 0, CHOLMOD_REAL, c);
  std::copy(wp.begin(), wp.end(), (Long *)W->p);
  std::copy(wi.begin(), wi.end(), (Long *)W->i);
  std::copy(wx.begin(), wx.end(), (double *)W->x);
  return W;
}

/// s = -W^T W (m x m, column major) with one BLAS syrk on the rows where W has entries (their union is the top of
/// the elimination tree: the separators above the contact nodes), gathered densely.
[[nodiscard]] PetscErrorCode SchurSyrk(const cholmod_sparse *W, std::vector<double> &s) {
  PetscFunctionBeginUser;
  const Long *wp = (Long *)W->p, *wi = (Long *)W->i;
  const double *wx = (double *)W->x;
  const Long m = (Long)W->ncol;
  std::vector<Long> compressed(W->nrow, -1);
  Long rows = 0;
  for (Long k = 0; k < wp[m]; ++k)
    if (compressed[wi[k]] < 0) compressed[wi[k]] = rows++;
  std::vector<double> dense((std::size_t)rows * m, 0.0);
  for (Long j = 0; j < m; ++j)
    for (Long k = wp[j]; k < wp[j + 1]; ++k)
      dense[(std::size_t)j * rows + compressed[wi[k]]] = wx[k];
  PetscBLASInt bm, brows;
  PetscCall(PetscBLASIntCast(m, &bm));
  PetscCall(PetscBLASIntCast(std::max<Long>(rows, 1), &brows));
  const double minus_one = -1, zero = 0;
  if (rows > 0)
    PetscCallBLAS("BLASsyrk", BLASsyrk_("L", "T", &bm, &brows, &minus_one, dense.data(), &brows, &zero, s.data(), &bm));
  for (Long j = 0; j < m; ++j)
    for (Long i = j + 1; i < m; ++i)
      s[i * m + j] = s[j * m + i];
  PetscFunctionReturn(0);
}

/// The whole matrix with the shift beta on the multiplier diagonal, M = [A11 A12; A21 beta I], in compressed columns
/// (lower triangle).
cholmod_sparse *Shifted(const SaddleMatrix &a, double beta, cholmod_common *c) {
  std::vector<Long> count(a.n + 1, 0);
  for (std::size_t k = 0; k < a.row.size(); ++k)
    ++count[a.row[k] + 1];
  for (PetscInt j = 0; j < a.n; ++j)
    count[j + 1] += count[j];
  cholmod_sparse *M = cholmod_l_allocate_sparse(a.n, a.n, count[a.n], 0, 1, -1, CHOLMOD_REAL, c);
  std::copy(count.begin(), count.end(), (Long *)M->p);
  for (std::size_t k = 0; k < a.row.size(); ++k) {
    const Long dst = count[a.row[k]]++;
    ((Long *)M->i)[dst] = a.col[k];
    ((double *)M->x)[dst] = a.row[k] >= a.nu ? beta : a.value[k];
  }
  cholmod_l_sort(M, c);
  return M;
}

} // namespace

/// CHOLMOD's factorisation of the shifted whole matrix M = [A11 A12; A21 beta I] with the multiplier rows last, the
/// way a multifrontal solver gets the Schur complement: the last block of the factor is beta I - A21 A11^-1 A12 =
/// L22 L22^T, so S = A22 - beta I + L22 L22^T. beta must make M positive definite (beta > the largest eigenvalue of
/// A21 A11^-1 A12, not known beforehand): it starts at 10 max_j |A12(:, j)|^2 / min_i A11(i, i) and grows by 100
/// while the factorisation fails in the multiplier rows (each retry a whole factorisation, counted in the time); S
/// loses about log10(beta / |S|) digits to the cancellation. The solves then use the factor's leading block.
[[nodiscard]] PetscErrorCode RunCholmodShifted(const SaddleMatrix &a, const std::vector<Long> &order, bool given,
                                               Result &r) {
  cholmod_common c;
  PetscFunctionBeginUser;
  cholmod_l_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1, c.method[0].ordering = CHOLMOD_GIVEN, c.postorder = 1;
  double a11_min = INFINITY;
  std::vector<double> column_norm(a.m, 0.0);
  for (std::size_t k = 0; k < a.row.size(); ++k) {
    if (a.row[k] == a.col[k] && a.row[k] < a.nu) a11_min = std::min(a11_min, a.value[k]);
    if (a.row[k] < a.nu && a.col[k] >= a.nu) column_norm[a.col[k] - a.nu] += a.value[k] * a.value[k];
  }
  double beta = 10 * *std::max_element(column_norm.begin(), column_norm.end()) / a11_min;
  cholmod_sparse *M = Shifted(a, beta, &c);
  double t = Now();
  std::vector<Long> perm(order);
  if (given)
    for (Long i = a.nu; i < (Long)a.n; ++i)
      perm.push_back(i);
  else {
    // CHOLMOD's own: CAMD with the multiplier rows constrained last.
    std::vector<Long> last(a.n, 0);
    std::fill(last.begin() + a.nu, last.end(), 1);
    perm.resize(a.n);
    PetscCheck(cholmod_l_camd(M, nullptr, 0, last.data(), perm.data(), &c), PETSC_COMM_SELF, PETSC_ERR_LIB,
               "cholmod_l_camd failed: status %d", c.status);
  }
  cholmod_factor *L = cholmod_l_analyze_p(M, perm.data(), nullptr, 0, &c);
  r.analyse = Now() - t;
  PetscCheck(L, PETSC_COMM_SELF, PETSC_ERR_LIB, "cholmod_l_analyze_p failed: status %d", c.status);
  for (Long k = a.nu; k < (Long)a.n; ++k)
    PetscCheck(((Long *)L->Perm)[k] >= a.nu, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the multiplier rows are not last");
  r.flops = c.fl;
  int retries = 0;
  t = Now();
  for (;; ++retries) {
    c.quick_return_if_not_posdef = 1;
    cholmod_l_factorize(M, L, &c);
    if (c.status == CHOLMOD_OK) break;
    PetscCheck(c.status == CHOLMOD_NOT_POSDEF && L->minor >= (size_t)a.nu && retries < 6, PETSC_COMM_SELF,
               PETSC_ERR_LIB, "cholmod_l_factorize of the shifted matrix: status %d, minor %ld", c.status,
               (long)L->minor);
    beta *= 100;
    cholmod_l_free_sparse(&M, &c);
    M = Shifted(a, beta, &c);
  }
  r.factor = Now() - t;
  r.entries = (double)L->xsize;
  // L22 from the supernodes' columns nu .. n - 1 (positions; Perm maps them to the multiplier rows), G = L22 L22^T.
  t = Now();
  const Long *super = (Long *)L->super, *pi = (Long *)L->pi, *px = (Long *)L->px, *ls = (Long *)L->s;
  const Long *lperm = (Long *)L->Perm;
  const double *lx = (double *)L->x;
  std::vector<double> l22((std::size_t)a.m * a.m, 0.0);
  for (Long sn = 0; sn < (Long)L->nsuper; ++sn)
    for (Long k = std::max<Long>(super[sn], a.nu); k < super[sn + 1]; ++k) {
      const Long nsrow = pi[sn + 1] - pi[sn], col = lperm[k] - a.nu;
      for (Long q = k - super[sn]; q < nsrow; ++q)
        l22[(std::size_t)col * a.m + (lperm[ls[pi[sn] + q]] - a.nu)] = lx[px[sn] + (k - super[sn]) * nsrow + q];
    }
  r.s.assign((std::size_t)a.m * a.m, 0.0);
  PetscBLASInt bm;
  PetscCall(PetscBLASIntCast(a.m, &bm));
  const double one = 1, zero = 0;
  PetscCallBLAS("BLASgemm",
                BLASgemm_("N", "T", &bm, &bm, &bm, &one, l22.data(), &bm, l22.data(), &bm, &zero, r.s.data(), &bm));
  for (PetscInt j = 0; j < a.m; ++j)
    r.s[j * (a.m + 1)] -= beta;
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.row[k] >= a.nu) r.s[(a.row[k] - a.nu) * (a.m + 1)] += a.value[k];
  r.schur = Now() - t;
  // Solves, with L = [L11 0; L21 L22] in pivot order (P2 the multiplier rows' part of P). Forward: [y1; y2] =
  // L^-1 P [b1; 0] gives y1 = L11^-1 P1 b1 and L21 y1 = -L22 y2, so b2 - A21 A11^-1 b1 = b2 + P2^T L22 y2.
  // Backward: x1 = P1^T L11^-T (y1 - L21^T P2 x2) is the first part of P^T L^-T [y1; L22^T P2 x2].
  std::vector<double> b, x2;
  RightHandSide(a, b, x2);
  std::vector<double> bz(b.begin(), b.begin() + a.nu);
  bz.resize(a.n, 0.0);
  cholmod_dense B = {};
  B.nrow = a.n, B.ncol = 1, B.nzmax = a.n, B.d = a.n, B.x = bz.data(), B.xtype = CHOLMOD_REAL, B.dtype = CHOLMOD_DOUBLE;
  cholmod_dense *Pb = nullptr, *y = nullptr, *z = nullptr, *x = nullptr, *Y = nullptr, *E = nullptr;
  r.reduced.resize(a.m);
  std::vector<double> tail(a.m);
  for (int pass = 0; pass < SOLVE_PASSES; ++pass) {
    t = Now();
    cholmod_l_solve2(CHOLMOD_P, L, &B, nullptr, &Pb, nullptr, &Y, &E, &c);
    cholmod_l_solve2(CHOLMOD_L, L, Pb, nullptr, &y, nullptr, &Y, &E, &c);
    double *yx = (double *)y->x;
    for (PetscInt j = 0; j < a.m; ++j)
      tail[j] = 0;
    for (PetscInt p = 0; p < a.m; ++p)
      tail[lperm[a.nu + p] - a.nu] = yx[a.nu + p];
    for (PetscInt i = 0; i < a.m; ++i)
      r.reduced[i] = b[a.nu + i];
    for (PetscInt j = 0; j < a.m; ++j)
      for (PetscInt i = 0; i < a.m; ++i)
        r.reduced[i] += l22[(std::size_t)j * a.m + i] * tail[j];
    r.forward = Now() - t;
    t = Now();
    for (PetscInt j = 0; j < a.m; ++j) {
      double sum = 0;
      for (PetscInt i = 0; i < a.m; ++i)
        sum += l22[(std::size_t)j * a.m + i] * x2[i];
      tail[j] = sum;
    }
    for (PetscInt p = 0; p < a.m; ++p)
      yx[a.nu + p] = tail[lperm[a.nu + p] - a.nu];
    cholmod_l_solve2(CHOLMOD_Lt, L, y, nullptr, &z, nullptr, &Y, &E, &c);
    cholmod_l_solve2(CHOLMOD_Pt, L, z, nullptr, &x, nullptr, &Y, &E, &c);
    r.backward = Now() - t;
  }
  r.x.assign((double *)x->x, (double *)x->x + a.n);
  r.peak = PeakRssMiB();
  r.note = std::string("ordering=") + (given ? "metis_nodes" : "camd") +
           " cholmod_peak_mib=" + std::to_string(c.memory_usage / 1048576.0) + " w=shift beta=" + std::to_string(beta) +
           " retries=" + std::to_string(retries) + " w_s=0";
  for (cholmod_dense **d : {&Pb, &y, &z, &x, &Y, &E})
    cholmod_l_free_dense(d, &c);
  cholmod_l_free_sparse(&M, &c);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_finish(&c);
  PetscFunctionReturn(0);
}

[[nodiscard]] PetscErrorCode RunCholmod(const SaddleMatrix &a, const std::vector<Long> &order, bool given,
                                        const std::string &w_method, const std::string &s_method, PetscInt block,
                                        Result &r) {
  cholmod_common c;
  PetscFunctionBeginUser;
  cholmod_l_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  if (given) c.nmethods = 1, c.method[0].ordering = CHOLMOD_GIVEN, c.postorder = 1;
  cholmod_sparse *A11 = Leading(a, &c);
  double t = Now();
  cholmod_factor *L =
      given ? cholmod_l_analyze_p(A11, (Long *)order.data(), nullptr, 0, &c) : cholmod_l_analyze(A11, &c);
  r.analyse = Now() - t;
  PetscCheck(L, PETSC_COMM_SELF, PETSC_ERR_LIB, "cholmod_l_analyze failed: status %d", c.status);
  r.note = std::string("ordering=") + (given ? "metis_nodes" : OrderingName(c.method[c.selected].ordering));
  r.flops = c.fl;
  t = Now();
  PetscCheck(cholmod_l_factorize(A11, L, &c) && c.status == CHOLMOD_OK, PETSC_COMM_SELF, PETSC_ERR_LIB,
             "cholmod_l_factorize: status %d, minor %ld", c.status, (long)L->minor);
  r.factor = Now() - t;
  r.entries = (double)L->xsize;
  t = Now();
  cholmod_sparse *W = nullptr;
  if (w_method == "spsolve") {
    cholmod_sparse *B = OffDiagonal(a, nullptr, &c), *PB = cholmod_l_spsolve(CHOLMOD_P, L, B, &c);
    W = cholmod_l_spsolve(CHOLMOD_L, L, PB, &c);
    cholmod_l_free_sparse(&B, &c), cholmod_l_free_sparse(&PB, &c);
  } else if (w_method == "blocks")
    W = ForwardColumnsBlocks(a, L, block, &c);
  else
    W = ForwardColumnsSparse(a, L, &c);
  PetscCheck(W && c.status == CHOLMOD_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "W = L^-1 P A12 failed: status %d", c.status);
  const double w_time = Now() - t;
  r.s.assign((std::size_t)a.m * a.m, 0.0);
  if (s_method == "ssmult") {
    cholmod_sparse *Wt = cholmod_l_transpose(W, 1, &c), *WtW = cholmod_l_ssmult(Wt, W, 0, 1, 0, &c);
    cholmod_dense *G = cholmod_l_sparse_to_dense(WtW, &c);
    const double *g = (double *)G->x;
    for (PetscInt j = 0; j < a.m; ++j)
      for (PetscInt i = 0; i < a.m; ++i)
        r.s[j * a.m + i] = -g[j * G->d + i];
    cholmod_l_free_dense(&G, &c), cholmod_l_free_sparse(&Wt, &c), cholmod_l_free_sparse(&WtW, &c);
  } else
    PetscCall(SchurSyrk(W, r.s));
  for (std::size_t k = 0; k < a.row.size(); ++k)
    if (a.row[k] >= a.nu) r.s[(a.row[k] - a.nu) * (a.m + 1)] += a.value[k];
  r.schur = Now() - t;
  const double nnz_w = (double)cholmod_l_nnz(W, &c);

  // Forward: y = L^-1 P b1, reduced = b2 - W^T y. Backward: x1 = P^T L^-T (y - W x2).
  std::vector<double> b, x2;
  RightHandSide(a, b, x2);
  cholmod_dense b1 = {};
  b1.nrow = a.nu, b1.ncol = 1, b1.nzmax = a.nu, b1.d = a.nu, b1.x = b.data(), b1.xtype = CHOLMOD_REAL,
  b1.dtype = CHOLMOD_DOUBLE;
  cholmod_dense red = b1, xm = b1;
  red.nrow = a.m, red.nzmax = a.m, red.d = a.m;
  xm.nrow = a.m, xm.nzmax = a.m, xm.d = a.m, xm.x = x2.data();
  cholmod_dense *Pb = nullptr, *y = nullptr, *z = nullptr, *x1 = nullptr, *Y = nullptr, *E = nullptr;
  double minus_one[2] = {-1, 0}, one[2] = {1, 0};
  for (int pass = 0; pass < SOLVE_PASSES; ++pass) {
    r.reduced.assign(b.begin() + a.nu, b.end());
    red.x = r.reduced.data();
    t = Now();
    cholmod_l_solve2(CHOLMOD_P, L, &b1, nullptr, &Pb, nullptr, &Y, &E, &c);
    cholmod_l_solve2(CHOLMOD_L, L, Pb, nullptr, &y, nullptr, &Y, &E, &c);
    cholmod_l_sdmult(W, 1, minus_one, one, y, &red, &c);
    r.forward = Now() - t;
    t = Now();
    cholmod_l_sdmult(W, 0, minus_one, one, &xm, y, &c);
    cholmod_l_solve2(CHOLMOD_Lt, L, y, nullptr, &z, nullptr, &Y, &E, &c);
    cholmod_l_solve2(CHOLMOD_Pt, L, z, nullptr, &x1, nullptr, &Y, &E, &c);
    r.backward = Now() - t;
  }
  r.x.assign((double *)x1->x, (double *)x1->x + a.nu);
  r.x.insert(r.x.end(), x2.begin(), x2.end());
  r.peak = PeakRssMiB();
  r.note += " cholmod_peak_mib=" + std::to_string(c.memory_usage / 1048576.0) +
            " nnz_w=" + std::to_string((long)nnz_w) + " w=" + w_method + " w_s=" + std::to_string(w_time) +
            " s=" + s_method;
  for (cholmod_dense **d : {&Pb, &y, &z, &x1, &Y, &E})
    cholmod_l_free_dense(d, &c);
  cholmod_l_free_sparse(&W, &c), cholmod_l_free_sparse(&A11, &c);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_finish(&c);
  PetscFunctionReturn(0);
}

} // namespace bench_cholmod
