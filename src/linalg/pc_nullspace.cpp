// PCNULLSPACE: the null-space method on the active constraint rows as a preconditioner of the augmented saddle-point
// matrix (pc_nullspace.hpp). A type of our own needs PETSc's private PC structure, as every PC type does; PETSc has no
// preconditioner that eliminates constraint rows this way (PCFIELDSPLIT's Schur forms approximate the multipliers'
// Schur complement instead).
#include "signorini/linalg/pc_nullspace.hpp"

#include <petsc/private/pcimpl.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace signorini {

namespace {

constexpr int MAX_DIM = 3;

/// An owned multiplier row: its node's first dof (local index in the displacement block; -1: a row without
/// coefficients), its coefficients on the node's dofs, its active node (index into PcNullSpace::nodes; -1: the node
/// has no active row) and 1/D (0 on an active row).
struct Row {
  PetscInt dof0 = -1;
  std::array<PetscScalar, MAX_DIM> b{};
  PetscInt node = -1;
  PetscScalar dinv = 0;
};

/// The active rows of one owned node and the inverse of their Gram matrix G = B_n B_n^T (one to dim rows: a node on
/// one facet, an edge, a corner).
struct ActiveNode {
  PetscInt u0 = 0;                      ///< the node's first dof, local index in the displacement block
  int k = 0;                            ///< its active rows
  std::array<PetscInt, MAX_DIM> rows{}; ///< their local multiplier rows
  std::array<std::array<PetscScalar, MAX_DIM>, MAX_DIM> ginv{}; ///< G^-1
};

struct PcNullSpace {
  KSP inner = nullptr;            ///< the displacement block's solver (M)
  Mat R = nullptr;                ///< the rows of the displacement block at the active nodes' dofs, every column
  Vec un = nullptr, rn = nullptr; ///< R's row layout: u_N at those dofs, products with R
  Vec z = nullptr;                ///< displacement layout
  PetscInt dim = 0;
  std::vector<Row> rows;                      ///< every owned multiplier row
  std::vector<ActiveNode> nodes;              ///< in the order of their dofs (R's rows: dim per node)
  PetscInt active_rows = 0, active_nodes = 0; ///< over all ranks, for the view
  Mat fine = nullptr;                         ///< the eliminated operator of the block's finest level (FineLevel)
  Mat fine_A = nullptr;                       ///< the block it eliminates the active rows of (not owned)
  Vec fine_t = nullptr, fine_diag = nullptr;  ///< its work vector and diagonal
  std::vector<PetscScalar> fine_scale;        ///< per active node: the weight of its eliminated directions
  bool eliminated_fine = true;                ///< the finest level on the eliminated operator (PCNullSpaceSetFineLevel)
};

PcNullSpace *Data(PC pc) {
  return static_cast<PcNullSpace *>(pc->data);
}

/// Inverts the k x k Gram matrix g in place (Gauss-Jordan with partial pivoting); false when a pivot is not above
/// 1e-12 of the largest diagonal entry (two active rows of one node with the same direction).
bool InvertGram(int k, std::array<std::array<PetscScalar, MAX_DIM>, MAX_DIM> &g) {
  std::array<std::array<PetscScalar, 2 * MAX_DIM>, MAX_DIM> a{};
  PetscReal scale = 0;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j)
      a[i][j] = g[i][j];
    a[i][k + i] = 1;
    scale = std::max(scale, PetscAbsScalar(g[i][i]));
  }
  for (int c = 0; c < k; ++c) {
    int p = c;
    for (int i = c + 1; i < k; ++i)
      if (PetscAbsScalar(a[i][c]) > PetscAbsScalar(a[p][c])) p = i;
    if (!(PetscAbsScalar(a[p][c]) > 1e-12 * scale)) return false;
    std::swap(a[p], a[c]);
    const PetscScalar pivot = a[c][c];
    for (int j = 0; j < 2 * k; ++j)
      a[c][j] /= pivot;
    for (int i = 0; i < k; ++i)
      if (i != c) {
        const PetscScalar f = a[i][c];
        for (int j = 0; j < 2 * k; ++j)
          a[i][j] -= f * a[c][j];
      }
  }
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      g[i][j] = a[i][k + j];
  return true;
}

/// b_p . x for x the node's dofs.
PetscScalar Dot(const Row &r, PetscInt dim, const PetscScalar *x) {
  PetscScalar v = 0;
  for (PetscInt d = 0; d < dim; ++d)
    v += r.b[d] * x[d];
  return v;
}

/// c = G^-1 (B_n x) for x the node's dofs.
void NodeSolve(const PcNullSpace *s, const ActiveNode &n, const PetscScalar *x, PetscScalar *c) {
  std::array<PetscScalar, MAX_DIM> bx{};
  for (int i = 0; i < n.k; ++i)
    bx[i] = Dot(s->rows[n.rows[i]], s->dim, x);
  for (int i = 0; i < n.k; ++i) {
    c[i] = 0;
    for (int j = 0; j < n.k; ++j)
      c[i] += n.ginv[i][j] * bx[j];
  }
}

/// x += scale B_n^T G^-1 v for values v of the node's active rows (x: the node's dofs).
void AddLift(const PcNullSpace *s, const ActiveNode &n, const PetscScalar *v, PetscScalar scale, PetscScalar *x) {
  std::array<PetscScalar, MAX_DIM> c{};
  for (int a = 0; a < n.k; ++a)
    for (int b = 0; b < n.k; ++b)
      c[a] += n.ginv[a][b] * v[b];
  for (int a = 0; a < n.k; ++a)
    for (PetscInt d = 0; d < s->dim; ++d)
      x[d] += scale * s->rows[n.rows[a]].b[d] * c[a];
}

/// mu_I = D_I^-1 (g_I - B_I u) on the inactive rows (u: the displacement block's local values).
void InactiveMultipliers(const PcNullSpace *s, const PetscScalar *g, const PetscScalar *u, PetscScalar *mu) {
  for (std::size_t p = 0; p < s->rows.size(); ++p) {
    const Row &r = s->rows[p];
    if (r.dinv != 0.0) mu[p] = r.dinv * (g[p] - (r.dof0 >= 0 ? Dot(r, s->dim, u + r.dof0) : 0.0));
  }
}

/// x <- P x = x - B_A^T G^-1 B_A x: x in the null space of the active rows.
PetscErrorCode Project(const PcNullSpace *s, Vec x) {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(x, &a));
  for (const ActiveNode &n : s->nodes) {
    std::array<PetscScalar, MAX_DIM> c{};
    NodeSolve(s, n, a + n.u0, c.data());
    for (int i = 0; i < n.k; ++i)
      for (PetscInt d = 0; d < s->dim; ++d)
        a[n.u0 + d] -= s->rows[n.rows[i]].b[d] * c[i];
  }
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

/// The finest level's operator with the active rows eliminated: A_e x = P A P x + d_n (I - P) x, where P is the
/// projection onto the null space of the active rows and d_n, per active node, the mean of its diagonal entries in A
/// (the eliminated directions decoupled, with a weight of the block's scale).
PetscErrorCode MatMult_Eliminated(Mat M, Vec x, Vec y) {
  PcNullSpace *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(M, &s));
  PetscCall(VecCopy(x, s->fine_t));
  PetscCall(Project(s, s->fine_t));
  PetscCall(MatMult(s->fine_A, s->fine_t, y));
  PetscCall(Project(s, y));
  const PetscScalar *xa;
  PetscScalar *ya;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (std::size_t i = 0; i < s->nodes.size(); ++i) {
    const ActiveNode &n = s->nodes[i];
    std::array<PetscScalar, MAX_DIM> c{};
    NodeSolve(s, n, xa + n.u0, c.data());
    for (int a = 0; a < n.k; ++a)
      for (PetscInt d = 0; d < s->dim; ++d)
        ya[n.u0 + d] += s->fine_scale[i] * s->rows[n.rows[a]].b[d] * c[a];
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(0);
}

PetscErrorCode MatGetInfo_Eliminated(Mat M, MatInfoType flag, MatInfo *info) {
  PcNullSpace *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(M, &s));
  PetscCall(MatGetInfo(s->fine_A, flag, info)); // what it multiplies by (-contact_ksp_view)
  PetscFunctionReturn(0);
}

PetscErrorCode MatGetDiagonal_Eliminated(Mat M, Vec d) {
  PcNullSpace *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(M, &s));
  PetscCall(VecCopy(s->fine_diag, d));
  PetscFunctionReturn(0);
}

/// The finest level of the block's multigrid (nullptr: one level, or not a multigrid).
PetscErrorCode FineSmoother(PC pc, PC &ip, PetscInt &levels, KSP &smoother) {
  PcNullSpace *s = Data(pc);
  PetscBool mg;
  PetscFunctionBeginUser;
  smoother = nullptr;
  levels = 0;
  PetscCall(KSPGetPC(s->inner, &ip));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ip, &mg, PCGAMG, PCMG, ""));
  if (mg && ip->setupcalled) PetscCall(PCMGGetLevels(ip, &levels));
  if (levels >= 2) PetscCall(PCMGGetSmoother(ip, levels - 1, &smoother));
  PetscFunctionReturn(0);
}

/// The operator of the finest level: its smoother's and its residual's.
PetscErrorCode SetFineOperator(PC ip, PetscInt levels, KSP smoother, Mat op) {
  PetscFunctionBeginUser;
  PetscCall(KSPSetOperators(smoother, op, op));
  PetscCall(PCMGSetResidual(ip, levels - 1, PCMGResidualDefault, op));
  PetscFunctionReturn(0);
}

/// The block's multigrid smooths its finest level on the operator with the active rows eliminated (MatMult_Eliminated),
/// the one the null-space method solves, instead of the augmented block A, whose springs on the active rows only
/// approximate the elimination; the coarse levels keep A's Galerkin products (and the hierarchy update). PETSc's
/// multigrid takes any operator per level (PCMGSetResidual, the smoother's KSPSetOperators); GAMG's own set-up reads
/// the finest operator from that smoother, so it gets the block back first. CG iterations of the
/// contact solve, one rank (docs/performance.md, twenty-eighth session): the octant of options/hertz3d.yml at 1.07M
/// dofs 40 against 45, the 824k-dof cube under a sphere 25 against 33, the 4.1M-dof one 31 against 42 (2 ranks), the
/// same states. By default the linear material's only (-contact_nullspace_fine_level, SaddlePointSystem).
/// eliminate false: the block itself on that level, as before the block's multigrid is set up again (GAMG takes the
/// operator of a finer level from its smoother for the Galerkin products).
PetscErrorCode FineLevel(PC pc, Mat A, bool eliminate) {
  PcNullSpace *s = Data(pc);
  PC ip;
  PetscInt levels;
  KSP smoother;
  PetscFunctionBeginUser;
  if (!s->inner) PetscFunctionReturn(0);
  PetscCall(FineSmoother(pc, ip, levels, smoother));
  if (!smoother) PetscFunctionReturn(0);
  if (!eliminate || !s->eliminated_fine || s->active_rows == 0) {
    // The block itself (with nothing to eliminate, an elastic solve's path unchanged).
    Mat op;
    PetscCall(KSPGetOperators(smoother, &op, nullptr));
    if (op != A) PetscCall(SetFineOperator(ip, levels, smoother, A));
    PetscFunctionReturn(0);
  }
  if (!s->fine) {
    PetscInt m, n, M, N;
    PetscCall(MatGetLocalSize(A, &m, &n));
    PetscCall(MatGetSize(A, &M, &N));
    PetscCall(MatCreateShell(PetscObjectComm((PetscObject)pc), m, n, M, N, s, &s->fine));
    PetscCall(MatShellSetOperation(s->fine, MATOP_MULT, (void (*)(void))MatMult_Eliminated));
    PetscCall(MatShellSetOperation(s->fine, MATOP_GET_DIAGONAL, (void (*)(void))MatGetDiagonal_Eliminated));
    PetscCall(MatShellSetOperation(s->fine, MATOP_GETINFO, (void (*)(void))MatGetInfo_Eliminated));
    PetscCall(MatCreateVecs(A, &s->fine_t, &s->fine_diag));
  }
  s->fine_A = A;
  // The diagonal: A's, and at an active node that of P K_n P + d_n (I - P) from the node's block K_n of A.
  PetscCall(MatGetDiagonal(A, s->fine_diag));
  PetscInt ustart;
  PetscCall(MatGetOwnershipRange(A, &ustart, nullptr));
  PetscScalar *dg;
  PetscCall(VecGetArray(s->fine_diag, &dg));
  const PetscInt dim = s->dim;
  s->fine_scale.assign(s->nodes.size(), 0.0);
  for (std::size_t i = 0; i < s->nodes.size(); ++i) {
    const ActiveNode &nd = s->nodes[i];
    std::array<PetscInt, MAX_DIM> idx{};
    for (PetscInt d = 0; d < dim; ++d)
      idx[d] = ustart + nd.u0 + d;
    std::array<PetscScalar, MAX_DIM * MAX_DIM> k{};
    PetscCall(MatGetValues(A, dim, idx.data(), dim, idx.data(), k.data()));
    // P = I - B_n^T G^-1 B_n, column by column
    std::array<std::array<PetscScalar, MAX_DIM>, MAX_DIM> P{};
    for (PetscInt j = 0; j < dim; ++j) {
      std::array<PetscScalar, MAX_DIM> e{};
      e[j] = 1;
      std::array<PetscScalar, MAX_DIM> c{};
      NodeSolve(s, nd, e.data(), c.data());
      for (PetscInt d = 0; d < dim; ++d) {
        P[d][j] = e[d];
        for (int a = 0; a < nd.k; ++a)
          P[d][j] -= s->rows[nd.rows[a]].b[d] * c[a];
      }
    }
    PetscScalar mean = 0;
    for (PetscInt d = 0; d < dim; ++d)
      mean += k[d * dim + d] / dim;
    s->fine_scale[i] = mean;
    for (PetscInt d = 0; d < dim; ++d) {
      PetscScalar v = 0;
      for (PetscInt a = 0; a < dim; ++a)
        for (PetscInt b = 0; b < dim; ++b)
          v += P[d][a] * k[a * dim + b] * P[b][d];
      dg[nd.u0 + d] = v + mean * (1.0 - P[d][d]);
    }
  }
  PetscCall(VecRestoreArray(s->fine_diag, &dg));
  PetscCall(PetscObjectStateIncrease((PetscObject)s->fine));
  PetscCall(SetFineOperator(ip, levels, smoother, s->fine));
  PetscFunctionReturn(0);
}

PetscErrorCode Blocks(PC pc, Mat &A, Mat &B, Mat &D, IS is[2]) {
  PetscBool nest;
  PetscInt nr, nc;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc->pmat, MATNEST, &nest));
  PetscCheck(nest, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": expected the saddle-point matrix as a MATNEST of its blocks");
  PetscCall(MatNestGetSize(pc->pmat, &nr, &nc));
  PetscCheck(nr == 2 && nc == 2, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": expected a 2 x 2 MATNEST, got %" PetscInt_FMT " x %" PetscInt_FMT, nr,
             nc);
  PetscCall(MatNestGetSubMat(pc->pmat, 0, 0, &A));
  PetscCall(MatNestGetSubMat(pc->pmat, 1, 0, &B));
  PetscCall(MatNestGetSubMat(pc->pmat, 1, 1, &D));
  PetscCall(MatNestGetISs(pc->pmat, is, nullptr));
  PetscFunctionReturn(0);
}

// Every row lies on the dofs of one node of this rank (Analyse checks it): the products with B and B^T are loops over
// the owned rows, and only the products with R (the displacement block's rows at the active nodes) communicate.
PetscErrorCode PCApply_NullSpace(PC pc, Vec x, Vec y) {
  PcNullSpace *s = Data(pc);
  Mat A, B, D;
  IS is[2];
  Vec f, g, yu, yl;
  const PetscInt dim = s->dim;
  PetscFunctionBeginUser;
  PetscCall(Blocks(pc, A, B, D, is));
  PetscCall(VecGetSubVector(x, is[0], &f));
  PetscCall(VecGetSubVector(x, is[1], &g));
  PetscCall(VecGetSubVector(y, is[0], &yu));
  PetscCall(VecGetSubVector(y, is[1], &yl));
  const PetscScalar *ga;
  PetscScalar *mu, *un;
  PetscCall(VecGetArrayRead(g, &ga));
  PetscCall(VecGetArray(yl, &mu));
  // u_N = B_A^T G^-1 g_A node by node (negated in un: z = f - R^T u_N below)
  PetscCall(VecGetArray(s->un, &un));
  for (std::size_t i = 0; i < s->nodes.size(); ++i) {
    const ActiveNode &n = s->nodes[i];
    std::array<PetscScalar, MAX_DIM> v{};
    for (int a = 0; a < n.k; ++a)
      v[a] = ga[n.rows[a]];
    for (PetscInt d = 0; d < dim; ++d)
      un[i * dim + d] = 0;
    AddLift(s, n, v.data(), -1.0, un + i * dim);
  }
  // the inactive rows' D_I^-1 (g_I - B_I u_N) into mu (overwritten below)
  for (std::size_t p = 0; p < s->rows.size(); ++p) {
    const Row &r = s->rows[p];
    mu[p] = r.dinv * (ga[p] + (r.node >= 0 ? Dot(r, dim, un + r.node * dim) : 0.0));
  }
  PetscCall(VecRestoreArray(s->un, &un));
  // z = P (f' - K' u_N) = P (f - R^T u_N - B_I^T D_I^-1 (g_I - B_I u_N))
  PetscCall(MatMultTransposeAdd(s->R, s->un, f, s->z));
  PetscScalar *za;
  PetscCall(VecGetArray(s->z, &za));
  for (std::size_t p = 0; p < s->rows.size(); ++p) {
    const Row &r = s->rows[p];
    if (r.dof0 < 0 || mu[p] == 0.0) continue;
    for (PetscInt d = 0; d < dim; ++d)
      za[r.dof0 + d] -= r.b[d] * mu[p];
  }
  PetscCall(VecRestoreArray(s->z, &za));
  PetscCall(Project(s, s->z));
  // u = u_N + P M z
  PetscCall(KSPSolve(s->inner, s->z, yu));
  PetscCall(KSPCheckSolve(s->inner, pc, yu));
  PetscCall(Project(s, yu));
  PetscScalar *ua;
  const PetscScalar *uan;
  PetscCall(VecGetArray(yu, &ua));
  PetscCall(VecGetArrayRead(s->un, &uan));
  for (std::size_t i = 0; i < s->nodes.size(); ++i)
    for (PetscInt d = 0; d < dim; ++d)
      ua[s->nodes[i].u0 + d] -= uan[i * dim + d];
  PetscCall(VecRestoreArrayRead(s->un, &uan));
  // mu_I = D_I^-1 (g_I - B_I u) (the active rows' below)
  InactiveMultipliers(s, ga, ua, mu);
  PetscCall(VecRestoreArray(yu, &ua));
  // mu_A = G^-1 B_A (f' - K' u) at the active nodes: f_N - R u - (B_I^T mu_I)_N
  PetscCall(MatMult(s->R, yu, s->rn));
  PetscScalar *rn;
  const PetscScalar *fa;
  PetscCall(VecGetArray(s->rn, &rn));
  PetscCall(VecGetArrayRead(f, &fa));
  for (std::size_t i = 0; i < s->nodes.size(); ++i)
    for (PetscInt d = 0; d < dim; ++d)
      rn[i * dim + d] = fa[s->nodes[i].u0 + d] - rn[i * dim + d];
  PetscCall(VecRestoreArrayRead(f, &fa));
  for (std::size_t p = 0; p < s->rows.size(); ++p) {
    const Row &r = s->rows[p];
    if (r.node < 0 || r.dinv == 0.0) continue;
    for (PetscInt d = 0; d < dim; ++d)
      rn[r.node * dim + d] -= r.b[d] * mu[p];
  }
  for (std::size_t i = 0; i < s->nodes.size(); ++i) {
    const ActiveNode &n = s->nodes[i];
    std::array<PetscScalar, MAX_DIM> c{};
    NodeSolve(s, n, rn + i * dim, c.data());
    for (int a = 0; a < n.k; ++a)
      mu[n.rows[a]] = c[a];
  }
  PetscCall(VecRestoreArray(s->rn, &rn));
  PetscCall(VecRestoreArray(yl, &mu));
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(VecRestoreSubVector(y, is[1], &yl));
  PetscCall(VecRestoreSubVector(y, is[0], &yu));
  PetscCall(VecRestoreSubVector(x, is[1], &g));
  PetscCall(VecRestoreSubVector(x, is[0], &f));
  PetscFunctionReturn(0);
}

// A Krylov start that satisfies every multiplier row: each active node's dofs moved by B_n^T G^-1 of its rows'
// violation, each inactive row's multiplier D_I^-1 (g_I - B_I u). The residual's multiplier rows are then zero, and so
// are those of A p for every direction p = P^-1 r (its active rows lie in the rows' null space, its inactive
// multipliers follow its displacements), so that p^T A p = p_u^T K' p_u > 0 and the preconditioner is P M P on the
// displacements, which is symmetric: CG on the saddle-point system is CG on the constrained displacements (a
// constraint preconditioner's projected CG). Without it CG met a negative curvature (DIVERGED_INDEFINITE_MAT) after
// a set change left inactive rows violated (the octant of options/hertz3d.yml, its third solve).
PetscErrorCode PCPreSolve_NullSpace(PC pc, KSP ksp, Vec b, Vec x) {
  PcNullSpace *s = Data(pc);
  Mat A, B, D;
  IS is[2];
  Vec xu, xl, g;
  PetscBool nonzero;
  PetscFunctionBeginUser;
  // KSPSolve calls this before it sets the PC up for a changed operator (in its first application): the active set
  // read here must be the operator's.
  PetscCall(PCSetUp(pc));
  PetscCall(KSPGetInitialGuessNonzero(ksp, &nonzero));
  if (!nonzero) PetscCall(VecZeroEntries(x)); // the start is made here; the KSP takes it as given
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
  PetscCall(Blocks(pc, A, B, D, is));
  PetscCall(VecGetSubVector(x, is[0], &xu));
  PetscCall(VecGetSubVector(x, is[1], &xl));
  PetscCall(VecGetSubVector(b, is[1], &g));
  PetscScalar *u, *mu;
  const PetscScalar *ga;
  PetscCall(VecGetArray(xu, &u));
  PetscCall(VecGetArray(xl, &mu));
  PetscCall(VecGetArrayRead(g, &ga));
  for (const ActiveNode &n : s->nodes) {
    std::array<PetscScalar, MAX_DIM> v{};
    for (int a = 0; a < n.k; ++a)
      v[a] = ga[n.rows[a]] - Dot(s->rows[n.rows[a]], s->dim, u + n.u0);
    AddLift(s, n, v.data(), 1.0, u + n.u0);
  }
  InactiveMultipliers(s, ga, u, mu);
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(VecRestoreArray(xl, &mu));
  PetscCall(VecRestoreArray(xu, &u));
  PetscCall(VecRestoreSubVector(b, is[1], &g));
  PetscCall(VecRestoreSubVector(x, is[1], &xl));
  PetscCall(VecRestoreSubVector(x, is[0], &xu));
  PetscFunctionReturn(0);
}

/// The owned rows of B with 1/D, the active nodes with their Gram inverses, and R.
PetscErrorCode Analyse(PC pc, Mat A, Mat B, Mat D) {
  PcNullSpace *s = Data(pc);
  MPI_Comm comm = PetscObjectComm((PetscObject)pc);
  PetscInt ustart, uend, lstart, lend;
  Vec diag;
  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(A, &ustart, &uend));
  PetscCall(MatGetOwnershipRange(B, &lstart, &lend));
  PetscCall(MatCreateVecs(D, &diag, nullptr));
  PetscCall(MatGetDiagonal(D, diag));
  const PetscScalar *dv;
  PetscCall(VecGetArrayRead(diag, &dv));
  s->rows.assign(lend - lstart, Row());
  std::map<PetscInt, ActiveNode> at; // by the node's first dof: the order of R's rows
  PetscInt bad_row = -1, bad_node = -1;
  for (PetscInt p = 0; p < lend - lstart && bad_row < 0 && bad_node < 0; ++p) {
    Row &r = s->rows[p];
    PetscInt ncols;
    const PetscInt *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(B, lstart + p, &ncols, &cols, &vals));
    PetscInt node = -1;
    for (PetscInt j = 0; j < ncols; ++j) {
      if (vals[j] == 0.0) continue;
      const PetscInt n = cols[j] / s->dim;
      if (node < 0) node = n;
      if (n != node || cols[j] < ustart || cols[j] >= uend)
        bad_row = lstart + p;
      else
        r.b[cols[j] - n * s->dim] = vals[j];
    }
    PetscCall(MatRestoreRow(B, lstart + p, &ncols, &cols, &vals));
    if (node >= 0) r.dof0 = node * s->dim - ustart;
    r.dinv = dv[p] != 0.0 ? 1.0 / dv[p] : 0.0;
    if (dv[p] != 0.0 || node < 0) continue; // inactive, or an active row without coefficients (it holds nothing)
    ActiveNode &a = at[r.dof0];
    a.u0 = r.dof0;
    if (a.k == s->dim)
      bad_node = node;
    else
      a.rows[a.k++] = p;
  }
  PetscCall(VecRestoreArrayRead(diag, &dv));
  PetscCall(VecDestroy(&diag));
  // Every rank must know about a row it cannot eliminate: the same error on all of them.
  PetscInt bad[2] = {bad_row, bad_node};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, bad, 2, MPIU_INT, MPI_MAX, comm));
  PetscCheck(bad[0] < 0, comm, PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": the multiplier row %" PetscInt_FMT " couples the dofs of several "
             "nodes, or of a node on another rank; expected pairs of one node each (rigid obstacles): a contact "
             "between bodies takes -contact_pc_type fieldsplit (options/solver/fieldsplit_gamg.yml)",
             bad[0]);
  PetscCheck(bad[1] < 0, comm, PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": node %" PetscInt_FMT " has more active rows than dofs; expected at "
             "most %" PetscInt_FMT,
             bad[1], s->dim);
  s->nodes.clear();
  std::map<PetscInt, PetscInt> index; // node's first dof -> its index in nodes
  PetscInt rows = 0, singular = -1;
  for (auto &[first, a] : at) {
    std::array<std::array<PetscScalar, MAX_DIM>, MAX_DIM> g{};
    for (int i = 0; i < a.k; ++i)
      for (int j = 0; j < a.k; ++j)
        g[i][j] = Dot(s->rows[a.rows[i]], s->dim, s->rows[a.rows[j]].b.data());
    if (!InvertGram(a.k, g) && singular < 0) singular = (ustart + first) / s->dim;
    a.ginv = g;
    rows += a.k;
    index[first] = (PetscInt)s->nodes.size();
    s->nodes.push_back(a);
  }
  for (Row &r : s->rows)
    if (r.dof0 >= 0 && index.count(r.dof0)) r.node = index[r.dof0];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &singular, 1, MPIU_INT, MPI_MAX, comm));
  PetscCheck(singular < 0, comm, PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": the active rows of node %" PetscInt_FMT " are linearly dependent; "
             "expected independent directions (one row per direction)",
             singular);
  PetscInt counts[2] = {rows, (PetscInt)s->nodes.size()};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm));
  s->active_rows = counts[0], s->active_nodes = counts[1];
  // R: the displacement block's rows at those dofs, every column (the columns' layout is A's).
  std::vector<PetscInt> global;
  for (const ActiveNode &n : s->nodes)
    for (PetscInt d = 0; d < s->dim; ++d)
      global.push_back(ustart + n.u0 + d);
  IS isrow, iscol;
  PetscCall(ISCreateGeneral(comm, (PetscInt)global.size(), global.data(), PETSC_COPY_VALUES, &isrow));
  PetscCall(ISCreateStride(comm, uend - ustart, ustart, 1, &iscol));
  PetscCall(MatDestroy(&s->R));
  PetscCall(MatCreateSubMatrix(A, isrow, iscol, MAT_INITIAL_MATRIX, &s->R));
  PetscCall(ISDestroy(&isrow));
  PetscCall(ISDestroy(&iscol));
  PetscCall(VecDestroy(&s->un));
  PetscCall(VecDestroy(&s->rn));
  PetscCall(MatCreateVecs(s->R, nullptr, &s->un));
  PetscCall(VecDuplicate(s->un, &s->rn));
  PetscFunctionReturn(0);
}

/// The displacement block's solver: one GAMG V-cycle unless the options say otherwise.
PetscErrorCode CreateInner(PC pc) {
  PcNullSpace *s = Data(pc);
  const char *prefix;
  PC ipc;
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)pc), &s->inner));
  PetscCall(PetscObjectIncrementTabLevel((PetscObject)s->inner, (PetscObject)pc, 1));
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(KSPSetOptionsPrefix(s->inner, prefix));
  PetscCall(KSPAppendOptionsPrefix(s->inner, "fieldsplit_u_"));
  PetscCall(KSPSetType(s->inner, KSPPREONLY));
  PetscCall(KSPGetPC(s->inner, &ipc));
  PetscCall(PCSetType(ipc, PCGAMG));
  PetscCall(KSPSetFromOptions(s->inner));
  PetscFunctionReturn(0);
}

PetscErrorCode PCSetFromOptions_NullSpace(PC pc, PetscOptionItems *PetscOptionsObject) {
  PetscFunctionBeginUser;
  // Under -help the block's solver lists its options here; a run creates it at the first set-up, when the defaults
  // that SaddlePointSystem adds for it (SetGamgDefaults3d) are in the options.
  if (PetscOptionsObject->printhelp && !Data(pc)->inner) PetscCall(CreateInner(pc));
  PetscFunctionReturn(0);
}

PetscErrorCode PCSetUp_NullSpace(PC pc) {
  PcNullSpace *s = Data(pc);
  MPI_Comm comm = PetscObjectComm((PetscObject)pc);
  Mat A, B, D;
  IS is[2];
  PetscFunctionBeginUser;
  PetscCall(Blocks(pc, A, B, D, is));
  PetscInt bs;
  PetscCall(MatGetBlockSize(A, &bs));
  PetscCheck(bs >= 1 && bs <= MAX_DIM, comm, PETSC_ERR_ARG_WRONG,
             "-contact_pc_type " PCNULLSPACE ": the displacement block's block size %" PetscInt_FMT
             " is not the dimension (1 to 3)",
             bs);
  s->dim = bs;
  if (!s->inner) PetscCall(CreateInner(pc));
  if (!s->z) PetscCall(MatCreateVecs(A, &s->z, nullptr));
  // The rigid-body modes that a fieldsplit gives its "u" block, from the index set (SaddlePointSystem).
  MatNullSpace near;
  PetscCall(PetscObjectQuery((PetscObject)is[0], "nearnullspace", (PetscObject *)&near));
  if (near) PetscCall(MatSetNearNullSpace(A, near));
  PetscCall(Analyse(pc, A, B, D));
  PetscCall(FineLevel(pc, A, false));
  PetscCall(KSPSetOperators(s->inner, A, A));
  PetscCall(KSPSetUp(s->inner));
  PetscCall(FineLevel(pc, A, true));
  PetscFunctionReturn(0);
}

PetscErrorCode PCView_NullSpace(PC pc, PetscViewer viewer) {
  PcNullSpace *s = Data(pc);
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "null-space method on the active rows (%" PetscInt_FMT " rows on %" PetscInt_FMT
                                   " nodes): u_N from the constraints, u_F by the displacement block's solver "
                                   "between projections onto the rows' null space, multipliers from the residual\n",
                                   s->active_rows, s->active_nodes));
  if (s->fine && s->eliminated_fine && s->active_rows > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer, "finest level smoothed on the operator with the active rows eliminated "
                                             "(-contact_nullspace_fine_level): the finest level's matrix below is "
                                             "a shell that multiplies by the block between the projections (its "
                                             "nonzeros are the block's)\n"));
  if (s->inner) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "displacement block's solver:\n"));
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(KSPView(s->inner, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PCReset_NullSpace(PC pc) {
  PcNullSpace *s = Data(pc);
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&s->inner));
  PetscCall(MatDestroy(&s->R));
  PetscCall(MatDestroy(&s->fine));
  for (Vec *w : {&s->un, &s->rn, &s->z, &s->fine_t, &s->fine_diag})
    PetscCall(VecDestroy(w));
  s->nodes.clear();
  s->rows.clear();
  PetscFunctionReturn(0);
}

PetscErrorCode PCDestroy_NullSpace(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(PCReset_NullSpace(pc));
  delete Data(pc);
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode PCCreate_NullSpace(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new PcNullSpace();
  pc->ops->apply = PCApply_NullSpace;
  pc->ops->setup = PCSetUp_NullSpace;
  pc->ops->setfromoptions = PCSetFromOptions_NullSpace;
  pc->ops->presolve = PCPreSolve_NullSpace;
  pc->ops->view = PCView_NullSpace;
  pc->ops->reset = PCReset_NullSpace;
  pc->ops->destroy = PCDestroy_NullSpace;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode PCNullSpaceRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(PCRegister(PCNULLSPACE, PCCreate_NullSpace));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode PCNullSpaceSetFineLevel(PC pc, bool eliminated) {
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCNULLSPACE, &is));
  if (is) Data(pc)->eliminated_fine = eliminated;
  PetscFunctionReturn(0);
}

PetscErrorCode PCNullSpaceGetSubKSP(PC pc, KSP *ksp) {
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCNULLSPACE, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG, "the PC is not of type " PCNULLSPACE);
  *ksp = Data(pc)->inner;
  PetscFunctionReturn(0);
}

} // namespace signorini
