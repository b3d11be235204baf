#pragma once
// GAMG's first Galerkin product P^T A P on several ranks in a rank's share of the memory (issue 37, item 5).
#include <petscmat.h>

namespace signorini {

/// -contact_gamg_product: how GAMG's first Galerkin product is formed on several ranks.
enum class GalerkinProduct { AUTO, LEAN, PETSC };
inline constexpr const char *GALERKIN_PRODUCT_NAMES[] = {"auto", "lean", "petsc"};

struct LeanPtAPSettings {
  GalerkinProduct mode = GalerkinProduct::AUTO;
  double budget = 0;         ///< -contact_memory_budget (bytes per rank) where given
  bool budget_given = false; ///< else the memory available at the product
};

/// PETSc's product keeps A P of the local rows: about this many bytes per stored entry of A (the 4.1M-dof hexahedral
/// cube on 2 ranks: 5.0 GB per rank in GAMG's set-up with it, for 1.67e8 entries of A per rank; docs/performance.md).
inline constexpr double PETSC_PTAP_BYTES_PER_ENTRY = 30;

/// Every later MatPtAP(A, P) of this MPIAIJ matrix (GAMG's first coarse operator, on any number of ranks above one)
/// is formed by LeanPtAP: each rank multiplies its own rows in a few chunks by PETSc's sequential product, which keeps
/// a row of A P at a time, and the ranks add their parts. PETSc 3.18's products of parallel matrices (its default,
/// `scalable` and `nonscalable` alike) form A P of all local rows first: 5.0 GB per rank on the 4.1M-dof hexahedral
/// cube on 2 ranks, where the whole one-rank run peaks at 8.1 GB (docs/performance.md). A sequential matrix, or one
/// rank, is left to PETSc. Other products of A go to PETSc's as before. AUTO takes PETSc's product (the faster) where
/// its A P fits in the memory available at the product (PETSC_PTAP_BYTES_PER_ENTRY per entry of A on every rank), else
/// this one; -info says which and why.
PetscErrorCode LeanPtAPAttach(Mat A, const LeanPtAPSettings &settings);

} // namespace signorini
