// Friction on the kept factorisation: the per-group maps between the current system and the fixed one
// (kept_rows.hpp).
#include "signorini/linalg/kept_rows.hpp"

#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>

namespace signorini {

namespace {

/// The inverse of the n x n row-major a (LAPACK getrf, getri); false when a pivot is not above 1e-12 of a's largest
/// entry.
bool Inverse(int n, const std::vector<double> &a, std::vector<double> &inv) {
  // Column-major for LAPACK: the transpose, whose inverse is the transposed inverse.
  std::vector<double> t(n * n);
  double largest = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) t[j * n + i] = a[i * n + j], largest = std::max(largest, std::fabs(a[i * n + j]));
  PetscBLASInt nn = n, info = 0, lwork = n * n;
  std::vector<PetscBLASInt> ipiv(n);
  std::vector<double> work(n * n);
  LAPACKgetrf_(&nn, &nn, t.data(), &nn, ipiv.data(), &info);
  if (info != 0 || !(largest > 0)) return false;
  for (int i = 0; i < n; ++i)
    if (!(std::fabs(t[i * n + i]) > 1e-12 * largest)) return false;
  LAPACKgetri_(&nn, t.data(), &nn, ipiv.data(), work.data(), &lwork, &info);
  if (info != 0) return false;
  inv.assign(n * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) inv[i * n + j] = t[j * n + i];
  return true;
}

} // namespace

void KeptRows::Set(std::vector<SparseRow> fixed, std::vector<RowGroup> groups) {
  fixed_ = std::move(fixed);
  given_ = std::move(groups);
}

PetscErrorCode KeptRows::Update(const std::vector<char> &kept, const std::vector<double> &d, double w) {
  PetscFunctionBeginUser;
  const std::size_t rows = fixed_.size();
  PetscCheck(kept.size() == rows && d.size() == rows, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
             "KeptRows::Update: %zu rows written, %zu fixed rows", kept.size(), rows);
  w_ = w;
  std::vector<char> covered(rows, 0);
  std::vector<RowGroup> all = given_;
  for (const RowGroup &g : given_)
    for (PetscInt r : g.rows) covered[r] = 1;
  for (std::size_t r = 0; r < rows; ++r)
    if (!covered[r]) all.push_back({{(PetscInt)r}, {1.0}, {1.0}});
  groups_.assign(all.size(), Group());
  x_diag_.assign(rows, 0.0);
  x_off_.clear();
  y_.assign(rows, 0.0);
  for (std::size_t k = 0; k < all.size(); ++k) {
    const RowGroup &g = all[k];
    const int n = (int)g.rows.size();
    Group &out = groups_[k];
    out.rows = g.rows;
    std::vector<double> pinv;
    PetscCheck(Inverse(n, g.p, pinv), PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "the columns of the multiplier rows from %" PetscInt_FMT " are not independent of each other",
               g.rows[0]);
    out.pinvt.assign(n * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) out.pinvt[i * n + j] = pinv[j * n + i];
    // F P^-T (F diagonal), and G = E + w F P^-T.
    std::vector<double> fp(n * n), gm(n * n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        fp[i * n + j] = d[g.rows[i]] * out.pinvt[i * n + j];
        gm[i * n + j] = (kept[g.rows[i]] ? g.q[i * n + j] : 0.0) + w * fp[i * n + j];
      }
    // G is singular only where a row's spring 1/|D| equals w (the caller keeps springs away from it: Friction's
    // kept_weight) or where a row is neither written nor given a diagonal entry.
    PetscCheck(Inverse(n, gm, out.ginv), PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "the multiplier rows from %" PetscInt_FMT " cannot be written on the kept factorisation's fixed rows "
               "(their map G is singular)", g.rows[0]);
    out.x.assign(n * n, 0.0);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double v = 0;
        for (int l = 0; l < n; ++l) v += out.ginv[i * n + l] * fp[l * n + j];
        out.x[i * n + j] = v;
        if (i == j) x_diag_[g.rows[i]] = v;
        else if (v != 0) x_off_.emplace_back(g.rows[i], g.rows[j], v);
      }
  }
  PetscFunctionReturn(0);
}

void KeptRows::Forward(PetscScalar *bm) {
  for (const Group &g : groups_) {
    const int n = (int)g.rows.size();
    for (int i = 0; i < n; ++i) {
      double v = 0;
      for (int j = 0; j < n; ++j) v += g.ginv[i * n + j] * bm[g.rows[j]];
      y_[g.rows[i]] = v;
    }
  }
  for (std::size_t r = 0; r < y_.size(); ++r) bm[r] = y_[r];
}

void KeptRows::Back(PetscScalar *xm) const {
  std::vector<double> t(3);
  for (const Group &g : groups_) {
    const int n = (int)g.rows.size();
    t.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
      double xmu = 0;
      for (int j = 0; j < n; ++j) xmu += g.x[i * n + j] * xm[g.rows[j]];
      t[i] = xm[g.rows[i]] + w_ * (y_[g.rows[i]] - xmu);
    }
    for (int i = 0; i < n; ++i) {
      double v = 0;
      for (int j = 0; j < n; ++j) v += g.pinvt[i * n + j] * t[j];
      xm[g.rows[i]] = v;
    }
  }
}

} // namespace signorini
