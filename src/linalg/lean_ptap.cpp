// GAMG's first Galerkin product P^T A P on several ranks in a rank's share of the memory (issue 37, item 5).
//
// Why not PETSc's own: PETSc 3.18's products of MPIAIJ matrices (MatPtAP's `scalable` default, `nonscalable`, and
// `allatonce_merged`) form A P of the local rows whole before multiplying by P^T. On the 4.1M-dof hexahedral cube on
// 2 ranks that is 5.0 GB per rank (each rank's resident memory went from 2.7 GB after the assembly to 7.7 GB in GAMG's
// set-up, against 8.1 GB for the whole one-rank run); `allatonce` keeps no A P but took 5 times as long
// (docs/performance.md). One rank's sequential product keeps one row of A P at a time, so each rank multiplies its
// own rows here with that product: for a chunk of its rows, A's entries of those rows in the numbering of the rows of
// P it needs (its own and its ghosts', rows P_e of P), the sequential P_e^T A_chunk P_e, and the ranks' parts added
// into the parallel coarse operator (its rows follow P's columns). A chunk's copy of A is a quarter of the rank's rows.
#include "signorini/linalg/lean_ptap.hpp"

#include "signorini/core/handle.hpp"
#include "signorini/linalg/solver_choice.hpp"

#include <algorithm>
#include <vector>

namespace signorini {

namespace {

constexpr PetscInt CHUNKS = 4; ///< the copies of A's rows are this many chunks
constexpr const char *PARTS_KEY = "signorini_lean_ptap_parts";
constexpr const char *SETTINGS_KEY = "signorini_lean_ptap_settings";
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
  // The rows of P this rank needs, in global order: the ghosts below its range, its own rows, the ghosts above.
  const PetscInt nlo = (PetscInt)(std::lower_bound(garray, garray + ng, rstart) - garray);
  const PetscInt next = n + ng;
  std::vector<PetscInt> ext(next);
  for (PetscInt k = 0; k < nlo; ++k)
    ext[k] = garray[k];
  for (PetscInt i = 0; i < n; ++i)
    ext[nlo + i] = rstart + i;
  for (PetscInt k = nlo; k < ng; ++k)
    ext[n + k] = garray[k];
  ISH rows, cols;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, next, ext.data(), PETSC_USE_POINTER, rows.out()));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, coarse, 0, 1, cols.out()));
  IS isrow = rows, iscol = cols;
  Mat *pe;
  PetscCall(MatCreateSubMatrices(P, 1, &isrow, &iscol, MAT_INITIAL_MATRIX, &pe));
  MatH Pe(pe[0]);
  PetscCall(PetscFree(pe));

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
  const PetscInt chunk = std::max<PetscInt>(1, (n + CHUNKS - 1) / CHUNKS);
  for (PetscInt r0 = 0; r0 < n || (n == 0 && r0 == 0); r0 += chunk) {
    const PetscInt r1 = std::min(n, r0 + chunk);
    // A's rows r0..r1 as rows nlo + i of a square matrix in the numbering of ext (columns: a ghost k below the range
    // is k, an own row j is nlo + j, a ghost k above is n + k; each row stays sorted).
    std::vector<PetscInt> ci(next + 1, 0);
    for (PetscInt i = r0; i < r1; ++i)
      ci[nlo + i + 1] = (ai[i + 1] - ai[i]) + (oi[i + 1] - oi[i]);
    for (PetscInt e = 0; e < next; ++e)
      ci[e + 1] += ci[e];
    std::vector<PetscInt> cj(std::max<PetscInt>(1, ci[next]));
    std::vector<PetscScalar> ca(cj.size());
    for (PetscInt i = r0; i < r1; ++i) {
      PetscInt q = ci[nlo + i];
      PetscInt o = oi[i];
      for (; o < oi[i + 1] && oj[o] < nlo; ++o)
        cj[q] = oj[o], ca[q++] = ov[o];
      for (PetscInt a = ai[i]; a < ai[i + 1]; ++a)
        cj[q] = nlo + aj[a], ca[q++] = av[a];
      for (; o < oi[i + 1]; ++o)
        cj[q] = n + oj[o], ca[q++] = ov[o];
    }
    MatH Achunk, Cchunk;
    PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, next, next, ci.data(), cj.data(), ca.data(), Achunk.out()));
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
    if (n == 0) break;
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
  PetscCall(MatSetBlockSizesFromMats(pre, P, P));
  PetscCall(MatSetUp(pre));
  PetscCall(AddParts(parts->mats, pre));
  PetscCall(MatSetSizes(C, pn, pn, pN, pN));
  PetscCall(MatSetBlockSizesFromMats(C, P, P));
  PetscCall(MatSetType(C, MATMPIAIJ));
  PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, C));
  PetscCall(MatSetOption(C, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(PetscObjectCompose((PetscObject)C, PARTS_KEY, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscCall(MatSetOperation(C, MATOP_PRODUCTNUMERIC, (void (*)(void))Numeric));
  PetscFunctionReturn(0);
}

PetscErrorCode DestroySettings(void *ctx) {
  PetscFunctionBeginUser;
  delete static_cast<LeanPtAPSettings *>(ctx);
  PetscFunctionReturn(0);
}

/// Whether P^T A P is LeanPtAP's: -contact_gamg_product, or (auto) PETSc's A P of the local rows does not fit.
PetscErrorCode UseLean(Mat A, bool &lean) {
  PetscFunctionBeginUser;
  MPI_Comm comm = PetscObjectComm((PetscObject)A);
  PetscContainer container = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)A, SETTINGS_KEY, (PetscObject *)&container));
  LeanPtAPSettings settings;
  if (container) {
    LeanPtAPSettings *s;
    PetscCall(PetscContainerGetPointer(container, (void **)&s));
    settings = *s;
  }
  lean = settings.mode == GalerkinProduct::LEAN;
  if (settings.mode != GalerkinProduct::AUTO) PetscFunctionReturn(0);
  MatInfo info;
  PetscCall(MatGetInfo(A, MAT_LOCAL, &info));
  double need[2] = {PETSC_PTAP_BYTES_PER_ENTRY * info.nz_used, 0}, available;
  if (settings.budget_given) {
    PetscLogDouble rss;
    PetscCall(PetscMemoryGetCurrentUsage(&rss));
    available = settings.budget - rss;
  } else
    PetscCall(MemoryBudget(comm, available));
  need[1] = need[0] > available ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, need, 2, MPI_DOUBLE, MPI_MAX, comm));
  lean = need[1] > 0;
  PetscCall(PetscInfo(A,
                      "GAMG's first Galerkin product: PETSc's keeps A P of the local rows (about %.3g MB per rank), "
                      "%.3g MB available (%s): %s\n",
                      need[0] / 1048576.0, available / 1048576.0,
                      settings.budget_given ? "-contact_memory_budget less the run's current use"
                                            : "the node's available memory shared by its ranks, less a tenth",
                      lean ? "the ranks' sequential products (LeanPtAP)" : "PETSc's"));
  PetscFunctionReturn(0);
}

/// MatProductSetFromOptions of a product with A first: P^T A P is LeanPtAP's (UseLean), every other product PETSc's.
PetscErrorCode SetFromOptions(Mat C) {
  PetscFunctionBeginUser;
  MatProductType type;
  Mat A, P, unused;
  PetscCall(MatProductGetType(C, &type));
  PetscCall(MatProductGetMats(C, &A, &P, &unused));
  bool lean = false;
  if (type == MATPRODUCT_PtAP) PetscCall(UseLean(A, lean));
  if (lean) {
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

PetscErrorCode LeanPtAPAttach(Mat A, const LeanPtAPSettings &settings) {
  PetscFunctionBeginUser;
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)A), &size));
  PetscBool mpiaij;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpiaij));
  if (size == 1 || !mpiaij) PetscFunctionReturn(0);
  // The settings are A's (a later call replaces them); the override stays once made.
  PetscContainer container;
  PetscCall(PetscContainerCreate(PETSC_COMM_SELF, &container));
  PetscCall(PetscContainerSetPointer(container, new LeanPtAPSettings(settings)));
  PetscCall(PetscContainerSetUserDestroy(container, DestroySettings));
  PetscCall(PetscObjectCompose((PetscObject)A, SETTINGS_KEY, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  if (settings.mode == GalerkinProduct::PETSC) PetscFunctionReturn(0);
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
