#pragma once
// GAMG's first Galerkin product P^T A P on several ranks in a rank's share of the memory (issue 37, item 5).
#include <petscmat.h>

namespace signorini {

/// -contact_gamg_product: how GAMG's first Galerkin product is formed on several ranks.
enum class GalerkinProduct { LEAN, PETSC };
inline constexpr const char *GALERKIN_PRODUCT_NAMES[] = {"lean", "petsc"};

/// Every later MatPtAP(A, P) of this MPIAIJ matrix (GAMG's first coarse operator, on any number of ranks above one)
/// is formed by LeanPtAP: each rank multiplies its own rows in a few chunks by PETSc's sequential product, which keeps
/// a row of A P at a time, and the ranks add their parts. PETSc 3.18's products of parallel matrices (its default,
/// `scalable` and `nonscalable` alike) form A P of all local rows first: 3.3 GB per rank on the 4.1M-dof hexahedral
/// cube on 2 ranks, where the whole one-rank run peaks at 8.1 GB (docs/performance.md). A sequential matrix, or one
/// rank, is left to PETSc. Other products of A go to PETSc's as before. On that cube: 5.3 instead of 7.7 GB per rank,
/// the contact solve about as fast (122-125 s against 117-123 s).
PetscErrorCode LeanPtAPAttach(Mat A);

/// G P for a G of few rows (the hierarchy update's changed rows carried down the levels, UpdateGalerkin) and a
/// parallel P: each rank fetches only the rows of P that its rows of G need and multiplies sequentially. PETSc 3.18's
/// parallel product copies all of the rank's rows of P first (MatMPIAIJGetLocalMat): on the 4.1M-dof cube on 2 ranks
/// 466 MB per rank at the first update, the run's peak. One rank: PETSc's product (no copy).
PetscErrorCode LeanRowsTimes(Mat G, Mat P, Mat *C);

/// GAMG's coarsener (PETSc's -mat_coarsen_type) for the iterative path's lean set-up, unless the run gives its own:
/// PETSc's distance-k aggregation (MATCOARSENMISK), whose matrix of each node's aggregate members on other ranks is
/// replaced by a copy of its filled entries (lean_coarsen.cpp). Registers the type once.
inline constexpr const char *LEAN_COARSEN = "signorini_misk";
PetscErrorCode LeanCoarsenDefault();

} // namespace signorini
