#include "signorini/linalg/solver_choice.hpp"

#include "signorini/linalg/pc_nullspace.hpp"

#include "signorini/core/parse.hpp"
#include "signorini/linalg/mumps_schur.hpp"
#include "signorini/linalg/parallel_dissection.hpp"
#include "signorini/linalg/schur_cholesky.hpp"

#include <petscksp.h>
#include <petscpc.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace signorini {

const char *const SOLVER_PATH_NAMES[] = {"auto", "direct", "iterative"};
const char *const CHOSEN_BY_NAMES[] = {"auto", "-contact_solver", "solver options"};

namespace {

// The measured models (docs/performance.md, *The automatic solver choice*). The run's memory besides the factors
// (mesh, matrices, vectors; about the iterative path's whole need) per displacement dof, in 2D and 3D.
constexpr double BASE_BYTES_PER_DOF_2D = 1000, BASE_BYTES_PER_DOF_3D = 2600;
// Elimination flops per second of one rank in the kept factorisation (the supernodal Cholesky and MUMPS, 3D).
constexpr double FLOP_RATE = 2e10;
// The iterative path's contact solve, seconds per displacement dof on one rank (3D fieldsplit_gamg).
constexpr double ITERATIVE_SECONDS_PER_DOF = 1e-4;
// One solve to the certificate's tolerance on the iterative path, seconds per displacement dof on one rank at
// ITERATIVE_SOLVE_DOFS dofs, growing with the square root of the dofs (3D Cattaneo-Mindlin with friction,
// fieldsplit_gamg with BiCGStab: 1.3e-5 at 13k dofs, 2.5e-5 at 38k, 5.5e-5 at 159k).
constexpr double ITERATIVE_SECONDS_PER_DOF_PER_SOLVE = 2.5e-5, ITERATIVE_SOLVE_DOFS = 38000;
// An LU factorisation against the Cholesky's: twice the entries (L and U); its time four times the Cholesky's at
// FLOP_RATE (twice the flops, and MUMPS's LU with pivoting of the indefinite saddle-point matrix measured at half that
// rate: 3D Cattaneo-Mindlin at 12.9k dofs, 0.52 s per iteration against 0.21 s for twice the node graph's flops).
constexpr double LU_ENTRIES = 2, LU_TIME = 4;
// Active-set changes a kept dense Schur complement is factored for (its m^3/3 flops each).
constexpr double DENSE_FACTORISATIONS = 4;
// Friction on the kept factorisation: the solves its one factorisation serves (Cattaneo-Mindlin: 34-71 in 2D, 47-60
// in 3D), the rate of a dense LU of the Schur complement with its solves (3D Cattaneo-Mindlin at 38k dofs, 3342
// multipliers: 0.59 s per solve for 2 m^3/3 = 2.5e10 flops), and the cost of a solve after a low-rank update of that
// LU (MumpsSchur::UpdateSchur) as a fraction of a new LU (3D Cattaneo-Mindlin: 0.12 at 3342 multipliers, 0.14 at
// 8853), with one new LU per run.
constexpr double FRICTION_SOLVES = 50, DENSE_LU_RATE = 4e10, DENSE_UPDATE_SHARE = 0.15;
// The dense Schur complement's memory with friction: S, and the cached columns of S_f^-1 and the capacitance matrix
// of its updates (at most half of S's columns each).
constexpr double DENSE_UPDATE_MEMORY = 1.75;
// The measured model of the factor (nested dissection: n^(4/3) entries and n^2 flops in 3D, n log n and n^1.5 in
// 2D); it decides alone when its memory is this factor or more above the budget, its time this factor or more above
// the iterative path's, or its memory this factor below the budget with the times this factor apart; else the node
// graph's symbolic factorisation (EstimateFactorization) decides (METIS on the node graph: about 10 s at 275k nodes).
constexpr double MODEL_MARGIN = 4;

FactorEstimate ModelEstimate(const SolverProblem &p) {
  const double n = (double)p.u_dofs;
  FactorEstimate e;
  if (p.dim == 3) e.entries = 30 * std::pow(n, 4.0 / 3), e.flops = 30 * n * n;
  else e.entries = 8 * n * std::log2(std::max(n, 2.0)), e.flops = 85 * std::pow(n, 1.5);
  return e;
}

/// Bytes per rank and seconds of the direct path with factor estimate e on size ranks; analysed: the analysis of the
/// matrix (who factors it, and MUMPS's own memory estimate) where it has been made.
void DirectCost(const SolverProblem &p, const FactorEstimate &e, PetscMPIInt size, double &bytes, double &seconds,
                const AnalysedFactor *analysed = nullptr) {
  const double m = (double)p.multipliers, rows = (double)(p.u_dofs + p.multipliers);
  // Friction's direct path (and svk's consistent mortar tangent): MUMPS LU refactored at every solve, no kept Schur
  // complement; seconds per solve.
  const bool cholesky = analysed ? analysed->cholesky
                                 : !p.refactored && rows <= (size == 1 ? CHOLESKY_MAX_ROWS : CHOLESKY_MAX_ROWS_GATHERED);
  // The Cholesky's factor with its update stack and the gathered entries, on rank 0 (the 108k-dof cube: 1.62 GB peak
  // against 1.61 estimated); MUMPS's with its workspace, shared unevenly by the ranks (2D Hertz at 600k dofs: the
  // estimate 1.35 times MUMPS's factor entries, the peak 0.8 times the estimated memory); after MUMPS's analysis,
  // its own estimate of its largest rank's memory (INFOG(16)).
  double factor = (cholesky ? 8 * 1.45 * e.entries : 8 * 1.2 * e.entries / size * (size > 1 ? 1.2 : 1.0)) *
                  (p.refactored ? LU_ENTRIES : 1.0);
  if (analysed && !cholesky && analysed->mumps_bytes > 0) factor = analysed->mumps_bytes;
  const bool dense = !p.refactored && !MumpsSchur::DenseCostsMore(m, e.flops);
  const double base = p.dim == 3 ? BASE_BYTES_PER_DOF_3D : BASE_BYTES_PER_DOF_2D;
  bytes = base * (double)p.u_dofs / size + factor + (dense ? 8 * m * m * (p.friction_kept ? DENSE_UPDATE_MEMORY : 1) : 0);
  seconds = (e.flops * (p.refactored ? LU_TIME : 1.0) + (dense ? DENSE_FACTORISATIONS * m * m * m / 3 : 0)) /
            (FLOP_RATE * (cholesky ? 1 : size));
  // Friction on the kept factorisation, per solve: its share of the one factorisation and of one dense LU, and a
  // low-rank update of that LU (declined: LU refactored at every solve).
  if (p.friction_kept)
    seconds = dense ? e.flops / (FLOP_RATE * (cholesky ? 1 : size)) / FRICTION_SOLVES +
                          2 * m * m * m / 3 / DENSE_LU_RATE * (1 / FRICTION_SOLVES + DENSE_UPDATE_SHARE)
                    : e.flops * LU_TIME / (FLOP_RATE * size);
}

/// What the compared times are for friction (per solve), else nothing.
const char *PerSolve(const SolverProblem &p) {
  if (p.refactored) return " per solve (an LU refactored at every solve: friction, or svk's consistent tangent between bodies)";
  if (p.friction_kept) return " per solve (friction: a low-rank update of the dense Schur complement's LU per solve)";
  return "";
}

std::string Bytes(double b) {
  char text[32];
  if (b >= 1 << 30) std::snprintf(text, sizeof(text), "%.3g GB", b / (1 << 30));
  else std::snprintf(text, sizeof(text), "%.3g MB", b / (1 << 20));
  return text;
}

} // namespace

bool ParseMemorySize(const std::string &text, double &bytes) {
  // A number as ParseFinite reads it, then an optional unit letter and an optional B.
  std::string number = text;
  if (!number.empty() && (number.back() == 'B' || number.back() == 'b')) number.pop_back();
  double scale = 1;
  const std::string units = "kKmMgGtT";
  const std::size_t unit = number.empty() ? std::string::npos : units.find(number.back());
  if (unit != std::string::npos) {
    scale = std::pow(1024.0, 1 + (double)(unit / 2));
    number.pop_back();
  }
  const std::optional<double> v = ParseFinite(number);
  if (!v || !(*v > 0) || !std::isfinite(*v * scale)) return false;
  bytes = *v * scale;
  return true;
}

PetscErrorCode MemoryBudget(MPI_Comm comm, double &bytes) {
  MPI_Comm node;
  PetscMPIInt on_node;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_size(node, &on_node));
  PetscCallMPI(MPI_Comm_free(&node));
  double available = 0;
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream in(line);
    std::string key;
    double kb;
    if (in >> key >> kb && key == "MemAvailable:") available = kb * 1024;
  }
  if (available <= 0) {
    // Not Linux: the physical memory's free pages.
    const double pages = (double)sysconf(_SC_AVPHYS_PAGES), page = (double)sysconf(_SC_PAGESIZE);
    available = pages > 0 && page > 0 ? pages * page : 0;
  }
  // A tenth stays for the system and whatever else the estimates leave out.
  bytes = 0.9 * available / on_node;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bytes, 1, MPI_DOUBLE, MPI_MIN, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode EstimateFactorization(MPI_Comm comm, const SolverProblem &problem, FactorEstimate &est) {
  PetscMPIInt rank;
  PetscInt num_nodes = 0;
  std::vector<idx_t> edges, all;
  std::vector<PetscMPIInt> displs;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(problem.node_graph(num_nodes, edges));
  PetscCall(GatherOnRoot(comm, edges, all, displs));
  std::vector<idx_t>().swap(edges);
  double cost[3] = {0, 0, 0};
  if (rank == 0) {
    Graph g = BuildGraph((idx_t)num_nodes, all);
    std::vector<idx_t>().swap(all);
    std::vector<idx_t> order;
    const int status = MetisOrder(g, order);
    cost[2] = status == METIS_OK && (PetscInt)order.size() == num_nodes;
    if (cost[2] != 0) {
      // The lower triangle of the node pattern with its diagonal, and each node's pivot position.
      std::vector<int> row, col, position(num_nodes);
      for (idx_t k = 0; k < (idx_t)order.size(); ++k) position[order[k]] = (int)k;
      for (idx_t v = 0; v < g.Size(); ++v) {
        row.push_back((int)v), col.push_back((int)v);
        for (idx_t e = g.xadj[v]; e < g.xadj[v + 1]; ++e)
          if (g.adjncy[e] > v) row.push_back((int)g.adjncy[e]), col.push_back((int)v);
      }
      Graph().xadj.swap(g.xadj);
      SchurCholesky symbolic;
      PetscCall(symbolic.Analyse(num_nodes, 0, row, col, position, 0));
      // A node column of c node rows holds about dim^2 c entries and costs dim^3 times its flops.
      const double d = problem.dim;
      cost[0] = d * d * symbolic.Entries(), cost[1] = d * d * d * symbolic.Flops();
    }
  }
  PetscCallMPI(MPI_Bcast(cost, 3, MPI_DOUBLE, 0, comm));
  PetscCheck(cost[2] != 0, comm, PETSC_ERR_LIB, "the nested dissection of the node graph failed (METIS)");
  est.entries = cost[0], est.flops = cost[1], est.exact = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ChooseSolverPath(MPI_Comm comm, const SolverPathOptions &opts, bool given, bool factor_pc,
                                const SolverProblem &problem, SolverChoice &choice) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  choice = SolverChoice();
  if (opts.path != SolverPath::AUTO) {
    choice.path = opts.path;
    choice.by = ChosenBy::CONTACT_SOLVER;
    choice.why = std::string("-contact_solver ") + SOLVER_PATH_NAMES[(int)opts.path];
    PetscFunctionReturn(0);
  }
  if (given) {
    choice.path = factor_pc ? SolverPath::DIRECT : SolverPath::ITERATIVE;
    choice.by = ChosenBy::SOLVER_OPTIONS;
    choice.why = "the run's own solver options";
    PetscFunctionReturn(0);
  }
  choice.by = ChosenBy::AUTO;
  choice.budget_given = opts.budget_set;
  if (opts.budget_set) choice.budget_bytes = opts.budget;
  else PetscCall(MemoryBudget(comm, choice.budget_bytes));
  const double n = (double)problem.u_dofs;
  choice.iterative_seconds = (problem.refactored || problem.friction_kept
                                  ? ITERATIVE_SECONDS_PER_DOF_PER_SOLVE * std::sqrt(n / ITERATIVE_SOLVE_DOFS)
                                  : ITERATIVE_SECONDS_PER_DOF) *
                             n / size;
  // The model first; where it is near a limit, the node graph's symbolic factorisation.
  choice.factor = ModelEstimate(problem);
  DirectCost(problem, choice.factor, size, choice.direct_bytes, choice.direct_seconds);
  const auto near = [](double a, double b) { return a < MODEL_MARGIN * b && b < MODEL_MARGIN * a; };
  const bool too_large = choice.direct_bytes >= MODEL_MARGIN * choice.budget_bytes;
  const bool too_slow = choice.direct_seconds >= MODEL_MARGIN * choice.iterative_seconds;
  const bool fits = MODEL_MARGIN * choice.direct_bytes <= choice.budget_bytes;
  const bool decided = too_large || too_slow || (fits && !near(choice.direct_seconds, choice.iterative_seconds));
  // Near a limit: the kept factorisation's own analysis decides (ConfirmDirect), before any numerical factorisation
  // (it orders the matrix anyway; the node graph's estimate would be a second nested dissection). Friction's LU is
  // analysed and factored in one call of PETSc's interface: there the node graph's symbolic factorisation decides.
  if (!decided && !problem.refactored) {
    choice.path = SolverPath::DIRECT;
    choice.analysis_decides = true;
    char text[256];
    std::snprintf(text, sizeof(text), "the measured model puts a factorisation near the limits (about %s per rank): "
                  "the analysis of the matrix decides", Bytes(choice.direct_bytes).c_str());
    choice.why = text;
    PetscCall(PetscInfo(nullptr, "model: direct %.4g bytes per rank, %.4g s; iterative %.4g s; budget %.4g bytes per "
                        "rank: the analysis decides\n", choice.direct_bytes, choice.direct_seconds,
                        choice.iterative_seconds, choice.budget_bytes));
    PetscFunctionReturn(0);
  }
  if (!decided) {
    PetscCall(EstimateFactorization(comm, problem, choice.factor));
    DirectCost(problem, choice.factor, size, choice.direct_bytes, choice.direct_seconds);
  }
  PetscCall(PetscInfo(nullptr, "factor %.4g entries, %.4g flops (%s); direct %.4g bytes per rank, %.4g s; iterative "
                      "%.4g s; budget %.4g bytes per rank\n", choice.factor.entries, choice.factor.flops,
                      choice.factor.exact ? "node graph" : "model", choice.direct_bytes, choice.direct_seconds,
                      choice.iterative_seconds, choice.budget_bytes));
  const std::string estimate = choice.factor.exact ? "" : " by the measured model";
  char text[512];
  if (choice.direct_bytes > choice.budget_bytes) {
    choice.path = SolverPath::ITERATIVE;
    std::snprintf(text, sizeof(text), "a factorisation would need about %s per rank%s, more than the %s %s",
                  Bytes(choice.direct_bytes).c_str(), estimate.c_str(), Bytes(choice.budget_bytes).c_str(),
                  opts.budget_set ? "of -contact_memory_budget" : "this machine has per rank");
  } else if (choice.direct_seconds > choice.iterative_seconds) {
    choice.path = SolverPath::ITERATIVE;
    std::snprintf(text, sizeof(text),
                  "a factorisation (about %s per rank) fits, but would take about %.3g s%s against %.3g s iterative%s",
                  Bytes(choice.direct_bytes).c_str(), choice.direct_seconds, estimate.c_str(),
                  choice.iterative_seconds, PerSolve(problem));
  } else {
    choice.path = SolverPath::DIRECT;
    // The budget stays out of this sentence (summary.json has it): the machine's free memory varies from run to run.
    std::snprintf(text, sizeof(text), "the factorisation fits (about %s per rank%s) and is the faster path",
                  Bytes(choice.direct_bytes).c_str(), estimate.c_str());
  }
  choice.why = text;
  PetscFunctionReturn(0);
}

bool ConfirmDirect(PetscMPIInt size, const SolverProblem &problem, const AnalysedFactor &analysed,
                   SolverChoice &choice) {
  choice.factor.entries = analysed.entries, choice.factor.flops = analysed.flops;
  choice.factor.exact = choice.factor.analysed = true;
  DirectCost(problem, choice.factor, size, choice.direct_bytes, choice.direct_seconds, &analysed);
  const std::string bytes = Bytes(choice.direct_bytes);
  char text[512];
  if (choice.direct_bytes > choice.budget_bytes) {
    choice.path = SolverPath::ITERATIVE;
    std::snprintf(text, sizeof(text), "the analysis of the matrix puts a factorisation at about %s per rank, more "
                  "than the %s %s", bytes.c_str(), Bytes(choice.budget_bytes).c_str(),
                  choice.budget_given ? "of -contact_memory_budget" : "this machine has per rank");
  } else if (choice.direct_seconds > choice.iterative_seconds) {
    choice.path = SolverPath::ITERATIVE;
    std::snprintf(text, sizeof(text), "a factorisation (about %s per rank by the analysis of the matrix) fits, but "
                  "would take about %.3g s against %.3g s iterative%s", bytes.c_str(), choice.direct_seconds,
                  choice.iterative_seconds, PerSolve(problem));
  } else {
    std::snprintf(text, sizeof(text), "the factorisation fits (about %s per rank by the analysis of the matrix) and is "
                  "the faster path", bytes.c_str());
  }
  choice.why = text;
  choice.left_direct = choice.path == SolverPath::ITERATIVE;
  return !choice.left_direct;
}

void LeaveDirect(const std::string &why, SolverChoice &choice) {
  choice.path = SolverPath::ITERATIVE;
  choice.left_direct = true;
  choice.why = why;
}

PetscErrorCode SolverOptionsGiven(bool &given, bool &factor_pc) {
  static const char *const NAMES[] = {"-contact_ksp_type",
                                      "-contact_pc_type",
                                      "-contact_pc_factor_mat_solver_type",
                                      "-contact_reuse_factorization",
                                      "-contact_reuse_max_it",
                                      "-contact_kept_solver",
                                      "-contact_nested_dissection",
                                      "-contact_nested_dissection_parallel"};
  PetscFunctionBeginUser;
  given = false;
  for (const char *name : NAMES) {
    PetscBool has;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &has));
    given = given || has;
  }
  char *all = nullptr;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  given = given || std::string(all ? all : "").find("-contact_mat_mumps_") != std::string::npos;
  PetscCall(PetscFree(all));
  char pc[64] = "";
  PetscBool has;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-contact_pc_type", pc, sizeof(pc), &has));
  factor_pc = !has || std::string(pc) == PCLU || std::string(pc) == PCCHOLESKY;
  PetscFunctionReturn(0);
}

PetscErrorCode SetIterativeDefaults(std::vector<std::string> &set, bool nullspace) {
  // options/solver/fieldsplit_gamg.yml (why each: there).
  static const char *const DEFAULTS[][2] = {{"-contact_ksp_type", "gmres"},
                                            {"-contact_ksp_pc_side", "right"},
                                            {"-contact_ksp_rtol", "1e-10"},
                                            {"-contact_ksp_max_it", "2000"},
                                            {"-contact_pc_type", "fieldsplit"},
                                            {"-contact_pc_fieldsplit_type", "schur"},
                                            {"-contact_pc_fieldsplit_schur_fact_type", "upper"},
                                            {"-contact_pc_fieldsplit_schur_precondition", "selfp"},
                                            {"-contact_fieldsplit_u_ksp_type", "preonly"},
                                            {"-contact_fieldsplit_u_pc_type", "gamg"},
                                            {"-contact_fieldsplit_u_pc_gamg_threshold", "0.01"},
                                            {"-contact_fieldsplit_lambda_ksp_type", "preonly"},
                                            {"-contact_fieldsplit_lambda_pc_type", "jacobi"}};
  PetscFunctionBeginUser;
  set.clear();
  const auto set_default = [&set](const char *name, const char *value) -> PetscErrorCode {
    PetscBool has;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &has));
    if (has) return 0;
    PetscCall(PetscOptionsSetValue(nullptr, name, value));
    set.push_back(name);
    return 0;
  };
  char pc[64] = "", ksp[64] = "", side[16] = "";
  PetscBool pc_given, ksp_given, side_given;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-contact_pc_type", pc, sizeof(pc), &pc_given));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-contact_ksp_type", ksp, sizeof(ksp), &ksp_given));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-contact_ksp_pc_side", side, sizeof(side), &side_given));
  char *all = nullptr;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const std::string given = all ? all : "";
  PetscCall(PetscFree(all));
  const bool schur_given = given.find("-contact_pc_fieldsplit_") != std::string::npos ||
                           given.find("-contact_fieldsplit_lambda_") != std::string::npos;
  // The null-space preconditioner where it applies, unless the run gives another preconditioner or options of the
  // Schur fieldsplit's own (its type, its multiplier block); -contact_pc_type nullspace given (or set by an earlier
  // system of the run) keeps it.
  nullspace = pc_given ? std::string(pc) == PCNULLSPACE : nullspace && !schur_given;
  // Its Krylov method: CG unless the run gives another (a right preconditioner side given: GMRES). CG: one V-cycle
  // per iteration, as GMRES, but a few vectors instead of GMRES's 30 (a gigabyte per rank at 4M dofs), and no
  // orthogonalisation; left-preconditioned, it tests the true residual as right-preconditioned GMRES does
  // (docs/performance.md, twenty-third session).
  const std::string method = ksp_given ? ksp : side_given && std::string(side) == "right" ? KSPGMRES : KSPCG;
  const bool right =
      method == KSPGMRES || method == KSPFGMRES || method == KSPLGMRES || method == KSPDGMRES || method == KSPPGMRES;
  if (nullspace) {
    PetscCall(set_default("-contact_pc_type", PCNULLSPACE));
    PetscCall(set_default("-contact_ksp_type", method.c_str()));
    if (method == KSPCG) {
      PetscCall(set_default("-contact_ksp_pc_side", "left"));
      PetscCall(set_default("-contact_ksp_norm_type", "unpreconditioned"));
    }
  }
  for (const auto &d : DEFAULTS) {
    const std::string name = d[0];
    const bool schur =
        name.rfind("-contact_pc_fieldsplit_", 0) == 0 || name.rfind("-contact_fieldsplit_lambda_", 0) == 0;
    if (nullspace && (schur || (name == "-contact_ksp_pc_side" && !right))) continue; // the fieldsplit's, GMRES's
    PetscCall(set_default(d[0], d[1]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SetGamgDefaults3d() {
  char type[64] = "";
  PetscBool has, gamg;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-contact_fieldsplit_u_pc_type", type, sizeof(type), &gamg));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-contact_fieldsplit_u_pc_gamg_square_graph", &has));
  if (!gamg || std::string(type) != PCGAMG || has) PetscFunctionReturn(0);
  // Aggregates of the squared graph on the second level as well: the Galerkin products of a 3D elastic matrix are
  // most of GAMG's set-up, and the second level's shrink from 4 to 1 s. Measured on one rank (docs/performance.md,
  // twelfth session): the 824k-dof hexahedral cube's elastic solve 27 -> 22 s (set-up 17.1 -> 13.4 s, 13 -> 14
  // BiCGStab iterations), the 1.07M-dof octant's contact solve 127 -> 94 s (set-ups 58 -> 23 s, 92 -> 94 Krylov
  // iterations). Not in 2D, where the set-up is cheap and the looser first level changed the 2D Hertz's active-set
  // path (300k dofs: 3 -> 7 active-set iterations, 4.8 -> 7.1 s).
  PetscCall(PetscOptionsSetValue(nullptr, "-contact_fieldsplit_u_pc_gamg_square_graph", "2"));
  PetscFunctionReturn(0);
}

} // namespace signorini
