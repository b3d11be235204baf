// Pattern, constraint rows, KSP set-up and solve of the saddle-point system (the kept factorisation:
// saddle_point_kept.cpp; the contact problem in the multipliers: saddle_point_lcp.cpp).
#include "signorini/linalg/saddle_point.hpp"
#include "signorini/core/handle.hpp"
#include "signorini/linalg/pc_nullspace.hpp"

#include "signorini/linalg/lean_ptap.hpp"
#include "signorini/linalg/pc_kept.hpp"
#include "signorini/linalg/solver_options.hpp"

#include "signorini/options/readers.hpp"
#include "signorini/core/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace signorini {

PetscErrorCode SaddlePointSystem::RowCounts(const std::vector<SparseRow> &rows, const std::vector<PetscInt> &d_nnz_k,
                                            const std::vector<PetscInt> &o_nnz_k, std::vector<PetscInt> &d_nnz,
                                            std::vector<PetscInt> &o_nnz) const {
  const PetscInt start = dofs_->RowStart(), end = start + dofs_->OwnedRows();
  PetscFunctionBeginUser;
  d_nnz.assign(d_nnz_k.begin(), d_nnz_k.end());
  o_nnz.assign(o_nnz_k.begin(), o_nnz_k.end());
  d_nnz.resize(dofs_->OwnedRows(), 1); // a multiplier row: its diagonal, then its columns below
  o_nnz.resize(dofs_->OwnedRows(), 0);
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const PetscInt r = dofs_->LambdaRow((PetscInt)p) - start;
    for (PetscInt i = 0; i < rows[p].ncols; ++i) {
      const PetscInt c = rows[p].cols[i];
      const bool mine = c >= start && c < end;
      (mine ? d_nnz[r] : o_nnz[r]) += 1;
      if (mine) d_nnz[c - start] += 1; // the transposed entry
    }
  }
  std::vector<PetscInt> remote;
  PetscCall(RemoteTransposed(rows, remote));
  for (PetscInt i = 0; i < dofs_->OwnedRows(); ++i)
    o_nnz[i] += remote[i];
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::RemoteTransposed(const std::vector<SparseRow> &rows,
                                                   std::vector<PetscInt> &counts) const {
  const PetscInt start = dofs_->RowStart(), end = start + dofs_->OwnedRows();
  PetscFunctionBeginUser;
  // A count vector in the system's layout, summed on the rows' owners (as ContactSolver::SystemPattern counts the
  // mortar rows' couplings): without it the transposed entries of a pair on the partition's interface were allocated
  // one by one during the assembly (137 reallocations of B^T's off-diagonal block, the 2D cylinders on 2 ranks).
  VecH extra;
  PetscCall(
      VecCreateMPI(PetscObjectComm((PetscObject)dofs_->IsU()), dofs_->OwnedRows(), dofs_->GlobalRows(), extra.out()));
  for (const SparseRow &row : rows)
    for (PetscInt i = 0; i < row.ncols; ++i)
      if (row.cols[i] < start || row.cols[i] >= end) PetscCall(VecSetValue(extra, row.cols[i], 1.0, ADD_VALUES));
  PetscCall(VecAssemblyBegin(extra));
  PetscCall(VecAssemblyEnd(extra));
  const PetscScalar *e;
  PetscCall(VecGetArrayRead(extra, &e));
  counts.resize(dofs_->OwnedRows());
  for (PetscInt i = 0; i < dofs_->OwnedRows(); ++i)
    counts[i] = (PetscInt)PetscRealPart(e[i]);
  PetscCall(VecRestoreArrayRead(extra, &e));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CreatePattern(const std::vector<SparseRow> &rows, Mat P) const {
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const PetscInt r = dofs_->LambdaRow((PetscInt)p);
    const std::vector<PetscScalar> zeros(rows[p].ncols, 0.0);
    PetscCall(MatSetValues(P, 1, &r, rows[p].ncols, rows[p].cols.data(), zeros.data(), ADD_VALUES));
    PetscCall(MatSetValues(P, rows[p].ncols, rows[p].cols.data(), 1, &r, zeros.data(), ADD_VALUES));
    PetscCall(MatSetValue(P, r, r, 0.0, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SetDefaultSolver(KSP ksp, SolverPath path, bool lu, bool nullspace) {
  PC pc;
  PetscFunctionBeginUser;
  // The iterative path: its settings become the options' defaults, which KSPSetFromOptions and the fieldsplit's
  // blocks read.
  std::vector<std::string> set;
  if (path == SolverPath::ITERATIVE) PetscCall(SetIterativeDefaults(set, nullspace));
  PetscCall(KSPSetOptionsPrefix(ksp, "contact_"));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, lu ? PCLU : PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetTolerances(ksp, 1e-10, 1e-50, PETSC_DEFAULT, 2000));
  PetscFunctionReturn(0);
}

PetscErrorCode ReadSaddlePointOptions(MPI_Comm comm, SaddlePointOptions &opts) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Saddle-point system", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(PetscOptionsBool("-contact_reuse_factorization",
                             "Factor once and follow active-set changes through MUMPS's Schur complement on the "
                             "multipliers (with a MUMPS LU/Cholesky solver; default on there, unless a dense "
                             "factorisation of the Schur complement would take more flops than the sparse one: then "
                             "MUMPS refactorises at each change; giving the option keeps it); svk: the kept "
                             "factorisation preconditions FGMRES on the current tangent; friction (linear material): "
                             "of fixed rows onto which its rows are mapped, the dense Schur complement updated per "
                             "change. The kept factorisation calls MUMPS itself with ICNTL(7) = 1 (the ordering below), ICNTL(14) = 50, ICNTL(24) = 1 and "
                             "CNTL(3) = 1e-12 unless -contact_mat_mumps_icntl_<k> / _cntl_<k> say otherwise; PETSc's "
                             "MUMPS options listed further down show PETSc's own defaults, which apply without it",
                             "", opts.reuse_factorization, &opts.reuse_factorization, &opts.reuse_set));
  PetscCall(OptionsInt(PetscOptionsObject, "-contact_reuse_max_it",
                       "svk with -contact_reuse_factorization: FGMRES iterations on the current tangent preconditioned "
                       "by the kept factorisation of an earlier one before MUMPS refactors (0: at every solve); a "
                       "solve whose residual contracted by less than 10 per iteration refactors at the next one",
                       0, SaddlePointOptions::REUSE_MAX_IT_MAX, opts.reuse_max_it, &opts.reuse_max_it_set));
  PetscInt ordering = (PetscInt)opts.ordering.graph;
  const std::string ordering_help = "Ordering of the kept factorisation (with -contact_mat_mumps_icntl_7 1, the "
                                    "default): METIS's nested dissection of the node graph, or cuts across coordinate "
                                    "axes; auto: METIS in 3D and from " + std::to_string(METIS_MIN_ROWS_2D) +
                                    " rows in 2D, coordinate cuts below, and METIS whenever "
                                    "-contact_nested_dissection_parallel is given (an option of METIS's ordering)";
  PetscCall(OptionsChoice(PetscOptionsObject, "-contact_nested_dissection", ordering_help.c_str(),
                          "auto, metis or coordinates", GRAPH_ORDERING_NAMES, 3, ordering, &opts.ordering_set));
  opts.ordering.graph = (GraphOrdering)ordering;
  PetscBool parallel = opts.ordering.parallel ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool("-contact_nested_dissection_parallel",
                             "METIS's nested dissection on every rank (the partition's interfaces as the top "
                             "separators, each rank orders its own nodes) instead of the whole node graph on rank 0",
                             "", parallel, &parallel, &opts.parallel_set));
  opts.ordering.parallel = parallel;
  // The parallel option is one of METIS's ordering: given, it picks METIS where auto would cut across coordinates
  // (a small 2D matrix), instead of being ignored there.
  if (opts.parallel_set && opts.ordering.graph == GraphOrdering::AUTO) opts.ordering.graph = GraphOrdering::METIS;
  PetscInt kept_solver = (PetscInt)opts.kept_solver;
  char tolerance[32];
  std::snprintf(tolerance, sizeof(tolerance), "%g", SchurCholesky::PIVOT_TOLERANCE);
  const std::string kept_solver_help =
      "Who factors the displacement block of the kept factorisation: MUMPS, or signorini's supernodal Cholesky "
      "(multifrontal, without pivoting, serial: on several ranks rank 0 factors the gathered matrix; the Cholesky "
      "preset, the given ordering, no -contact_mat_mumps_ controls); auto: the Cholesky where it applies, up to " +
      std::to_string(CHOLESKY_MAX_ROWS) + " rows on one rank and " + std::to_string(CHOLESKY_MAX_ROWS_GATHERED) +
      " on several. A block that is not safely positive definite (a pivot not above " + tolerance +
      " of the largest diagonal entry: a body that the candidates do not hold, an svk tangent past a "
      "limit point) goes to MUMPS, whose null-pivot detection judges it";
  PetscCall(OptionsChoice(PetscOptionsObject, "-contact_kept_solver", kept_solver_help.c_str(),
                          "auto, mumps or cholesky", KEPT_SOLVER_NAMES, 3, kept_solver, &opts.kept_solver_set));
  opts.kept_solver = (KeptSolver)kept_solver;
  PetscInt path = (PetscInt)opts.path.path;
  PetscCall(OptionsChoice(PetscOptionsObject, "-contact_solver",
                          "The path that solves the saddle-point systems: direct (the kept factorisation: MUMPS or the "
                          "supernodal Cholesky), iterative (options/solver/fieldsplit_gamg.yml: a Schur fieldsplit, "
                          "GAMG on the displacement block), or auto: direct where its factorisation fits in "
                          "-contact_memory_budget and is estimated faster, else iterative (near the limits the "
                          "analysis of the matrix decides before the factorisation; a MUMPS factorisation out of "
                          "memory hands the run to the iterative path). A run's own "
                          "-contact_ksp_type, -contact_pc_type or kept-factorisation options decide instead; "
                          "-contact_* options refine either path",
                          "auto, direct or iterative", SOLVER_PATH_NAMES, 3, path, &opts.path.path_set));
  opts.path.path = (SolverPath)path;
  PetscCall(PetscOptionsBool("-contact_hierarchy_update",
                             "Iterative path, linear material: the displacement block's GAMG hierarchy follows the "
                             "active set, its coarse operators updated by the Galerkin images of the rows that "
                             "changed weight (one set-up per load step); false: set up again when more than 30 % of "
                             "the candidate rows changed weight, else kept as it is",
                             "", opts.hierarchy_update, &opts.hierarchy_update, nullptr));
  PetscCall(PetscOptionsBool("-contact_hierarchy_check",
                             "Diagnostic of -contact_hierarchy_update: after each update, the first coarse operator "
                             "against a new Galerkin product of the current block (-info prints their relative "
                             "difference; a product of the whole matrix per update)",
                             "", opts.hierarchy_check, &opts.hierarchy_check, nullptr));
  PetscInt product = (PetscInt)opts.galerkin_product;
  PetscCall(OptionsChoice(PetscOptionsObject, "-contact_gamg_product",
                          "Iterative path on several ranks: GAMG's first Galerkin product P^T A P by each rank's "
                          "sequential products of its own rows in chunks, the parts added (lean), or by PETSc's "
                          "product of parallel matrices (petsc), which keeps A P of each rank's rows: 7.7 instead of "
                          "5.3 GB per rank on a 4.1M-dof hexahedral cube on 2 ranks, the contact solve as fast; lean "
                          "also compacts GAMG's matrix of the aggregates' members on other ranks (the coarsener "
                          "signorini_misk, unless -contact_fieldsplit_u_mat_coarsen_type is given)",
                          "lean or petsc", GALERKIN_PRODUCT_NAMES, 2, product));
  opts.galerkin_product = (GalerkinProduct)product;
  PetscInt fine = (PetscInt)opts.fine_level;
  PetscCall(
      OptionsChoice(PetscOptionsObject, "-contact_nullspace_fine_level",
                    "Iterative path, the null-space preconditioner (-contact_pc_type nullspace): its displacement "
                    "block's multigrid smooths the finest level on the operator with the active rows eliminated "
                    "(the one the method solves) or on the augmented block; auto: eliminated for the linear "
                    "material, augmented for svk",
                    "auto, eliminated or augmented", SaddlePointOptions::FINE_LEVEL_NAMES, 3, fine));
  opts.fine_level = (SaddlePointOptions::FineLevel)fine;
  char weight_help[512];
  std::snprintf(weight_help, sizeof(weight_help),
                "Iterative path: the augmentation weight r of an active row (K + r B_A^T B_A) as a multiple of K's "
                "mean diagonal entry on the candidate rows, at least the mean diagonal entry of an element stiffness "
                "(inactive rows: a hundredth of that element scale); 0: r is the element scale (the direct path's "
                "weight; a tenth of an assembled entry on a tetrahedral mesh's surface); default %g in 3D without "
                "friction, else 0; range [0, 100]",
                SaddlePointOptions::AUGMENTATION_WEIGHT_3D);
  PetscCall(PetscOptionsReal("-contact_augmentation_weight", weight_help, "", opts.augmentation_weight,
                             &opts.augmentation_weight, &opts.augmentation_weight_set));
  PetscCheck((opts.augmentation_weight >= 0 && opts.augmentation_weight <= 100), comm, PETSC_ERR_USER_INPUT,
             "-contact_augmentation_weight %g: expected a number in [0, 100] (0: the element stiffness scale)",
             (double)opts.augmentation_weight);
  std::string budget;
  PetscCall(OptionsString(PetscOptionsObject, "-contact_memory_budget",
                          "Memory per rank that -contact_solver auto lets a factorisation use (bytes, or with a unit "
                          "k, M, G, T: 512M, 1.5G); default: the memory available at the start, shared by the node's "
                          "ranks, less a tenth",
                          "a memory size such as 512M or 1.5G", budget, &opts.path.budget_set));
  PetscCheck(!opts.path.budget_set || ParseMemorySize(budget, opts.path.budget), comm, PETSC_ERR_USER_INPUT,
             "-contact_memory_budget %s: expected a memory size: a positive number of bytes with an optional unit "
             "k, M, G or T (powers of 1024), such as 512M or 1.5G",
             budget.c_str());
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Create(const DofMap &dofs, const std::vector<SparseRow> &rows,
                                         const std::vector<double> &coords, bool constant_k, double kscale,
                                         const std::vector<PetscInt> &d_nnz_k, const std::vector<PetscInt> &o_nnz_k,
                                         const std::function<PetscErrorCode(Mat)> &insert_k) {
  MPI_Comm comm = PetscObjectComm((PetscObject)dofs.IsU());
  PetscFunctionBeginUser;
  dofs_ = &dofs;
  aug_ = kscale;
  aug_inactive_ = kscale;
  bool applies;
  std::string why_not;
  PetscCall(NullSpaceApplies(rows, applies, why_not));
  nullspace_ = applies && dofs.Dim() == 3; // the default's choice (CreateKsp); 2D keeps the fieldsplit's paths
  bool fieldsplit;
  PetscCall(CreateKsp(comm, fieldsplit));
  PetscCheck(!nullspace_ || why_not.empty(), comm, PETSC_ERR_USER_INPUT,
             "-contact_pc_type " PCNULLSPACE " does not apply to this problem: %s; expected -contact_pc_type "
             "fieldsplit (-options_file options/solver/fieldsplit_gamg.yml) or a direct solver",
             why_not.c_str());
  nest_.on = fieldsplit && dofs.GlobalLambda() > 0;
  if (nest_.on) {
    PetscCall(CreateNest(rows, d_nnz_k, o_nnz_k, insert_k));
  } else {
    PetscCall(MatCreate(comm, A_.out()));
    PetscCall(MatSetType(A_, MATAIJ));
    PetscCall(MatSetSizes(A_, dofs.OwnedRows(), dofs.OwnedRows(), dofs.GlobalRows(), dofs.GlobalRows()));
    // Without multipliers a fieldsplit's displacement block is this whole matrix: its node blocks (bs = dim) let
    // GAMG coarsen it as elasticity (as the nested matrix's block has them; without, a 108k-dof cube's first coarse
    // level was 4 times larger and its solve 9 times slower; test elastic_fieldsplit_block_size). Other solvers get
    // block size 1: GAMG on the whole matrix with node blocks left a true residual of 1e-6 on the 2-rank cantilever
    // (test elastic_gamg), against 1e-10 unblocked.
    if (fieldsplit) PetscCall(MatSetBlockSizes(A_, dofs.Dim(), dofs.Dim()));
    std::vector<PetscInt> d_nnz, o_nnz;
    PetscCall(RowCounts(rows, d_nnz_k, o_nnz_k, d_nnz, o_nnz));
    PetscCall(MatSeqAIJSetPreallocation(A_, 0, d_nnz.data()));
    PetscCall(MatMPIAIJSetPreallocation(A_, 0, d_nnz.data(), 0, o_nnz.data()));
    // The pattern: zeros inserted at every entry of K and of the constraint rows (the counts hold them all; an entry
    // beyond them would be allocated then), compressed by the final assembly and fixed from then on.
    PetscCall(MatSetOption(A_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
    PetscCall(insert_k(A_.get()));
    PetscCall(CreatePattern(rows, A_));
    PetscCall(MatSetOption(A_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(MatSetOption(A_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  }
  PetscCall(MatSetOption(A_, MAT_SYMMETRIC, nonsymmetric_.empty() ? PETSC_TRUE : PETSC_FALSE));
  PetscCall(MatSetOption(A_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PetscCall(PetscObjectSetName((PetscObject)A_.get(), "saddle_point"));
  PetscCall(MatCreateVecs(A_, x_.out(), b_.out()));
  PetscCall(VecDuplicate(b_, r_.out()));
  PetscCall(SetupKsp(coords, constant_k));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CreateNest(const std::vector<SparseRow> &rows,
                                             const std::vector<PetscInt> &d_nnz_k, const std::vector<PetscInt> &o_nnz_k,
                                             const std::function<PetscErrorCode(Mat)> &insert_k) {
  MPI_Comm comm = PetscObjectComm((PetscObject)dofs_->IsU());
  const PetscInt nu = dofs_->OwnedU(), nl = dofs_->OwnedLambda(), gu = dofs_->GlobalU(), gl = dofs_->GlobalLambda();
  const PetscInt start = dofs_->RowStart();
  const auto mine = [&](PetscInt c) { return c >= start && c < start + nu; };
  const auto create = [&](PetscInt m, PetscInt n, PetscInt gm, PetscInt gn, const std::vector<PetscInt> &d_nnz,
                          const std::vector<PetscInt> &o_nnz, MatH &M) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(MatCreate(comm, M.out()));
    PetscCall(MatSetType(M, MATAIJ));
    PetscCall(MatSetSizes(M, m, n, gm, gn));
    PetscCall(MatSeqAIJSetPreallocation(M, 0, d_nnz.data()));
    PetscCall(MatMPIAIJSetPreallocation(M, 0, d_nnz.data(), 0, o_nnz.data()));
    // An entry beyond the counts (rows shared between ranks) is allocated when it is set; the pattern is then fixed.
    PetscCall(MatSetOption(M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
    PetscFunctionReturn(0);
  };
  PetscFunctionBeginUser;
  // The displacement block: K's pattern, node blocks of dim (as PCFIELDSPLIT's copy of it had them, for GAMG).
  PetscCall(create(nu, nu, gu, gu, d_nnz_k, o_nnz_k, nest_.K));
  PetscCall(MatSetBlockSizes(nest_.K, dofs_->Dim(), dofs_->Dim()));
  PetscCall(insert_k(nest_.K.get()));
  // B (rows: this rank's multipliers) and B^T (rows: displacement rows, the entries of other ranks' rows counted).
  std::vector<PetscInt> b_d(nl, 0), b_o(nl, 0), bt_d(nu, 0), bt_o(nu, 0), d_d(nl, 1), d_o(nl, 0);
  for (std::size_t p = 0; p < rows.size(); ++p)
    for (PetscInt i = 0; i < rows[p].ncols; ++i) {
      const PetscInt c = rows[p].cols[i];
      (mine(c) ? b_d[p] : b_o[p]) += 1;
      if (mine(c)) bt_d[c - start] += 1;
    }
  std::vector<PetscInt> remote;
  PetscCall(RemoteTransposed(rows, remote));
  for (PetscInt i = 0; i < nu; ++i)
    bt_o[i] = remote[i];
  PetscCall(create(nl, nu, gl, gu, b_d, b_o, nest_.B));
  PetscCall(create(nu, nl, gu, gl, bt_d, bt_o, nest_.Bt));
  PetscCall(create(nl, nl, gl, gl, d_d, d_o, nest_.D));
  for (std::size_t p = 0; p < rows.size(); ++p)
    PetscCall(SetRow(rows[p], (PetscInt)p, std::vector<PetscScalar>(rows[p].ncols, 0.0).data(), 0.0));
  for (Mat M : {nest_.K.get(), nest_.B.get(), nest_.Bt.get(), nest_.D.get()}) {
    PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSetOption(M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(MatSetOption(M, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  }
  PetscCall(MatSetOption(nest_.K, MAT_SYMMETRIC, nonsymmetric_k_ ? PETSC_FALSE : PETSC_TRUE));
  PetscCall(MatSetOption(nest_.K, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  IS is[2] = {dofs_->IsU(), dofs_->IsLambda()};
  Mat blocks[4] = {nest_.K, nest_.Bt, nest_.B, nest_.D};
  PetscCall(MatCreateNest(comm, 2, is, 2, is, blocks, A_.out()));
  // Standard vectors in the layout of the whole system (each rank: its displacement rows, then its multipliers).
  PetscCall(MatNestSetVecType(A_, VECSTANDARD));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetRow(const SparseRow &row, PetscInt p, const PetscScalar *coef,
                                         PetscScalar d, const PetscScalar *column) {
  PetscFunctionBeginUser;
  if (!column) column = coef;
  if (!nest_.on) {
    const PetscInt r = dofs_->LambdaRow(p);
    PetscCall(MatSetValues(A_, 1, &r, row.ncols, row.cols.data(), coef, INSERT_VALUES));
    PetscCall(MatSetValues(A_, row.ncols, row.cols.data(), 1, &r, column, INSERT_VALUES));
    PetscCall(MatSetValue(A_, r, r, d, INSERT_VALUES));
    PetscFunctionReturn(0);
  }
  const PetscInt r = dofs_->LambdaBlockRow(p);
  std::vector<PetscInt> cols(row.ncols);
  for (PetscInt i = 0; i < row.ncols; ++i) cols[i] = dofs_->UBlockRow(row.cols[i]);
  PetscCall(MatSetValues(nest_.B, 1, &r, row.ncols, cols.data(), coef, INSERT_VALUES));
  PetscCall(MatSetValues(nest_.Bt, row.ncols, cols.data(), 1, &r, column, INSERT_VALUES));
  PetscCall(MatSetValue(nest_.D, r, r, d, INSERT_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CreateKsp(MPI_Comm comm, bool &nested) {
  PC pc;
  PetscBool is_fieldsplit, is_nullspace;
  PetscFunctionBeginUser;
  PetscCall(PCNullSpaceRegister());
  PetscCall(KSPCreate(comm, ksp_.out()));
  PetscCall(SetDefaultSolver(ksp_, path_, !nonsymmetric_.empty(), nullspace_));
  PetscCall(KSPSetFromOptions(ksp_));
  // Every solve must end within ACCEPTED_RESIDUAL (CheckAndConvert): a looser Krylov tolerance would only fail after
  // the solve. The iterative presets take 1e-10 (PETSc reads no tolerance for KSPPREONLY, the direct presets).
  PetscReal rtol;
  PetscCall(KSPGetTolerances(ksp_, &rtol, nullptr, nullptr, nullptr));
  PetscCheck(rtol <= ACCEPTED_RESIDUAL, comm, PETSC_ERR_USER_INPUT,
             "-contact_ksp_rtol %.6g: a saddle-point solve must leave a relative residual of at most %.6g; expected a "
             "value in [0, %.6g] (the solver presets take 1e-10)",
             (double)rtol, ACCEPTED_RESIDUAL, ACCEPTED_RESIDUAL);
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &is_fieldsplit));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCNULLSPACE, &is_nullspace));
  nested = is_fieldsplit || is_nullspace;
  nullspace_ = is_nullspace;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::NullSpaceApplies(const std::vector<SparseRow> &rows, bool &applies,
                                                   std::string &why) const {
  MPI_Comm comm = PetscObjectComm((PetscObject)dofs_->IsU());
  PetscFunctionBeginUser;
  // The null-space method eliminates each node's active rows with the node's own dofs (a small Gram matrix per node):
  // a rigid obstacle's pair. A mortar row couples a slave node with master nodes; friction's rows make the matrix
  // nonsymmetric. In 2D the fieldsplit keeps the paths its cases were measured with.
  const PetscInt first = dofs_->RowStart(), end = first + dofs_->OwnedU();
  const int dim = dofs_->Dim();
  PetscBool local = PETSC_TRUE;
  for (const SparseRow &row : rows)
    for (PetscInt c : row.cols)
      if (c < first || c >= end || (c - first) / dim != (row.cols[0] - first) / dim) local = PETSC_FALSE;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &local, 1, MPIU_BOOL, MPI_LAND, comm));
  why.clear();
  if (dofs_->GlobalLambda() == 0)
    why = "it has no contact candidates";
  else if (!local)
    why = "a contact row couples several nodes (a contact between bodies)";
  else if (!nonsymmetric_.empty() || tangential_from_ >= 0)
    why = "friction makes the matrix nonsymmetric";
  applies = why.empty();
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::DisplacementKsp(KSP &u) const {
  PC pc;
  PetscBool fieldsplit;
  PetscFunctionBeginUser;
  u = nullptr;
  PetscCall(KSPGetPC(ksp_, &pc));
  if (nullspace_) {
    PetscCall(PCNullSpaceGetSubKSP(pc, &u));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit || !ksp_set_up_) PetscFunctionReturn(0);
  KSP *sub;
  PetscInt n;
  PetscCall(PCFieldSplitGetSubKSP(pc, &n, &sub));
  if (n > 0) u = sub[0];
  PetscCall(PetscFree(sub));
  PetscFunctionReturn(0);
}

namespace {

/// "-contact_nested_dissection <graph>" or "-contact_nested_dissection_parallel <true|false>" as opts has it, for
/// messages.
std::string OrderingOptionText(const SaddlePointOptions &opts, bool parallel) {
  return parallel ? std::string("-contact_nested_dissection_parallel ") + (opts.ordering.parallel ? "true" : "false")
                  : std::string("-contact_nested_dissection ") + GRAPH_ORDERING_NAMES[(int)opts.ordering.graph];
}

} // namespace

PetscErrorCode SaddlePointSystem::SetupKsp(const std::vector<double> &coords, bool constant_k) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PC pc;
  PetscFunctionBeginUser;
  PetscCall(KSPSetOperators(ksp_, A_, A_));
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(SetNearNullSpace(comm, coords));
  PetscBool preonly;
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp_.get(), KSPPREONLY, &preonly));
  preonly_ = preonly;
  if (!preonly_) PetscCall(KSPConvergedDefaultSetUIRNorm(ksp_)); // relative to the start's residual (InitialGuess)
  PetscBool fieldsplit;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (fieldsplit) {
    PetscCall(PCFieldSplitSetIS(pc, "u", dofs_->IsU()));
    PetscCall(PCFieldSplitSetIS(pc, "lambda", dofs_->IsLambda()));
  }
  if ((fieldsplit || nullspace_) && dofs_->Dim() == 3) PetscCall(SetGamgDefaults3d());
  PetscBool factor;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  if (factor) PetscCall(SetupMumpsFactor(comm, pc));
  SaddlePointOptions opts;
  PetscCall(ReadSaddlePointOptions(comm, opts));
  PetscCall(CheckReuseOptions(comm, opts, constant_k));
  if (!nonsymmetric_.empty()) {
    // A nonsymmetric matrix: a factorisation with pivoting of the plain form at every change, or a Krylov method for
    // nonsymmetric matrices (BiCGStab, GMRES, ...) with a preconditioner that does not assume symmetry.
    PetscBool symmetric_pc, symmetric_ksp;
    PCType type;
    KSPType ksp_type;
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &symmetric_pc, PCCHOLESKY, PCICC, ""));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)ksp_.get(), &symmetric_ksp, KSPCG, KSPPIPECG, KSPCR, KSPPIPECR,
                                        KSPMINRES, KSPSYMMLQ, KSPFCG, KSPPIPEFCG, KSPGROPPCG, KSPNASH, KSPSTCG,
                                        KSPGLTR, KSPQCG, ""));
    PetscCall(PCGetType(pc, &type));
    PetscCall(KSPGetType(ksp_, &ksp_type));
    PetscCheck(!symmetric_pc && !symmetric_ksp, comm, PETSC_ERR_USER_INPUT,
               "%s makes the saddle-point matrix nonsymmetric, which the given solver (-contact_ksp_type %s "
               "-contact_pc_type %s) cannot solve; expected an LU factorisation (no solver option, or -options_file "
               "options/solver/mumps_lu.yml) or a Krylov method for nonsymmetric matrices (-options_file "
               "options/solver/fieldsplit_gamg.yml: BiCGStab; or -contact_ksp_type gmres)",
               nonsymmetric_.c_str(), ksp_type, type);
    PetscCheck(!(opts.reuse_set && opts.reuse_factorization && !constant_k), comm, PETSC_ERR_USER_INPUT,
               "-contact_reuse_factorization with %s and -material_model svk: the kept factorisation of friction's "
               "rows needs a constant stiffness (the linear material); expected -contact_reuse_factorization 0 or no "
               "such option", nonsymmetric_.c_str());
  }
  const bool possible = mumps_factor_ != nullptr;
  // Friction keeps the factorisation for a constant K: of fixed rows, onto which its rows are mapped (KeptRows).
  reuse_ = possible && opts.reuse_factorization && dofs_->GlobalLambda() > 0 && (nonsymmetric_.empty() || constant_k);
  turned_ = reuse_ && !nonsymmetric_.empty();
  // PETSc's MUMPS interface takes no given ordering (it would stop at the factorisation).
  PetscCheck(!(possible && !reuse_ && mumps_controls_.Icntl(7, 7) == 1), comm, PETSC_ERR_USER_INPUT,
             "-contact_mat_mumps_icntl_7 1 (the given nested dissection) applies to the kept factorisation only "
             "(-contact_reuse_factorization with contact candidates); expected 0, 2, 4, 6 or 7, one of MUMPS's own "
             "orderings");
  kept_.ordering_given.clear();
  if (opts.ordering_set) kept_.ordering_given = OrderingOptionText(opts, false);
  if (opts.parallel_set)
    kept_.ordering_given += (kept_.ordering_given.empty() ? "" : " and ") + OrderingOptionText(opts, true);
  kept_.forced = reuse_ && (opts.reuse_set || opts.reuse_max_it_set);
  constant_k_ = constant_k;
  kept_.max_it = opts.reuse_max_it;
  hierarchy_update_ = opts.hierarchy_update, hierarchy_check_ = opts.hierarchy_check;
  lean_product_ = opts.galerkin_product == GalerkinProduct::LEAN;
  if (nest_.on && nest_.K && lean_product_) PetscCall(LeanPtAPAttach(nest_.K));
  if (!factor && lean_product_) PetscCall(LeanCoarsenDefault());
  // An iterative solver gets the augmented form too: its displacement block K + r B_C^T B_C is regular when the
  // candidates hold the body, so that a Schur fieldsplit with AMG on that block works for a body held by contact.
  // Friction's kept factorisation is of a fixed augmented matrix of its own (FactorFixedRows): A stays plain.
  augmented_ = (reuse_ && !turned_) || (!factor && dofs_->GlobalLambda() > 0);
  // Its inactive rows get a smaller weight (INACTIVE_WEIGHT; NULLSPACE_INACTIVE_WEIGHT for the null-space
  // preconditioner of the linear material); the kept factorisation needs a constant block.
  const bool light = nullspace_ && constant_k_;
  // The null-space preconditioner smooths its multigrid's finest level on the eliminated operator for the linear
  // material only, unless -contact_nullspace_fine_level says otherwise: svk's tangents may stop being positive
  // definite, and on the 3D survey's case 18 (test krylov_fallback_restart) its Newton steps then took another course
  // than the direct path's.
  if (nullspace_) {
    PC pc;
    PetscCall(KSPGetPC(ksp_, &pc));
    const bool eliminated = opts.fine_level == SaddlePointOptions::FineLevel::AUTO
                                ? constant_k_
                                : opts.fine_level == SaddlePointOptions::FineLevel::ELIMINATED;
    PetscCall(PCNullSpaceSetFineLevel(pc, eliminated));
  }
  if (augmented_ && !reuse_) aug_inactive_ = (light ? NULLSPACE_INACTIVE_WEIGHT : INACTIVE_WEIGHT) * aug_;
  // The iterative path's weight relative to K's diagonal (IterativeWeight); by default in 3D without friction: in 2D
  // the element scale is already a third to a half of an assembled entry and the measured paths moved either way
  // (IterativeWeight), and friction's tangential rows keep the weights their cases were measured with.
  double relative = opts.augmentation_weight;
  if (!opts.augmentation_weight_set) relative = dofs_->Dim() == 3 && tangential_from_ < 0 ? relative : 0.0;
  aug_relative_ = augmented_ && !reuse_ ? relative : 0.0;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &lu_));
  PetscCall(CheckKeptSolver(comm, opts, possible));
  kept_.solver = opts.kept_solver;
  kept_.solver_set = opts.kept_solver_set;
  if (reuse_) {
    kept_.coords = coords;
    kept_.ordering = opts.ordering;
    PetscCall(GatherSchurRows(comm));
  }
  if (reuse_ && !constant_k_ && kept_.max_it > 0) PetscCall(CreateKeptKsp(comm));
  // The solver is chosen: an option that it will never read is refused now, not after the whole solve.
  PetscCall(RefuseSolverOptionsNotRead(ksp_, reuse_));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::KrylovIsCg(bool &cg) const {
  PetscBool is_cg = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (ksp_) PetscCall(PetscObjectTypeCompare((PetscObject)ksp_.get(), KSPCG, &is_cg));
  cg = is_cg;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetNearNullSpace(MPI_Comm comm, const std::vector<double> &coords) {
  PetscFunctionBeginUser;
  // Rigid-body modes of the displacement block, offered to fieldsplit's "u" solver as its near-null space.
  VecH xyz;
  const int dim = dofs_->Dim();
  PetscCall(VecCreateMPI(comm, dofs_->OwnedU(), PETSC_DECIDE, xyz.out()));
  PetscCall(VecSetBlockSize(xyz, dim));
  PetscScalar *a;
  PetscCall(VecGetArray(xyz, &a));
  for (PetscInt i = 0; i < dofs_->OwnedU(); ++i) a[i] = coords[i];
  PetscCall(VecRestoreArray(xyz, &a));
  PetscCall(MatNullSpaceCreateRigidBody(xyz, near_null_.out()));
  PetscCall(PetscObjectCompose((PetscObject)dofs_->IsU(), "nearnullspace", (PetscObject)near_null_.get()));
  if (dofs_->GlobalLambda() == 0) PetscCall(MatSetNearNullSpace(A_, near_null_));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetupMumpsFactor(MPI_Comm comm, PC pc) {
  PetscFunctionBeginUser;
  // A direct MUMPS factorisation detects null pivots (ICNTL(24)): a body that nothing holds yet is then an error
  // instead of a solution with an arbitrary rigid motion.
  MatSolverType type;
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscBool mumps = PETSC_FALSE;
  if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (mumps) {
    // The factor's options (-contact_mat_mumps_*) have the PC's prefix: PCSetUp would give it, but the factor is
    // created here, and the options were read (CreateKsp) before the matrix existed.
    const char *prefix;
    PetscCall(PCGetOptionsPrefix(pc, &prefix));
    PetscCall(MatSetOptionsPrefixFactor(A_, prefix));
    PetscCall(PCFactorSetUpMatSolverType(pc));
    PetscCall(PCFactorGetMatrix(pc, &mumps_factor_));
    PetscCall(MatMumpsSetIcntl(mumps_factor_, 24, 1));
    // A pivot below 1e-12 ||A|| is null: MUMPS's default (1e-5 eps ||A||) misses the rigid modes of 2D
    // elasticity; -contact_mat_mumps_cntl_3 overrides.
    PetscCall(MatMumpsSetCntl(mumps_factor_, 3, 1e-12));
    // MUMPS_WORKSPACE_INCREASE % over the analysis' workspace estimate (MUMPS's default 20 %): LDL^T pivots
    // differently from run to run in parallel, and a 3D hexahedral mesh then stopped about every other 2-rank run
    // with INFOG(1) = -9 (workspace too small); -contact_mat_mumps_icntl_14 overrides.
    PetscCall(MatMumpsSetIcntl(mumps_factor_, 14, MUMPS_WORKSPACE_INCREASE));
    PetscCall(ReadMumpsControls(comm, mumps_controls_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CheckReuseOptions(MPI_Comm comm, const SaddlePointOptions &opts,
                                                    bool constant_k) const {
  PetscFunctionBeginUser;
  const bool possible = mumps_factor_ != nullptr;
  PetscCheck(!(opts.reuse_set && opts.reuse_factorization && !possible), comm, PETSC_ERR_USER_INPUT,
             "-contact_reuse_factorization needs a MUMPS LU or Cholesky solver (-contact_pc_type lu|cholesky "
             "-contact_pc_factor_mat_solver_type mumps)");
  PetscCheck(!(opts.reuse_max_it_set && (constant_k || !possible || !opts.reuse_factorization)), comm,
             PETSC_ERR_USER_INPUT,
             "-contact_reuse_max_it %" PetscInt_FMT " applies to a nonlinear material (-material_model svk) with the "
             "kept factorisation (-contact_reuse_factorization and a MUMPS LU or Cholesky solver)", opts.reuse_max_it);
  // The pivot order is computed only for the kept factorisation (MumpsSchur), and only when MUMPS is told to take it:
  // otherwise PETSc's MUMPS interface orders by ICNTL(7) alone and these options would be ignored.
  const PetscInt icntl7 = mumps_controls_.Icntl(7, 1);
  const std::string ordering = OrderingOptionText(opts, false), parallel = OrderingOptionText(opts, true);
  for (const auto &[set, given] : {std::make_pair(opts.ordering_set, &ordering),
                                   std::make_pair(opts.parallel_set, &parallel)}) {
    PetscCheck(!set || (possible && opts.reuse_factorization), comm, PETSC_ERR_USER_INPUT,
               "%s applies to the kept MUMPS factorisation only (-contact_reuse_factorization with a MUMPS LU or "
               "Cholesky solver, the default)", given->c_str());
    PetscCheck(!set || icntl7 == 1, comm, PETSC_ERR_USER_INPUT,
               "%s does not apply with -contact_mat_mumps_icntl_7 %" PetscInt_FMT " (one of MUMPS's own orderings); "
               "expected -contact_mat_mumps_icntl_7 1, or no %s", given->c_str(), icntl7,
               given->substr(0, given->find(' ')).c_str());
  }
  PetscCheck(!(opts.parallel_set && opts.ordering_set && opts.ordering.graph == GraphOrdering::COORDINATES), comm,
             PETSC_ERR_USER_INPUT, "-contact_nested_dissection_parallel applies to METIS's ordering only, not to "
             "-contact_nested_dissection coordinates");
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CheckKeptSolver(MPI_Comm comm, const SaddlePointOptions &opts,
                                                  bool possible) const {
  PetscFunctionBeginUser;
  const char *name = KEPT_SOLVER_NAMES[(int)opts.kept_solver];
  PetscCheck(!opts.kept_solver_set || (possible && opts.reuse_factorization), comm, PETSC_ERR_USER_INPUT,
             "-contact_kept_solver %s applies to the kept factorisation only (-contact_reuse_factorization with a "
             "MUMPS LU or Cholesky solver, the default)", name);
  if (opts.kept_solver != KeptSolver::CHOLESKY) PetscFunctionReturn(0);
  PetscCheck(!lu_ || turned_, comm, PETSC_ERR_USER_INPUT,
             "-contact_kept_solver cholesky factors a symmetric matrix; expected the Cholesky preset "
             "(-contact_pc_type cholesky, the default), not LU, or -contact_kept_solver mumps");
  PetscCheck(mumps_controls_.icntl.empty() && mumps_controls_.cntl.empty(), comm, PETSC_ERR_USER_INPUT,
             "-contact_kept_solver cholesky takes no MUMPS controls (-contact_mat_mumps_icntl_<k>, _cntl_<k>: they "
             "would not apply); expected -contact_kept_solver mumps with them, or none of them");
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::GatherSchurRows(MPI_Comm comm) {
  PetscFunctionBeginUser;
  // The Schur complement on every multiplier row, centralised on rank 0 (what PETSc's MUMPS interface supports in
  // parallel): rank 0 lists all of them, in global order.
  PetscMPIInt size, rank;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<PetscInt> mine(dofs_->OwnedLambda()), all;
  for (PetscInt p = 0; p < dofs_->OwnedLambda(); ++p) mine[p] = dofs_->LambdaRow(p);
  PetscMPIInt n = (PetscMPIInt)mine.size();
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  if (rank == 0) {
    for (PetscMPIInt r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    all.resize(dofs_->GlobalLambda());
  }
  PetscCallMPI(MPI_Gatherv(mine.data(), n, MPIU_INT, all.data(), counts.data(), displs.data(), MPIU_INT, 0, comm));
  schur_rows_ = all;
  PetscCall(VecCreateMPI(comm, dofs_->OwnedLambda(), PETSC_DECIDE, diag_lambda_.out()));
  PetscCall(VecScatterCreateToZero(diag_lambda_, &to_root_, diag_root_.out()));
  active_.assign(dofs_->OwnedLambda(), 0);
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CreateKeptKsp(MPI_Comm comm) {
  PetscFunctionBeginUser;
  // FGMRES on the current matrix, right-preconditioned by the kept factorisation: the residual it tests is the true
  // one (tolerances: SolveWithKeptFactor).
  PC kept;
  PetscCall(KSPCreate(comm, ksp_kept_.out()));
  PetscCall(KSPSetType(ksp_kept_, KSPFGMRES)); // keeps the preconditioned directions: no apply to form the solution
  PetscCall(KSPGMRESSetRestart(ksp_kept_, kept_.max_it));
  PetscCall(KSPSetPCSide(ksp_kept_, PC_RIGHT));
  PetscCall(KSPSetResidualHistory(ksp_kept_, nullptr, kept_.max_it + 1, PETSC_TRUE));
  PetscCall(KSPSetNormType(ksp_kept_, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetOperators(ksp_kept_, A_, A_));
  PetscCall(KSPGetPC(ksp_kept_, &kept));
  PetscCall(PCKeptRegister());
  PetscCall(PCSetType(kept, PCKEPT));
  PetscCall(PCKeptSetFactorization(kept, &mumps_schur_, "an earlier tangent"));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::AddAugmentation(const std::vector<SparseRow> &rows) {
  PetscFunctionBeginUser;
  if (aug_relative_ > 0) PetscCall(IterativeWeight(rows));
  // The weights of the current active set (an iterative solver's inactive rows: r_I), so that SetConstraints only
  // changes the rows whose state changes.
  std::vector<double> weight(rows.size(), aug_);
  for (std::size_t p = 0; p < rows.size() && p < active_.size(); ++p)
    if (!(p < heavy_.size() ? heavy_[p] : active_[p])) weight[p] = aug_inactive_;
  weight_.assign(rows.size(), 0.0);
  PetscCall(Reweight(rows, weight));
  if (nest_.on && constant_k_ && hierarchy_update_) aug_rows_ = rows; // UpdateGalerkin's (a K that stays)
  pc_current_ = false; // after an assembly of K
  // A new tangent (svk) keeps the displacement block's preconditioner of an earlier one while its solves stay cheap
  // (SolveKsp, LAGGED_U_PC_GROWTH): the Newton iterations' tangents differ little.
  if (constant_k_) u_pc_.valid = false;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::IterativeWeight(const std::vector<SparseRow> &rows) {
  PetscFunctionBeginUser;
  // The Schur complement of an active row is b (K + r B_A^T B_A)^-1 b^T, between about 1/(k + r) for a pressure that
  // changes from node to node (k = b diag(K) b^T) and 1/r for a smooth one, and selfp's diagonal is 1/(k + r): with r
  // the mean element diagonal entry (a tenth of k on a tetrahedral mesh's surface, a third in 2D) the preconditioned
  // Schur complement spreads over a factor of about 10, with r near k over about 2, while GAMG on K + r B_A^T B_A loses
  // more the larger r is. Measured (the octant Hertz at 290k dofs, one rank, iterative path): r as the element scale
  // times 1, 2, 5, 10, 20, 50 took 53, 39, 36, 38, 49, 100 Krylov iterations (4, 4, 4, 5, 6, 9 active-set
  // iterations); r = 0.5 of the candidate rows' mean diagonal entry is about 5 times that scale there (40 Krylov
  // iterations; at 1.07M dofs 41 instead of 58, 87 V-cycles instead of 122).
  // The weighted mean sum_j c_j K_jj / sum_j c_j, c_j the sum of the candidate rows' squared coefficients on dof j,
  // of the block as assembled (before any augmentation: the first AddAugmentation after K's first assembly).
  Mat K = Stiffness();
  VecH diag, c;
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY)); // the element matrices' additions (SetConstraints' later)
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(K, diag.out(), nullptr));
  PetscCall(VecDuplicate(diag, c.out()));
  PetscCall(MatGetDiagonal(K, diag));
  PetscCall(VecSet(c, 0.0));
  for (const SparseRow &row : rows)
    for (PetscInt i = 0; i < row.ncols; ++i)
      PetscCall(VecSetValue(c, nest_.on ? dofs_->UBlockRow(row.cols[i]) : row.cols[i], row.coef[i] * row.coef[i],
                            ADD_VALUES));
  PetscCall(VecAssemblyBegin(c));
  PetscCall(VecAssemblyEnd(c));
  PetscScalar num, den;
  PetscCall(VecDot(c, diag, &num));
  PetscCall(VecSum(c, &den));
  const double mean = (double)(num / std::max<PetscScalar>(den, 1e-300));
  const double r = std::max(aug_, aug_relative_ * mean); // never below the element scale (r > r_I)
  PetscCall(PetscInfo(nullptr,
                      "iterative augmentation weight r = %.6g (%.6g of the candidates' mean diagonal entry %.6g, at "
                      "least the element scale %.6g)\n",
                      r, aug_relative_, mean, aug_));
  // The inactive rows keep r_I, INACTIVE_WEIGHT times the element scale: scaled with r they made the elastic
  // reference of the octant at 1.07M dofs (no active pair) take 22 Krylov iterations instead of 14 (selfp's 1/r_I
  // misjudges an inactive row's Schur complement 1/(r_I (1 + r_I mu)), mu its compliance, the more the larger r_I).
  aug_ = r;
  aug_relative_ = 0; // once per run: the weights that K carries and the multipliers' conversion stay consistent
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Reweight(const std::vector<SparseRow> &rows, const std::vector<double> &weight) {
  PetscFunctionBeginUser;
  // Adds (w_new - w_old) B_p^T B_p: the rows must have the coefficients AddAugmentation added them with (they change
  // only with a new assembly of K, which AddAugmentation follows).
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const SparseRow &row = rows[p];
    const double dw = weight[p] - weight_[p];
    if (dw == 0) continue;
    std::vector<PetscScalar> v(row.ncols * row.ncols);
    std::vector<PetscInt> cols(row.ncols);
    for (PetscInt i = 0; i < row.ncols; ++i) {
      cols[i] = nest_.on ? dofs_->UBlockRow(row.cols[i]) : row.cols[i];
      for (PetscInt j = 0; j < row.ncols; ++j) v[i * row.ncols + j] = dw * row.coef[i] * row.coef[j];
    }
    PetscCall(MatSetValues(Stiffness(), row.ncols, cols.data(), row.ncols, cols.data(), v.data(), ADD_VALUES));
    weight_[p] = weight[p];
  }
  PetscCall(MatAssemblyBegin(Stiffness(), MAT_FLUSH_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Stiffness(), MAT_FLUSH_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::StiffnessTimesApplies(const std::vector<SparseRow> &rows, bool &applies) const {
  const PetscInt nu = dofs_->OwnedU(), start = dofs_->RowStart();
  PetscFunctionBeginUser;
  // The nested block is K + sum_p w_p B_p^T B_p (Reweight keeps weight_ to what it holds) as long as no stabilisation,
  // no row's D and no column of its own changed the system (friction, svk's mortar tangent), and K is constant.
  bool possible = nest_.on && augmented_ && !reuse_ && constant_k_ && stab_ == 0 && weight_.size() == rows.size();
  for (double d : aug_diag_)
    possible = possible && d == 0;
  for (const SparseRow &extra : col_extra_)
    possible = possible && extra.ncols == 0;
  for (const SparseRow &row : rows)
    for (PetscInt i = 0; i < row.ncols && possible; ++i)
      possible = row.cols[i] >= start && row.cols[i] < start + nu;
  PetscCallMPI(MPI_Allreduce(&possible, &applies, 1, MPI_CXX_BOOL, MPI_LAND, PetscObjectComm((PetscObject)A_.get())));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::StiffnessTimes(const std::vector<SparseRow> &rows, const PetscScalar *du,
                                                 std::vector<double> &y) {
  const PetscInt nu = dofs_->OwnedU(), start = dofs_->RowStart();
  PetscFunctionBeginUser;
  VecH kx, ky;
  PetscCall(MatCreateVecs(nest_.K, kx.out(), ky.out()));
  PetscScalar *a;
  PetscCall(VecGetArrayWrite(kx, &a));
  std::copy(du, du + nu, a);
  PetscCall(VecRestoreArrayWrite(kx, &a));
  PetscCall(MatMult(nest_.K, kx, ky));
  const PetscScalar *b;
  PetscCall(VecGetArrayRead(ky, &b));
  y.assign(b, b + nu);
  PetscCall(VecRestoreArrayRead(ky, &b));
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const SparseRow &row = rows[p];
    double bu = 0;
    for (PetscInt i = 0; i < row.ncols; ++i)
      bu += row.coef[i] * du[row.cols[i] - start];
    for (PetscInt i = 0; i < row.ncols; ++i)
      y[row.cols[i] - start] -= weight_[p] * row.coef[i] * bu;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::ToRoot(const std::vector<double> &owned, std::vector<PetscScalar> &root) {
  PetscScalar *a;
  PetscInt m;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(diag_lambda_, &a));
  for (PetscInt p = 0; p < dofs_->OwnedLambda(); ++p) a[p] = owned[p];
  PetscCall(VecRestoreArray(diag_lambda_, &a));
  PetscCall(VecScatterBegin(to_root_, diag_lambda_, diag_root_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_root_, diag_lambda_, diag_root_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(diag_root_, &m));
  PetscCall(VecGetArray(diag_root_, &a));
  root.assign(a, a + m);
  PetscCall(VecRestoreArray(diag_root_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::FromRoot(const std::vector<PetscScalar> &root, std::vector<double> &owned) {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(diag_root_, &a));
  for (std::size_t i = 0; i < root.size(); ++i) a[i] = root[i];
  PetscCall(VecRestoreArray(diag_root_, &a));
  PetscCall(VecScatterBegin(to_root_, diag_root_, diag_lambda_, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(to_root_, diag_root_, diag_lambda_, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecGetArray(diag_lambda_, &a));
  owned.assign(a, a + dofs_->OwnedLambda());
  PetscCall(VecRestoreArray(diag_lambda_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::MultiplierDiagonal(std::vector<PetscScalar> &d) {
  PetscFunctionBeginUser;
  // The values SetConstraints wrote.
  std::vector<double> owned(dofs_->OwnedLambda());
  for (PetscInt p = 0; p < dofs_->OwnedLambda(); ++p) owned[p] = active_[p] ? 0.0 : InactiveDiagonal(0.0, aug_inactive_);
  PetscCall(ToRoot(owned, d));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SetConstraints(const std::vector<SparseRow> &rows,
                                                 const std::vector<char> &active, double inactive_diag,
                                                 double stabilisation,
                                                 const std::vector<std::vector<double>> *columns,
                                                 const std::vector<double> *diag, const std::vector<char> *heavy) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  std::vector<PetscScalar> zeros;
  PetscFunctionBeginUser;
  PetscCheck(stabilisation >= 0 && stabilisation < aug_inactive_, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "stabilisation weight %.6g outside [0, %.6g)", stabilisation, aug_inactive_);
  if (active != active_ || stabilisation != stab_) pc_current_ = false;
  stab_ = stabilisation;
  const std::vector<char> &weighs = heavy ? *heavy : active;
  if (augmented_ && aug_inactive_ != aug_) {
    std::vector<double> weight(rows.size());
    for (std::size_t p = 0; p < rows.size(); ++p) weight[p] = weighs[p] ? aug_ : aug_inactive_;
    PetscCall(Reweight(rows, weight));
  }
  if (heavy) heavy_ = *heavy;
  else heavy_.clear();
  // The augmented form's D and column differences (SetConstraints' declaration); a change of them is a new matrix.
  std::vector<double> aug_diag(augmented_ ? rows.size() : 0, 0.0);
  std::vector<SparseRow> col_extra(aug_diag.size());
  for (std::size_t p = 0; p < aug_diag.size(); ++p) {
    if (!active[p]) continue;
    if (diag) aug_diag[p] = (*diag)[p];
    if (!columns || (*columns)[p].empty()) continue;
    PetscCheck(aug_diag[p] == 0, comm, PETSC_ERR_ARG_WRONG, "an active row with both D and its own column");
    for (PetscInt i = 0; i < rows[p].ncols; ++i)
      if ((*columns)[p][i] != rows[p].coef[i]) col_extra[p].Add(rows[p].cols[i], (*columns)[p][i] - rows[p].coef[i]);
  }
  for (std::size_t p = 0; p < aug_diag.size(); ++p) {
    const double w = weight_[p], scale = 1.0 + w * aug_diag[p];
    // 1 + w D = 1 - w / k for a spring k = -1/D: the caller gives such a row a weight away from k (heavy).
    PetscCheck(std::fabs(scale) > 1e-8, comm, PETSC_ERR_ARG_WRONG,
               "an augmentation weight %.6g equal to a row's spring stiffness %.6g", w, -1.0 / aug_diag[p]);
  }
  const auto same = [](const SparseRow &a, const SparseRow &b) { return a.cols == b.cols && a.coef == b.coef; };
  bool changed = aug_diag != aug_diag_ || col_extra.size() != col_extra_.size();
  for (std::size_t p = 0; p < col_extra.size() && !changed; ++p) changed = !same(col_extra[p], col_extra_[p]);
  if (changed) pc_current_ = false;
  aug_diag_ = std::move(aug_diag);
  col_extra_ = std::move(col_extra);
  std::vector<char> written(rows.size());
  std::vector<double> written_d(rows.size());
  for (std::size_t p = 0; p < rows.size(); ++p) {
    const bool keep = active[p] || augmented_ || stab_ > 0;
    if (!keep) zeros.assign(rows[p].ncols, 0.0);
    const bool column = keep && columns && !(*columns)[p].empty();
    double d = active[p] ? (diag ? (*diag)[p] : 0.0) : InactiveDiagonal(inactive_diag, augmented_ ? weight_[p] : 0.0);
    if (augmented_ && active[p]) d /= RowScale(p);
    PetscCall(SetRow(rows[p], (PetscInt)p, keep ? rows[p].coef.data() : zeros.data(), d,
                     column ? (*columns)[p].data() : nullptr));
    written[p] = keep, written_d[p] = d;
  }
  // Friction on the kept factorisation: the multiplier block of the fixed rows that this system maps onto.
  if (turned_) PetscCall(kept_rows_.Update(written, written_d, aug_));
  active_ = active;
  PetscCall(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

double SaddlePointSystem::InactiveDiagonal(double plain, double w) const {
  // Eliminating an inactive row -B_i du + D mu_i = 0 adds (w - 1/D) B_i^T B_i (augmented form, weight w) or
  // -B_i^T B_i / D (plain form, row kept) to the displacement block: the spring stab_ B_i^T B_i, or nothing in the
  // augmented form without stabilisation.
  if (augmented_) return 1.0 / (w - stab_);
  return stab_ > 0 ? -1.0 / stab_ : plain;
}

PetscErrorCode SaddlePointSystem::ShiftRhs() {
  PetscFunctionBeginUser;
  // Only friction gives rows a D or their own column (it makes the matrix nonsymmetric): nothing to do per solve else.
  if (nonsymmetric_.empty()) PetscFunctionReturn(0);
  bool any = false;
  for (std::size_t p = 0; p < aug_diag_.size() && !any; ++p) any = aug_diag_[p] != 0 || col_extra_[p].ncols > 0;
  PetscBool shift = any ? PETSC_TRUE : PETSC_FALSE;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &shift, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)b_.get())));
  if (!shift) PetscFunctionReturn(0);
  if (!b_given_) PetscCall(VecDuplicate(b_, b_given_.out()));
  PetscCall(VecCopy(b_, b_given_));
  // Rows with D: g / (1 + w D); a column B_i^T + e_i: -w g e_i on the displacement rows (the rows' columns are
  // rows of the whole system, possibly another rank's).
  PetscScalar *b;
  PetscCall(VecGetArray(b_, &b));
  std::vector<std::pair<PetscInt, PetscScalar>> moved;
  for (std::size_t p = 0; p < aug_diag_.size(); ++p) {
    const PetscInt i = dofs_->OwnedU() + (PetscInt)p;
    b[i] /= RowScale(p);
    const SparseRow &e = col_extra_[p];
    for (PetscInt k = 0; k < e.ncols; ++k) moved.emplace_back(e.cols[k], -weight_[p] * b[i] * e.coef[k]);
  }
  PetscCall(VecRestoreArray(b_, &b));
  for (const auto &m : moved) PetscCall(VecSetValue(b_, m.first, m.second, ADD_VALUES));
  PetscCall(VecAssemblyBegin(b_));
  PetscCall(VecAssemblyEnd(b_));
  rhs_shifted_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::RestoreRhs() {
  PetscFunctionBeginUser;
  if (rhs_shifted_) PetscCall(VecCopy(b_given_, b_));
  rhs_shifted_ = false;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::FailureAdvice(std::string &advice) const {
  PC pc;
  PetscBool fieldsplit;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  fieldsplit = fieldsplit || nullspace_ ? PETSC_TRUE : PETSC_FALSE;
  // Iterative solvers get the augmented block K + r B_C^T B_C, regular when the candidates hold the body; a failure
  // then means the candidates do not hold it, or the preconditioner does not fit the problem.
  const std::string direct = "; expected a solver that fits: the default MUMPS LDL^T (no solver preset, or "
                             "options/solver/mumps_cholesky.yml) solves every system whose body is held";
  if (!fieldsplit) {
    advice = ": the system is singular or the solver unsuitable; is the body held (Dirichlet conditions or enough "
             "active contact), and is the material not nearly incompressible (-material_nu near 0.5 locks the "
             "displacement formulation and makes the system nearly singular)?" + direct;
    PetscFunctionReturn(0);
  }
  KSP u;
  PCType u_pc = nullptr;
  PetscCall(DisplacementKsp(u));
  if (u) {
    PC upc;
    PetscCall(KSPGetPC(u, &upc));
    PetscCall(PCGetType(upc, &u_pc));
  }
  advice =
      std::string(nullspace_ ? ": the null-space preconditioner" : ": a Schur fieldsplit") + " with the u block by " +
      (u_pc ? u_pc : "?") +
      " failed on the block K + r B_C^T B_C, which is singular when neither the Dirichlet conditions nor the "
      "candidate contact pairs hold the body; raise -contact_ksp_max_it or -contact_ksp_rtol if it was converging" +
      direct;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::InitialGuess() {
  PetscFunctionBeginUser;
  if (reuse_ || preonly_) {
    PetscCall(VecZeroEntries(x_));
    PetscFunctionReturn(0);
  }
  // An iterative solve starts from the last multipliers (x_ holds them, in the plain form's meaning) in this system's
  // variables, and no displacement increment; its tolerance is relative to that start's residual (SetupKsp). The
  // multiplier unknown is the whole force, not an increment: from zero, a relative tolerance on the whole force
  // would leave an equilibrium error (times r in the augmented form) that no correction solve removes.
  PetscScalar *x;
  const PetscScalar *b;
  PetscCall(VecGetArray(x_, &x));
  PetscCall(VecGetArrayRead(b_, &b));
  for (PetscInt i = 0; i < dofs_->OwnedU(); ++i) x[i] = 0;
  for (PetscInt p = 0; p < dofs_->OwnedLambda(); ++p) {
    const PetscInt i = dofs_->OwnedU() + p;
    // Augmented: mu = (1 + w D)(lambda - w g') with g' = g / (1 + w D) the row's right-hand side (SetConstraints).
    x[i] = active_[p] ? (augmented_ ? RowScale(p) * (x[i] - weight_[p] * b[i]) : x[i]) : 0.0;
  }
  PetscCall(VecRestoreArrayRead(b_, &b));
  PetscCall(VecRestoreArray(x_, &x));
  PetscCall(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Solve(PetscInt &krylov_iterations, double &residual, bool &singular, double rtol,
                                        bool loose, bool inexact) {
  PetscFunctionBeginUser;
  PetscCall(ShiftRhs());
  PetscCall(SolveShifted(krylov_iterations, residual, singular, rtol, loose, inexact));
  PetscCall(RestoreRhs());
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveShifted(PetscInt &krylov_iterations, double &residual, bool &singular,
                                               double rtol, bool loose, bool inexact) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  KSPConvergedReason reason;
  PetscFunctionBeginUser;
  PetscCheck(!released_, comm, PETSC_ERR_ORDER, "a saddle-point solve after Release()");
  PetscCall(InitialGuess());
  singular = false;
  loose = loose && Iterative();
  inexact = inexact && Iterative();
  // The relative residual above which a solve is an error (CheckAndConvert); a loose solve and an inexact Newton step
  // only have to be finite.
  double check_tol = loose || inexact ? INFINITY : ACCEPTED_RESIDUAL;
  PetscReal known_residual[2] = {-1, -1}; // ||b - A x||, ||b|| of the final x_ when the restart loop computed them
  // The first solve of the reuse mode factors the current matrix (or declines the Schur complement: Factor).
  const bool fresh = reuse_ && !factored_;
  if (fresh) PetscCall(Factor());
  if (!direct_rejected_.empty()) {
    singular = true;
    PetscFunctionReturn(0);
  }
  if (reuse_) {
    PetscCall(SolveKept(fresh, rtol, krylov_iterations, check_tol, singular));
    if (singular) PetscFunctionReturn(0);
    reason = KSP_CONVERGED_ITS;
  } else {
    PetscCall(SolveKsp(rtol, loose, inexact, reason, krylov_iterations, known_residual));
    singular = !direct_rejected_.empty();
    if (singular) PetscFunctionReturn(0);
  }
  if (mumps_factor_ && !reuse_) {
    PetscCall(MatMumpsGetInfog(mumps_factor_, 28, &null_pivots_));
    singular = null_pivots_ > 0;
    if (singular) PetscFunctionReturn(0);
  }
  // A direct solve of a matrix singular to round-off can find no null pivot and return garbage (a block that rolls on
  // a disc, whose springs on the pairs' normals do not hold the roll, left a relative residual of 1.2): that is a
  // singular system too (the caller may repeat the step with wider pairs), not a solver failure. A residual between
  // the accepted one and SINGULAR_RESIDUAL is an ill-conditioned but regular matrix (-material_nu 0.4999999999 left
  // 1e-4): CheckAndConvert reports it with its advice.
  singular_residual_ = 0;
  if (reuse_ || (mumps_factor_ && preonly_)) {
    if (known_residual[0] < 0) PetscCall(TrueResidual(known_residual[0], known_residual[1]));
    if (!(known_residual[0] <= std::max(check_tol, SINGULAR_RESIDUAL) * known_residual[1] + 1e-300)) {
      singular_residual_ = std::isfinite(known_residual[0]) ? known_residual[0] / known_residual[1] : INFINITY;
      singular = true;
      PetscFunctionReturn(0);
    }
  }
  const PetscReal *known = known_residual[0] >= 0 ? known_residual : nullptr;
  PetscCall(CheckAndConvert(reason, krylov_iterations, residual, check_tol, known));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveKept(bool fresh, double rtol, PetscInt &krylov_iterations, double &check_tol,
                                            bool &singular) {
  PetscFunctionBeginUser;
  // Later solves are exact for a constant K (only D changed), else the kept factorisation preconditions the current
  // matrix (and may refactor it).
  std::vector<PetscScalar> d;
  PetscCall(MultiplierDiagonal(d));
  krylov_iterations = 1;
  singular = FactorStopped();
  if (singular) PetscFunctionReturn(0);
  if (fresh || constant_k_) {
    // The KSP's PC is the kept factorisation (PCKEPT, UseKeptPc): an exact solve with the current D (friction's: the
    // fixed rows' block X).
    PC pc;
    PetscCall(KSPGetPC(ksp_, &pc));
    if (turned_) PetscCall(UseFixedRowBlock());
    else PetscCall(PCKeptSetDiagonal(pc, d));
    PetscCall(KSPSolve(ksp_, b_, x_));
    kept_viewed_ = true; // KSPSolve shows the KSP with -contact_ksp_view
  } else
    PetscCall(SolveWithKeptFactor(d, rtol, krylov_iterations, check_tol));
  singular = FactorStopped();
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveKsp(double rtol, bool loose, bool inexact, KSPConvergedReason &reason,
                                           PetscInt &krylov_iterations, PetscReal known_residual[2]) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PetscFunctionBeginUser;
  // KSPSetUp sets the preconditioner up (a factorisation, for the direct presets) before KSPSolve would.
  // An iterative solver's preconditioner stays for a solve with the matrix it was set up for (a correction solve:
  // the same active set, K not reassembled; the values SetConstraints wrote are the same): one set-up less.
  // The active set may have changed on another rank only: all ranks must agree.
  PetscBool same = augmented_ && !reuse_ && pc_current_ ? PETSC_TRUE : PETSC_FALSE;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, comm));
  PetscCall(KSPSetReusePreconditioner(ksp_, same));
  PetscCall(KeepDisplacementPreconditioner());
  ProgressBegin(mumps_factor_ ? "preconditioner set-up (analysis and factorisation)" : "preconditioner set-up");
  PetscCall(KSPSetUp(ksp_));
  ProgressEnd();
  if (mumps_factor_) {
    // PETSc's MUMPS interface leaves a failed factorisation to the solve, which then returns infinities: a failure
    // for memory (a working-memory limit, ICNTL(23), too low) was reported as a singular system. -10, a numerically
    // singular matrix, is the singular case of Solve.
    PetscInt info[2];
    PetscCall(MatMumpsGetInfog(mumps_factor_, 1, &info[0]));
    PetscCall(MatMumpsGetInfog(mumps_factor_, 2, &info[1]));
    if (info[0] < 0 && confirm_direct_ && MumpsOutOfMemory((int)info[0])) {
      // The automatic choice leaves the direct path: the caller solves again on the iterative one.
      direct_rejected_ = MumpsOutOfMemoryText((int)info[0], (int)info[1], "factorisation");
      PetscFunctionReturn(0);
    }
    PetscCheck(info[0] >= 0 || info[0] == -10, comm, info[0] == -13 ? PETSC_ERR_MEM : PETSC_ERR_LIB, "%s",
               MumpsFailure((int)info[0], (int)info[1], "factorisation").c_str());
  }
  PetscCall(SplitMultiplierBlock());
  pc_current_ = augmented_ && !reuse_;
  ksp_set_up_ = true;
  if (!nest_.on && lean_product_) {
    // Without multipliers the fieldsplit's one block is its own copy of the matrix, made by the set-up above; GAMG
    // sets up on it at the first application: the lean product is attached to it here (the 4.1M-dof cube's elastic
    // solve on 2 ranks: 7.3 GB per rank with PETSc's product, where one rank takes 8.4 GB).
    KSP u;
    PetscCall(DisplacementKsp(u));
    if (u) {
      Mat P;
      PetscCall(KSPGetOperators(u, nullptr, &P));
      PetscCall(LeanPtAPAttach(P));
    }
  }
  PetscReal ksp_rtol, abstol, dtol;
  PetscInt max_it;
  PetscCall(KSPGetTolerances(ksp_, &ksp_rtol, &abstol, &dtol, &max_it));
  if (loose) {
    // A loose solve stops at rtol of the series' first start residual (the load step's loads), not of its own: after
    // a solve held at a touching point, the next one starts from the penetrations of the pairs it activates, 500
    // times the loads' residual (octant Hertz, 290k dofs), and rtol of that left multipliers wrong by 0.5 % of the
    // load: 457 of 1550 pairs released that an exact solve keeps (1530), and 9 active-set iterations instead of 5.
    // The later solves, whose start is small, stop earlier.
    // The KSP's test is relative to the solve's own start residual (KSPConvergedDefaultSetUIRNorm): rtol scaled by
    // the step's first ||b|| over this ||b|| (about the loads' whatever the start) asks a solve that starts small for
    // as many decades as one that starts at the loads. Measured and not kept (twelfth session): the target 1e-3 of
    // the step's first start residual itself (rtol scaled by that residual over this start's) made the later solves
    // cheaper (2-5 Krylov iterations instead of 6-10) but misled the active set: the octant Hertz at 1.07M dofs 13
    // active-set iterations instead of 9 (83.3 s against 80.6 s), the ball on a block 9 instead of 5 (7.2 s against
    // 5.4 s).
    PetscReal bnorm;
    PetscCall(VecNorm(b_, NORM_2, &bnorm));
    if (!(loose_reference_ > 0)) loose_reference_ = bnorm;
    if (bnorm > 0) rtol = std::min<double>(std::max<double>(LOOSE_RTOL_MAX, rtol), rtol * loose_reference_ / bnorm);
    PetscCall(PetscInfo(nullptr, "loose solve: rtol %.6g of ||b|| = %.6g (the load step's first ||b||: %.6g)\n", rtol,
                        (double)bnorm, (double)loose_reference_));
  }
  if (rtol > ksp_rtol) PetscCall(KSPSetTolerances(ksp_, rtol, abstol, dtol, max_it));
  PetscCall(KSPSolve(ksp_, b_, x_));
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PetscCall(KSPGetIterationNumber(ksp_, &krylov_iterations));
  if (reason < 0 && !preonly_) PetscCall(RetryKrylov(reason, krylov_iterations));
  // A Krylov method stops on its own (preconditioned) residual, which can sit orders of magnitude below the true
  // one (CG with GAMG on 2 ranks: 1e-10 against 3e-6). The solve restarts from where it stopped while that helps;
  // the true residual is what CheckAndConvert accepts or refuses. An inexact Newton step (svk) restarts only while
  // its true residual is above its own tolerance: restarts towards the accepted residual did again part of the work
  // its forcing saved (the octant of options/hertz3d.yml at 290k dofs, svk, one rank: 214 Krylov iterations instead
  // of 338, contact solve 42.7 s instead of 56.5 s, the same 14 iterations and state to 1e-8).
  const double target = inexact ? std::max<double>(rtol, ACCEPTED_RESIDUAL) : ACCEPTED_RESIDUAL;
  double last = INFINITY;
  for (int restart = 0; !preonly_ && !loose && reason > 0 && restart < MAX_KRYLOV_RESTARTS; ++restart) {
    PetscReal rnorm, bnorm;
    PetscCall(TrueResidual(rnorm, bnorm));
    if (!(rnorm > target * bnorm) || !(rnorm < 0.1 * last)) {
      known_residual[0] = rnorm, known_residual[1] = bnorm; // x_ stays as it is: CheckAndConvert reuses them
      break;
    }
    last = rnorm;
    PetscInt its;
    PetscCall(
        PetscInfo(nullptr, "Krylov restart %d: true relative residual %.6g\n", restart + 1, (double)(rnorm / bnorm)));
    PetscCall(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE));
    PetscCall(KSPSolve(ksp_, b_, x_));
    PetscCall(KSPGetConvergedReason(ksp_, &reason));
    PetscCall(KSPGetIterationNumber(ksp_, &its));
    krylov_iterations += its;
  }
  // A restart can break down too (CG on an svk tangent that is no longer positive definite: the 3D survey's seed 777
  // case 18 ended in an error, DIVERGED_INDEFINITE_PC in a restart of an inexact Newton step): the same fallback.
  if (reason < 0 && !preonly_) PetscCall(RetryKrylov(reason, krylov_iterations));
  const double solve_rtol = std::max<double>(rtol, ksp_rtol);
  if (rtol > ksp_rtol) PetscCall(KSPSetTolerances(ksp_, ksp_rtol, abstol, dtol, max_it));
  if (!constant_k_ && augmented_ && !reuse_) {
    // The lagged preconditioner of a changing K: set up again for the next solve once this one (its restarts
    // included) took too many iterations. Inexact Newton steps ask for fewer decades than exact ones: the iterations
    // are compared per decade of the tolerance asked (relative to the solve's start residual).
    const double decades = std::max(1.0, -std::log10(solve_rtol));
    const double rate = (double)krylov_iterations / decades;
    if (u_pc_.first_rate < 0)
      u_pc_.first_rate = rate;
    else if (krylov_iterations > LAGGED_U_PC_GROWTH * std::max(u_pc_.first_rate * decades, 5.0))
      u_pc_.valid = false;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::RetryKrylov(KSPConvergedReason &reason, PetscInt &krylov_iterations) {
  KSPType type;
  PetscFunctionBeginUser;
  // A breakdown (BiCGStab's, or CG's on this indefinite system), a divergence or a stagnation of the Krylov method
  // is not the answer to a system that some method solves: the preconditioner is set up again from the current
  // matrix (the displacement block's too), and GMRES (restart 100, right-preconditioned: it tests the true residual)
  // solves again from the start's guess, and stays for the rest of the run. Its own failure is the solve's.
  PetscCall(KSPGetType(ksp_, &type));
  const std::string failed = type;
  // CG on the null-space preconditioner needs its V-cycle positive definite. A hierarchy whose coarse operators
  // followed the active set while their smoothers kept the bounds of the set-up was not (the octant at 3.9M dofs, one
  // rank: DIVERGED_INDEFINITE_PC in its second solve; EstimateCoarseBounds now prevents it); should a V-cycle still
  // not be, GMRES does not need it: the same preconditioner serves, without a new set-up (20 s there).
  const bool indefinite = reason == KSP_DIVERGED_INDEFINITE_PC || reason == KSP_DIVERGED_INDEFINITE_MAT;
  const bool keep_pc = nullspace_ && indefinite;
  PetscCall(PetscInfo(nullptr, "%s stopped with %s after %" PetscInt_FMT " iterations: %s, solved by GMRES\n",
                      failed.c_str(), KSPConvergedReasons[reason], krylov_iterations,
                      keep_pc ? "the preconditioner kept" : "set up again"));
  krylov_fallbacks_++;
  if (keep_pc) {
    PetscCall(KSPSetType(ksp_, KSPGMRES));
    PetscCall(KSPGMRESSetRestart(ksp_, 100));
    PetscCall(KSPSetPCSide(ksp_, PC_RIGHT));
    PetscCall(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED));
    PetscCall(InitialGuess());
    PetscCall(SolveAgain(reason, krylov_iterations));
    PetscFunctionReturn(0);
  }
  PetscCall(KSPSetReusePreconditioner(ksp_, PETSC_FALSE));
  PC pc;
  PetscBool fieldsplit;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (fieldsplit) {
    KSP *sub;
    PetscInt n;
    PetscCall(PCFieldSplitGetSubKSP(pc, &n, &sub));
    for (PetscInt i = 0; i < n; ++i) PetscCall(KSPSetReusePreconditioner(sub[i], PETSC_FALSE));
    PetscCall(PetscFree(sub));
  }
  KSP u;
  PetscCall(DisplacementKsp(u));
  if (u && nullspace_) PetscCall(KSPSetReusePreconditioner(u, PETSC_FALSE));
  u_pc_.valid = false;
  // A set-up of the same matrix would be skipped: an assembly (of no new values) moves the matrices' states on.
  for (Mat M : {Stiffness(), A_.get()}) {
    PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  }
  if (failed != KSPFGMRES) { // the iterative preset's GMRES(30) too: a longer restart against a stagnation
    PetscCall(KSPSetType(ksp_, KSPGMRES));
    PetscCall(KSPGMRESSetRestart(ksp_, 100));
    PetscCall(KSPSetPCSide(ksp_, PC_RIGHT));
  }
  PetscCall(InitialGuess());
  PetscCall(KSPSetUp(ksp_));
  PetscCall(SolveAgain(reason, krylov_iterations));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SolveAgain(KSPConvergedReason &reason, PetscInt &krylov_iterations) {
  PetscInt its;
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(ksp_, b_, x_));
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PetscCall(KSPGetIterationNumber(ksp_, &its));
  krylov_iterations += its;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::Release() {
  PetscFunctionBeginUser;
  // The kept factorisation's solves in the multiplier space make no KSPSolve: -contact_ksp_view shows the KSP with
  // its kept factorisation here, after the last of them.
  if (reuse_ && factored_ && !kept_viewed_) PetscCall(KSPViewFromOptions(ksp_, nullptr, "-ksp_view"));
  PetscCall(KSPReset(ksp_));
  if (ksp_kept_) PetscCall(KSPReset(ksp_kept_));
  mumps_schur_.Release();
  mumps_factor_ = nullptr; // the PC's, destroyed
  factored_ = pc_current_ = ksp_set_up_ = u_pc_.valid = false;
  released_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::KeepDisplacementPreconditioner() {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PC pc;
  PetscBool fieldsplit;
  PetscFunctionBeginUser;
  if (!augmented_ || reuse_) PetscFunctionReturn(0);
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit && !nullspace_) PetscFunctionReturn(0);
  // The displacement block K + sum_p w_p B_p^T B_p changes with the active set only in the weights of the rows that
  // changed: a rank-k change. While K is the one of the last set-up and k is small against the candidates, the
  // preconditioner of that block (a GAMG hierarchy) stays; the outer Krylov method works on the current matrix, and
  // the Schur approximation is formed again. 3D Hertz at 110k dofs, fieldsplit_gamg: 2 GAMG set-ups instead of 6,
  // the same Krylov counts (20, 28, 28, 29, 27, 29, 5; at most 111 of 2202 rows changed since the set-up).
  PetscInt changed = 0, total = (PetscInt)weight_.size();
  if (u_pc_.weight.size() != weight_.size())
    changed = total;
  else
    for (std::size_t p = 0; p < weight_.size(); ++p)
      changed += weight_[p] != u_pc_.weight[p];
  PetscInt counts[2] = {changed, total};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm));
  PetscBool valid = u_pc_.valid && ksp_set_up_ ? PETSC_TRUE : PETSC_FALSE;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &valid, 1, MPIU_BOOL, MPI_LAND, comm));
  PetscBool keep = valid && counts[0] <= KEEP_U_PC_FRACTION * counts[1] ? PETSC_TRUE : PETSC_FALSE;
  const char *how = keep ? "kept" : "set up again";
  KSP u = nullptr;
  if (ksp_set_up_) PetscCall(DisplacementKsp(u));
  if (u) {
    PC upc;
    PetscBool gamg;
    PetscCall(KSPGetPC(u, &upc));
    PetscCall(PetscObjectTypeCompare((PetscObject)upc, PCGAMG, &gamg));
    // A constant K whose GAMG hierarchy exists: the changed weights go down its levels instead of a new set-up.
    // Measured on one rank (docs/performance.md, twelfth session): the octant Hertz at 1.07M dofs 94.2 and 88.6 s ->
    // 84.4 and 84.9 s (one GAMG set-up instead of two; 9 active-set iterations instead of 8, 103 Krylov iterations
    // instead of 94), the ball on a block at 316k 6.5 -> 5.4 s.
    // Friction's rows (nonsymmetric_) are left to the set-ups: its 3D tangential rows turn with the slip.
    // Whether some rank has augmented rows: a rank without pairs has none, and UpdateGalerkin is collective (the
    // 3D patch test of a tetrahedral block on a hexahedral one, 2 ranks, with its slave side on one rank, hung here).
    PetscBool rows = aug_rows_.empty() ? PETSC_FALSE : PETSC_TRUE;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &rows, 1, MPIU_BOOL, MPI_LOR, comm));
    if (hierarchy_update_ && valid && constant_k_ && nonsymmetric_.empty() && gamg && counts[0] > 0 && rows) {
      bool updated;
      PetscCall(UpdateGalerkin(upc, updated));
      if (updated) {
        u_pc_.weight = weight_;
        keep = PETSC_TRUE;
        how = "updated (the changed rows' Galerkin images added to the coarse operators)";
      }
    }
    PetscCall(KSPSetReusePreconditioner(u, keep));
  }
  PetscCall(PetscInfo(nullptr,
                      "displacement block: %" PetscInt_FMT " of %" PetscInt_FMT " weights changed since its "
                      "preconditioner's set-up: %s\n",
                      counts[0], counts[1], how));
  if (!keep) {
    u_pc_.weight = weight_;
    u_pc_.valid = true;
    u_pc_.first_rate = -1;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::UpdateGalerkin(PC mg, bool &updated) {
  MPI_Comm comm = PetscObjectComm((PetscObject)mg);
  PetscInt levels;
  PetscFunctionBeginUser;
  updated = false;
  // The displacement block changed by sum_p (w_p - w0_p) b_p b_p^T since its hierarchy was set up with the weights
  // w0: a change of rank k, the rows that changed weight. Each coarse operator A_l = P_l^T A_{l+1} P_l then changes
  // by G_l^T S G_l, with G_l = B_k P_{L-1} ... P_l the changed rows carried down the levels (scaled by the square
  // roots of |w_p - w0_p|) and S their signs: products of k short rows, against Galerkin products of the whole
  // matrix for a new set-up. The prolongators stay (the aggregates and their smoothing are those of K + w0 terms).
  PetscCall(PCMGGetLevels(mg, &levels));
  if (levels < 2) PetscFunctionReturn(0); // one level: GAMG's factorisation of the block, to be set up again
  // The block itself; its finest smoother may smooth on the block's form with the active rows eliminated
  // (PCNULLSPACE's fine level), which is set again as it is.
  Mat P_fine, A_fine, Ap_fine, S_fine, Sp_fine;
  KSP fine;
  PetscCall(PCMGGetInterpolation(mg, levels - 1, &P_fine));
  PetscCall(PCGetOperators(mg, &A_fine, &Ap_fine));
  PetscCall(PCMGGetSmoother(mg, levels - 1, &fine));
  PetscCall(KSPGetOperators(fine, &S_fine, &Sp_fine));
  PetscInt fine_start, fine_end;
  PetscCall(MatGetOwnershipRange(P_fine, &fine_start, &fine_end));
  std::vector<std::size_t> changed;
  for (std::size_t p = 0; p < weight_.size(); ++p)
    if (weight_[p] != u_pc_.weight[p]) changed.push_back(p);
  const PetscInt k = (PetscInt)changed.size();
  std::vector<PetscInt> d_nnz(k), o_nnz(k);
  for (PetscInt i = 0; i < k; ++i)
    for (PetscInt c : aug_rows_[changed[i]].cols) {
      const PetscInt u = dofs_->UBlockRow(c);
      (u >= fine_start && u < fine_end ? d_nnz : o_nnz)[i]++;
    }
  MatH G;
  VecH sign;
  PetscCall(MatCreateAIJ(comm, k, fine_end - fine_start, PETSC_DETERMINE, PETSC_DETERMINE, 0, d_nnz.data(), 0,
                         o_nnz.data(), G.out()));
  PetscCall(VecCreateMPI(comm, k, PETSC_DETERMINE, sign.out()));
  PetscInt row;
  PetscCall(MatGetOwnershipRange(G, &row, nullptr));
  PetscScalar *s;
  PetscCall(VecGetArray(sign, &s));
  for (PetscInt i = 0; i < k; ++i, ++row) {
    const SparseRow &b = aug_rows_[changed[i]];
    const double dw = weight_[changed[i]] - u_pc_.weight[changed[i]], scale = std::sqrt(std::fabs(dw));
    s[i] = dw > 0 ? 1.0 : -1.0;
    std::vector<PetscInt> cols(b.ncols);
    std::vector<PetscScalar> v(b.ncols);
    for (PetscInt j = 0; j < b.ncols; ++j)
      cols[j] = dofs_->UBlockRow(b.cols[j]), v[j] = scale * b.coef[j];
    PetscCall(MatSetValues(G, 1, &row, b.ncols, cols.data(), v.data(), INSERT_VALUES));
  }
  PetscCall(VecRestoreArray(sign, &s));
  PetscCall(MatAssemblyBegin(G, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(G, MAT_FINAL_ASSEMBLY));
  for (PetscInt l = levels - 1; l >= 1; --l) {
    MatH coarse, scaled, delta;
    Mat P;
    PetscCall(PCMGGetInterpolation(mg, l, &P));
    PetscCall(LeanRowsTimes(G, P, coarse.out()));
    PetscCall(MatDuplicate(coarse, MAT_COPY_VALUES, scaled.out()));
    PetscCall(MatDiagonalScale(scaled, sign, nullptr));
    PetscCall(MatTransposeMatMult(coarse, scaled, MAT_INITIAL_MATRIX, PETSC_DEFAULT, delta.out()));
    KSP smoother;
    Mat A, Ap;
    PetscCall(PCMGGetSmoother(mg, l - 1, &smoother));
    PetscCall(KSPGetOperators(smoother, &A, &Ap));
    PetscCall(MatAXPY(A, 1.0, delta, SUBSET_NONZERO_PATTERN));
    if (Ap != A) PetscCall(MatAXPY(Ap, 1.0, delta, SUBSET_NONZERO_PATTERN));
    // Set again, so that its preconditioner (Jacobi, the coarse factorisation) is set up for the new values.
    PetscCall(KSPSetOperators(smoother, A, Ap));
    G = std::move(coarse);
  }
  if (hierarchy_check_) {
    Mat Ac;
    KSP kc;
    PetscCall(PCMGGetSmoother(mg, levels - 2, &kc));
    PetscCall(KSPGetOperators(kc, &Ac, nullptr));
    MatH fresh;
    PetscCall(MatPtAP(A_fine, P_fine, MAT_INITIAL_MATRIX, PETSC_DEFAULT, fresh.out()));
    PetscReal nf, nd;
    PetscCall(MatNorm(fresh, NORM_FROBENIUS, &nf));
    PetscCall(MatAXPY(fresh, -1.0, Ac, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatNorm(fresh, NORM_FROBENIUS, &nd));
    PetscCall(PetscInfo(nullptr,
                        "hierarchy check: the first coarse operator differs from a new Galerkin product by "
                        "%.3g of its norm\n",
                        (double)(nd / nf)));
  }
  // The finest level's operator is the block itself (or its eliminated form), changed in place: its smoother's Jacobi
  // diagonal too.
  PetscCall(KSPSetOperators(fine, S_fine, Sp_fine));
  PetscCall(EstimateCoarseBounds(mg, levels));
  updated = true;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::EstimateCoarseBounds(PC mg, PetscInt levels) {
  PetscFunctionBeginUser;
  // GAMG gives each Chebyshev smoother the eigenvalue bounds of its level's operator at the set-up (from the
  // prolongator smoothing's estimate) and no estimator of its own, so after UpdateGalerkin the smoothers of the coarse
  // levels kept bounds that no longer hold: the changed rows' images weigh most there. The octant at 3.9M dofs, 4
  // levels between the finest and the coarsest: the largest eigenvalue of D^-1 A went from 1.84 and 2.28 to 4.41 and
  // 4.58 on the two coarsest of them (1.65 -> 1.67, 2.14, 2.34 on the others), so their Chebyshev polynomials
  // amplified those modes and the V-cycle was no longer positive definite (CG on the null-space preconditioner:
  // DIVERGED_INDEFINITE_PC). Such a level's smoother now estimates its bounds itself, as PETSc's Chebyshev does
  // without GAMG's (10 Krylov iterations on a noisy right-hand side, the same transform), and again whenever its
  // operator changes. The finest level (its operator changed in place by the weights alone: 2.34 -> 2.34) keeps
  // GAMG's: PETSc's estimate on every level at every update cost 9 % of the 1.07M octant's contact solve.
  for (PetscInt l = 1; l < levels - 1; ++l) {
    KSP smoother, est;
    PetscBool cheb;
    PetscCall(PCMGGetSmoother(mg, l, &smoother));
    PetscCall(PetscObjectTypeCompare((PetscObject)smoother, KSPCHEBYSHEV, &cheb));
    if (!cheb) continue;
    PetscCall(KSPChebyshevEstEigGetKSP(smoother, &est));
    if (est) continue; // estimating already: it does again for the changed operator
    // Its bounds from GAMG cannot be taken back through the interface: a new Chebyshev context, then the options.
    PetscCall(KSPSetType(smoother, KSPRICHARDSON));
    PetscCall(KSPSetType(smoother, KSPCHEBYSHEV));
    PetscCall(KSPChebyshevEstEigSet(smoother, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE));
    PetscCall(KSPChebyshevEstEigSetUseNoisy(smoother, PETSC_TRUE));
    PetscCall(KSPSetFromOptions(smoother));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::SplitMultiplierBlock() {
  PC pc, spc;
  PetscBool fieldsplit;
  PetscFunctionBeginUser;
  if (!nest_.on || multiplier_split_) PetscFunctionReturn(0);
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit) PetscFunctionReturn(0);
  PCCompositeType type;
  PetscCall(PCFieldSplitGetType(pc, &type));
  if (type != PC_COMPOSITE_SCHUR) PetscFunctionReturn(0);
  KSP *sub;
  PetscInt n;
  PetscCall(PCFieldSplitGetSubKSP(pc, &n, &sub));
  PetscCall(KSPGetPC(sub[n - 1], &spc));
  PetscCall(PetscFree(sub));
  PetscCall(PetscObjectTypeCompare((PetscObject)spc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit) PetscFunctionReturn(0);
  // The Schur complement's rows are the multiplier block's (global multiplier numbering).
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  const PetscInt owned = dofs_->OwnedLambda(), first = tangential_from_ < 0 ? owned : tangential_from_;
  PetscCheck(tangential_from_ >= 0, comm, PETSC_ERR_USER_INPUT,
             "-contact_fieldsplit_lambda_pc_type fieldsplit: the multiplier block has one kind of rows (normal) "
             "without friction; expected a preconditioner of one block (jacobi, the default) or -contact_friction > 0");
  ISH normal, tangential;
  PetscCall(ISCreateStride(comm, first, dofs_->LambdaBlockRow(0), 1, normal.out()));
  PetscCall(ISCreateStride(comm, owned - first, dofs_->LambdaBlockRow(first), 1, tangential.out()));
  PetscCall(PCFieldSplitSetIS(spc, "lambda_n", normal));
  PetscCall(PCFieldSplitSetIS(spc, "lambda_t", tangential));
  multiplier_split_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::TrueResidual(PetscReal &rnorm, PetscReal &bnorm) {
  PetscFunctionBeginUser;
  PetscCall(MatMult(A_, x_, r_));
  PetscCall(VecAYPX(r_, -1.0, b_));
  PetscCall(VecNorm(r_, NORM_2, &rnorm));
  PetscCall(VecNorm(b_, NORM_2, &bnorm));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::CheckAndConvert(KSPConvergedReason reason, PetscInt krylov_iterations,
                                                  double &residual, double tol, const PetscReal *known) {
  MPI_Comm comm = PetscObjectComm((PetscObject)A_.get());
  PetscReal bnorm, rnorm;
  PetscFunctionBeginUser;
  if (reason < 0) {
    std::string advice;
    PetscCall(FailureAdvice(advice));
    SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "the saddle-point solve failed (%s after %" PetscInt_FMT " iterations)%s",
            KSPConvergedReasons[reason], krylov_iterations, advice.c_str());
  }
  // A factorisation of a singular matrix can "succeed" with garbage: check the residual.
  if (known) rnorm = known[0], bnorm = known[1];
  else PetscCall(TrueResidual(rnorm, bnorm));
  const bool finite = std::isfinite(rnorm);
  if (!finite || rnorm > tol * bnorm + 1e-300) {
    // A Krylov method can report convergence on a singular system too (its preconditioned residual): the advice
    // names the solver as for a reported failure.
    std::string advice;
    PetscCall(FailureAdvice(advice));
    SETERRQ(comm, PETSC_ERR_NOT_CONVERGED,
            "the saddle-point solve failed (relative residual %.6g after %" PetscInt_FMT " iteration(s))%s",
            finite ? (double)(rnorm / bnorm) : -1.0, krylov_iterations, advice.c_str());
  }
  residual = rnorm;
  if (augmented_) {
    // Augmented form: an active row holds (1 + w D) lambda - w g (g: its right-hand side; w: its weight, D: 0 but on
    // a spring row), an inactive one (w - s) B du; the latter becomes the spring force -s B du of the plain form (0
    // without stabilisation).
    PetscScalar *x;
    const PetscScalar *b;
    PetscCall(VecGetArray(x_, &x));
    PetscCall(VecGetArrayRead(b_, &b));
    for (PetscInt p = 0; p < dofs_->OwnedLambda(); ++p) {
      const PetscInt i = dofs_->OwnedU() + p;
      x[i] = active_[p] ? x[i] / RowScale(p) + weight_[p] * b[i] : -stab_ * x[i] / (weight_[p] - stab_);
    }
    PetscCall(VecRestoreArrayRead(b_, &b));
    PetscCall(VecRestoreArray(x_, &x));
  }
  PetscFunctionReturn(0);
}

} // namespace signorini
