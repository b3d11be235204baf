// The contact solver per run and per load step: set-up, the pairs and the system built on them, the load steps (Solve,
// LoadStep) and the record of each iteration. Per active-set iteration: active_set_step.cpp; per Newton iteration:
// newton_step.cpp.
#include "signorini/loop/contact_solver.hpp"

#include "contact_solver_detail.hpp"
#include "signorini/core/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace signorini {

using namespace detail;

PetscLogEvent detail::EV_ASSEMBLY = 0, detail::EV_ACTIVE_SET = 0, detail::EV_SOLVE = 0, detail::EV_FINT = 0,
              detail::EV_STIFFNESS = 0, detail::EV_PRODUCT = 0;

PetscErrorCode ContactSolver::Setup() {
  MPI_Comm comm = mesh_.Comm();
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  if (!EV_ASSEMBLY) {
    PetscClassId id;
    PetscCall(PetscClassIdRegister("signorini", &id));
    PetscCall(PetscLogEventRegister("SigAssembly", id, &EV_ASSEMBLY));
    PetscCall(PetscLogEventRegister("SigActiveSet", id, &EV_ACTIVE_SET));
    PetscCall(PetscLogEventRegister("SigSolve", id, &EV_SOLVE));
    PetscCall(PetscLogEventRegister("SigInternalForces", id, &EV_FINT));
    PetscCall(PetscLogEventRegister("SigStiffness", id, &EV_STIFFNESS));
    PetscCall(PetscLogEventRegister("SigStiffnessProduct", id, &EV_PRODUCT));
  }
  PetscCall(BuildDirichlet(mesh_, bc_, dirichlet_));
  if (!contact_.pairs.empty()) PetscCall(SetBodyCompliance());
  if (friction_.On()) mortar_.KeepWeights();
  // svk between bodies: the variation of the mortar rows enters the Newton tangent (-newton_mortar_tangent; friction
  // keeps the rows of the current iterate).
  const bool consistent = opts_.mortar_tangent == (PetscInt)SolverOptions::MortarTangent::CONSISTENT;
  PetscCheck(!opts_.mortar_tangent_set || !contact_.pairs.empty(), comm, PETSC_ERR_USER_INPUT,
             "-newton_mortar_tangent %s applies to pairs of bodies (-contact_pairs) only",
             SolverOptions::MORTAR_TANGENT_NAMES[opts_.mortar_tangent]);
  PetscCheck(!(opts_.mortar_tangent_set && consistent && friction_.On()), comm, PETSC_ERR_USER_INPUT,
             "-newton_mortar_tangent consistent: with friction the mortar rows' tangent is the frozen one (the "
             "tangential rows' variation is not built); expected -newton_mortar_tangent frozen or no such option");
  if (model_->CurrentConfiguration() && !contact_.pairs.empty() && !friction_.On() && consistent)
    mortar_.UseConsistentTangent();
  PetscCall(mortar_.Build(mesh_, contact_, dirichlet_.fixed, (PetscInt)obstacle_.facets.size()));
  // Pairs of bodies with svk: their mortar rows follow the configuration at every Newton iteration, which the lagged
  // searches in the multiplier space of the factored tangent do not see, and cycled (the 2D cylinders of
  // options/cylinders_2d.yml: 50 iterations before the step was repeated with exact Newton steps, which took 9).
  // Exact Newton steps unless -newton_lagged_search is given.
  lagged_search_ = opts_.lagged_search && (mortar_.Empty() || opts_.lagged_search_set);
  PetscCall(FindAllPairs(pairs_, candidate_, nullptr, &held_));
  if (!model_->CurrentConfiguration()) DropOutOfZone(pairs_);
  PetscCall(dofs_.Create(mesh_, (PetscInt)pairs_.size() * RowsPerPair()));
  assembler_ = std::make_unique<Assembler>(mesh_, material_, dofs_, dirichlet_);
  PetscCall(assembler_->CheckCells());
  PetscCall(assembler_->StiffnessScale(kscale_, &krow_));
  u_local_.assign(mesh_.NumLocalVertices() * dim, 0.0);
  paired_at_ = u_local_;
  PetscCall(CreateSystem());
  lambda_.assign(pairs_.size(), 0.0);
  mult_.assign(pairs_.size(), 0.0);
  active_set_.Reset(pairs_.size());
  PetscCall(rigid_.Setup(mesh_, dirichlet_.fixed, &mortar_));
  const bool kept = system_->ReusesFactorization() || dofs_.GlobalLambda() == 0;
  PetscCheck(!(opts_.lagged_search_set && opts_.lagged_search && !kept), comm, PETSC_ERR_USER_INPUT,
             "-newton_lagged_search needs -material_model svk and the kept factorisation (-contact_reuse_factorization "
             "with a MUMPS LU or Cholesky solver)");
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SetBodyCompliance() {
  PetscFunctionBeginUser;
  // Per body the mean over its cells of (1 - nu^2) / (E t) (plane stress: 1 / (E t); t the thickness in 2D, 1 in
  // 3D: a line force indents a thinner body more), the same on every rank.
  const PetscInt nb = mesh_.NumBodies();
  std::vector<double> sum(2 * nb, 0.0);
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    double E = material_.E, nu = material_.nu;
    if (!material_.cell_constants.empty()) {
      const auto &k = material_.constants[material_.cell_constants[c]];
      E = k[0], nu = k[1];
    }
    // Each cell lives on one rank (the partition has no overlap of cells).
    sum[2 * mesh_.CellBody(c)] += (material_.plane_stress ? 1.0 : 1.0 - nu * nu) / (E * material_.CellThickness(c));
    sum[2 * mesh_.CellBody(c) + 1] += 1;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sum.data(), (int)sum.size(), MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  std::vector<double> compliance(nb, 0.0);
  for (PetscInt b = 0; b < nb; ++b) compliance[b] = sum[2 * b + 1] > 0 ? sum[2 * b] / sum[2 * b + 1] : 0.0;
  mortar_.SetCompliance(std::move(compliance));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CreateSystem() {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  // Coordinates of the owned vertices in dof order, for the rigid-body modes.
  std::vector<double> coords(dofs_.OwnedU());
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) coords[dofs_.LocalOffset(v, k)] = mesh_.X(v)[k];
  if (!mortar_.Empty()) PetscCall(mortar_.Bind(mesh_, dofs_, dirichlet_.fixed, pairs_));
  PetscCall(EvaluateAt(u_local_.data(), false));
  std::vector<PetscInt> d_nnz, o_nnz;
  PetscCall(assembler_->PatternCounts(d_nnz, o_nnz));
  system_ = std::make_unique<SaddlePointSystem>();
  if (!stats_.solver_chosen) PetscCall(ChooseSolver());
  // A path chosen by the run's own solver options takes no defaults of a path.
  system_->UsePath(stats_.solver.by == ChosenBy::SOLVER_OPTIONS ? SolverPath::DIRECT : stats_.solver.path);
  if (stats_.solver.by == ChosenBy::AUTO && stats_.solver.path == SolverPath::DIRECT) {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(mesh_.Comm(), &size));
    system_->ConfirmDirectWith([this, size](const AnalysedFactor &analysed, std::string &why) {
      const bool direct = ConfirmDirect(size, solver_problem_, analysed, stats_.solver);
      // The decision is news where the model left it to the analysis (the header said so), or where it changes
      // (LeaveDirectPath says that).
      if (!direct) why = stats_.solver.why;
      else if (stats_.solver.analysis_decides) {
        ProgressNote("solver: direct (auto: %s)", stats_.solver.why.c_str());
        PetscCallAbort(mesh_.Comm(),
                       PetscPrintf(mesh_.Comm(), "  solver: direct, confirmed: %s\n", stats_.solver.why.c_str()));
        stats_.solver.analysis_decides = false; // said once (a new system, e.g. after new pairs, is analysed again)
      }
      return direct;
    });
  }
  std::function<PetscErrorCode(Mat)> insert_pattern;
  PetscCall(SystemPattern(d_nnz, o_nnz, insert_pattern));
  std::vector<ConstraintRow> rows = rows_;
  if (friction_.On()) {
    // The tangential rows after the normal ones, on the same columns.
    std::vector<char> flags;
    friction_.Bind(mesh_, dofs_, dirichlet_.fixed, pairs_, normals_, mortar_);
    std::vector<std::vector<double>> columns;
    std::vector<double> diag;
    friction_.SystemRows(rows_, std::vector<char>(pairs_.size(), 0), rows, flags, columns, diag);
    system_->UseNonsymmetric(friction_.Describe());
    system_->UseTangentialRows((PetscInt)pairs_.size());
  }
  if (mortar_.ConsistentTangent())
    system_->UseNonsymmetric("svk between bodies with the mortar rows' consistent tangent (-newton_mortar_tangent "
                             "consistent; frozen keeps the matrix symmetric)", true);
  PetscCall(system_->Create(dofs_, rows, coords, !model_->Nonlinear(), kscale_, d_nnz, o_nnz, insert_pattern));
  if (opts_.lagged_search_set && opts_.lagged_search) system_->KeepFactorization();
  k_assembled_ = false;
  PetscCall(MatCreateVecs(system_->A(), u_.out(), nullptr));
  PetscCall(VecDuplicate(u_, du_.out()));
  PetscCall(VecDuplicate(u_, fext_.out()));
  PetscCall(VecDuplicate(u_, fint_.out()));
  fint_at_.u.clear();
  fdir_.Reset(); // made by the first step that moves a Dirichlet value
  PetscCall(PetscObjectSetName((PetscObject)u_.get(), "displacement"));
  std::vector<PetscInt> from(mesh_.NumLocalVertices() * dim);
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    for (int k = 0; k < dim; ++k) from[v * dim + k] = dofs_.Row(v, k);
  ISH is_from;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)from.size(), from.data(), PETSC_COPY_VALUES, is_from.out()));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)from.size(), u_seq_.out()));
  PetscCall(VecScatterDestroy(&scatter_));
  PetscCall(VecScatterCreate(u_, is_from, u_seq_, nullptr, &scatter_));
  keys_.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    keys_[p] = {pairs_[p].vertex, mesh_.VertexOriginal(pairs_[p].vertex), pairs_[p].facet};
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SystemPattern(std::vector<PetscInt> &d_nnz, std::vector<PetscInt> &o_nnz,
                                            std::function<PetscErrorCode(Mat)> &insert) const {
  PetscFunctionBeginUser;
  // A mortar row couples its slave node with master nodes of another body: the augmented forms add B_p^T B_p to the
  // displacement block (SaddlePointSystem::Reweight), so its entries join K's fixed pattern.
  std::vector<const ConstraintRow *> coupling;
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    if (mortar_.IsMortar(pairs_[p])) coupling.push_back(&rows_[p]);
  // A row's columns may be another rank's rows: each entry's count goes to the row's owner (a count vector in the
  // system's layout, summed), which reserves it on both its diagonal and its off-diagonal part. Without the counts
  // of other ranks' rows, the insertion reallocated row by row: 172 s of the set-up on 2 ranks at 316k dofs (3D).
  if (!mortar_.Empty()) {
    VecH extra;
    PetscCall(VecCreateMPI(mesh_.Comm(), dofs_.OwnedRows(), dofs_.GlobalRows(), extra.out()));
    for (const ConstraintRow *row : coupling)
      for (PetscInt i : row->cols) PetscCall(VecSetValue(extra, i, (PetscScalar)row->ncols, ADD_VALUES));
    PetscCall(VecAssemblyBegin(extra));
    PetscCall(VecAssemblyEnd(extra));
    const PetscScalar *e;
    PetscCall(VecGetArrayRead(extra, &e));
    for (PetscInt i = 0; i < dofs_.OwnedU(); ++i) {
      const PetscInt n = (PetscInt)PetscRealPart(e[i]);
      d_nnz[i] += std::min(n, dofs_.OwnedU()), o_nnz[i] += std::min(n, dofs_.GlobalU() - dofs_.OwnedU());
    }
    PetscCall(VecRestoreArrayRead(extra, &e));
  }
  insert = [this, coupling](Mat A) -> PetscErrorCode {
    PetscInt rows;
    PetscFunctionBeginUser;
    PetscCall(assembler_->InsertPattern(A));
    PetscCall(MatGetSize(A, &rows, nullptr));
    const bool block = rows != dofs_.GlobalRows(); // the displacement block of a nested matrix
    for (const ConstraintRow *row : coupling) {
      std::vector<PetscInt> cols(row->cols);
      if (block)
        for (PetscInt &c : cols) c = dofs_.UBlockRow(c);
      const std::vector<PetscScalar> zeros(cols.size() * cols.size(), 0.0);
      PetscCall(MatSetValues(A, (PetscInt)cols.size(), cols.data(), (PetscInt)cols.size(), cols.data(), zeros.data(),
                             ADD_VALUES));
    }
    PetscFunctionReturn(0);
  };
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::FindAllPairs(std::vector<ContactPair> &pairs, std::vector<char> &candidate,
                                           const double *u_local, std::vector<char> *held) {
  PetscFunctionBeginUser;
  PetscCall(FindContactPairs(mesh_, obstacle_, contact_, dirichlet_.fixed, pairs, candidate, u_local, held));
  if (mortar_.Empty()) PetscFunctionReturn(0);
  // Without an obstacle the default candidates (the whole boundary) are no one's.
  if (obstacle_.facets.empty()) std::fill(candidate.begin(), candidate.end(), 0);
  mortar_.AppendPairs(mesh_, pairs, candidate);
  SortPairs(mesh_, pairs);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::EvaluateAt(const double *u, bool current) {
  PetscFunctionBeginUser;
  EvaluatePairs(mesh_, obstacle_, contact_, pairs_, dofs_, dirichlet_.fixed, current, u, states_, rows_, normals_);
  // svk: the tangent planes follow the current normals.
  if (current && friction_.On()) friction_.Frame(pairs_, normals_);
  if (mortar_.Empty()) PetscFunctionReturn(0);
  mortar_.ExtendRows(rows_);
  PetscCall(mortar_.AddMasterGaps(mesh_, dofs_, u, states_));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::ChooseSolver() {
  MPI_Comm comm = mesh_.Comm();
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  SaddlePointOptions opts;
  PetscCall(ReadSaddlePointOptions(comm, opts));
  bool given, factor_pc;
  PetscCall(SolverOptionsGiven(given, factor_pc));
  SolverProblem problem;
  problem.u_dofs = dofs_.GlobalU(), problem.multipliers = dofs_.GlobalLambda(), problem.dim = dim;
  // Friction's LU is refactored at every solve where K changes (svk); with the linear material the kept factorisation
  // maps its rows onto fixed ones (KeptRows) and costs what frictionless contact does.
  problem.refactored = (friction_.On() || mortar_.ConsistentTangent()) && model_->Nonlinear();
  problem.friction_kept = friction_.On() && !model_->Nonlinear();
  // The graph of the mesh nodes, numbered by displacement block row: two nodes of a cell are neighbours.
  problem.node_graph = [&](PetscInt &num_nodes, std::vector<idx_t> &edges) -> PetscErrorCode {
    PetscFunctionBeginUser;
    num_nodes = dofs_.GlobalU() / dim;
    for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
      PetscInt n;
      const PetscInt *v = mesh_.CellVertices(c, n);
      for (PetscInt a = 0; a < n; ++a)
        if (mesh_.Owned(v[a]))
          for (PetscInt b = 0; b < n; ++b)
            if (b != a) edges.push_back((idx_t)(dofs_.URow(v[a], 0) / dim)), edges.push_back((idx_t)(dofs_.URow(v[b], 0) / dim));
    }
    PetscFunctionReturn(0);
  };
  PetscCall(ChooseSolverPath(comm, opts.path, given, factor_pc, problem, stats_.solver));
  solver_problem_ = problem;
  solver_problem_.node_graph = nullptr;
  stats_.solver_chosen = true;
  ProgressNote("solver: %s (%s: %s)", SOLVER_PATH_NAMES[(int)stats_.solver.path], CHOSEN_BY_NAMES[(int)stats_.solver.by],
               stats_.solver.why.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UpdateMortar(const std::vector<double> &u_eval, bool &rebuilt) {
  bool changed;
  PetscFunctionBeginUser;
  rebuilt = false;
  if (mortar_.Empty()) PetscFunctionReturn(0);
  PetscCall(mortar_.Update(mesh_, contact_, dirichlet_.fixed, u_eval.data(), changed));
  if (!changed) {
    // The same rows and columns: new coefficients in the same pattern.
    mortar_.RefreshPairs(pairs_);
    PetscCall(mortar_.Bind(mesh_, dofs_, dirichlet_.fixed, pairs_));
    PetscFunctionReturn(0);
  }
  // A slave node that gained or lost its row, or a row whose master nodes changed (the slave side slid along the
  // master): a new pattern, a new system; the pairs that persist keep their multipliers and active flags.
  std::vector<ContactPair> pairs;
  for (const ContactPair &p : pairs_)
    if (!mortar_.IsMortar(p)) pairs.push_back(p);
  std::vector<char> candidate = candidate_;
  mortar_.AppendPairs(mesh_, pairs, candidate);
  SortPairs(mesh_, pairs);
  PetscCall(AdoptPairsFrom(std::move(pairs), IndexPairs(pairs_), lambda_, mult_, active_set_.Flags()));
  rebuilt = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Repair(const std::vector<double> &u_eval, bool force, bool &rebuilt) {
  const int dim = mesh_.Dim();
  PetscFunctionBeginUser;
  rebuilt = false;
  // Search again when a candidate node has moved more than half the search radius since the last search (or at the
  // start of a load step): the pairs then cover every facet within half the radius of every node.
  double moved = 0;
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (candidate_[v]) {
      double d2 = 0;
      for (int k = 0; k < dim; ++k) d2 += std::pow(u_eval[v * dim + k] - paired_at_[v * dim + k], 2);
      moved = std::max(moved, std::sqrt(d2));
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
  if (!force && moved <= 0.5 * contact_.search_radius) PetscFunctionReturn(0);
  std::vector<ContactPair> pairs;
  std::vector<char> candidate;
  PetscCall(FindAllPairs(pairs, candidate, u_eval.data()));
  paired_at_ = u_eval;
  bool same = pairs.size() == pairs_.size();
  for (std::size_t p = 0; same && p < pairs.size(); ++p)
    same = pairs[p].vertex == pairs_[p].vertex && pairs[p].facet == pairs_[p].facet;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_CXX_BOOL, MPI_LAND, mesh_.Comm()));
  if (same) {
    // The same pairs: keep their multipliers and active flags; only the start of the path moves.
    for (std::size_t p = 0; p < pairs.size(); ++p) pairs_[p] = pairs[p];
    PetscFunctionReturn(0);
  }
  const PairIndex old = IndexPairs(pairs_);
  // Pairs that are new but farther than half the radius from their node are not needed before the next search (it
  // comes before any candidate has moved half the radius): if every new pair is such, the current pairs stay (those
  // found again move the start of their path), and so do the system and its factorisation. The contact zone growing
  // into the radius at the start of every svk load step rebuilt the system each time (2D Hertz at 1M dofs: two
  // orderings, analyses and factorisations of 7-9 s).
  bool needed = false;
  for (const auto &pair : pairs)
    if (!old.count({pair.vertex, pair.facet}) && pair.g0 <= 0.5 * contact_.search_radius) needed = true;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &needed, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  if (!needed) {
    for (const auto &pair : pairs) {
      const auto it = old.find({pair.vertex, pair.facet});
      if (it != old.end()) pairs_[it->second] = pair;
    }
    PetscCall(PetscInfo(nullptr, "pair search: the new pairs are all farther than half the search radius; the pairs "
                        "stay\n"));
    PetscFunctionReturn(0);
  }
  // New pairs: carry the multiplier and the active flag of every pair that persists, then a new pattern.
  PetscCall(AdoptPairsFrom(std::move(pairs), old, lambda_, mult_, active_set_.Flags()));
  stats_.repairings++;
  rebuilt = true;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AdoptPairs(std::vector<ContactPair> pairs, const std::vector<double> &lambda,
                                         const std::vector<double> &mult, const std::vector<char> &active) {
  PetscFunctionBeginUser;
  std::vector<double> u_owned;
  PetscCall(OwnedDisplacement(u_owned));
  // The friction state of the pairs that persist (svk's new pairs keep their stick or slip and slip's origin).
  const Friction::Memory friction = friction_.On() ? friction_.Remember(pairs_) : Friction::Memory();
  pairs_ = std::move(pairs);
  PetscCall(dofs_.Create(mesh_, (PetscInt)pairs_.size() * RowsPerPair()));
  PetscCall(CreateSystem());
  if (friction_.On()) friction_.Recall(friction, pairs_);
  PetscCall(SetOwnedDisplacement(u_owned));
  lambda_ = lambda, mult_ = mult;
  active_set_.Reset(pairs_.size());
  active_set_.Set(active);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::AdoptPairsFrom(std::vector<ContactPair> pairs, const PairIndex &old,
                                             const std::vector<double> &lambda, const std::vector<double> &mult,
                                             const std::vector<char> &active) {
  std::vector<double> l(pairs.size(), 0.0), m(pairs.size(), 0.0);
  std::vector<char> a(pairs.size(), 0);
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto it = old.find({pairs[p].vertex, pairs[p].facet});
    if (it != old.end()) l[p] = lambda[it->second], m[p] = mult[it->second], a[p] = active[it->second];
  }
  PetscCall(AdoptPairs(std::move(pairs), l, m, a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::OwnedDisplacement(std::vector<double> &u) const {
  const PetscScalar *a;
  PetscFunctionBeginUser;
  // The displacement rows come first on every rank, in an order that does not depend on the pairs.
  PetscCall(VecGetArrayRead(u_, &a));
  u.assign(a, a + dofs_.OwnedU());
  PetscCall(VecRestoreArrayRead(u_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SetOwnedDisplacement(const std::vector<double> &u) {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(u_, &a));
  std::copy(u.begin(), u.end(), a);
  PetscCall(VecRestoreArray(u_, &a));
  PetscCall(UpdateLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::UpdateLocal() {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(scatter_, u_, u_seq_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter_, u_, u_seq_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar *a;
  PetscCall(VecGetArrayRead(u_seq_, &a));
  std::copy(a, a + u_local_.size(), u_local_.begin());
  PetscCall(VecRestoreArrayRead(u_seq_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SetDirichlet(double factor) {
  const int dim = mesh_.Dim();
  PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(u_, &u));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (dirichlet_.fixed[v * dim + k]) u[dofs_.LocalOffset(v, k)] = dirichlet_.At(v * dim + k, factor);
  PetscCall(VecRestoreArray(u_, &u));
  PetscCall(UpdateLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Monitor(const IterationRecord &r) const {
  PetscFunctionBeginUser;
  ProgressNote("step %" PetscInt_FMT " iteration %" PetscInt_FMT ": %" PetscInt_FMT " active pairs, %" PetscInt_FMT
               " changed", r.step, r.iteration, r.active, r.changed);
  if (contact_.monitor)
    PetscCall(PetscPrintf(mesh_.Comm(),
                          "  step %" PetscInt_FMT " (load %.4g) it %" PetscInt_FMT ": active %" PetscInt_FMT
                          " changed %" PetscInt_FMT " min lambda %.6e max penetration %.6e residual %.6e ksp its %"
                          PetscInt_FMT "\n",
                          r.step, r.load_factor, r.iteration, r.active, r.changed, r.min_lambda, r.max_penetration,
                          r.residual, r.krylov));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::CertifiedAtRest(StepState &st, bool &ok) {
  PetscFunctionBeginUser;
  // Loads that start later or ended earlier: the step's loads and prescribed values are those of its start, whose
  // state (the unloaded one before the first step) stays if the certificate says it is a solution.
  PetscCall(EvaluateIterate(st, 0));
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    states_[p].lambda = lambda_[p];
    states_[p].active = active_set_.Flags()[p];
  }
  Certificate cert;
  PetscCall(Certify(st.u_eval, st.r.norm, EquilibriumTol(st.r.scale, st.r.roundoff), cert));
  ok = cert.Satisfied();
  if (ok) certificate_ = cert, stats_.reason = model_->ConvergedReason();
  PetscCall(PetscInfo(nullptr, "load step %" PetscInt_FMT ": no ramp moves; its start %s\n", st.step,
                      ok ? "is certified, no solve" : "is not certified, the step solves"));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::LoadStep(PetscInt step, double from, double factor, bool &ok) {
  // The first step's rule (the pairs touching at the start) holds until some load or prescribed value has moved.
  const bool first = !AnyRampMoves(bc_, 0, from);
  StepState st{step, factor, first};
  PetscFunctionBeginUser;
  st.newton.exact = retry_.exact_newton;
  ok = false;
  // The increment of the prescribed displacements enters through the first solve of the step (its Dirichlet rows
  // and the coupling K_fd du_d of the free rows), not by moving the boundary nodes alone, which could invert the
  // cells next to them under large prescribed displacements.
  st.delta.assign(u_local_.size(), 0.0);
  st.u_eval.resize(u_local_.size());
  st.next.assign(pairs_.size(), 0);
  for (std::size_t i = 0; i < st.delta.size(); ++i)
    if (dirichlet_.fixed[i]) st.delta[i] = dirichlet_.At(i, factor) - u_local_[i];
  PetscCall(VecZeroEntries(fext_));
  PetscCall(assembler_->AssembleLoads(bc_, factor, fext_));
  PetscReal load_scale;
  PetscCall(VecNorm(fext_, NORM_INFINITY, &load_scale));
  active_set_.BeginStep(load_scale);
  system_->BeginLooseSolves();
  // Friction: the slips of this step count from the converged state.
  if (friction_.On()) PetscCall(friction_.BeginStep(pairs_, states_, u_local_.data()));
  retry_.widen_to = 0;
  retry_.unheld_detail.clear();
  if (!AnyRampMoves(bc_, from, factor)) {
    PetscCall(CertifiedAtRest(st, ok));
    if (ok) PetscFunctionReturn(0);
  }
  // svk too against rigid obstacles: its first update reads the linearised gaps of the touching solve's whole
  // increment (StepState::touch_gaps), then the next solve restarts from the step's start like the linear material's.
  st.restartable = first && system_->Iterative() && !friction_.On() && (!model_->Nonlinear() || mortar_.Empty());
  active_set_.SetOverlapRule(st.restartable && !model_->Nonlinear());
  if (st.restartable) PetscCall(OwnedDisplacement(st.u_start));
  PetscInt it = 0;
  for (;; ++it) {
    PetscInt changes = 0;
    // svk after its touching solve: the iterate is the step's start (SolveAndUpdate), the gaps its increment's.
    const bool at_start = it == 1 && !st.touch_gaps.empty();
    PetscCall(EvaluateIterate(st, it));
    if (it == 0) {
      // The iterative path's verdict on a body that no forces on its pairs can hold (UnbalancedLoad).
      bool unheld;
      PetscCall(UnbalancedLoad(unheld));
      if (unheld) {
        stats_.reason = Reason::DIVERGED_NOT_HELD;
        break;
      }
    }
    {
      // Active-set update: first the pairs touching at the start, then the complementarity rule (ActiveSet).
      ScopedTimer t(stats_.time_active_set);
      for (std::size_t p = 0; p < pairs_.size(); ++p) {
        states_[p].lambda = lambda_[p];
        states_[p].active = active_set_.Flags()[p];
      }
      if (it == 0) {
        PetscCall(active_set_.First(states_, first, keys_, normals_, st.next));
      } else if (at_start) {
        // svk after its touching solve: the step length cut that solve's increment while det F <= MIN_DET_F
        // somewhere (a body held at one node deforms there without bound; the octant of options/hertz3d.yml at 290k
        // dofs: to 1/128), and the cut iterate's gaps misled the first update: it activated 72 pairs, the next 3845,
        // and the updates after it released the surplus a ring at a time (14 Newton iterations, 214 Krylov ones). The
        // whole increment's linearised gaps are the linear material's, whose first update takes about the final set:
        // 1542 pairs, then 7 Newton iterations in all, 116 Krylov iterations, the same state. The increment is not
        // applied: the next solve starts from the step's start (as RestartFromStepStart would choose), whose gaps
        // states_ keeps for its right-hand side.
        std::vector<PairState> touched = states_;
        for (std::size_t p = 0; p < pairs_.size(); ++p)
          touched[p].gap = st.touch_gaps[p];
        st.touch_gaps.clear();
        PetscCall(PetscInfo(nullptr, "first update: from the gaps of the touching solve's whole increment (svk); the "
                                     "next solve starts from the step's start\n"));
        PetscCall(active_set_.Next(touched, it, st.loose, keys_, normals_, st.next, changes));
      } else {
        PetscCall(active_set_.Next(states_, it, st.loose, keys_, normals_, st.next, changes));
      }
      if (friction_.On()) {
        // The stick and slip sets of the next solve, from this solve's multipliers and slips.
        st.friction_changes = st.friction_turns = 0;
        if (it == 0) friction_.First(st.next);
        else
          PetscCall(friction_.Next(mesh_.Comm(), pairs_, states_, st.next, st.u_eval.data(), contact_.c,
                                   st.friction_changes, st.friction_turns));
        friction_.SetKey(st.next, st.key);
        PetscCall(PetscInfo(nullptr, "friction: %" PetscInt_FMT " pair(s) change set, %" PetscInt_FMT
                            " slip direction(s) turn\n", st.friction_changes, st.friction_turns));
      }
    }
    Outcome outcome;
    PetscCall(StepControl(st, it, changes, outcome));
    if (outcome == Outcome::STOP && !st.singular && st.pivoted < 2 &&
        (stats_.reason == Reason::DIVERGED_CYCLING || stats_.reason == Reason::DIVERGED_NOT_HELD ||
         stats_.reason == Reason::DIVERGED_MAX_IT)) {
      // The rule's sets cycled, or the body seemed free: the linear material's last resort, a finite method (again
      // after a set that came back was pivoted: the sets from it may have cycled, or not held the body). Out of
      // iterations, only its verdict on the body counts.
      Pivot pivot;
      PetscCall(PivotedActiveSet(st, it, ReasonName(stats_.reason), pivot));
      if (pivot == Pivot::UNHELD) stats_.reason = Reason::DIVERGED_NOT_HELD;
      else if (pivot == Pivot::SET && stats_.reason != Reason::DIVERGED_MAX_IT) {
        outcome = Outcome::SOLVE, changes = 1;
        stats_.reason = Reason::NONE;
      }
    }
    st.searching = it == 0 || changes > 0;
    if (outcome == Outcome::CONVERGED) ok = true;
    if (outcome == Outcome::CONVERGED || outcome == Outcome::STOP) break;
    if (outcome == Outcome::EXTENDED) continue;
    if (it == 1 && changes > 0 && st.restartable && !st.stabilised && !at_start)
      PetscCall(RestartFromStepStart(st, it));
    active_set_.Set(st.next);
    friction_.Adopt();
    bool held;
    PetscCall(Held(st.next, held));
    st.stabilised = !held;
    st.touching = false;
    if (it == 0 && st.restartable && held) {
      PetscInt pairs = (PetscInt)std::count(st.next.begin(), st.next.end(), (char)1);
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &pairs, 1, MPIU_INT, MPI_SUM, mesh_.Comm()));
      st.touching = pairs >= 1 && pairs <= TOUCHING_PAIRS;
    }
    PetscCall(AssembleSystem(st));
    PetscCall(SolveAndUpdate(st));
    if (st.singular) break;
  }
  // The automatic choice's direct path stopped before it could solve: the step runs again on the iterative path.
  if (!system_->DirectRejected().empty()) PetscFunctionReturn(0);
  // A factorisation found null pivots: the supports and the candidate pairs do not hold the body, or the MUMPS controls
  // call regular pivots null (the step may be repeated with the pairs of a wider radius, UnpairedAfterFailure).
  if (st.singular) stats_.reason = Reason::DIVERGED_SINGULAR;
  if (!ok) PetscCall(UnpairedAfterFailure(st, it));
  PetscFunctionReturn(0);
}

void ContactSolver::HoldingRows(const std::vector<char> &next, HoldingSet &h) const {
  h.keys = keys_, h.normals = normals_, h.flags = next;
  h.pair_of.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p) h.pair_of[p] = p;
  if (!friction_.On()) return;
  // A stick pair holds its node along its tangents too, a 3D slip pair across its slip.
  std::vector<std::array<double, 3>> dirs;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    if (!next[p]) continue;
    friction_.HeldDirections(p, dirs);
    for (const auto &d : dirs)
      h.keys.push_back(keys_[p]), h.normals.push_back(d), h.flags.push_back(1), h.pair_of.push_back(p);
  }
}

PetscErrorCode ContactSolver::Held(const std::vector<char> &next, bool &held) const {
  PetscFunctionBeginUser;
  if (!friction_.On()) {
    PetscCall(rigid_.Held(keys_, normals_, next, held));
    PetscFunctionReturn(0);
  }
  HoldingSet h;
  HoldingRows(next, h);
  PetscCall(rigid_.Held(h.keys, h.normals, h.flags, held, &h.pair_of));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::MoveRigidly(const RigidMotion &motion, double t) {
  const int dim = mesh_.Dim();
  PetscScalar *u;
  PetscFunctionBeginUser;
  // u += t m(x) a on the owned displacement rows; a free mode moves no fixed component (its Dirichlet rows are in
  // the Gram matrix whose null space it is), which are skipped all the same.
  PetscCall(VecGetArray(u_, &u));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v) {
    if (!mesh_.Owned(v)) continue;
    double m[3];
    rigid_.Motion(v, motion, m);
    for (int k = 0; k < dim; ++k)
      if (!dirichlet_.fixed[v * dim + k]) u[dofs_.LocalOffset(v, k)] += t * m[k];
  }
  PetscCall(VecRestoreArray(u_, &u));
  PetscCall(UpdateLocal());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::RecordIteration(PetscInt step, PetscInt it, double factor, const std::vector<char> &next,
                                              PetscInt changes, PetscInt krylov, double rnorm, double solve_time) {
  // Active pairs of the next solve; min lambda over the current active set; deepest penetration in a pair's zone.
  PetscInt count = 0, gcount;
  double m[2] = {INFINITY, 0}, gm[2];
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    count += next[p];
    if (states_[p].active) m[0] = std::min(m[0], lambda_[p]);
    if (states_[p].InZone()) m[1] = std::max(m[1], -states_[p].gap);
  }
  m[0] = -m[0];
  PetscCallMPI(MPI_Allreduce(&count, &gcount, 1, MPIU_INT, MPI_SUM, mesh_.Comm()));
  PetscCallMPI(MPI_Allreduce(m, gm, 2, MPI_DOUBLE, MPI_MAX, mesh_.Comm()));
  const IterationRecord rec{step, it, gcount, changes, krylov, factor, std::isfinite(gm[0]) ? -gm[0] : 0.0,
                            gm[1], rnorm, solve_time};
  stats_.history.push_back(rec);
  PetscCall(Monitor(rec));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::SaveConverged(Converged &c) const {
  PetscFunctionBeginUser;
  PetscCall(OwnedDisplacement(c.u));
  c.pairs = pairs_;
  c.lambda = lambda_;
  c.mult = mult_;
  c.active = active_set_.Flags();
  if (friction_.On()) c.friction = friction_.Save();
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::RestoreConverged(const Converged &c) {
  PetscFunctionBeginUser;
  PetscCall(SetOwnedDisplacement(c.u));
  // The tangent of the failed attempt is not lagged into the next one.
  k_assembled_ = false;
  bool differ = pairs_.size() != c.pairs.size() ||
                !std::equal(pairs_.begin(), pairs_.end(), c.pairs.begin(),
                            [](const ContactPair &a, const ContactPair &b) {
                              return a.vertex == b.vertex && a.facet == b.facet;
                            });
  // Collective decision: the pairs may have changed on some ranks only.
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_CXX_BOOL, MPI_LOR, mesh_.Comm()));
  if (differ) PetscCall(AdoptPairs(c.pairs, c.lambda, c.mult, c.active));
  pairs_ = c.pairs;
  lambda_ = c.lambda;
  mult_ = c.mult;
  active_set_.Set(c.active);
  if (friction_.On() && c.friction.grip.size() == pairs_.size()) friction_.Restore(c.friction);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::LeaveDirectPath(const Converged &saved) {
  PetscFunctionBeginUser;
  if (!stats_.solver.left_direct) LeaveDirect(system_->DirectRejected(), stats_.solver);
  PetscCall(PetscPrintf(mesh_.Comm(), "Solver: the direct path stopped (%s): the iterative path solves the load step "
                        "again\n", stats_.solver.why.c_str()));
  ProgressNote("solver: iterative (auto: %s)", stats_.solver.why.c_str());
  stats_.reason = Reason::NONE;
  // The last converged state, and a new system (CreateSystem) on the iterative path.
  PetscCall(RestoreConverged(saved));
  PetscCall(AdoptPairs(pairs_, lambda_, mult_, active_set_.Flags()));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Solve(const std::function<PetscErrorCode(PetscInt, double)> &step_done) {
  MPI_Comm comm = mesh_.Comm();
  PetscFunctionBeginUser;
  Converged saved;
  PetscCall(SaveConverged(saved));
  double t = 0, dt = 1.0 / opts_.load_steps;
  PetscInt step = 0;
  Reason repeated = Reason::NONE; // svk: the failure that this attempt repeats with exact Newton steps, if it does
  bool exact_tried = false;       // svk: a step has been repeated so (once per run)
  while (t < 1.0 - 1e-12) {
    const double t_try = std::min(1.0, t + dt);
    bool ok;
    PetscCall(LoadStep(step + 1, t, t_try, ok));
    if (!ok && !system_->DirectRejected().empty()) {
      PetscCall(LeaveDirectPath(saved));
      continue;
    }
    if (contact_.converged_reason)
      PetscCall(PetscPrintf(comm, "Contact solve %s: %s at load factor %.6g after %" PetscInt_FMT " solve(s)\n",
                            ok ? "converged" : "diverged", ReasonName(stats_.reason), t_try, stats_.solves));
    if (ok) {
      t = t_try;
      stats_.steps = ++step;
      repeated = Reason::NONE; // a repeat that converged is over: a later failure is its own step's
      PetscCall(SaveConverged(saved));
      // After the last solve the factorisation or preconditioner goes before the last step's output.
      if (t >= 1.0 - 1e-12) PetscCall(system_->Release());
      PetscCall(step_done(step, t));
      continue;
    }
    const RetryHistory history{model_->Nonlinear(), lagged_search_ && system_->ReusesFactorization(),
                               retry_.exact_newton, exact_tried,
                               stats_.cuts,         opts_.max_cuts,
                               retry_.first_unheld};
    const RetryDecision d = DecideRetry({stats_.reason, retry_.widen_to > 0, repeated}, history);
    stats_.reason = d.reason;
    retry_.exact_newton = d.exact_newton;
    if (!d.wider_search) retry_.widen_to = 0;
    repeated = Reason::NONE;
    switch (d.action) {
    case Retry::WIDEN:
      PetscCall(PrintWidening(t_try));
      PetscCall(SetOwnedDisplacement(saved.u));
      k_assembled_ = false;
      pairs_ = saved.pairs;
      PetscCall(WidenSearch(saved.lambda, saved.mult, saved.active));
      saved.pairs = pairs_;
      saved.lambda = lambda_;
      saved.mult = mult_;
      saved.active = active_set_.Flags();
      break;
    case Retry::EXACT_NEWTON:
      exact_tried = true;
      repeated = stats_.reason;
      PetscCall(PetscPrintf(comm,
                            "Load step at factor %.6g failed (%s) after lagged Newton searches: repeating it with "
                            "exact Newton steps\n",
                            t_try, ReasonName(stats_.reason)));
      PetscCall(SetOwnedDisplacement(saved.u));
      k_assembled_ = false;
      PetscCall(AdoptPairs(saved.pairs, saved.lambda, saved.mult, saved.active));
      break;
    case Retry::CUT:
      stats_.cuts++;
      dt *= 0.5;
      PetscCall(PetscPrintf(comm, "Load step at factor %.6g failed (%s); cutting the increment to %.6g\n", t_try,
                            ReasonName(stats_.reason), dt));
      PetscCall(RestoreConverged(saved));
      break;
    case Retry::FAIL: {
      std::string message;
      PetscCall(Failure(t_try, d, message));
      SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "%s", message.c_str());
    }
    }
  }
  stats_.search_radius = contact_.search_radius;
  // The final state is the last converged step's, whose pairs (states_), internal force (fint_) and certificate
  // StepControl left as they are.
  PetscCheck(certificate_.Satisfied(), comm, PETSC_ERR_NOT_CONVERGED,
             "the final state is not a contact solution: %s", certificate_.Violation().c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::PrintWidening(double t_try) const {
  MPI_Comm comm = mesh_.Comm();
  PetscFunctionBeginUser;
  // A candidate went into a facet it has no pair with: the step is repeated, from the last converged state, with
  // pairs found within a wider radius (linear material: and that pair; not a cut: the increment stays).
  if (retry_.widen_node >= 0)
    PetscCall(PetscPrintf(comm,
                          "Load step at factor %.6g failed (%s) with node %" PetscInt_FMT " %.6g inside the "
                          "obstacle, on a facet it has no contact pair with: searching the pairs again within %.6g "
                          "(was %.6g)\n",
                          t_try, ReasonName(stats_.reason), retry_.widen_node, retry_.widen_depth, retry_.widen_to,
                          contact_.search_radius));
  else
    PetscCall(PetscPrintf(comm,
                          "Load step at factor %.6g failed (%s): searching the pairs again within %.6g (was %.6g), "
                          "for facets beyond the radius that may hold the body\n",
                          t_try, ReasonName(stats_.reason), retry_.widen_to, contact_.search_radius));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSolver::Failure(double t_try, const RetryDecision &d, std::string &message) {
  PetscFunctionBeginUser;
  FailureReport r;
  r.reason = d.reason;
  r.load_factor = t_try;
  r.svk = model_->Nonlinear();
  r.deformed_after_unheld = d.deformed_after_unheld;
  r.has_obstacle = !obstacle_.facets.empty() || !mortar_.Empty();
  r.search_radius = contact_.search_radius;
  if (d.reason == Reason::DIVERGED_SINGULAR) r.singular_prefix = system_->SingularReport("");
  r.unheld_detail = retry_.unheld_detail;
  r.violation = stats_.violation;
  if (model_->Nonlinear() && d.reason == Reason::DIVERGED_MAX_IT) {
    bool held_by_supports;
    PetscCall(rigid_.Held(keys_, normals_, std::vector<char>(active_set_.Flags().size(), 0), held_by_supports));
    r.free_without_contact = !held_by_supports;
  }
  message = FailureMessage(r);
  PetscFunctionReturn(0);
}

} // namespace signorini
