// The kept factorisation as a preconditioner type of its own, PCKEPT ("kept"): it applies the factorisation that a
// MumpsSchur holds, with the multipliers' diagonal D of the current operator, so that a KSP solves with it as with any
// other PC and -contact_ksp_view shows which factorisation ran, its ordering and its sizes.
#pragma once

#include "signorini/linalg/kept_rows.hpp"
#include "signorini/linalg/mumps_schur.hpp"

#include <petscksp.h>

#include <vector>

#define PCKEPT "kept"

namespace signorini {

/// Registers PCKEPT with PETSc (once; later calls do nothing). Not collective.
[[nodiscard]] PetscErrorCode PCKeptRegister();

/// Gives pc (of type PCKEPT) the factorisation it applies (not owned: it must outlive the PC's use) and what it is a
/// factorisation of, for the view ("the current matrix", "an earlier tangent"). Logically collective.
[[nodiscard]] PetscErrorCode PCKeptSetFactorization(PC pc, MumpsSchur *factor, const char *of);
/// The factorisation pc applies, for the solves in the multiplier space (MumpsSchur::Condense, SolveReduced, Expand),
/// as PCFieldSplitGetSubKSP exposes a fieldsplit's sub-solver. Not collective.
[[nodiscard]] PetscErrorCode PCKeptGetFactorization(PC pc, MumpsSchur **factor);
/// The multipliers' diagonal D (rank 0, in the Schur complement's order) of the operator the next applications solve
/// with. Logically collective.
[[nodiscard]] PetscErrorCode PCKeptSetDiagonal(PC pc, const std::vector<PetscScalar> &d);
/// Friction's rows (KeptRows, not owned; null: none): the operator's multiplier rows (from row owned_u of each rank's
/// part) are mapped to the factored fixed rows before the solve and its multipliers back after it. Logically
/// collective.
[[nodiscard]] PetscErrorCode PCKeptSetRows(PC pc, KeptRows *rows, PetscInt owned_u);

} // namespace signorini
