// The saddle-point system [K -B^T; -B D] [du; lambda] = [f - F_int; g] in one parallel AIJ matrix with a fixed
// nonzero pattern, and its KSP (options prefix -contact_). B holds the contact normals of the active pairs
// (B = -C in the notation of docs/theory.md §3, so that lambda >= 0 is a compressive force); an inactive pair has a
// zero row in B and a nonzero D entry, which gives lambda = 0 without changing the pattern. Knows nothing about
// geometry.
//
// Reuse of the factorisation (-contact_reuse_factorization, linear material with a MUMPS LU/Cholesky solver): the
// augmented form [K + r B_C^T B_C, -B_C^T; -B_C, D] keeps every candidate row C in B, with D = 0 on active rows and
// 1/r on inactive ones. Eliminating the inactive multipliers (mu_I = r B_I du) gives back K on the displacement
// block, and the active multipliers come out as lambda_A - r g_A; Solve() returns lambda_A. Only D changes with
// the active set, so MUMPS factors the matrix once with the Schur complement S = D - B_C (K + r B_C^T B_C)^-1
// B_C^T on the multipliers (MumpsSchur, applied by the KSP's PC of type PCKEPT), and an active-set change costs a
// dense m x m factorisation of S (m candidates) and one pair of triangular solves. K + r B_C^T B_C is regular when the
// candidates hold the body, even if K alone is not (a body held only by contact).
//
// A nonlinear material (svk: the tangent K changes at every Newton iteration) keeps the factorisation too: the
// factorisation of an earlier tangent, with the Schur complement over every candidate, follows the active set exactly
// (only D changes), so that it is a close preconditioner of the current system, whose tangent alone is stale. Each
// solve is FGMRES on the current matrix preconditioned by it, to the KSP's relative tolerance (the Newton iteration
// stays exact) or to a looser one the caller asks for (Solve's rtol); when FGMRES has not converged after
// -contact_reuse_max_it iterations, MUMPS refactors the current matrix numerically (the analysis is kept) and solves
// directly, and a solve whose residual contracted by less than KEPT_CONTRACTION per iteration refactors at the next
// solve. The condensed solves of the active-set search (Condense, SolveCondensed, Expand) then solve with the
// factored tangent itself: a modified Newton step (ContactSolver).
//
// Iterative solvers (a Schur fieldsplit: no factorisation) get the augmented form too, with a weight that follows the
// active set: r on an active row, r_I = INACTIVE_WEIGHT r on an inactive one (D = 1/r_I). The displacement block is
// then regular when the candidates hold the body, as above, and the Schur complement stays well conditioned: on an
// inactive row it is 1/r_I - B_i (K + ...)^-1 B_i^T, which vanishes for r_I = r in every direction the augmentation
// stiffens more than K (the smooth ones), but stays near 1/r_I when r_I is small against K's stiffness there. The
// displacement block changes with the active set; a Schur fieldsplit keeps that block's preconditioner across small
// changes (KeepDisplacementPreconditioner) and the whole preconditioner for a solve with an unchanged matrix.
// A Schur fieldsplit gets the matrix as a MATNEST of its four blocks (displacement block, B^T, B, D; vectors standard,
// rows in the order above), so that the fieldsplit works on the blocks themselves: as one AIJ matrix, PCFIELDSPLIT
// copied the displacement block (168 MB at 1M dofs in 2D), and its preconditioner comes out the same.
#pragma once

#include "signorini/core/handle.hpp"
#include "signorini/fem/dof_map.hpp"
#include "signorini/linalg/kept_rows.hpp"
#include "signorini/linalg/lcp.hpp"
#include "signorini/linalg/lean_ptap.hpp"
#include "signorini/linalg/mumps_schur.hpp"
#include "signorini/linalg/solver_choice.hpp"
#include "signorini/linalg/sparse_row.hpp"

#include <functional>
#include <string>
#include <vector>

namespace signorini {

/// The default saddle-point solver of a path (direct: MUMPS LDL^T of the whole matrix; iterative: the settings of
/// options/solver/fieldsplit_gamg.yml, SetIterativeDefaults), options prefix -contact_, iterative tolerances rtol
/// 1e-10; options given by the user override it at KSPSetFromOptions.
/// lu: the matrix is nonsymmetric (friction): the direct path's default is MUMPS LU. nullspace: the iterative path's
/// preconditioner is the null-space method (PCNULLSPACE) instead of the Schur fieldsplit (SetIterativeDefaults).
[[nodiscard]] PetscErrorCode SetDefaultSolver(KSP ksp, SolverPath path = SolverPath::DIRECT, bool lu = false,
                                              bool nullspace = false);

/// Options of the saddle-point system: -contact_reuse_factorization (set tells whether the user gave it),
/// -contact_reuse_max_it (the FGMRES iterations on a kept factorisation of an earlier tangent before a refactorisation,
/// nonlinear material; 0 refactors at every solve) and -contact_nested_dissection (the ordering of the kept
/// factorisation).
struct SaddlePointOptions {
  static constexpr PetscInt REUSE_MAX_IT_MAX = 1000;
  PetscBool reuse_factorization = PETSC_TRUE;
  PetscBool reuse_set = PETSC_FALSE;
  PetscInt reuse_max_it = 6; ///< in [0, REUSE_MAX_IT_MAX]
  PetscBool reuse_max_it_set = PETSC_FALSE;
  OrderingOptions ordering; ///< -contact_nested_dissection, -contact_nested_dissection_parallel
  PetscBool ordering_set = PETSC_FALSE, parallel_set = PETSC_FALSE; ///< the user gave them
  KeptSolver kept_solver = KeptSolver::AUTO; ///< -contact_kept_solver
  PetscBool kept_solver_set = PETSC_FALSE;
  SolverPathOptions path; ///< -contact_solver, -contact_memory_budget
  PetscBool hierarchy_update = PETSC_TRUE; ///< -contact_hierarchy_update (UpdateGalerkin)
  PetscBool hierarchy_check = PETSC_FALSE; ///< -contact_hierarchy_check
  GalerkinProduct galerkin_product = GalerkinProduct::LEAN; ///< -contact_gamg_product (LeanPtAPAttach)
  /// -contact_nullspace_fine_level: the null-space preconditioner's finest multigrid level on the eliminated operator
  /// or the augmented block; auto: eliminated for the linear material, augmented for svk
  enum class FineLevel { AUTO, ELIMINATED, AUGMENTED } fine_level = FineLevel::AUTO;
  static constexpr const char *FINE_LEVEL_NAMES[] = {"auto", "eliminated", "augmented"};
  /// -contact_augmentation_weight (the iterative path's r over the candidates' mean diagonal entry); not given: this
  /// in 3D without friction, else 0
  static constexpr double AUGMENTATION_WEIGHT_3D = 0.5;
  PetscReal augmentation_weight = AUGMENTATION_WEIGHT_3D;
  PetscBool augmentation_weight_set = PETSC_FALSE;
};
[[nodiscard]] PetscErrorCode ReadSaddlePointOptions(MPI_Comm comm, SaddlePointOptions &opts);

/// The saddle-point matrix, its vectors and its solvers. Its data members (about 36) stay in one class: the matrix
/// and its KSP, and the state of the two solve paths that share them, the kept factorisation (condensed solves,
/// refactorisations, the complementarity problem: saddle_point_kept.cpp, saddle_point_lcp.cpp) and the KSP's
/// preconditioner set-ups, are read across the three files by the same solves. What belongs to one concern is
/// grouped: how the kept factorisation is made (KeptChoices), the fieldsplit's blocks (NestBlocks), the kept
/// displacement preconditioner (DisplacementPc), and the factorisation itself (MumpsSchur, the PC kept).
class SaddlePointSystem {
public:
  /// Creates the matrix with the pattern of K (inserted by insert_k; d_nnz_k, o_nnz_k: its counts per displacement
  /// row, see Assembler::PatternCounts), the constraint rows and the multiplier diagonal,
  /// the vectors and the KSP. coords: dim values per owned vertex, in dof order (for the rigid-body near-null space
  /// of the "u" block). constant_k: K never changes (linear material; otherwise a kept factorisation preconditions the
  /// changed matrix, see above); kscale: the stiffness scale, the weight of the augmentation. insert_k gets
  /// Stiffness().
  /// Collective.
  /// The path (SolverChoice) whose default solver Create sets up: direct unless told otherwise before Create.
  void UsePath(SolverPath path) { path_ = path; }
  /// The automatic solver choice's direct path (before the first factorisation): the kept factorisation's analysis
  /// is checked by confirm before the numerical factorisation, and a MUMPS failure for memory (MumpsOutOfMemory) in
  /// any factorisation is no error: the solve that met either returns as singular, with DirectRejected() saying why,
  /// and the caller solves again on the iterative path.
  void ConfirmDirectWith(ConfirmFactor confirm) { confirm_direct_ = std::move(confirm); }
  /// Why the direct path stopped (ConfirmDirectWith); empty while it has not.
  const std::string &DirectRejected() const { return direct_rejected_; }
  /// The matrix will be nonsymmetric (friction's slip rows; before Create): the default solver is MUMPS LU, and a
  /// solver that needs symmetry (a Cholesky factorisation, a fieldsplit preset) is refused naming what would do. With
  /// a constant K the factorisation is kept across the sets all the same, of the fixed rows that SetRowGroups gives
  /// (KeptRows: friction's turned rows and slip columns mapped onto them); with a changing K it is the plain form,
  /// refactored at every change. why: the cause, for the messages.
  /// stiffness: the displacement block itself is nonsymmetric (svk's consistent mortar tangent), not only B^T and B.
  void UseNonsymmetric(const std::string &why, bool stiffness = false) {
    nonsymmetric_ = why, nonsymmetric_k_ = stiffness;
  }
  bool Nested() const { return nest_.on; }
  /// Friction on the kept factorisation (TurnsRows()): every owned multiplier row's fixed row and the groups that map
  /// the current rows onto them (KeptRows), given before each SetConstraints.
  void SetRowGroups(std::vector<SparseRow> fixed, std::vector<RowGroup> groups) {
    kept_rows_.Set(std::move(fixed), std::move(groups));
  }
  /// The kept factorisation is of fixed rows that the current ones are mapped onto (friction with a constant K).
  bool TurnsRows() const { return turned_; }
  /// The augmentation weight of the fixed rows' factorisation (TurnsRows(); else 0): a row's spring 1/|D| near it
  /// would make the map singular (Friction::SystemRows' kept_weight keeps springs away from it).
  double FixedRowWeight() const { return turned_ ? aug_ : 0.0; }
  /// The owned multiplier rows from first on are tangential (friction; before Create): a Schur fieldsplit whose
  /// multiplier block is preconditioned by a fieldsplit (-contact_fieldsplit_lambda_pc_type fieldsplit) gets that
  /// block's splits "lambda_n" (normal rows) and "lambda_t" (tangential rows), addressed by
  /// -contact_fieldsplit_lambda_fieldsplit_lambda_n_ and ..._lambda_t_ options.
  void UseTangentialRows(PetscInt first) { tangential_from_ = first; }
  [[nodiscard]] PetscErrorCode Create(const DofMap &dofs, const std::vector<SparseRow> &rows,
                                      const std::vector<double> &coords, bool constant_k, double kscale,
                                      const std::vector<PetscInt> &d_nnz_k, const std::vector<PetscInt> &o_nnz_k,
                                      const std::function<PetscErrorCode(Mat)> &insert_k);
  Mat A() const { return A_; }
  /// The matrix K is assembled into (Assembler::Assemble; zeroed first): A, or its displacement block when A is
  /// nested (a Schur fieldsplit; the block's rows are DofMap::URow's).
  Mat Stiffness() const { return nest_.on ? nest_.K.get() : A_.get(); }
  Vec Solution() const { return x_; }
  Vec Rhs() const { return b_; }
  KSP Ksp() const { return ksp_; }

  /// Whether the factorisation is kept across active sets (the augmented form below). Then the caller adds
  /// AddAugmentation() after every assembly of K (Augmented()).
  bool ReusesFactorization() const { return reuse_; }
  /// Changing K with the kept factorisation: the next solve refactors the current matrix instead of preconditioning.
  void RefactorNext() { refactor_next_ = true; }
  /// The kept factorisation is asked for (an option that needs it, such as -newton_lagged_search): its Schur
  /// complement is never declined (Factor).
  void KeepFactorization() { kept_.forced = kept_.forced || reuse_; }
  /// Whether the kept factorisation is exact for every solve (constant K: the condensed solves below are possible).
  bool ExactFactorization() const { return reuse_ && constant_k_ && !turned_; }
  /// Whether the system is in the augmented form (the reuse mode, and every solver that is not a factorisation).
  bool Augmented() const { return augmented_; }
  /// Adds r B_C^T B_C over every candidate row to the displacement block (ADD_VALUES, flush assembly); an iterative
  /// solver's rows inactive in the current system get r_I (SetConstraints changes the weights of the next).
  [[nodiscard]] PetscErrorCode AddAugmentation(const std::vector<SparseRow> &rows);
  /// Changes the augmentation weight of every owned row to weight[p] (ADD_VALUES of the difference, flush assembly).
  [[nodiscard]] PetscErrorCode Reweight(const std::vector<SparseRow> &rows, const std::vector<double> &weight);
  /// K du without a pass over the cells (the linear material on the iterative path): the displacement block of the
  /// augmented form less the augmentation it carries, y = A du - sum_p w_p B_p^T B_p du, on the owned displacement
  /// rows (du and y: OwnedU values, in the order of Solution()'s displacement rows; du 0 on the Dirichlet rows, where
  /// y is then 0 too). rows: those AddAugmentation and SetConstraints were given. Only where StiffnessTimesApplies.
  /// Collective.
  [[nodiscard]] PetscErrorCode StiffnessTimes(const std::vector<SparseRow> &rows, const PetscScalar *du,
                                              std::vector<double> &y);
  /// Whether StiffnessTimes gives K du: not where the block is more than K and the augmentation (no augmented nested
  /// block, springs or columns of friction's rows, a stabilised system) or a row has columns on other ranks (mortar).
  /// Collective.
  [[nodiscard]] PetscErrorCode StiffnessTimesApplies(const std::vector<SparseRow> &rows, bool &applies) const;
  /// The iterative path's r from K's diagonal on the candidate rows, at the first AddAugmentation.
  [[nodiscard]] PetscErrorCode IterativeWeight(const std::vector<SparseRow> &rows);
  /// Writes the constraint rows. Plain form: active rows get their coefficients (in both B and B^T) and D = 0,
  /// inactive rows zeros and D = inactive_diag. Augmented form: every row keeps its coefficients, D = 0 on active
  /// rows and 1/r_I on inactive ones (weights r, r_I: Reweight). stabilisation s > 0 (s < r_I) adds a spring
  /// s B_i^T B_i on the normal of every inactive pair to the displacement block (plain form: the row kept with
  /// D = -1/s; augmented: D = 1/(r_I - s)), for a body that the active set does not hold. Ends with a final assembly
  /// of A. Collective.
  /// columns (if given): per row, the coefficients of its column B^T where they differ from the row's (empty: the
  /// same), on the row's pattern (a nonsymmetric matrix, UseNonsymmetric); diag (if given): per row, D on an active
  /// row instead of 0 (a spring 1/|D| on the row's direction: friction's slip rows in 3D); heavy (if given): per row,
  /// whether its augmentation weight is r (else r_I; default: active), so that the caller can give rows that turn
  /// together one weight (friction's tangential rows of a pair: their sum B_1^T B_1 + B_2^T B_2 is then the same
  /// however the rows turn in the tangent plane). In the augmented form an active row with D != 0 and weight w is
  /// solved as B du + D / (1 + w D) mu = g / (1 + w D) with mu = (1 + w D) lambda - w g, and a column that differs
  /// from its row by e (given on an active row with D = 0) moves -w g e to the displacement rows' right-hand side
  /// (Solve does both, and gives lambda back).
  [[nodiscard]] PetscErrorCode SetConstraints(const std::vector<SparseRow> &rows, const std::vector<char> &active,
                                              double inactive_diag, double stabilisation = 0,
                                              const std::vector<std::vector<double>> *columns = nullptr,
                                              const std::vector<double> *diag = nullptr,
                                              const std::vector<char> *heavy = nullptr);
  /// The augmentation weight of a row (SetConstraints' heavy: r, else r_I); 0 when the form is not augmented.
  double AugmentationWeight(bool heavy) const { return augmented_ ? (heavy ? aug_ : aug_inactive_) : 0.0; }
  /// Solves A x = b; a failed or inaccurate solve is an error naming the likely cause. On return the multiplier
  /// rows of the solution hold, in both forms, the contact multipliers lambda on active rows and the spring forces
  /// -s B du on inactive ones (0 without stabilisation), so that F_int(u + du) = f + B^T x on the free rows.
  /// residual: ||b - A x||.
  /// rtol > 0: the relative residual that FGMRES on a kept factorisation of an earlier tangent may stop at (an
  /// inexact Newton step; otherwise the KSP's tolerance), and that an iterative KSP may stop at if it is looser than
  /// the KSP's own (a correction solve, see ContactSolver::StepControl); it does not apply to direct solves.
  /// singular: a MUMPS factorisation found null pivots (ICNTL(24)): nothing is solved, and SingularReport() says so;
  /// the caller decides what the singularity means (a body that the supports and the candidate pairs do not hold).
  /// loose (an iterative solver, Iterative()): the solve stops at rtol relative to the start's residual of the first
  /// loose solve since BeginLooseSolves (the load step's: its loads' scale), without the restarts and the accepted
  /// residual of other solves (an active-set iteration whose set is still changing: the caller solves again, to its
  /// tolerance, once the set stays). Each loose iterate is then as accurate as the first, whatever its own start.
  /// inexact (an iterative solver): an inexact Newton step of svk, to rtol relative to its start's residual, whose
  /// residual is only checked finite (ContactSolver::NewtonForcing chose rtol; the caller evaluates the equilibrium).
  /// Collective.
  [[nodiscard]] PetscErrorCode Solve(PetscInt &krylov_iterations, double &residual, bool &singular, double rtol = 0,
                                     bool loose = false, bool inexact = false);
  /// Starts a series of loose solves (a load step): the next loose solve's start residual is the series' reference.
  void BeginLooseSolves() { loose_reference_ = 0; }
  /// Solves that failed in the Krylov method and were solved again by GMRES (RetryKrylov).
  PetscInt KrylovFallbacks() const { return krylov_fallbacks_; }
  /// An iterative solver (a Krylov method with no kept factorisation).
  bool Iterative() const { return !reuse_ && !preonly_; }
  /// The saddle-point KSP is CG (the null-space preconditioner's method in 3D, unless the user chose another).
  [[nodiscard]] PetscErrorCode KrylovIsCg(bool &cg) const;
  /// "the saddle-point system is singular (MUMPS found N null pivot(s)): " and cause (the caller's: what leaves the
  /// body free), with the MUMPS controls given that decide which pivots are null (-contact_mat_mumps_cntl_<k>, ...)
  /// named first as another possible cause.
  std::string SingularReport(const std::string &cause) const;
  /// An iterative solver's caller found that the supports and every candidate pair together leave a rigid-body
  /// motion free: the displacement block K + r B_C^T B_C is singular for every active set, so the caller skips the
  /// solve and reports it as singular (SingularReport says why), as a direct solver finds it by its null pivots.
  void SetUnheld(bool unheld) { unheld_ = unheld; }

  /// Frees the factorisations and preconditioners (MUMPS's factors, the fieldsplit's blocks, GAMG's hierarchy), so
  /// that what follows the last solve (the output of the last load step) does not add to them; the matrix and the
  /// vectors stay. A later Solve is an error. Collective.
  [[nodiscard]] PetscErrorCode Release();

  /// Reuse mode: the active-set iterations of a load step (svk: of a Newton iteration's search, with the factored
  /// tangent) in the multiplier space. Condense takes the current right-hand side (its displacement rows b_u stay
  /// those of every SolveCondensed until the next Condense), factoring first if needed. SolveCondensed solves for the
  /// current constraints (SetConstraints, without stabilisation) with the multiplier rows bm (owned rows) in the
  /// multiplier space alone (the dense Schur complement on rank 0; no pass over the factors); it returns per owned
  /// multiplier row the contact multiplier (0 on inactive rows) and B_p du, the normal displacement of the solution's
  /// increment (the gap change), and the residual of the reduced system. Expand then gives the whole solution of the
  /// last SolveCondensed in Solution(), as Solve() does (one backward substitution), with residual ||b - A x|| for the
  /// right-hand side [b_u; bm] that the caller has written into Rhs(). Condense's singular: as Solve's (nothing
  /// condensed). Collective.
  [[nodiscard]] PetscErrorCode Condense(bool &singular);
  [[nodiscard]] PetscErrorCode SolveCondensed(const std::vector<double> &bm, std::vector<double> &lambda,
                                              std::vector<double> &shift, double &residual);
  [[nodiscard]] PetscErrorCode Expand(double &residual);
  /// Reuse mode with a constant K, after Condense of a right-hand side whose multiplier rows are zero: the contact
  /// problem of the linear material from that state as a linear complementarity problem in the multipliers, solved
  /// by Lemke's method (SolveLcp) on rank 0, and the active set of its solution. gap: the current gap per owned row;
  /// key: a number per owned row that orders the rows the same way on any number of ranks (the problem's rows are
  /// taken in that order). With H = B A11^-1 B^T (A11 = K + r B^T B) and c = B A11^-1 b_u, a multiplier vector lambda
  /// gives the gaps g + P^-1 c + H P^-1 lambda, P = I - r H, which is singular along the rigid motions that K leaves
  /// free (a body held by contact alone); P + LCP_REGULARISATION I is taken instead, so that such a motion is held
  /// by a weak spring and the problem stays solvable. The set is a proposal that the caller's exact solves confirm.
  /// unbalanced: the force along those motions that the spring would still carry as its stiffness goes to 0, on the
  /// solution's active set (extrapolated from a second solve with 100 LCP_REGULARISATION), relative to the load or the
  /// contact forces along them (whichever is larger), as a norm of projections onto their eigenspace (the same on any
  /// number of ranks): round-off (below 1e-7 in the tests) when the pairs hold the body, whatever the units, 0.009 to
  /// 1 in the tests when no contact forces on them can (a body that rolls off a disc). Collective.
  [[nodiscard]] PetscErrorCode ContactLcp(const std::vector<double> &gap, const std::vector<double> &key,
                                          std::vector<char> &active, LcpStatus &status, int &pivots,
                                          double &unbalanced);
  /// See ContactLcp. The rigid motions are the eigenvectors of r H whose eigenvalue is within LCP_RIGID_TOL of 1 (an
  /// elastic mode is there only for a body some 1000 times longer than thick).
  static constexpr double LCP_REGULARISATION = 1e-10, LCP_RIGID_TOL = 1e-9;

private:
  /// The KSP from the options (-contact_ prefix, before the matrix exists); nested: its PC works on the blocks of a
  /// MATNEST (a fieldsplit, or the null-space preconditioner). Collective.
  [[nodiscard]] PetscErrorCode CreateKsp(MPI_Comm comm, bool &nested);
  /// Whether the null-space preconditioner (PCNULLSPACE) applies to the rows: 3D, no friction, every row on the dofs of
  /// one node of its own rank (rigid obstacles); else why not (for the message when it is asked for). Collective.
  [[nodiscard]] PetscErrorCode NullSpaceApplies(const std::vector<SparseRow> &rows, bool &applies,
                                                std::string &why) const;
  bool nullspace_ = false; ///< the KSP's PC is PCNULLSPACE
  /// The displacement block's solver of the KSP's PC (a fieldsplit's "u" block, PCNULLSPACE's), or null (none yet,
  /// or another PC). Not collective.
  [[nodiscard]] PetscErrorCode DisplacementKsp(KSP &u) const;
  /// Inserts zeros at the constraint entries and the multiplier diagonal, then assembles A (final). Collective.
  [[nodiscard]] PetscErrorCode CreatePattern(const std::vector<SparseRow> &rows, Mat A) const;
  /// A as a MATNEST of the blocks nest_.K, Bt, B, D with their patterns (K's from insert_k, the constraint entries
  /// and the multiplier diagonal), assembled. Collective.
  [[nodiscard]] PetscErrorCode CreateNest(const std::vector<SparseRow> &rows, const std::vector<PetscInt> &d_nnz_k,
                                          const std::vector<PetscInt> &o_nnz_k,
                                          const std::function<PetscErrorCode(Mat)> &insert_k);
  /// Writes constraint row p (its coefficients coef, or zeros) into B and B^T and its diagonal d (INSERT_VALUES), in A
  /// or in the nest's blocks. Not collective.
  /// column (if given): the coefficients of its column B^T instead of coef.
  [[nodiscard]] PetscErrorCode SetRow(const SparseRow &row, PetscInt p, const PetscScalar *coef, PetscScalar d,
                                      const PetscScalar *column = nullptr);
  /// Nonzeros per owned row of the whole matrix: K's counts plus the constraint entries. Collective.
  [[nodiscard]] PetscErrorCode RowCounts(const std::vector<SparseRow> &rows, const std::vector<PetscInt> &d_nnz_k,
                                         const std::vector<PetscInt> &o_nnz_k, std::vector<PetscInt> &d_nnz,
                                         std::vector<PetscInt> &o_nnz) const;
  /// For each owned row of the whole matrix: the entries of B^T that other ranks' constraint rows put there (their
  /// columns of this rank's displacement rows), all in the off-diagonal block. Collective.
  [[nodiscard]] PetscErrorCode RemoteTransposed(const std::vector<SparseRow> &rows,
                                                std::vector<PetscInt> &counts) const;
  /// The KSP's operators and what depends on them (near-null space, fieldsplit index sets, MUMPS controls, the reuse
  /// mode). Collective.
  [[nodiscard]] PetscErrorCode SetupKsp(const std::vector<double> &coords, bool constant_k);
  /// SetupKsp: the rigid-body modes at coords (owned displacement rows) as the displacement block's near-null space.
  [[nodiscard]] PetscErrorCode SetNearNullSpace(MPI_Comm comm, const std::vector<double> &coords);
  /// SetupKsp, a factorisation PC: with MUMPS, creates its factor and sets the controls it needs (null pivots,
  /// workspace) before the user's (ReadMumpsControls). Collective.
  [[nodiscard]] PetscErrorCode SetupMumpsFactor(MPI_Comm comm, PC pc);
  /// SetupKsp: the reuse and ordering options (opts) against the solver and each other. Collective.
  /// Refuses -contact_kept_solver where the kept factorisation does not run (possible: a MUMPS solver), and
  /// cholesky where it does not apply (LU, MUMPS controls). After lu_ is known.
  [[nodiscard]] PetscErrorCode CheckKeptSolver(MPI_Comm comm, const SaddlePointOptions &opts, bool possible) const;
  [[nodiscard]] PetscErrorCode CheckReuseOptions(MPI_Comm comm, const SaddlePointOptions &opts, bool constant_k) const;
  /// Reuse mode: every multiplier row's global number on rank 0 (schur_rows_), the diagonal's vectors. Collective.
  [[nodiscard]] PetscErrorCode GatherSchurRows(MPI_Comm comm);
  /// svk with the kept factorisation: the FGMRES KSP that it preconditions (ksp_kept_). Collective.
  [[nodiscard]] PetscErrorCode CreateKeptKsp(MPI_Comm comm);
  /// Reuse mode: the multiplier diagonal D of A (from the active flags) on rank 0, in the order of schur_rows_.
  /// Collective.
  [[nodiscard]] PetscErrorCode MultiplierDiagonal(std::vector<PetscScalar> &d);
  /// Reuse mode: a value per owned multiplier row to rank 0 (Schur order; empty elsewhere), and back. Collective.
  [[nodiscard]] PetscErrorCode ToRoot(const std::vector<double> &owned, std::vector<PetscScalar> &root);
  [[nodiscard]] PetscErrorCode FromRoot(const std::vector<PetscScalar> &root, std::vector<double> &owned);
  /// Reuse mode: the analysis and factorisation with the Schur complement, once; a singular A11 sets null_pivots_
  /// (and leaves the system unfactored). Unless
  /// -contact_reuse_factorization was given, the Schur complement is declined when it would cost more than it saves
  /// (MumpsSchur::DenseCostsMore): the reuse mode ends, and the KSP factorises the augmented matrix at every change.
  /// Collective.
  [[nodiscard]] PetscErrorCode Factor();
  /// ||b - A x|| and ||b|| for the current x_. Collective.
  [[nodiscard]] PetscErrorCode TrueResidual(PetscReal &rnorm, PetscReal &bnorm);
  /// Reuse mode, changing K: the numerical refactorisation of the current matrix (the analysis of Factor); a singular
  /// A11 sets null_pivots_. Collective.
  [[nodiscard]] PetscErrorCode Refactor();
  /// Solve's two paths. The kept factorisation (factored first when fresh): an exact solve of a constant K, else
  /// SolveWithKeptFactor; singular: null pivots. Collective.
  [[nodiscard]] PetscErrorCode SolveKept(bool fresh, double rtol, PetscInt &krylov_iterations, double &check_tol,
                                         bool &singular);
  /// The KSP: its set-up, the solve to the relative tolerance rtol (when above the KSP's), after a Krylov failure
  /// GMRES (RetryKrylov), and unless loose the restarts from where it stopped while they reduce the true residual
  /// above the accepted one (an inexact Newton step's: rtol of ||b||) (known_residual: ||b - A x||, ||b|| when
  /// computed). Collective.
  [[nodiscard]] PetscErrorCode SolveKsp(double rtol, bool loose, bool inexact, KSPConvergedReason &reason,
                                        PetscInt &krylov_iterations, PetscReal known_residual[2]);
  /// Reuse mode, changing K: x_ from FGMRES on the current matrix preconditioned by the kept factorisation, or, when
  /// it does not converge within -contact_reuse_max_it iterations (or the last solve contracted too slowly),
  /// after a refactorisation. d: the current multiplier diagonal (rank 0); rtol: see Solve. iterations: FGMRES's, plus
  /// one for a direct solve; check_tol: the relative residual the solution may have (1e-6, or 2 rtol after an
  /// inexact FGMRES solve). Collective.
  [[nodiscard]] PetscErrorCode SolveWithKeptFactor(const std::vector<PetscScalar> &d, double rtol,
                                                   PetscInt &iterations, double &check_tol);
  /// Makes the KSP's PC the kept factorisation (PCKEPT) once it is made, so that the KSP solves with it and
  /// -contact_ksp_view shows it. Collective.
  [[nodiscard]] PetscErrorCode UseKeptPc();
  /// The kept factorisation that the KSP's PC (PCKEPT) applies, for the solves in the multiplier space.
  [[nodiscard]] PetscErrorCode KeptFactorization(MumpsSchur *&kept) const;
  /// After a solve into x_ (reason, iterations: the KSP's): an error naming the likely cause for a failed or
  /// inaccurate solve (relative residual above tol), residual = ||b - A x||, and the multiplier rows of x_ in the
  /// plain form's meaning. known: {||b - A x||, ||b||} of the current x_ when the caller has them (else computed).
  /// Collective.
  [[nodiscard]] PetscErrorCode CheckAndConvert(KSPConvergedReason reason, PetscInt krylov_iterations,
                                               double &residual, double tol, const PetscReal *known = nullptr);
  /// The largest true residual ||b - A x|| / ||b|| a solve may leave (an inexact svk search step: 2 rtol), and the
  /// restarts of a Krylov solve that stopped above it on its preconditioned residual (each must divide the true
  /// residual by 10).
  static constexpr double ACCEPTED_RESIDUAL = 1e-6;
  /// The largest relative tolerance of a loose solve whose start residual is small against the series' reference
  /// (or -contact_active_set_rtol, if larger). 0.01, not 0.1: a prescribed displacement puts its rows (stiffness scale
  /// times the increment) into the first right-hand side only, and the punch on a plate (options/punch_on_plate.yml,
  /// iterative path) solved every later set to 0.1 in one Krylov iteration and cycled (DIVERGED_CYCLING); with 0.01, 7
  /// active-set iterations to the direct path's set. The octant Hertz and the cube under a sphere stay below it (4e-3
  /// at most).
  static constexpr double LOOSE_RTOL_MAX = 0.01;
  /// A direct solve that leaves a relative residual above this solved nothing: its matrix is singular to round-off.
  static constexpr double SINGULAR_RESIDUAL = 1e-2;
  /// The mean contraction of the residual per FGMRES iteration on the kept factorisation above which the next solve
  /// refactors (the factored tangent has drifted from the current one); a factorisation of the undeformed tangent of
  /// a moderately deformed body contracts by well under it (docs/performance.md).
  static constexpr double KEPT_CONTRACTION = 0.1;
  static constexpr int MAX_KRYLOV_RESTARTS = 3;
  /// r_I / r of an iterative solver (see the head of this file). On 2D Hertz with fieldsplit_gamg (FGMRES, upper Schur
  /// factorisation, selfp) at 20k/195k/1M dofs: Krylov iterations per solve 57-65/94-113/121-164 with 1 (the earlier
  /// constant weight), 24-36/26-41/29-42 with 0.01, about the same with 0.001; it must stay well above the
  /// stabilisation spring (ContactSolver::STABILISATION r).
  static constexpr double INACTIVE_WEIGHT = 1e-2;
  /// r_I / r of the null-space preconditioner (PCNULLSPACE). It eliminates the inactive rows exactly, so r_I only
  /// enters the V-cycle M, built on K + r B_A^T B_A + r_I B_I^T B_I where the operator it preconditions is K + r
  /// B_A^T B_A: the inactive rows' springs hold the whole candidate surface in M alone. A body held at a touching node
  /// (the octant Hertz's first solve) sinks about it in the operator and hardly at all in M, and its Krylov iterations
  /// converged at a third of an elastic solve's rate per decade. Measured (the octant of options/hertz3d.yml, its
  /// touching solve to 0.03, one rank): 290k dofs r_I/r = 1e-2, 1e-3, 3e-4, 2e-4, 1e-4, 1e-6: 10, 8, 7, 7, 6, 6
  /// Krylov iterations; 1.07M 12 -> 8 (1e-4: 7), 3.9M 13 -> 8 (1e-6: 8); the other solves and the elastic reference
  /// (every row inactive) unchanged. Twice the stabilisation spring (ContactSolver::STABILISATION), which must stay
  /// below it. svk keeps INACTIVE_WEIGHT: with this weight the 3D survey's seed 777 case 18 (svk, no solution) ended
  /// DIVERGED_NOT_HELD on 2 ranks instead of the direct path's DIVERGED_MAX_IT (test krylov_fallback_restart).
  static constexpr double NULLSPACE_INACTIVE_WEIGHT = 2e-4;
  /// A Schur fieldsplit keeps its displacement block's preconditioner while at most this fraction of the candidate
  /// rows changed weight since its set-up (and K did not change): KeepDisplacementPreconditioner. 0.3 against 0.1
  /// (fieldsplit_gamg, one rank; the same active sets): the ball on a block at 316k dofs 4 -> 2 GAMG set-ups, Krylov
  /// iterations 179 -> 183, contact solve 77.6 -> 63.3 s; the octant Hertz at 290k 4 -> 2, 297 -> 313 V-cycles, 48.7-50.9
  /// -> 46.4 s; the same counts at 16-20k dofs (2D and 3D Hertz, the ball on a block). Every row changed (1.0: the
  /// first hierarchy, built on the start's few active rows, kept) took the octant to 12 active-set iterations and 80 s.
  static constexpr double KEEP_U_PC_FRACTION = 0.3;
  [[nodiscard]] PetscErrorCode KeepDisplacementPreconditioner();
  /// The displacement block's GAMG hierarchy (mg) follows the weights that changed since its set-up: each coarse
  /// operator gets the Galerkin image of the rank-k change (why: in saddle_point.cpp); updated: false for a
  /// hierarchy of one level (to be set up again). Collective.
  [[nodiscard]] PetscErrorCode UpdateGalerkin(PC mg, bool &updated);
  [[nodiscard]] PetscErrorCode EstimateCoarseBounds(PC mg, PetscInt levels);
  std::vector<SparseRow> aug_rows_; ///< the augmented rows of the last AddAugmentation (UpdateGalerkin)
  bool hierarchy_update_ = true, hierarchy_check_ = false; ///< -contact_hierarchy_update, -contact_hierarchy_check
  bool lean_product_ = true;                               ///< -contact_gamg_product lean (LeanPtAPAttach)
  /// After the first set-up of a Schur fieldsplit: the multiplier block's fieldsplit (if it is one) gets its splits
  /// (UseTangentialRows).
  [[nodiscard]] PetscErrorCode SplitMultiplierBlock();
  PetscInt tangential_from_ = -1; ///< UseTangentialRows (-1: no tangential rows)
  bool multiplier_split_ = false; ///< SplitMultiplierBlock gave the multiplier block's fieldsplit its splits
  /// After a Krylov failure (reason < 0): the preconditioner set up again and GMRES from the start's guess; reason and
  /// krylov_iterations become the retry's (iterations added).
  [[nodiscard]] PetscErrorCode RetryKrylov(KSPConvergedReason &reason, PetscInt &krylov_iterations);
  /// RetryKrylov's solve from x_: reason becomes its, its iterations are added. Collective.
  [[nodiscard]] PetscErrorCode SolveAgain(KSPConvergedReason &reason, PetscInt &krylov_iterations);
  /// The start of the next solve in x_: zero for a direct solver; the last multipliers for an iterative one.
  [[nodiscard]] PetscErrorCode InitialGuess();
  /// What to use instead after a failed KSP solve (": ...; expected ..."), from the preconditioner that failed.
  [[nodiscard]] PetscErrorCode FailureAdvice(std::string &advice) const;
  /// D on an inactive row of augmentation weight w (plain: the value of the plain form without stabilisation).
  double InactiveDiagonal(double plain, double w) const;
  /// Augmented form with SetConstraints' diag or columns: the right-hand side the caller wrote, kept in b_given_,
  /// becomes the augmented system's (SetConstraints above); RestoreRhs puts it back. Collective.
  [[nodiscard]] PetscErrorCode ShiftRhs();
  /// Solve on the shifted right-hand side.
  [[nodiscard]] PetscErrorCode SolveShifted(PetscInt &krylov_iterations, double &residual, bool &singular, double rtol,
                                            bool loose, bool inexact);
  [[nodiscard]] PetscErrorCode RestoreRhs();
  /// The augmented form's scale 1 + w D of owned row p (1 on a row without D).
  double RowScale(std::size_t p) const {
    return p < aug_diag_.size() && aug_diag_[p] != 0 ? 1.0 + weight_[p] * aug_diag_[p] : 1.0;
  }
  const DofMap *dofs_ = nullptr;
  bool reuse_ = false, augmented_ = false, factored_ = false, constant_k_ = true;
  bool released_ = false;              ///< Release() freed the solver
  bool refactor_next_ = false;         ///< the last FGMRES solve on the kept factorisation needed many iterations
  bool pc_current_ = false; ///< iterative solver: A is the matrix of the last preconditioner set-up (a correction)
  bool preonly_ = false;            ///< the KSP is KSPPREONLY (a direct solve; set once, in SetupKsp)
  PetscInt krylov_fallbacks_ = 0;    ///< RetryKrylov's count
  PetscReal loose_reference_ = 0;    ///< the start residual of the series' first loose solve (BeginLooseSolves)
  bool ksp_set_up_ = false;         ///< iterative solver: the KSP has been set up (a fieldsplit's sub-KSPs exist)
  /// The displacement block's preconditioner kept across set-ups (KeepDisplacementPreconditioner).
  struct DisplacementPc {
    bool valid = false;         ///< the displacement block's preconditioner may serve the current K
    std::vector<double> weight; ///< the augmentation weights at that set-up
    double first_rate = -1;     ///< Krylov iterations per decade of the first solve after the set-up (-1: none)
  } u_pc_;
  /// A changing K (svk): its Newton iterations keep the displacement block's preconditioner of an earlier tangent
  /// while a solve takes at most this factor times the iterations that the first solve after its set-up took for
  /// as many decades (at least 5).
  static constexpr double LAGGED_U_PC_GROWTH = 1.5;
  bool kept_viewed_ = false; ///< a KSPSolve with the kept PC showed it (-contact_ksp_view); else Release does
  KSPH ksp_kept_;                      ///< changing K: FGMRES preconditioned by the kept factorisation
  PetscBool lu_ = PETSC_FALSE; ///< the PC is LU (the mumps_lu preset): the reuse mode factors with LU too
  double aug_ = 1;             ///< augmentation weight r (the stiffness scale; the iterative path: IterativeWeight)
  double aug_relative_ = 0;    ///< -contact_augmentation_weight; 0 once IterativeWeight set r (or never: direct)
  SolverPath path_ = SolverPath::DIRECT; ///< UsePath
  ConfirmFactor confirm_direct_;         ///< ConfirmDirectWith
  std::string direct_rejected_;          ///< DirectRejected
  /// The last factorisation gave nothing to solve with: null pivots, or the direct path stopped (DirectRejected).
  bool FactorStopped() const { return null_pivots_ > 0 || !direct_rejected_.empty(); }
  std::string nonsymmetric_; ///< UseNonsymmetric's cause (empty: symmetric)
  bool nonsymmetric_k_ = false; ///< UseNonsymmetric's stiffness
  bool turned_ = false;      ///< the kept factorisation is of fixed rows (TurnsRows)
  KeptRows kept_rows_;       ///< SetRowGroups' rows and groups, and their maps (SetConstraints)
  /// TurnsRows(): the fixed matrix [K + w B^T B, B^T; B, 1/w] factored with its Schur complement (Factor).
  [[nodiscard]] PetscErrorCode FactorFixedRows(const FactorChoices &how);
  /// A row of X couples with at most this many others (a 3D pair's other two rows).
  static constexpr int MAX_ROW_COUPLINGS = 2;
  /// TurnsRows(): the multiplier block X of the current sets to the kept PC (its diagonal, and the entries off it to
  /// MumpsSchur on rank 0). Collective.
  [[nodiscard]] PetscErrorCode UseFixedRowBlock();
  double aug_inactive_ = 1; ///< augmentation weight r_I of an inactive row (r, or INACTIVE_WEIGHT r: iterative)
  std::vector<double> weight_; ///< owned multiplier rows: the augmentation weight A holds now (AddAugmentation)
  double stab_ = 0; ///< stabilisation spring s of the current system (0: none)
  /// Augmented form, owned multiplier rows (SetConstraints): D of an active row (0: none), a column's difference from
  /// its row on an active row (empty: none), the heavy flags; b_given_ the caller's right-hand side while ShiftRhs has
  /// changed b_.
  std::vector<double> aug_diag_;
  std::vector<SparseRow> col_extra_;
  std::vector<char> heavy_;
  VecH b_given_;
  bool rhs_shifted_ = false;
  std::vector<char> active_;          ///< owned multiplier rows active in the current system
  std::vector<PetscInt> schur_rows_;  ///< rank 0: every multiplier row, in global order
  MumpsSchur mumps_schur_;
  /// How the kept factorisation is made (SetupKsp, from SaddlePointOptions): its options and the coordinates for its
  /// ordering.
  struct KeptChoices {
    bool forced = false;      ///< -contact_reuse_factorization given: the Schur complement is never declined (Factor)
    PetscInt max_it = 0;      ///< -contact_reuse_max_it
    OrderingOptions ordering; ///< -contact_nested_dissection, -contact_nested_dissection_parallel
    KeptSolver solver = KeptSolver::AUTO; ///< -contact_kept_solver
    bool solver_set = false;              ///< the user gave -contact_kept_solver
    std::vector<double> coords;           ///< reuse mode: the coordinates of SetupKsp, for the ordering
    std::string ordering_given; ///< "-contact_nested_dissection X" and/or "..._parallel Y" as given (else empty)
  } kept_;
  VecH diag_lambda_, diag_root_;
  VecScatter to_root_ = nullptr;      ///< multiplier diagonal to rank 0
  MatH A_;
  /// A Schur fieldsplit's blocks: A_ is then a MATNEST of K (displacement block), Bt (B^T), B and D.
  struct NestBlocks {
    bool on = false; ///< A_ is a MATNEST
    MatH K, Bt, B, D;
  } nest_;
  VecH x_, b_, r_;
  KSPH ksp_;
  NullSpaceH near_null_;
  Mat mumps_factor_ = nullptr; ///< the MUMPS factor of a direct solve (owned by the PC), for the null-pivot check
  MumpsControls mumps_controls_; ///< -contact_mat_mumps_icntl_<k>, _cntl_<k> (a MUMPS solver only)
  PetscInt null_pivots_ = 0;     ///< null pivots of the last MUMPS factorisation (INFOG(28))
  bool unheld_ = false;          ///< SetUnheld
  double singular_residual_ = 0; ///< the relative residual of a direct solve that found no null pivot but solved
                                 ///< nothing (a matrix singular to round-off), else 0

public:
  SaddlePointSystem() = default;
  SaddlePointSystem(const SaddlePointSystem &) = delete;
  SaddlePointSystem &operator=(const SaddlePointSystem &) = delete;
  ~SaddlePointSystem() { (void)VecScatterDestroy(&to_root_); }
};

} // namespace signorini
