// A direct solver for a symmetric matrix [A11 A12; A21 D] whose last block D (the multipliers) is diagonal and
// changes between solves while the rest stays fixed. MUMPS (called directly: PETSc 3.18's interface solves with a
// Schur complement only on one rank) factors the matrix once with the Schur complement S0 = D0 - A21 A11^-1 A12 on
// the multiplier rows, centralised on rank 0. A solve with another diagonal D uses S = S0 + (D - D0), factored
// densely (LAPACK LDL^T) on rank 0 when D changes: MUMPS condenses the right-hand side onto the multipliers, rank 0
// solves with S, MUMPS expands the solution. LU instead of LDL^T on request (the mumps_lu preset). The ordering is a
// nested dissection of the node graph (METIS's, computed by all ranks with the partition's interfaces as the top
// separators, or coordinate cuts for a small 2D matrix, computed on rank 0), given to MUMPS (ICNTL(7) = 1), the
// analysis sequential, with null-pivot detection (ICNTL(24)) so that a singular A11 is reported; the options
// -contact_mat_mumps_icntl_<k> and -contact_mat_mumps_cntl_<k> override them as for PETSc's interface. Where A11 is
// positive definite and the problem small enough (KeptSolver), SchurCholesky does MUMPS's part instead (analysis,
// factorisation with the Schur complement, condensation and expansion), from the same order, on rank 0.
#pragma once

#include "signorini/core/handle.hpp"
#include "signorini/linalg/schur_cholesky.hpp"

#include <dmumps_c.h>

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

/// MUMPS's ICNTL(14) for every MUMPS factorisation of the saddle-point system: the workspace is this many per cent
/// above the analysis' estimate (MUMPS's default, 20, was exceeded by 2-rank LDL^T of 3D hexahedral meshes).
constexpr int MUMPS_WORKSPACE_INCREASE = 50;
/// Factorisations run again with twice the extra workspace after MUMPS ran out of it (INFOG(1) = -8 or -9).
constexpr int MUMPS_WORKSPACE_RETRIES = 4;
/// The message of a MUMPS failure (INFOG(1) < 0, INFOG(2)) in phase ("analysis", "factorisation", ...) of the
/// saddle-point system: what it means and what would do instead.
std::string MumpsFailure(int infog1, int infog2, const char *phase);

/// MUMPS's errors for memory or workspace (INFOG(1)): -8, -9, -11, -12, -14, -15, -17, -20 (a workspace too small),
/// -13 (an allocation failed), -19 (more than ICNTL(23) allows).
bool MumpsOutOfMemory(int infog1);
/// What a MUMPS failure for memory that ends the automatic choice's direct path says (phase: "factorisation", ...).
std::string MumpsOutOfMemoryText(int infog1, int infog2, const char *phase);

/// The analysis of the matrix that Factor is about to factor: its factor entries and elimination flops, and MUMPS's
/// own estimate of its memory per rank (INFOG(16), in bytes; 0 for the supernodal Cholesky, whose factor is exact).
struct AnalysedFactor {
  double entries = 0, flops = 0, mumps_bytes = 0;
  bool cholesky = false;
};
/// A check of the analysis before the numerical factorisation (the automatic solver choice's, ConfirmDirect): false
/// with a reason stops the factorisation (MumpsSchur::Rejected).
using ConfirmFactor = std::function<bool(const AnalysedFactor &analysed, std::string &why)>;

/// Rows from which a 2D saddle-point matrix is ordered by METIS (below: by coordinate cuts; 3D: always METIS).
constexpr PetscInt METIS_MIN_ROWS_2D = 50000;

/// The nested dissection of the node graph given to MUMPS (-contact_nested_dissection): AUTO is METIS in 3D and from
/// METIS_MIN_ROWS_2D rows in 2D, coordinate cuts below (CoordinateNestedDissection).
enum class GraphOrdering { AUTO, METIS, COORDINATES };
inline const char *const GRAPH_ORDERING_NAMES[] = {"auto", "metis", "coordinates"};

/// The ordering given to MUMPS: which nested dissection, and for METIS's whether all ranks compute it
/// (-contact_nested_dissection_parallel, DistributedNestedDissection) or rank 0 alone.
struct OrderingOptions {
  GraphOrdering graph = GraphOrdering::AUTO;
  bool parallel = true;
};

/// Who factors the kept factorisation's displacement block (-contact_kept_solver): MUMPS, or SchurCholesky (a
/// supernodal Cholesky without pivoting, serial: on several ranks rank 0 factors the gathered matrix) where it
/// applies: an LDL^T solver, the given nested dissection (ICNTL(7) = 1) and no MUMPS controls; AUTO takes it there
/// up to CHOLESKY_MAX_ROWS rows on one rank, CHOLESKY_MAX_ROWS_GATHERED on several. A block that
/// is not safely positive definite (a body that the candidates do not hold, an svk tangent past a limit point) goes
/// to MUMPS, whose null-pivot detection then judges it.
enum class KeptSolver { AUTO, MUMPS, CHOLESKY };
inline const char *const KEPT_SOLVER_NAMES[] = {"auto", "mumps", "cholesky"};
/// The Cholesky is faster than MUMPS at every size measured, but its merged supernodes' zeros cost more memory, so the
/// larger matrices, where memory binds, stay with MUMPS (measurements: docs/performance.md).
constexpr PetscInt CHOLESKY_MAX_ROWS = 500000;
/// On several ranks the Cholesky factors on rank 0 alone (the matrix gathered there), against MUMPS on all ranks:
/// AUTO takes it up to this many rows, beyond which rank 0's memory grows and the time gained vanishes
/// (docs/performance.md).
constexpr PetscInt CHOLESKY_MAX_ROWS_GATHERED = 50000;

/// The MUMPS controls given for the saddle-point solver (-contact_mat_mumps_icntl_<k>, k in 1..60, and
/// -contact_mat_mumps_cntl_<k>, k in 1..15), which both MUMPS paths take: PETSc's interface and MumpsSchur.
struct MumpsControls {
  /// ICNTL(7) values of the orderings that this MUMPS lacks (Debian's has no SCOTCH, 3, and no METIS, 5, of its
  /// own): MUMPS would replace them by its automatic choice without a word.
  static constexpr PetscInt ICNTL7_SCOTCH = 3, ICNTL7_METIS = 5;
  std::vector<std::pair<int, PetscInt>> icntl; ///< (k, value) of every ICNTL given
  std::vector<std::pair<int, double>> cntl;    ///< (k, value) of every CNTL given
  /// ICNTL(k) as given, else fallback.
  PetscInt Icntl(int k, PetscInt fallback) const;
  /// The controls given that decide which pivots MUMPS counts as null (every CNTL; ICNTL 6, 8, 12, 24 and 56:
  /// matching, scaling, the symmetric ordering strategy, null-pivot detection, rank revelation) as
  /// "-contact_mat_mumps_cntl_3 0.5, ..."; empty when none was.
  std::string PivotControls() const;
};

/// Reads the controls and checks them: a CNTL must be finite (MUMPS compares pivots with it), ICNTL(7) an ordering of
/// MUMPS 5.5 (0 to 7) that this build has. Called where the saddle-point solver reads its options, before any
/// factorisation. Collective.
[[nodiscard]] PetscErrorCode ReadMumpsControls(MPI_Comm comm, MumpsControls &controls);

/// The matrix that MumpsSchur::Factor factors: its Schur rows with their diagonal, and the node layout of its
/// displacement rows for the ordering.
struct SchurLayout {
  const std::vector<PetscInt> &schur_rows; ///< global rows of the Schur complement (rank 0 only; the order of D)
  const std::vector<PetscScalar> &d0;      ///< A's diagonal on those rows now (rank 0 only)
  PetscInt owned_u;                        ///< the first owned_u owned rows of each rank are displacements
  PetscInt node_size;                      ///< consecutive displacement rows per node
  const std::vector<double> &coords;       ///< coords[node_size * i + k]: coordinate k of the owned node i
};

/// How MumpsSchur::Factor factors.
struct FactorChoices {
  bool symmetric = true;                 ///< LDL^T (MUMPS SYM = 2, LAPACK sytrf for S) or LU (SYM = 0, getrf)
  OrderingOptions ordering;              ///< the nested dissection given to MUMPS
  MumpsControls controls;                ///< the user's (ReadMumpsControls), over this class's defaults
  bool keep_values = false;              ///< keep the entries in MUMPS's format for Refactor (else freed)
  bool may_decline = false;              ///< decline the Schur complement where it costs more (DenseCostsMore)
  KeptSolver solver = KeptSolver::MUMPS; ///< who factors (CHOLESKY only where it applies, which the caller checked)
  /// Given: the analysis is checked before the factorisation, and a MUMPS failure for memory (MumpsOutOfMemory) is
  /// no error: Factor or Refactor return with Rejected() and everything released.
  ConfirmFactor confirm;
};

class MumpsSchur {
public:
  MumpsSchur() = default;
  MumpsSchur(const MumpsSchur &) = delete;
  MumpsSchur &operator=(const MumpsSchur &) = delete;
  ~MumpsSchur();

  /// Analyses and factors A (parallel AIJ, symmetric; its values now are the ones factored) with the Schur
  /// complement on the rows of layout, as how says. With how.may_decline it declines after the analysis (Declined(),
  /// nothing factored, everything released) when the dense Schur complement would cost more than the sparse
  /// factorisation it saves (DenseCostsMore). Collective.
  [[nodiscard]] PetscErrorCode Factor(Mat A, const SchurLayout &layout, const FactorChoices &how);
  /// The factorisation in use is SchurCholesky's (else MUMPS's).
  bool UsesCholesky() const { return cholesky_in_use_; }
  /// The last Factor declined the Schur complement.
  bool Declined() const { return declined_; }
  /// Why the last Factor or Refactor stopped with FactorChoices::confirm given: the analysis' check refused to factor,
  /// or MUMPS ran out of memory (everything is released); empty when it did not.
  const std::string &Rejected() const { return rejected_; }
  /// The rule of Factor's may_decline, from the analysis' estimate: a dense LDL^T of the m x m Schur complement, which
  /// every active-set change costs, takes more flops than the whole sparse factorisation (flops), which a
  /// refactorisation at every change would cost instead: a thin plate whose whole face is a candidate declines, a
  /// Hertz contact keeps it (examples: docs/performance.md).
  static bool DenseCostsMore(double m, double flops) { return m * m * m / 3 > flops; }
  /// The numerical factorisation of A's current values (the pattern and the analysis of Factor, which kept the
  /// values) with the Schur complement, d0 its multiplier diagonal now. Collective.
  [[nodiscard]] PetscErrorCode Refactor(Mat A, const std::vector<PetscScalar> &d0);
  /// Solves with the factored matrix whose multiplier diagonal is replaced by d (rank 0, Schur order): Condense,
  /// the reduced system, Expand. Collective.
  [[nodiscard]] PetscErrorCode Solve(const std::vector<PetscScalar> &d, Vec b, Vec x);
  /// An entry of the multiplier block off its diagonal (rank 0, Schur order: row i, column j).
  struct Coupling {
    PetscInt i, j;
    double v;
    bool operator==(const Coupling &o) const { return i == o.i && j == o.j && v == o.v; }
  };
  /// The multiplier block's entries off the diagonal for the next solves (rank 0; empty elsewhere): S = S0 + (D - D0)
  /// + these, factored by LU (LAPACK getrf) when there are any. Friction's rows in the kept factorisation
  /// (KeptRows). Not collective.
  /// Once given, a change of D or of these entries is solved by a low-rank update of the factored S (Woodbury: the
  /// factors' solves for the changed rows and an LU of their capacitance matrix) while that costs at most half a new
  /// LU, each such solve checked against S (UPDATE_RESIDUAL).
  void SetCoupling(std::vector<Coupling> off) { off_ = std::move(off), coupled_ = true; }
  /// An updated dense solve whose residual exceeds this fraction of its right-hand side refactors S.
  static constexpr double UPDATE_RESIDUAL = 1e-11;
  /// New dense factorisations of S and low-rank updates of it so far (rank 0).
  PetscInt DenseFactorisations() const { return dense_factorisations_; }
  PetscInt DenseUpdates() const { return dense_updates_; }
  /// The forward elimination of the right-hand side b (MUMPS keeps it for Expand) and its part A21 A11^-1 b_u that
  /// SolveReduced takes off. Collective.
  [[nodiscard]] PetscErrorCode Condense(Vec b);
  /// Solves with the multiplier diagonal d for a right-hand side [b_u; y] whose displacement part b_u is that of the
  /// last Condense: y (rank 0, Schur order) is replaced by the multiplier part of the solution, which is kept for
  /// Expand; residual is ||y - A21 A11^-1 b_u - S y_solved|| (every rank). Only the dense m x m system. Collective.
  [[nodiscard]] PetscErrorCode SolveReduced(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y,
                                            double &residual);
  /// The whole solution x for the right-hand side of the last Condense and the multiplier part of the last
  /// SolveReduced (or Solve): MUMPS's backward substitution. A new Condense is needed after it. Collective.
  [[nodiscard]] PetscErrorCode Expand(Vec x);
  /// Rank 0 (elsewhere both empty): A21 A11^-1 A12 = D0 - S0 (m x m, column major, Schur order; symmetrised) and
  /// A21 A11^-1 b_u of the last Condense. Not collective.
  void ReducedOperator(std::vector<double> &h, std::vector<double> &condensed) const;
  /// A Condense holds a right-hand side that Expand has not used yet (every rank).
  bool Condensed() const { return condensed_; }
  /// Frees the factors and every array (MUMPS's JOB = -2); a new Factor starts again. Collective.
  void Release();
  /// Null pivots MUMPS met in A11 (INFOG(28)).
  PetscInt NullPivots() const { return null_pivots_; }
  /// Prints who factored, the ordering, the sizes, the factor's entries and flops (ASCII viewers). Collective on the
  /// viewer's communicator.
  [[nodiscard]] PetscErrorCode View(PetscViewer viewer) const;

private:
  [[nodiscard]] PetscErrorCode Call(int job, const char *phase);
  /// Factor's steps, in its order. MUMPS's instance (job -1) with the controls this class relies on. Collective.
  [[nodiscard]] PetscErrorCode InitialiseMumps();
  /// The user's MUMPS controls and the ordering (ordering.graph: AUTO resolved for N rows of node_size). Collective.
  [[nodiscard]] PetscErrorCode ApplyControls(const MumpsControls &controls, PetscInt N, PetscInt node_size,
                                             OrderingOptions &ordering);
  /// The symbolic analysis by the supernodal Cholesky or by MUMPS (cholesky_in_use_), with its estimated elimination
  /// flops and factor entries. Collective.
  [[nodiscard]] PetscErrorCode Analyse(const FactorChoices &how, PetscInt N, PetscInt m_all, double &flops,
                                       double &entries);
  /// Frees the matrix entries kept for a refactorisation.
  void FreeValues();
  /// MUMPS's analysis of the entries read (irn_, jcn_) with perm_in_ when ICNTL(7) = 1. Collective.
  [[nodiscard]] PetscErrorCode MumpsAnalysis();
  /// A's owned entries in MUMPS's distributed format (irn_, jcn_, val_): with the pattern, or (pattern false) the
  /// values alone into the pattern read before. Collective only through A.
  [[nodiscard]] PetscErrorCode ReadValues(Mat A, bool pattern);
  /// MUMPS's numerical factorisation of val_ and the Schur complement S0 (s0_) for the multiplier diagonal d0.
  /// Collective.
  [[nodiscard]] PetscErrorCode FactorNumeric(const std::vector<PetscScalar> &d0);
  /// The dense factors of S = S0 + diag(d - d0) on rank 0 (FactorSchurOnRoot), unless they are those of d already.
  /// Collective.
  [[nodiscard]] PetscErrorCode FactorSchur(const std::vector<PetscScalar> &d);
  /// See FactorSchur; raises PETSC_ERR_NOT_CONVERGED for a singular S. Rank 0 (RunOnRoot).
  [[nodiscard]] PetscErrorCode FactorSchurOnRoot(const std::vector<PetscScalar> &d);
  /// y = S^-1 y with the factored Schur complement and its low-rank update, if any (nothing for no multipliers).
  /// Rank 0 (RunOnRoot).
  [[nodiscard]] PetscErrorCode DenseSolve(std::vector<PetscScalar> &y) const;
  /// DenseSolve, checked against S for D = d when an update is in use (refactored and solved again above
  /// UPDATE_RESIDUAL). Rank 0.
  [[nodiscard]] PetscErrorCode CheckedDenseSolve(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y);
  /// The nrhs columns of y (m rows each) times the factored S^-1 (no update). Rank 0.
  [[nodiscard]] PetscErrorCode ReferenceSolve(double *y, PetscInt nrhs) const;
  /// The low-rank update of the factored S to D = d and the entries off_ (updated: taken; else a new LU is due).
  /// Rank 0.
  [[nodiscard]] PetscErrorCode UpdateSchur(const std::vector<PetscScalar> &d, bool &updated);
  /// See SolveReduced: y, and the residual of the reduced system. Rank 0 (RunOnRoot).
  [[nodiscard]] PetscErrorCode SolveReducedOnRoot(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y,
                                                  double &residual);
  /// Nested dissection (METIS's, on all ranks or rank 0, or CoordinateNestedDissection of coords on rank 0, see
  /// Factor) of the graph of the nodes coupled by the entries in irn_/jcn_ (n rows; this rank's start at rstart, its
  /// first owned_u rows displacements, node_size per node), into perm_in_ on rank 0 (MUMPS's PERM_IN: each node's
  /// rows together, the Schur rows last). Collective.
  [[nodiscard]] PetscErrorCode NestedDissection(PetscInt n, PetscInt rstart, PetscInt owned_u, PetscInt node_size,
                                                const std::vector<double> &coords, OrderingOptions ordering);

  DMUMPS_STRUC_C id_{};
  SchurCholesky cholesky_;
  /// The Cholesky's matrix entries on rank 0 when several ranks hold them (gathered from irn_, jcn_, val_; on one rank
  /// these stay empty and the owned arrays serve), and where each rank's part starts there.
  std::vector<MUMPS_INT> root_irn_, root_jcn_;
  std::vector<double> root_val_;
  std::vector<PetscMPIInt> gather_counts_, gather_displs_; ///< GatherLayout's (rank 0)
  bool gathered_ = false;                                  ///< the Cholesky's entries are gathered (every rank)
  double cholesky_flops_ = 0, cholesky_entries_ = 0; ///< the Cholesky's analysis (every rank)
  /// The Cholesky's entries: gathered on several ranks, the owned ones on one (rank 0; elsewhere empty).
  const std::vector<MUMPS_INT> &CholeskyRows() const { return gathered_ ? root_irn_ : irn_; }
  const std::vector<MUMPS_INT> &CholeskyCols() const { return gathered_ ? root_jcn_ : jcn_; }
  const std::vector<double> &CholeskyValues() const { return gathered_ ? root_val_ : val_; }
  /// The Cholesky's analysis of the entries read (gathered to rank 0 on several ranks) with perm_in_ (N rows, the
  /// last m the Schur rows): cholesky_flops_, cholesky_entries_ on every rank. Collective.
  [[nodiscard]] PetscErrorCode CholeskyAnalysis(PetscInt N, PetscInt m);
  /// Gathers val_ (and with pattern the entries' rows and columns) to rank 0 for the Cholesky. Collective.
  [[nodiscard]] PetscErrorCode GatherEntries(bool pattern);
  bool cholesky_in_use_ = false; ///< cholesky_ holds the analysis (and factors): MUMPS has not analysed the matrix
  const char *ordering_name_ = "";
  bool initialised_ = false, keep_values_ = false, declined_ = false;
  bool rejectable_ = false; ///< FactorChoices::confirm was given: a MUMPS failure for memory sets rejected_
  std::string rejected_;
  MPI_Comm comm_ = MPI_COMM_NULL;
  PetscMPIInt rank_ = 0;
  PetscInt null_pivots_ = 0;
  std::vector<MUMPS_INT> irn_, jcn_, listvar_, perm_in_;
  std::vector<double> val_;
  std::vector<double> schur_raw_, s0_, d0_, s_, d_factored_, redrhs_, work_;
  std::vector<double> condensed_u_; ///< A21 A11^-1 b_u of the last Condense (rank 0)
  std::vector<double> reduced_;     ///< the multiplier part of the last reduced solve, for Expand (rank 0)
  bool condensed_ = false;          ///< MUMPS holds a forward elimination (Condense) that Expand has not used yet
  std::vector<PetscBLASInt> ipiv_;
  bool s_factored_ = false, symmetric_ = true;
  std::vector<Coupling> off_, off_factored_; ///< SetCoupling's entries, and those of the factored S (rank 0)
  std::vector<Coupling> off_current_;        ///< the entries of S that the solves use (factored or updated)
  std::vector<double> d_current_;            ///< the diagonal D of S that the solves use
  bool coupled_ = false;                     ///< SetCoupling was called: changes are low-rank updates
  /// The update in use (rank 0): the changed rows R, their entries of Delta (column, value) and the LU of
  /// C = I + Delta_R W, W = S_f^-1 E_R; the columns of W computed since S_f was factored (w_cache_, m each, at
  /// w_index_[row]).
  std::vector<PetscInt> update_rows_;
  std::vector<std::vector<std::pair<PetscInt, double>>> update_entries_;
  std::vector<double> update_c_, w_cache_;
  std::map<PetscInt, PetscInt> w_index_;
  std::vector<PetscBLASInt> update_ipiv_;
  PetscInt dense_factorisations_ = 0, dense_updates_ = 0;
  bool dense_lu_ = false;                    ///< S is factored by LU (not symmetric, or entries off the diagonal)
  VecScatter to_root_ = nullptr;
  VecH root_; ///< the whole right-hand side / solution on rank 0
};

} // namespace signorini
