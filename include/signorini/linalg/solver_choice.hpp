// Which path solves the saddle-point systems of a run: the direct one (the kept factorisation, MUMPS) or the
// iterative one (a Schur fieldsplit with GAMG on the displacement block), chosen by -contact_solver or, by default,
// from the factorisation's memory and time against the machine's memory and the iterative path's time.
#pragma once

#include "signorini/linalg/mumps_schur.hpp"

#include <metis.h>
#include <petscsys.h>

#include <functional>
#include <string>
#include <vector>

namespace signorini {

enum class SolverPath { AUTO, DIRECT, ITERATIVE };
extern const char *const SOLVER_PATH_NAMES[]; ///< "auto", "direct", "iterative"

/// -contact_solver and -contact_memory_budget (read by ReadSaddlePointOptions).
struct SolverPathOptions {
  SolverPath path = SolverPath::AUTO;
  PetscBool path_set = PETSC_FALSE;
  double budget = 0; ///< bytes per rank; 0: the machine's (MemoryBudget)
  PetscBool budget_set = PETSC_FALSE;
};

/// A memory size as people write it: a number of bytes with an optional unit k, M, G or T (powers of 1024, an
/// optional trailing B: "512M", "1.5GB", "2e9"). Returns false when text is not one.
bool ParseMemorySize(const std::string &text, double &bytes);

/// The elimination cost of factoring the displacement block in the kept factorisation's order: factor entries and
/// flops (from the node graph, times dim^2 and dim^3), or from the measured model (exact false).
struct FactorEstimate {
  double entries = 0, flops = 0;
  bool exact = false;
  bool analysed = false; ///< from the analysis of the matrix itself (ConfirmDirect)
};

/// What the choice needs from the problem. node_graph: this rank's edges of the graph of the mesh nodes (pairs of
/// global node numbers, each rank's nodes numbered after the lower ranks', in displacement row order) and the number
/// of nodes; called only when the measured model cannot decide.
struct SolverProblem {
  PetscInt u_dofs = 0, multipliers = 0;
  int dim = 2;
  /// The direct path factors at every solve (friction, svk's consistent tangent between bodies: MUMPS LU of a
  /// nonsymmetric matrix, no kept factorisation), and
  /// the iterative path solves every active-set iteration to its tolerance: the two are compared per solve.
  bool refactored = false;
  /// Friction on the kept factorisation (the linear material): one factorisation for the run, a dense LU of the
  /// multipliers' Schur complement at every solve; compared per solve too.
  bool friction_kept = false;
  std::function<PetscErrorCode(PetscInt &num_nodes, std::vector<idx_t> &edges)> node_graph;
};

/// Who chose the path: the automatic choice, -contact_solver, or the run's own solver options.
enum class ChosenBy { AUTO, CONTACT_SOLVER, SOLVER_OPTIONS };
extern const char *const CHOSEN_BY_NAMES[]; ///< "auto", "-contact_solver", "solver options"

/// The path and why (for the run's header, -progress and summary.json).
struct SolverChoice {
  SolverPath path = SolverPath::DIRECT; ///< DIRECT or ITERATIVE
  ChosenBy by = ChosenBy::AUTO;
  std::string why;                      ///< one sentence
  double direct_bytes = -1, budget_bytes = -1;         ///< per rank (auto only)
  bool budget_given = false;                           ///< budget_bytes is -contact_memory_budget's
  bool left_direct = false; ///< the direct path was chosen, then left at run time (ConfirmDirect, LeaveDirect)
  bool analysis_decides = false; ///< the model left the choice to the analysis of the matrix, not yet said
  double direct_seconds = -1, iterative_seconds = -1;  ///< the models' estimates (auto only)
  FactorEstimate factor;
};

/// Memory a run may use per rank: the node's available memory (MemAvailable of /proc/meminfo) shared by the ranks on
/// the node, the least over the nodes. Collective.
[[nodiscard]] PetscErrorCode MemoryBudget(MPI_Comm comm, double &bytes);

/// The kept factorisation's cost from the node graph: METIS's nested dissection of the graph (on rank 0) and the
/// symbolic Cholesky factorisation of the node pattern (SchurCholesky::Analyse). Collective.
[[nodiscard]] PetscErrorCode EstimateFactorization(MPI_Comm comm, const SolverProblem &problem, FactorEstimate &est);

/// The path of a run: -contact_solver's when given; else, given: the run gave a solver of its own (-contact_ksp_type,
/// -contact_pc_type or the kept factorisation's options), which then decides, direct when its PC factors
/// (factor_pc); else the automatic choice. Collective.
[[nodiscard]] PetscErrorCode ChooseSolverPath(MPI_Comm comm, const SolverPathOptions &opts, bool given, bool factor_pc,
                                              const SolverProblem &problem, SolverChoice &choice);

/// The automatic choice's direct path, checked against the analysis of the matrix before its factorisation (the
/// kept factorisation's symbolic analysis: the Cholesky's exact factor, or MUMPS's estimates): the same comparison
/// as ChooseSolverPath's with the analysed factor. Updates choice (the estimates, and the path and why when the
/// direct path does not fit or is the slower one) and returns whether the direct path stays. Not collective (the
/// analysis is the same on every rank).
bool ConfirmDirect(PetscMPIInt size, const SolverProblem &problem, const AnalysedFactor &analysed,
                   SolverChoice &choice);

/// The automatic choice's direct path failed at run time (why: MUMPS out of memory, said as it is): choice turns to
/// the iterative path and says so.
void LeaveDirect(const std::string &why, SolverChoice &choice);

/// Whether the run gave a solver of its own: -contact_ksp_type, -contact_pc_type, a factor's solver type, the kept
/// factorisation's options or MUMPS controls (-contact_mat_mumps_*); factor_pc: its PC factors (LU or Cholesky, the
/// default when only the Krylov method is given).
[[nodiscard]] PetscErrorCode SolverOptionsGiven(bool &given, bool &factor_pc);

/// The iterative path's settings (options/solver/fieldsplit_gamg.yml) as defaults of the options database under the
/// prefix contact_: each one that the run did not give. Returns the names set, so that they can be taken out again.
/// nullspace: the null-space preconditioner (PCNULLSPACE, pairs of one node each without friction) instead of the
/// Schur fieldsplit, with the same displacement-block solver (-contact_fieldsplit_u_*) and Krylov method.
[[nodiscard]] PetscErrorCode SetIterativeDefaults(std::vector<std::string> &set, bool nullspace = false);

/// 3D, a fieldsplit whose displacement block is GAMG's (the iterative path, or a preset such as
/// options/solver/fieldsplit_gamg.yml): GAMG squares the graph on its first two levels unless the run gave
/// -contact_fieldsplit_u_pc_gamg_square_graph (PETSc's default: one level).
[[nodiscard]] PetscErrorCode SetGamgDefaults3d();

} // namespace signorini
