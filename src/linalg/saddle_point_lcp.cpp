// The saddle-point system's contact problem in the multipliers: the linear complementarity problem of ContactLcp,
// set up and solved on rank 0 from the kept factorisation's Schur complement.
#include "signorini/linalg/saddle_point.hpp"

#include "signorini/core/errors.hpp"

#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace signorini {

namespace {

/// ContactLcp's problem with the spring eps: q = g + V diag(inv) V^T c and M = W W^T, W = V diag(sqrt(eta inv)),
/// inv = 1 / (1 + eps - r eta) (H = V diag(eta) V^T, h holds V; P + eps I = V diag(1 + eps - r eta) V^T commutes with
/// H), proj = V^T c; row a of M and q is row perm[a] of H.
[[nodiscard]] PetscErrorCode RegularisedLcp(const std::vector<double> &h, const std::vector<double> &eta,
                                            const std::vector<double> &proj, const std::vector<PetscScalar> &g,
                                            const std::vector<PetscInt> &perm, double aug, double eps,
                                            std::vector<double> &M, std::vector<double> &q) {
  const PetscInt m = (PetscInt)perm.size();
  PetscFunctionBeginUser;
  std::vector<double> inv(m), W((std::size_t)m * m);
  M.assign((std::size_t)m * m, 0.0);
  q.assign(m, 0.0);
  for (PetscInt k = 0; k < m; ++k) inv[k] = 1 / std::max(1 + eps - aug * eta[k], eps);
  for (PetscInt a = 0; a < m; ++a) {
    const PetscInt i = perm[a];
    double pc = 0;
    for (PetscInt k = 0; k < m; ++k) {
      pc += h[i + k * m] * inv[k] * proj[k];
      W[a + k * m] = h[i + k * m] * std::sqrt(eta[k] * inv[k]);
    }
    q[a] = g[i] + pc;
  }
  if (m > 0) {
    PetscBLASInt n;
    const double one = 1, zero = 0;
    PetscCall(PetscBLASIntCast(m, &n));
    BLASgemm_("N", "T", &n, &n, &n, &one, W.data(), &n, W.data(), &n, &zero, M.data(), &n);
  }
  PetscFunctionReturn(0);
}

/// The solution of the problem (M, q) whose active set is that of z (z_a > 0): M_SS x_S = -q_S, x = 0 elsewhere. ok:
/// M_SS is not singular.
[[nodiscard]] PetscErrorCode SolveOnSet(const std::vector<double> &M, const std::vector<double> &q,
                                        const std::vector<double> &z, std::vector<double> &x, bool &ok) {
  const PetscInt m = (PetscInt)q.size();
  std::vector<PetscInt> set;
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < m; ++a)
    if (z[a] > 0) set.push_back(a);
  const PetscInt ns = (PetscInt)set.size();
  std::vector<double> a((std::size_t)ns * ns), b(ns);
  for (PetscInt i = 0; i < ns; ++i) {
    b[i] = -q[set[i]];
    for (PetscInt j = 0; j < ns; ++j) a[i + j * ns] = M[set[i] + set[j] * m];
  }
  x.assign(m, 0.0);
  ok = true;
  if (ns > 0) {
    PetscBLASInt n, one = 1, info;
    std::vector<PetscBLASInt> ipiv(ns);
    PetscCall(PetscBLASIntCast(ns, &n));
    LAPACKgesv_(&n, &one, a.data(), &n, ipiv.data(), b.data(), &n, &info);
    ok = info == 0;
  }
  for (PetscInt i = 0; i < ns && ok; ++i) x[set[i]] = b[i];
  PetscFunctionReturn(0);
}

/// ContactLcp's problem on rank 0: its data, H (h, then V of H = V diag(eta) V^T), c, the gaps g and the keys of the
/// rows, r; its work, V^T c (proj), the rigid motions (rigid: the k with 1 - r eta_k <= LCP_RIGID_TOL), the rows in
/// key order (perm); and its results.
struct ReducedContact {
  std::vector<double> h, condensed;
  std::vector<PetscScalar> g, order;
  double aug = 0;
  std::vector<double> eta, proj;
  std::vector<PetscInt> rigid, perm;
  LcpStatus status = LcpStatus::SOLVED;
  int pivots = 0;
  double unbalanced = 0;
  std::vector<PetscScalar> z; ///< 1 on the rows of the solution's active set, 0 elsewhere
};

/// H = V diag(eta) V^T (eta clamped at 0), V^T c, the rigid motions and the key order of ReducedContact.
[[nodiscard]] PetscErrorCode Decompose(ReducedContact &p) {
  const PetscInt m = (PetscInt)p.g.size();
  PetscFunctionBeginUser;
  p.eta.assign(m, 0.0);
  if (m > 0) {
    PetscBLASInt n, lwork = -1, info;
    double query;
    PetscCall(PetscBLASIntCast(m, &n));
    LAPACKsyev_("V", "L", &n, p.h.data(), &n, p.eta.data(), &query, &lwork, &info);
    lwork = std::max<PetscBLASInt>(1, (PetscBLASInt)query);
    std::vector<double> work(lwork);
    LAPACKsyev_("V", "L", &n, p.h.data(), &n, p.eta.data(), work.data(), &lwork, &info);
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "LAPACK syev of the multipliers' reduced operator failed: info %d", (int)info);
  }
  p.proj.assign(m, 0.0);
  p.rigid.clear();
  for (PetscInt k = 0; k < m; ++k) {
    p.eta[k] = std::max(p.eta[k], 0.0);
    for (PetscInt i = 0; i < m; ++i) p.proj[k] -= p.h[i + k * m] * p.condensed[i]; // V^T c, c = -A21 A11^-1 b_u
    if (1 - p.aug * p.eta[k] <= SaddlePointSystem::LCP_RIGID_TOL) p.rigid.push_back(k);
  }
  p.perm.resize(m);
  for (PetscInt i = 0; i < m; ++i) p.perm[i] = i;
  std::sort(p.perm.begin(), p.perm.end(), [&](PetscInt a, PetscInt b) { return p.order[a] < p.order[b]; });
  PetscFunctionReturn(0);
}

/// The verdict on a solution z (in key order) that leaves rigid motions: p.unbalanced, or p.status INACCURATE when
/// the second solve on its set fails.
[[nodiscard]] PetscErrorCode RigidVerdict(ReducedContact &p, const std::vector<double> &z) {
  const PetscInt m = (PetscInt)p.perm.size();
  const double eps = SaddlePointSystem::LCP_REGULARISATION;
  PetscFunctionBeginUser;
  // The verdict, independent of the spring's stiffness eps. A rigid motion rho that only contact holds is a null
  // vector v = B rho of P (H v = v / r): along it, V^T lambda is the work of the contact forces and r V^T c that of
  // the load, their sum f(eps) the force that the spring carries instead of the obstacles, r eps times the rigid
  // travel t(eps). On the solution's active set, f(eps) = f0 + eps f1 + O(eps^2): a body that the pairs hold travels
  // a finite distance as eps -> 0 (f0 = 0, and f = r eps t grows with E / load and with refinement, 0.004 of the
  // load for a block held between a floor and a wall), a free one as far as the spring lets it (f0, the part of the
  // load that no contact forces on these pairs balance, 0.009 to 1 in the tests). f0 by Richardson extrapolation from
  // a second solve on the same set with 100 eps; its size, and the load's, are norms of projections onto the rigid
  // eigenspace, which do not depend on the basis LAPACK picks in it.
  const double eps2 = 100 * eps;
  std::vector<double> M2, q2, z2;
  PetscCall(RegularisedLcp(p.h, p.eta, p.proj, p.g, p.perm, p.aug, eps2, M2, q2));
  bool ok;
  PetscCall(SolveOnSet(M2, q2, z, z2, ok));
  if (!ok) {
    p.status = LcpStatus::INACCURATE;
    PetscFunctionReturn(0);
  }
  double f0 = 0, work = 0, load = 0;
  for (PetscInt k : p.rigid) {
    double w1 = 0, w2 = 0;
    for (PetscInt a = 0; a < m; ++a) w1 += p.h[p.perm[a] + k * m] * z[a], w2 += p.h[p.perm[a] + k * m] * z2[a];
    const double f1 = w1 + p.aug * p.proj[k], f2 = w2 + p.aug * p.proj[k];
    const double fk = (eps2 * f1 - eps * f2) / (eps2 - eps);
    f0 += fk * fk, work += w1 * w1, load += p.aug * p.proj[k] * p.aug * p.proj[k];
  }
  const double scale = std::sqrt(std::max(work, load));
  p.unbalanced = scale > 0 ? std::sqrt(f0) / scale : 0.0;
  PetscFunctionReturn(0);
}

/// Solves ContactLcp's problem p: Lemke's method on the regularised problem in key order, then the verdict on the
/// rigid motions. Rank 0 (RunOnRoot).
[[nodiscard]] PetscErrorCode SolveReducedContact(ReducedContact &p) {
  const PetscInt m = (PetscInt)p.g.size();
  std::vector<double> M, q, z, w;
  PetscFunctionBeginUser;
  PetscCall(Decompose(p));
  PetscCall(RegularisedLcp(p.h, p.eta, p.proj, p.g, p.perm, p.aug, SaddlePointSystem::LCP_REGULARISATION, M, q));
  p.status = SolveLcp((int)m, M, q, z, w, &p.pivots);
  p.z.assign(m, 0.0);
  for (PetscInt a = 0; a < m; ++a) p.z[p.perm[a]] = z[a] > 0 ? 1.0 : 0.0;
  p.unbalanced = 0;
  if (p.status == LcpStatus::SOLVED && !p.rigid.empty()) PetscCall(RigidVerdict(p, z));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SaddlePointSystem::ContactLcp(const std::vector<double> &gap, const std::vector<double> &key,
                                             std::vector<char> &active, LcpStatus &status, int &pivots,
                                             double &unbalanced) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PetscFunctionBeginUser;
  PetscCheck(reuse_ && factored_ && constant_k_ && mumps_schur_.Condensed(), comm, PETSC_ERR_ORDER,
             "the contact problem in the multipliers needs the kept factorisation of a constant K and a Condense");
  // The problem on rank 0 (the other ranks' parts are empty).
  ReducedContact lcp;
  lcp.aug = aug_;
  PetscCall(ToRoot(gap, lcp.g));
  PetscCall(ToRoot(key, lcp.order));
  mumps_schur_.ReducedOperator(lcp.h, lcp.condensed);
  PetscCall(RunOnRoot(comm, [&] { return SolveReducedContact(lcp); }));
  int code[2] = {(int)lcp.status, lcp.pivots};
  PetscCallMPI(MPI_Bcast(code, 2, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&lcp.unbalanced, 1, MPI_DOUBLE, 0, comm));
  status = (LcpStatus)code[0];
  pivots = code[1];
  unbalanced = lcp.unbalanced;
  std::vector<double> owned;
  PetscCall(FromRoot(lcp.z, owned));
  active.assign(owned.size(), 0);
  for (std::size_t p = 0; p < owned.size(); ++p) active[p] = owned[p] > 0.5;
  PetscFunctionReturn(0);
}

} // namespace signorini
