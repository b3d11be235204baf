// GAMG's first Galerkin product P^T A P on several ranks in a rank's share of the memory (issue 37, item 5).
//
// Why not PETSc's own: PETSc 3.18's products of MPIAIJ matrices (MatPtAP's default, `scalable` and `nonscalable`)
// form A P of the local rows whole before multiplying by P^T: on the 4.1M-dof hexahedral cube on 2 ranks each rank's
// resident memory went from 4.4 GB before the product to 7.7 GB (the whole one-rank run: 8.1 GB); `allatonce` keeps
// no A P but took 5 times as long (docs/performance.md). One rank's sequential product keeps one row of A P at a time,
// so each rank multiplies its own rows with that product, in CHUNKS chunks: A's entries of a chunk's rows renumbered
// to the rows of P they need (own and ghost rows, fetched by MatCreateSubMatrices), the sequential P_c^T A_c P_c, and
// the ranks' parts added into the parallel coarse operator (its rows follow P's columns; its pattern through a
// MATPREALLOCATOR). On that cube the product then adds 50 MB per rank instead of 3.3 GB, and takes about as long.
#include "signorini/linalg/lean_ptap.hpp"

#include "signorini/core/handle.hpp"

#include <algorithm>
#include <vector>

namespace signorini {

namespace {

constexpr PetscInt CHUNKS = 8; ///< each rank's rows in this many chunks, each with the rows of P it needs
constexpr const char *PARTS_KEY = "signorini_lean_ptap_parts";
PetscErrorCode (*mpiaij_set_from_options)(Mat) = nullptr; ///< PETSc's MatProductSetFromOptions of MPIAIJ

/// The ranks' parts of a product that the symbolic phase computed and the first numeric phase adds.
struct Parts {
  std::vector<Mat> mats;
};

PetscErrorCode DestroyParts(void *ctx) {
  auto *parts = static_cast<Parts *>(ctx);
  PetscFunctionBeginUser;
  for (Mat &m : parts->mats)
    PetscCall(MatDestroy(&m));
  delete parts;
  PetscFunctionReturn(0);
}

/// This rank's parts of P^T A P: one sequential matrix per chunk of its rows, with global coarse indices.
PetscErrorCode ComputeParts(Mat A, Mat P, std::vector<Mat> &parts) {
  PetscFunctionBeginUser;
  Mat Ad, Ao;
  const PetscInt *garray;
  PetscCall(MatMPIAIJGetSeqAIJ(A, &Ad, &Ao, &garray));
  PetscInt rstart, rend, ng, coarse;
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  PetscCall(MatGetLocalSize(Ao, nullptr, &ng));
  PetscCall(MatGetSize(P, nullptr, &coarse));
  const PetscInt n = rend - rstart;
  const PetscInt nlo = (PetscInt)(std::lower_bound(garray, garray + ng, rstart) - garray); // ghosts below the range
  ISH all_columns;
  PetscCall(ISCreateStride(PETSC_COMM_SELF, coarse, 0, 1, all_columns.out()));

  const PetscInt *ai, *aj, *oi, *oj;
  const PetscScalar *av, *ov;
  PetscInt m;
  PetscBool done;
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ai, &aj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "the diagonal block's row structure is not available");
  PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &m, &oi, &oj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "the off-diagonal block's row structure is not available");
  PetscCall(MatSeqAIJGetArrayRead(Ad, &av));
  PetscCall(MatSeqAIJGetArrayRead(Ao, &ov));
  // Position of an own row j and of a ghost k among the rows of P that a chunk needs (-1: not needed).
  std::vector<PetscInt> own(n), ghost(ng);
  for (PetscInt c = 0; c < CHUNKS; ++c) { // every rank CHUNKS times: MatCreateSubMatrices is collective
    const PetscInt r0 = n * c / CHUNKS, r1 = n * (c + 1) / CHUNKS;
    // The rows of P the chunk needs, in global order: the columns of A's rows r0..r1 (ghosts below the range, own
    // rows, ghosts above), each chunk row among them.
    std::fill(own.begin(), own.end(), -1);
    std::fill(ghost.begin(), ghost.end(), -1);
    for (PetscInt i = r0; i < r1; ++i) {
      own[i] = 0;
      for (PetscInt a = ai[i]; a < ai[i + 1]; ++a)
        own[aj[a]] = 0;
      for (PetscInt o = oi[i]; o < oi[i + 1]; ++o)
        ghost[oj[o]] = 0;
    }
    std::vector<PetscInt> rows;
    for (PetscInt k = 0; k < nlo; ++k)
      if (ghost[k] == 0) ghost[k] = (PetscInt)rows.size(), rows.push_back(garray[k]);
    for (PetscInt j = 0; j < n; ++j)
      if (own[j] == 0) own[j] = (PetscInt)rows.size(), rows.push_back(rstart + j);
    for (PetscInt k = nlo; k < ng; ++k)
      if (ghost[k] == 0) ghost[k] = (PetscInt)rows.size(), rows.push_back(garray[k]);
    const PetscInt ne = (PetscInt)rows.size();
    ISH isrows;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, ne, rows.data(), PETSC_USE_POINTER, isrows.out()));
    IS isrow = isrows, iscol = all_columns;
    Mat *pe;
    PetscCall(MatCreateSubMatrices(P, 1, &isrow, &iscol, MAT_INITIAL_MATRIX, &pe));
    MatH Pe(pe[0]);
    PetscCall(PetscFree(pe));
    // A's rows r0..r1 as a square matrix in the numbering of those rows (each row stays sorted: the positions keep
    // the global order, and a row's ghosts below, own columns and ghosts above come in that order).
    std::vector<PetscInt> ci(ne + 1, 0);
    for (PetscInt i = r0; i < r1; ++i)
      ci[own[i] + 1] = (ai[i + 1] - ai[i]) + (oi[i + 1] - oi[i]);
    for (PetscInt e = 0; e < ne; ++e)
      ci[e + 1] += ci[e];
    std::vector<PetscInt> cj(std::max<PetscInt>(1, ci[ne]));
    std::vector<PetscScalar> ca(cj.size());
    for (PetscInt i = r0; i < r1; ++i) {
      PetscInt q = ci[own[i]];
      PetscInt o = oi[i];
      for (; o < oi[i + 1] && oj[o] < nlo; ++o)
        cj[q] = ghost[oj[o]], ca[q++] = ov[o];
      for (PetscInt a = ai[i]; a < ai[i + 1]; ++a)
        cj[q] = own[aj[a]], ca[q++] = av[a];
      for (; o < oi[i + 1]; ++o)
        cj[q] = ghost[oj[o]], ca[q++] = ov[o];
    }
    MatH Achunk, Cchunk;
    PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, ne, ne, ci.data(), cj.data(), ca.data(), Achunk.out()));
    PetscCall(MatProductCreate(Achunk, Pe, nullptr, Cchunk.out()));
    PetscCall(MatProductSetType(Cchunk, MATPRODUCT_PtAP));
    PetscCall(MatProductSetAlgorithm(Cchunk, MATPRODUCTALGORITHMDEFAULT));
    PetscCall(MatProductSetFill(Cchunk, PETSC_DEFAULT));
    PetscCall(MatProductSetFromOptions(Cchunk));
    PetscCall(MatProductSymbolic(Cchunk));
    PetscCall(MatProductNumeric(Cchunk));
    // The part keeps neither the chunk (whose arrays are freed here) nor the product's intermediate data.
    PetscCall(MatProductClear(Cchunk));
    Achunk.Reset();
    Mat part = Cchunk;
    PetscCall(PetscObjectReference((PetscObject)part));
    parts.push_back(part);
  }
  PetscCall(MatSeqAIJRestoreArrayRead(Ad, &av));
  PetscCall(MatSeqAIJRestoreArrayRead(Ao, &ov));
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ai, &aj, &done));
  PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &m, &oi, &oj, &done));
  PetscFunctionReturn(0);
}

/// Adds the parts' rows into M (a preallocator or the coarse operator).
PetscErrorCode AddParts(const std::vector<Mat> &parts, Mat M) {
  PetscFunctionBeginUser;
  for (Mat part : parts) {
    const PetscInt *pi, *pj;
    const PetscScalar *pv;
    PetscInt rows;
    PetscBool done;
    PetscCall(MatGetRowIJ(part, 0, PETSC_FALSE, PETSC_FALSE, &rows, &pi, &pj, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "a part's row structure is not available");
    PetscCall(MatSeqAIJGetArrayRead(part, &pv));
    for (PetscInt r = 0; r < rows; ++r)
      if (pi[r + 1] > pi[r]) PetscCall(MatSetValues(M, 1, &r, pi[r + 1] - pi[r], pj + pi[r], pv + pi[r], ADD_VALUES));
    PetscCall(MatSeqAIJRestoreArrayRead(part, &pv));
    PetscCall(MatRestoreRowIJ(part, 0, PETSC_FALSE, PETSC_FALSE, &rows, &pi, &pj, &done));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Numeric(Mat C) {
  PetscFunctionBeginUser;
  Mat A, P, unused;
  PetscCall(MatProductGetMats(C, &A, &P, &unused));
  PetscContainer container = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)C, PARTS_KEY, (PetscObject *)&container));
  std::vector<Mat> parts;
  if (container) {
    // The symbolic phase's parts (it computed the values with the pattern), used once.
    Parts *kept;
    PetscCall(PetscContainerGetPointer(container, (void **)&kept));
    parts.swap(kept->mats);
    PetscCall(PetscObjectCompose((PetscObject)C, PARTS_KEY, nullptr));
  } else
    PetscCall(ComputeParts(A, P, parts));
  PetscCall(MatZeroEntries(C));
  PetscErrorCode added = AddParts(parts, C);
  for (Mat &m : parts)
    PetscCall(MatDestroy(&m));
  PetscCall(added);
  PetscFunctionReturn(0);
}

PetscErrorCode Symbolic(Mat C) {
  PetscFunctionBeginUser;
  Mat A, P, unused;
  PetscCall(MatProductGetMats(C, &A, &P, &unused));
  MPI_Comm comm = PetscObjectComm((PetscObject)A);
  PetscInt pn, pN;
  PetscCall(MatGetLocalSize(P, nullptr, &pn));
  PetscCall(MatGetSize(P, nullptr, &pN));
  PetscInt cbs; // the coarse operator's blocks are P's column blocks (the near null space's vectors per node)
  PetscCall(MatGetBlockSizes(P, nullptr, &cbs));
  auto *parts = new Parts;
  PetscContainer container;
  PetscCall(PetscContainerCreate(PETSC_COMM_SELF, &container));
  PetscCall(PetscContainerSetPointer(container, parts));
  PetscCall(PetscContainerSetUserDestroy(container, DestroyParts));
  PetscCall(ComputeParts(A, P, parts->mats));
  // The pattern: the parts' rows through a preallocator; the values wait for the numeric phase.
  MatH pre;
  PetscCall(MatCreate(comm, pre.out()));
  PetscCall(MatSetType(pre, MATPREALLOCATOR));
  PetscCall(MatSetSizes(pre, pn, pn, pN, pN));
  PetscCall(MatSetBlockSizes(pre, cbs, cbs));
  PetscCall(MatSetUp(pre));
  PetscCall(AddParts(parts->mats, pre));
  PetscCall(MatSetSizes(C, pn, pn, pN, pN));
  PetscCall(MatSetBlockSizes(C, cbs, cbs));
  PetscCall(MatSetType(C, MATMPIAIJ));
  PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, C));
  PetscCall(MatSetOption(C, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(PetscObjectCompose((PetscObject)C, PARTS_KEY, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscCall(MatSetOperation(C, MATOP_PRODUCTNUMERIC, (void (*)(void))Numeric));
  PetscFunctionReturn(0);
}

/// MatProductSetFromOptions of a product with A first: P^T A P is LeanPtAP's, every other product PETSc's.
PetscErrorCode SetFromOptions(Mat C) {
  PetscFunctionBeginUser;
  MatProductType type;
  PetscCall(MatProductGetType(C, &type));
  if (type == MATPRODUCT_PtAP) {
    PetscCall(PetscInfo(C, "P^T A P by the ranks' sequential products (LeanPtAP)\n"));
    PetscCall(MatSetOperation(C, MATOP_PRODUCTSYMBOLIC, (void (*)(void))Symbolic));
  } else
    PetscCall(mpiaij_set_from_options(C));
  PetscFunctionReturn(0);
}

/// A's own MatProductSetFromOptions: only differs from P's, so that PETSc asks A for the composed one (SetFromOptions).
PetscErrorCode SetFromOptionsOfA(Mat C) {
  PetscFunctionBeginUser;
  PetscCall(mpiaij_set_from_options(C));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LeanRowsTimes(Mat G, Mat P, Mat *C) {
  MPI_Comm comm = PetscObjectComm((PetscObject)G);
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) {
    PetscCall(MatMatMult(G, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, C));
    PetscFunctionReturn(0);
  }
  // The rows of P that G's own rows need (G's columns), in global order.
  PetscInt g0, g1, pN, cstart, cend;
  PetscCall(MatGetOwnershipRange(G, &g0, &g1));
  PetscCall(MatGetSize(P, nullptr, &pN));
  PetscCall(MatGetOwnershipRangeColumn(P, &cstart, &cend));
  std::vector<PetscInt> gi(1, 0), gj, rows;
  std::vector<PetscScalar> gv;
  for (PetscInt r = g0; r < g1; ++r) {
    PetscInt nc;
    const PetscInt *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(G, r, &nc, &cols, &vals));
    gj.insert(gj.end(), cols, cols + nc);
    gv.insert(gv.end(), vals, vals + nc);
    PetscCall(MatRestoreRow(G, r, &nc, &cols, &vals));
    gi.push_back((PetscInt)gj.size());
  }
  rows = gj;
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  for (PetscInt &c : gj) // a column's position among the rows (each row's columns stay sorted)
    c = (PetscInt)(std::lower_bound(rows.begin(), rows.end(), c) - rows.begin());
  const PetscInt kg = g1 - g0, ne = (PetscInt)rows.size();
  ISH isrows, all_columns;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, ne, rows.data(), PETSC_USE_POINTER, isrows.out()));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, pN, 0, 1, all_columns.out()));
  IS isrow = isrows, iscol = all_columns;
  Mat *pe;
  PetscCall(MatCreateSubMatrices(P, 1, &isrow, &iscol, MAT_INITIAL_MATRIX, &pe)); // collective
  MatH Pe(pe[0]);
  PetscCall(PetscFree(pe));
  if (gj.empty()) gj.push_back(0), gv.push_back(0); // valid arrays for a rank without rows
  MatH Gl, Cl;
  PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, kg, ne, gi.data(), gj.data(), gv.data(), Gl.out()));
  PetscCall(MatMatMult(Gl, Pe, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Cl.out()));
  // Cl's rows are C's own rows; its columns are global.
  const PetscInt *ci, *cj;
  const PetscScalar *cv;
  PetscInt m;
  PetscBool done;
  PetscCall(MatGetRowIJ(Cl, 0, PETSC_FALSE, PETSC_FALSE, &m, &ci, &cj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "the product's row structure is not available");
  std::vector<PetscInt> d_nnz(kg, 0), o_nnz(kg, 0);
  for (PetscInt i = 0; i < kg; ++i)
    for (PetscInt a = ci[i]; a < ci[i + 1]; ++a)
      (cj[a] >= cstart && cj[a] < cend ? d_nnz : o_nnz)[i]++;
  PetscCall(MatCreateAIJ(comm, kg, cend - cstart, PETSC_DETERMINE, pN, 0, d_nnz.data(), 0, o_nnz.data(), C));
  PetscCall(MatSeqAIJGetArrayRead(Cl, &cv));
  for (PetscInt i = 0; i < kg; ++i) {
    const PetscInt row = g0 + i;
    if (ci[i + 1] > ci[i])
      PetscCall(MatSetValues(*C, 1, &row, ci[i + 1] - ci[i], cj + ci[i], cv + ci[i], INSERT_VALUES));
  }
  PetscCall(MatSeqAIJRestoreArrayRead(Cl, &cv));
  PetscCall(MatRestoreRowIJ(Cl, 0, PETSC_FALSE, PETSC_FALSE, &m, &ci, &cj, &done));
  PetscCall(MatAssemblyBegin(*C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*C, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode LeanPtAPAttach(Mat A) {
  PetscFunctionBeginUser;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)A), &size));
  PetscBool mpiaij;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpiaij));
  if (size == 1 || !mpiaij) PetscFunctionReturn(0);
  // PETSc's MatProductSetFromOptions_Private calls A's op when A's and P's agree; when they differ it asks A for the
  // composed MatProductSetFromOptions_mpiaij_mpiaij_C, which is this one.
  void (*op)(void) = nullptr;
  PetscCall(MatGetOperation(A, MATOP_PRODUCTSETFROMOPTIONS, &op));
  if (op == (void (*)(void))SetFromOptionsOfA) PetscFunctionReturn(0);
  mpiaij_set_from_options = (PetscErrorCode(*)(Mat))op;
  PetscCall(MatSetOperation(A, MATOP_PRODUCTSETFROMOPTIONS, (void (*)(void))SetFromOptionsOfA));
  PetscCall(PetscObjectComposeFunction((PetscObject)A, "MatProductSetFromOptions_mpiaij_mpiaij_C", SetFromOptions));
  PetscFunctionReturn(0);
}

} // namespace signorini
