// PCKEPT: the kept factorisation (MumpsSchur) as a registered PETSc preconditioner type (pc_kept.hpp). A type of our
// own needs PETSc's private PC structure, as every PC type does.
#include "signorini/linalg/pc_kept.hpp"

#include <petsc/private/pcimpl.h>

#include <string>

namespace signorini {

namespace {

struct PcKept {
  MumpsSchur *factor = nullptr;
  std::vector<PetscScalar> d;
  std::string of = "the current matrix";
  KeptRows *rows = nullptr; ///< friction's rows mapped to the fixed ones (PCKeptSetRows)
  PetscInt owned_u = 0;
  Vec work = nullptr;       ///< the right-hand side mapped
};

PcKept *Data(PC pc) { return static_cast<PcKept *>(pc->data); }

PetscErrorCode PCApply_Kept(PC pc, Vec b, Vec x) {
  PcKept *k = Data(pc);
  PetscFunctionBeginUser;
  PetscCheck(k->factor, PetscObjectComm((PetscObject)pc), PETSC_ERR_ORDER,
             "the kept factorisation PC has no factorisation (PCKeptSetFactorization)");
  if (!k->rows) {
    PetscCall(k->factor->Solve(k->d, b, x));
    PetscFunctionReturn(0);
  }
  if (!k->work) PetscCall(VecDuplicate(b, &k->work));
  PetscCall(VecCopy(b, k->work));
  PetscScalar *a;
  PetscCall(VecGetArray(k->work, &a));
  k->rows->Forward(a + k->owned_u);
  PetscCall(VecRestoreArray(k->work, &a));
  PetscCall(k->factor->Solve(k->d, k->work, x));
  PetscCall(VecGetArray(x, &a));
  k->rows->Back(a + k->owned_u);
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode PCView_Kept(PC pc, PetscViewer viewer) {
  PcKept *k = Data(pc);
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "kept factorisation of %s, with the Schur complement on the "
                                   "multipliers\n", k->of.c_str()));
  if (k->rows)
    PetscCall(PetscViewerASCIIPrintf(viewer, "friction's rows mapped per pair onto fixed rows (the normal one and "
                                     "the fixed tangents'), the slip law in the multiplier block\n"));
  if (k->factor) {
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(k->factor->View(viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "  no factorisation set\n"));
  PetscFunctionReturn(0);
}

PetscErrorCode PCDestroy_Kept(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&Data(pc)->work));
  delete Data(pc);
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode PCSetUp_Kept(PC) {
  PetscFunctionBeginUser;
  // The factorisation is made by its owner (SaddlePointSystem::Factor), which knows when the matrix changed.
  PetscFunctionReturn(0);
}

PetscErrorCode PCCreate_Kept(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new PcKept();
  pc->ops->apply = PCApply_Kept;
  pc->ops->view = PCView_Kept;
  pc->ops->destroy = PCDestroy_Kept;
  pc->ops->setup = PCSetUp_Kept;
  PetscFunctionReturn(0);
}

PetscErrorCode CheckKept(PC pc) {
  PetscBool kept;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCKEPT, &kept));
  PetscCheck(kept, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG, "the PC is not of type " PCKEPT);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode PCKeptRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(PCRegister(PCKEPT, PCCreate_Kept));
  registered = true;
  PetscFunctionReturn(0);
}

PetscErrorCode PCKeptSetFactorization(PC pc, MumpsSchur *factor, const char *of) {
  PetscFunctionBeginUser;
  PetscCall(CheckKept(pc));
  Data(pc)->factor = factor;
  Data(pc)->of = of;
  PetscFunctionReturn(0);
}

PetscErrorCode PCKeptGetFactorization(PC pc, MumpsSchur **factor) {
  PetscFunctionBeginUser;
  PetscCall(CheckKept(pc));
  *factor = Data(pc)->factor;
  PetscFunctionReturn(0);
}

PetscErrorCode PCKeptSetDiagonal(PC pc, const std::vector<PetscScalar> &d) {
  PetscFunctionBeginUser;
  PetscCall(CheckKept(pc));
  Data(pc)->d = d;
  PetscFunctionReturn(0);
}

PetscErrorCode PCKeptSetRows(PC pc, KeptRows *rows, PetscInt owned_u) {
  PetscFunctionBeginUser;
  PetscCall(CheckKept(pc));
  Data(pc)->rows = rows;
  Data(pc)->owned_u = owned_u;
  PetscFunctionReturn(0);
}

} // namespace signorini
