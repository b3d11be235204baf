// The null-space preconditioner of the augmented saddle-point matrix, PCNULLSPACE ("nullspace"), for pairs whose
// constraint rows each lie on one node (rigid obstacles, without friction).
//
// The matrix is the MATNEST [A B^T; B D] of SaddlePointSystem's iterative path: A = K plus the augmentation terms, D =
// 0 on an active row and nonzero on an inactive one. An inactive row gives mu_I = D_I^-1 (g_I - B_I u); what is left is
// K' u + B_A^T mu_A = f', B_A u = g_A with K' = A - B_I^T D_I^-1 B_I and f' = f - B_I^T D_I^-1 g_I. Its exact solution
// by the null-space method: u = u_N + u_F with u_N = B_A^T G^-1 g_A (G = B_A B_A^T, blocks of the active rows of one
// node), u_F in the null space of B_A from P K' P u_F = P (f' - K' u_N) (P = I - B_A^T G^-1 B_A, the projection onto
// it), and mu_A = G^-1 B_A (f' - K' u). The preconditioner is that solution with (P K' P)^+ replaced by P M P, M one
// application of the displacement block's solver (GAMG on A, whose active terms the projection removes): no
// approximation of the Schur complement on the multipliers, which on a Schur fieldsplit's selfp diagonal spreads over
// (k + r) / r and slows every solve with many active pairs (the octant Hertz at 290k dofs: 20 GMRES iterations of
// the last solve against 16 here; docs/performance.md, twenty-third session). The products with K' at the active
// nodes take the rows of A there (a submatrix of a few rows, formed at each set-up), not a whole product.
// The displacement block's solver is a KSP of the options prefix <pc prefix>fieldsplit_u_, the one a Schur
// fieldsplit's "u" block has, so that the same options (GAMG's) apply to both.
#pragma once

#include <petscksp.h>

#define PCNULLSPACE "nullspace"

namespace signorini {

/// Registers PCNULLSPACE with PETSc (once; later calls do nothing). Not collective.
[[nodiscard]] PetscErrorCode PCNullSpaceRegister();

/// The displacement block's solver of pc (of type PCNULLSPACE; null before the PC's first set-up), as
/// PCFieldSplitGetSubKSP gives a fieldsplit's. Not collective.
[[nodiscard]] PetscErrorCode PCNullSpaceGetSubKSP(PC pc, KSP *ksp);
/// Whether the displacement block's multigrid smooths its finest level on the operator with the active rows eliminated
/// (true, the default) or on the augmented block (-contact_nullspace_fine_level); no effect on a PC of another type.
[[nodiscard]] PetscErrorCode PCNullSpaceSetFineLevel(PC pc, bool eliminated);

} // namespace signorini
