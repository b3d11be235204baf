// GAMG's aggregation on several ranks without PETSc 3.18's oversized ghost matrix (issue 37, item 5).
//
// Why: PETSc 3.18's distance-k aggregation (MATCOARSENMISK, GAMG's default coarsener) ends by building a matrix of
// each local node's aggregate members on other ranks, which GAMG's prolongator set-up reads for its ghost data. It
// preallocates as many off-process entries for every local row as the largest aggregate has members, most of which
// stay empty, and GAMG keeps it until that level's prolongator is made: the octant at 1.07M dofs on 2 ranks, 51.1M
// entries allocated on the finest level for 4666 filled (about 300 MB per rank; -log_view_memory: 564 MB more
// resident memory in MatCoarsen, summed over the ranks, against 54 MB on one rank). On one rank that size is 0.
// signorini's coarsener is PETSc's MISK with that matrix replaced by a copy of its filled entries right after the
// aggregation (MatDuplicate allocates the entries only); the aggregates are PETSc's.
#include "signorini/linalg/lean_ptap.hpp"

#include <petsc/private/matimpl.h>
#include <petscversion.h>

// PETSc's own MISK coarsener's constructor: exported by the library, declared in no header.
PETSC_EXTERN PetscErrorCode MatCoarsenCreate_MISK(MatCoarsen);

namespace signorini {

namespace {

PetscErrorCode (*misk_apply)(MatCoarsen) = nullptr; ///< PETSc's MISK apply, which LeanApply runs first

PetscErrorCode LeanApply(MatCoarsen coarse) {
  PetscFunctionBeginUser;
  PetscCall(misk_apply(coarse));
  Mat ghosts = nullptr;
  PetscCall(PetscCDGetMat(coarse->agg_lists, &ghosts));
  if (!ghosts) PetscFunctionReturn(0);
  MatInfo info;
  PetscCall(MatGetInfo(ghosts, MAT_GLOBAL_SUM, &info));
  Mat compact;
  PetscCall(MatDuplicate(ghosts, MAT_COPY_VALUES, &compact));
  // PETSc 3.18's PetscCDSetMat replaces the pointer without destroying the matrix it held.
  static_assert(PETSC_VERSION_LT(3, 19, 0), "PetscCDSetMat destroys the previous matrix from PETSc 3.19 on");
  PetscCall(MatDestroy(&ghosts));
  PetscCall(PetscCDSetMat(coarse->agg_lists, compact));
  PetscCall(PetscInfo(nullptr,
                      "aggregates' members on other ranks: %.0f entries kept of %.0f allocated (LeanCoarsen)\n",
                      (double)info.nz_used, (double)info.nz_allocated));
  PetscFunctionReturn(0);
}

PetscErrorCode CreateLean(MatCoarsen coarse) {
  PetscFunctionBeginUser;
  PetscCall(MatCoarsenCreate_MISK(coarse));
  misk_apply = coarse->ops->apply;
  coarse->ops->apply = LeanApply;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LeanCoarsenDefault() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(MatCoarsenRegister(LEAN_COARSEN, CreateLean));
  registered = true;
  // GAMG reads the coarsener's type from the options with its PC's prefix (the displacement block's, whose
  // Galerkin product LeanPtAPAttach takes too). The value set here is read once so that a run whose block is not
  // GAMG's (-contact_fieldsplit_u_pc_type hypre) is not refused for an option it never gave.
  const char *name = "-contact_fieldsplit_u_mat_coarsen_type";
  PetscBool set;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &set));
  if (set) PetscFunctionReturn(0);
  PetscCall(PetscOptionsSetValue(nullptr, name, LEAN_COARSEN));
  char value[64];
  PetscCall(PetscOptionsGetString(nullptr, nullptr, name, value, sizeof(value), &set));
  PetscFunctionReturn(0);
}

} // namespace signorini
