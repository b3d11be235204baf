// MUMPS with a Schur complement on the multipliers: one factorisation, then solves with a changing diagonal D.
#include "signorini/linalg/mumps_schur.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/linalg/nested_dissection.hpp"
#include "signorini/linalg/parallel_dissection.hpp"

#include <metis.h>
#include <petscblaslapack.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace signorini {

#define ICNTL(I) icntl[(I)-1]
#define CNTL(I) cntl[(I)-1]
#define INFOG(I) infog[(I)-1]

namespace {
PetscLogEvent EV_ORDERING = 0, EV_ANALYSIS = 0, EV_FACTOR = 0, EV_SCHUR = 0, EV_SOLVE = 0, EV_REDUCED = 0;
PetscLogEvent EV_CHOL_ANALYSIS = 0, EV_CHOL_FACTOR = 0, EV_CHOL_SOLVE = 0;
PetscErrorCode RegisterEvents() {
  PetscClassId id;
  PetscFunctionBeginUser;
  if (EV_ANALYSIS) PetscFunctionReturn(0);
  PetscCall(PetscClassIdRegister("signorini MUMPS-Schur", &id));
  PetscCall(PetscLogEventRegister("SigOrdering", id, &EV_ORDERING));
  PetscCall(PetscLogEventRegister("SigMumpsAnalysis", id, &EV_ANALYSIS));
  PetscCall(PetscLogEventRegister("SigMumpsFactor", id, &EV_FACTOR));
  PetscCall(PetscLogEventRegister("SigSchurFactor", id, &EV_SCHUR));
  PetscCall(PetscLogEventRegister("SigMumpsSolve", id, &EV_SOLVE));
  PetscCall(PetscLogEventRegister("SigReducedSolve", id, &EV_REDUCED));
  PetscCall(PetscLogEventRegister("SigCholAnalysis", id, &EV_CHOL_ANALYSIS));
  PetscCall(PetscLogEventRegister("SigCholFactor", id, &EV_CHOL_FACTOR));
  PetscCall(PetscLogEventRegister("SigCholSolve", id, &EV_CHOL_SOLVE));
  PetscFunctionReturn(0);
}
} // namespace

PetscInt MumpsControls::Icntl(int k, PetscInt fallback) const {
  for (const auto &[i, v] : icntl)
    if (i == k) return v;
  return fallback;
}

std::string MumpsControls::PivotControls() const {
  std::string list;
  const auto add = [&list](const std::string &item) { list += (list.empty() ? "" : ", ") + item; };
  for (const auto &[k, v] : icntl)
    if (k == 6 || k == 8 || k == 12 || k == 24 || k == 56)
      add("-contact_mat_mumps_icntl_" + std::to_string(k) + " " + std::to_string(v));
  char value[32];
  for (const auto &[k, v] : cntl) {
    std::snprintf(value, sizeof(value), "%.6g", v);
    add("-contact_mat_mumps_cntl_" + std::to_string(k) + " " + value);
  }
  return list;
}

PetscErrorCode ReadMumpsControls(MPI_Comm comm, MumpsControls &controls) {
  PetscFunctionBeginUser;
  controls = MumpsControls{};
  // Under the solver's prefix, as PETSc's interface reads them (MUMPS 5.5 has 60 ICNTL and 15 CNTL entries).
  const auto name = [](const char *array, int k) {
    return "-mat_mumps_" + std::string(array) + "_" + std::to_string(k);
  };
  for (int k = 1; k <= 60; ++k) {
    PetscInt v;
    PetscBool set;
    PetscCall(PetscOptionsGetInt(nullptr, "contact_", name("icntl", k).c_str(), &v, &set));
    if (set) controls.icntl.emplace_back(k, v);
  }
  for (int k = 1; k <= 15; ++k) { // the values were checked at set-up (CheckSolverOptionValues): finite, in range
    PetscReal v;
    PetscBool set;
    PetscCall(PetscOptionsGetReal(nullptr, "contact_", name("cntl", k).c_str(), &v, &set));
    if (!set) continue;
    controls.cntl.emplace_back(k, v);
  }
  // ICNTL(7), the ordering (MUMPS 5.5): 0 AMD, 1 the given one (the kept factorisation's nested dissection), 2 AMF,
  // 3 SCOTCH, 4 PORD, 5 METIS, 6 QAMD, 7 automatic. MUMPS replaces an ordering it was built without (Debian's: SCOTCH
  // and METIS) by its automatic choice, and PETSc's interface stops at the factorisation on any other value.
  const PetscInt order = controls.Icntl(7, 7);
  PetscCheck(order >= 0 && order <= 7, comm, PETSC_ERR_USER_INPUT,
             "-contact_mat_mumps_icntl_7 %" PetscInt_FMT ": expected a MUMPS ordering, 0 (AMD), 1 (the nested "
             "dissection of -contact_nested_dissection), 2 (AMF), 4 (PORD), 6 (QAMD) or 7 (automatic)", order);
  PetscCheck(order != MumpsControls::ICNTL7_SCOTCH && order != MumpsControls::ICNTL7_METIS, comm,
             PETSC_ERR_USER_INPUT,
             "-contact_mat_mumps_icntl_7 %" PetscInt_FMT ": this MUMPS is built without %s (it would order by its "
             "automatic choice instead); expected 0 (AMD), 1 (the nested dissection of -contact_nested_dissection, "
             "METIS's in 3D), 2 (AMF), 4 (PORD), 6 (QAMD) or 7 (automatic)", order,
             order == MumpsControls::ICNTL7_METIS ? "METIS" : "SCOTCH");
  PetscFunctionReturn(0);
}

MumpsSchur::~MumpsSchur() { Release(); }

void MumpsSchur::Release() {
  if (initialised_) {
    id_.job = -2;
    dmumps_c(&id_);
  }
  initialised_ = condensed_ = s_factored_ = cholesky_in_use_ = false;
  cholesky_.Clear();
  for (auto *v : {&root_irn_, &root_jcn_})
    std::vector<MUMPS_INT>().swap(*v);
  std::vector<double>().swap(root_val_);
  gathered_ = false;
  for (auto *v : {&gather_counts_, &gather_displs_})
    std::vector<PetscMPIInt>().swap(*v);
  for (auto *v : {&irn_, &jcn_, &listvar_, &perm_in_}) std::vector<MUMPS_INT>().swap(*v);
  for (auto *v : {&val_, &schur_raw_, &s0_, &d0_, &s_, &d_factored_, &redrhs_, &work_, &condensed_u_, &reduced_})
    std::vector<double>().swap(*v);
  std::vector<PetscBLASInt>().swap(ipiv_);
  off_.clear(), off_factored_.clear(), off_current_.clear(), d_current_.clear();
  update_rows_.clear(), update_entries_.clear(), update_c_.clear(), update_ipiv_.clear();
  w_index_.clear(), std::vector<double>().swap(w_cache_);
  coupled_ = false;
  (void)VecScatterDestroy(&to_root_);
  root_.Reset();
}

std::string MumpsFailure(int infog1, int infog2, const char *phase) {
  char text[512];
  const char *instead = "expected a smaller mesh, more ranks on more memory, or the iterative path (-contact_solver "
                        "iterative)";
  if (infog1 == -13) {
    // An allocation failed; INFOG(2) is its size in entries, or in millions of entries when negative.
    const double entries = infog2 < 0 ? -1e6 * infog2 : (double)infog2;
    std::snprintf(text, sizeof(text),
                  "MUMPS could not allocate %.3g GB in the %s of the saddle-point system (INFOG(1) = -13): the "
                  "factors do not fit in this machine's memory; %s", 8e-9 * entries, phase, instead);
  } else if (infog1 == -19) {
    std::snprintf(text, sizeof(text),
                  "MUMPS needs more working memory in the %s of the saddle-point system than -contact_mat_mumps_icntl_23 "
                  "allows (INFOG(1) = -19, INFOG(2) = %d); expected a larger ICNTL(23), 0 (MUMPS's own estimate) or "
                  "the iterative path (-contact_solver iterative)", phase, infog2);
  } else {
    std::snprintf(text, sizeof(text),
                  "MUMPS failed in the %s of the saddle-point system: INFOG(1) = %d, INFOG(2) = %d (see the MUMPS "
                  "users' guide; -8/-9/-17/-20: out of workspace, -10: the matrix is singular)", phase, infog1, infog2);
  }
  return text;
}

bool MumpsOutOfMemory(int infog1) {
  for (int code : {-8, -9, -11, -12, -13, -14, -15, -17, -19, -20})
    if (infog1 == code) return true;
  return false;
}

std::string MumpsOutOfMemoryText(int infog1, int infog2, const char *phase) {
  char text[160];
  std::snprintf(text, sizeof(text), "MUMPS ran out of memory in the %s (INFOG(1) = %d, INFOG(2) = %d)", phase, infog1,
                infog2);
  return text;
}

PetscErrorCode MumpsSchur::Call(int job, const char *phase) {
  PetscFunctionBeginUser;
  id_.job = job;
  dmumps_c(&id_);
  // INFOG is the same on every rank, so every rank takes the same branch. A factorisation out of workspace (-8, -9:
  // the analysis' estimate was too small, e.g. for the delayed pivots of the indefinite matrix on 3 ranks) is run
  // again with twice the extra room (ICNTL(14)), as MUMPS's guide advises, a few times.
  for (int retry = 0; job == 2 && (id_.INFOG(1) == -8 || id_.INFOG(1) == -9) && retry < MUMPS_WORKSPACE_RETRIES;
       ++retry) {
    id_.ICNTL(14) = 2 * std::max<MUMPS_INT>(id_.ICNTL(14), MUMPS_WORKSPACE_INCREASE);
    PetscCall(PetscInfo(nullptr, "MUMPS factorisation out of workspace (INFOG(1) = %d): again with ICNTL(14) = %d\n",
                        (int)id_.INFOG(1), (int)id_.ICNTL(14)));
    dmumps_c(&id_);
  }
  if (id_.INFOG(1) < 0 && rejectable_ && MumpsOutOfMemory((int)id_.INFOG(1))) {
    // The automatic solver choice leaves the direct path (FactorChoices::confirm): the caller releases and reports.
    rejected_ = MumpsOutOfMemoryText((int)id_.INFOG(1), (int)id_.INFOG(2), phase);
    PetscFunctionReturn(0);
  }
  PetscCheck(id_.INFOG(1) >= 0, comm_, id_.INFOG(1) == -13 ? PETSC_ERR_MEM : PETSC_ERR_LIB, "%s",
             MumpsFailure((int)id_.INFOG(1), (int)id_.INFOG(2), phase).c_str());
  PetscFunctionReturn(0);
}

namespace {

/// The rows of the ranks (ranges[3 r]: rank r's first row, [3 r + 1]: its displacement rows, [3 r + 2]: its nodes)
/// and each rank's first node (first_node[r], first_node[size]: all nodes). Nodes are numbered by rank, in row order.
struct NodeNumbering {
  std::vector<PetscInt> ranges, first_node;
  PetscInt node_size = 1;
  PetscInt Nodes() const { return first_node.back(); }
  /// The node of a global row, -1 for a multiplier row.
  PetscInt NodeOf(PetscInt row) const {
    std::size_t r = 0;
    while (r + 2 < first_node.size() && ranges[3 * (r + 1)] <= row) ++r;
    const PetscInt offset = row - ranges[3 * r];
    return offset < ranges[3 * r + 1] ? first_node[r] + offset / node_size : -1;
  }
  /// The first global row of node k.
  PetscInt FirstRow(PetscInt k) const {
    const std::size_t r = std::upper_bound(first_node.begin(), first_node.end(), k) - first_node.begin() - 1;
    return ranges[3 * r] + (k - first_node[r]) * node_size;
  }
};

/// The edges of the node graph from the entries (irn, jcn: 1-based global rows, grouped by row) of this rank's rows
/// (one triangle holds every coupled pair in the rows of its earlier node; a row alone may have none: a Dirichlet row
/// holds its diagonal only), one per row and neighbour: pairs of node numbers, the first one this rank's.
std::vector<idx_t> NodeEdges(PetscMPIInt rank, const NodeNumbering &nodes, PetscInt rstart,
                             const std::vector<MUMPS_INT> &irn, const std::vector<MUMPS_INT> &jcn) {
  std::vector<idx_t> edges;
  // At most one edge per entry: reserved (pages untouched cost nothing) instead of grown by copies.
  edges.reserve(2 * irn.size());
  const PetscInt owned_u = nodes.ranges[3 * rank + 1];
  PetscInt last_row = -1, last_node = -1, row_node = -1;
  for (std::size_t e = 0; e < irn.size(); ++e) {
    const PetscInt i = irn[e] - 1, j = jcn[e] - 1;
    if (i != last_row) {
      last_row = i, last_node = -1;
      row_node = i - rstart < owned_u ? nodes.first_node[rank] + (i - rstart) / nodes.node_size : -1;
    }
    if (row_node < 0) continue;
    const PetscInt col_node = nodes.NodeOf(j);
    if (col_node < 0 || col_node == row_node || col_node == last_node) continue;
    last_node = col_node;
    edges.push_back((idx_t)row_node), edges.push_back((idx_t)col_node);
  }
  return edges;
}

/// The node graph of the edges of every rank (NodeEdges) on rank 0. Collective.
PetscErrorCode GatherNodeGraph(MPI_Comm comm, PetscMPIInt rank, PetscInt num_nodes, std::vector<idx_t> &edges,
                               Graph &g) {
  std::vector<idx_t> all;
  std::vector<PetscMPIInt> displs;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) { // the edges are all here: no copy
    PetscCheck(edges.size() <= (std::size_t)INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP,
               "the matrix graph is too large for the nested-dissection ordering on one rank; choose one of MUMPS's "
               "orderings with -contact_mat_mumps_icntl_7");
    g = BuildGraph((idx_t)num_nodes, edges);
    PetscFunctionReturn(0);
  }
  PetscCall(GatherOnRoot(comm, edges, all, displs));
  edges.clear();
  edges.shrink_to_fit();
  if (rank == 0) g = BuildGraph((idx_t)num_nodes, all);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode MumpsSchur::NestedDissection(PetscInt n, PetscInt rstart, PetscInt owned_u, PetscInt node_size,
                                            const std::vector<double> &coords, OrderingOptions ordering) {
  PetscMPIInt size;
  PetscLogDouble start, graph_built;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(EV_ORDERING, 0, 0, 0, 0));
  PetscCall(PetscTime(&start));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  // The graph of the nodes: a node's displacement rows are node_size consecutive rows of one rank, and the rows of
  // two nodes are coupled all or not at all. The multiplier rows are left out: MUMPS puts them last (they are the
  // Schur rows), and each couples the rows of one node only.
  NodeNumbering nodes;
  nodes.node_size = node_size;
  PetscInt mine[3] = {rstart, owned_u, owned_u / node_size};
  nodes.ranges.resize(3 * size);
  PetscCallMPI(MPI_Allgather(mine, 3, MPIU_INT, nodes.ranges.data(), 3, MPIU_INT, comm_));
  nodes.first_node.assign(size + 1, 0);
  for (PetscMPIInt r = 0; r < size; ++r) nodes.first_node[r + 1] = nodes.first_node[r] + nodes.ranges[3 * r + 2];
  const PetscInt num_nodes = nodes.Nodes();
  // METIS on every rank: the edges stay where they are (PartitionNestedDissection); otherwise the graph on rank 0.
  const bool distributed = ordering.graph == GraphOrdering::METIS && ordering.parallel && size > 1;
  std::vector<idx_t> edges = NodeEdges(rank_, nodes, rstart, irn_, jcn_);
  Graph g;
  if (!distributed) PetscCall(GatherNodeGraph(comm_, rank_, num_nodes, edges, g));
  // The node coordinates for the coordinate cuts, in the same node numbering.
  std::vector<double> x;
  if (ordering.graph == GraphOrdering::COORDINATES) {
    std::vector<PetscMPIInt> xcounts(size), xdispls(size, 0);
    for (PetscMPIInt r = 0; r < size; ++r) {
      PetscCall(PetscMPIIntCast(nodes.ranges[3 * r + 2] * node_size, &xcounts[r]));
      if (r > 0) xdispls[r] = xdispls[r - 1] + xcounts[r - 1];
    }
    if (rank_ == 0) x.resize(num_nodes * node_size);
    PetscCallMPI(MPI_Gatherv(coords.data(), xcounts[rank_], MPI_DOUBLE, x.data(), xcounts.data(), xdispls.data(),
                             MPI_DOUBLE, 0, comm_));
  }
  PetscCall(PetscTime(&graph_built));
  // The order of the nodes (position k: the node eliminated k-th) on rank 0: METIS's nested dissection (on every
  // rank, DistributedNestedDissection, or on rank 0) or the coordinate cuts (rank 0).
  int status = METIS_OK;
  std::vector<int64_t> perm;
  if (ordering.graph == GraphOrdering::COORDINATES) {
    if (rank_ == 0)
      perm = CoordinateNestedDissection(std::vector<int64_t>(g.xadj.begin(), g.xadj.end()),
                                        std::vector<int64_t>(g.adjncy.begin(), g.adjncy.end()), x, (int)node_size);
  } else if (distributed) {
    std::vector<idx_t> first(nodes.first_node.begin(), nodes.first_node.end()), order;
    PetscCall(PartitionNestedDissection(comm_, first, edges, order, status));
    perm.assign(order.begin(), order.end());
  } else if (rank_ == 0) {
    std::vector<idx_t> order;
    status = MetisOrder(g, order);
    perm.assign(order.begin(), order.end());
  }
  if (rank_ == 0) {
    // Each node's rows in that order, then the Schur rows (MUMPS wants them last: INFOG(1) = -4); MUMPS takes the
    // position of each variable in the pivot order (1-based).
    perm_in_.assign(n, 0);
    MUMPS_INT position = 0;
    for (std::size_t k = 0; k < perm.size(); ++k)
      for (PetscInt c = 0; c < node_size; ++c) perm_in_[nodes.FirstRow(perm[k]) + c] = ++position;
    for (MUMPS_INT v : listvar_) perm_in_[v - 1] = ++position;
    status = status == METIS_OK && position == (MUMPS_INT)n && (PetscInt)perm.size() == num_nodes ? METIS_OK
                                                                                                    : METIS_ERROR;
  }
  PetscCallMPI(MPI_Bcast(&status, 1, MPI_INT, 0, comm_));
  PetscCheck(status == METIS_OK, comm_, PETSC_ERR_LIB, "the nested dissection of the saddle-point matrix failed (%d)",
             status);
  PetscLogDouble end;
  PetscCall(PetscTime(&end));
  PetscCall(PetscInfo(nullptr, "ordering: node graph %.3g s, nested dissection %.3g s (%s)\n",
                      graph_built - start, end - graph_built,
                      ordering.graph == GraphOrdering::COORDINATES ? "coordinate cuts, rank 0"
                      : distributed                                ? "METIS, all ranks"
                                                                   : "METIS, rank 0"));
  PetscCall(PetscLogEventEnd(EV_ORDERING, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::ReadValues(Mat A, bool pattern) {
  PetscInt rstart, rend;
  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  // The owned rows, 1-based; for LDL^T their upper triangle only (MUMPS sums duplicate entries of a symmetric matrix).
  // Counted first, then written in place: growing the arrays entry by entry took a quarter of the contact solve at
  // 20k rows (reallocations, copies, page faults). A refactorisation (pattern false) rewrites the values alone, in
  // the order of the pattern read before (A's pattern is fixed).
  std::size_t nnz = 0;
  for (int pass = pattern ? 0 : 1; pass < 2; ++pass) {
    if (pass == 1 && pattern) irn_.resize(nnz), jcn_.resize(nnz), val_.resize(nnz), nnz = 0;
    for (PetscInt i = rstart; i < rend; ++i) {
      PetscInt ncols;
      const PetscInt *cols;
      const PetscScalar *vals;
      PetscCall(MatGetRow(A, i, &ncols, &cols, pass == 1 ? &vals : nullptr));
      for (PetscInt k = 0; k < ncols; ++k)
        if (cols[k] >= i || !symmetric_) {
          if (pass == 1) {
            PetscAssert(pattern || (nnz < val_.size() && irn_[nnz] == (MUMPS_INT)(i + 1) &&
                                    jcn_[nnz] == (MUMPS_INT)(cols[k] + 1)),
                        PETSC_COMM_SELF, PETSC_ERR_PLIB, "the pattern of the refactored matrix changed");
            if (pattern) irn_[nnz] = (MUMPS_INT)(i + 1), jcn_[nnz] = (MUMPS_INT)(cols[k] + 1);
            val_[nnz] = vals[k];
          }
          ++nnz;
        }
      PetscCall(MatRestoreRow(A, i, &ncols, &cols, pass == 1 ? &vals : nullptr));
    }
  }
  PetscCheck(nnz == val_.size(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "the pattern of the refactored matrix changed");
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::Factor(Mat A, const SchurLayout &layout, const FactorChoices &how) {
  const std::vector<PetscInt> &schur_rows = layout.schur_rows;
  PetscInt rstart, rend, N;
  PetscFunctionBeginUser;
  Release(); // an earlier factorisation (one that found null pivots) goes first
  declined_ = false;
  rejected_.clear();
  rejectable_ = (bool)how.confirm;
  PetscCall(RegisterEvents());
  symmetric_ = how.symmetric;
  PetscCall(PetscObjectGetComm((PetscObject)A, &comm_));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  PetscCall(MatGetSize(A, &N, nullptr));
  PetscCall(ReadValues(A, true));
  const PetscInt m = rank_ == 0 ? (PetscInt)schur_rows.size() : 0;
  PetscInt m_all = m;
  PetscCallMPI(MPI_Bcast(&m_all, 1, MPIU_INT, 0, comm_));
  listvar_.resize(m);
  for (PetscInt i = 0; i < m; ++i) listvar_[i] = (MUMPS_INT)(schur_rows[i] + 1);
  PetscCall(InitialiseMumps());
  OrderingOptions ordering = how.ordering;
  PetscCall(ApplyControls(how.controls, N, layout.node_size, ordering));
  id_.n = (MUMPS_INT)N;
  id_.nnz_loc = (MUMPS_INT8)val_.size();
  id_.irn_loc = irn_.data();
  id_.jcn_loc = jcn_.data();
  id_.a_loc = val_.data();
  id_.size_schur = (MUMPS_INT)m_all;
  id_.listvar_schur = listvar_.data();
  id_.schur_lld = (MUMPS_INT)m_all;
  if (id_.ICNTL(7) == 1) {
    PetscCall(NestedDissection(N, rstart, layout.owned_u, layout.node_size, layout.coords, ordering));
    if (rank_ == 0) id_.perm_in = perm_in_.data();
  }
  double flops, entries;
  PetscCall(Analyse(how, N, m_all, flops, entries));
  if (rejected_.empty() && how.confirm) {
    // MUMPS's INFOG(16) is in millions of bytes, the largest rank's.
    const AnalysedFactor analysed{entries, flops, cholesky_in_use_ ? 0.0 : 1e6 * (double)id_.INFOG(16),
                                  cholesky_in_use_};
    if (!how.confirm(analysed, rejected_) && rejected_.empty()) rejected_ = "the analysis' check refused";
  }
  if (!rejected_.empty()) {
    Release();
    PetscFunctionReturn(0);
  }
  if (how.may_decline && DenseCostsMore((double)m_all, flops)) {
    PetscCall(
        PetscInfo(nullptr,
                  "dense Schur complement of %" PetscInt_FMT " candidates: %.6g flops per active-set "
                  "change and %.6g entries, against %.6g flops and %.6g entries of the sparse factors: declined\n",
                  m_all, (double)m_all * m_all * m_all / 3, 2.0 * m_all * m_all, flops, entries));
    Release();
    declined_ = true;
    PetscFunctionReturn(0);
  }
  {
    VecH layout;
    PetscCall(MatCreateVecs(A, layout.out(), nullptr));
    PetscCall(VecScatterCreateToZero(layout, &to_root_, root_.out()));
  }
  redrhs_.assign(m, 0.0);
  ordering_name_ = id_.ICNTL(7) == 1 ? GRAPH_ORDERING_NAMES[(int)ordering.graph] : "MUMPS's";
  PetscCall(FactorNumeric(layout.d0));
  if (!rejected_.empty()) {
    Release();
    PetscFunctionReturn(0);
  }
  keep_values_ = how.keep_values;
  if (!how.keep_values) FreeValues();
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::InitialiseMumps() {
  PetscFunctionBeginUser;
  id_.comm_fortran = (MUMPS_INT)MPI_Comm_c2f(comm_);
  id_.par = 1;
  id_.sym = symmetric_ ? 2 : 0; // general symmetric: the saddle-point matrix is indefinite
  id_.job = -1;
  dmumps_c(&id_);
  initialised_ = true;
  PetscCheck(id_.INFOG(1) >= 0, comm_, PETSC_ERR_LIB, "MUMPS initialisation failed: INFOG(1) = %d",
             (int)id_.INFOG(1));
  id_.ICNTL(1) = -1; // errors are reported through INFOG
  id_.ICNTL(2) = -1;
  id_.ICNTL(3) = -1;
  id_.ICNTL(4) = 0;
  id_.ICNTL(18) = 3; // distributed assembled matrix
  // Schur complement in MUMPS's distributed layout on a 1 x 1 process grid: the whole (complete) matrix on rank 0.
  // (The centralised layout, ICNTL(19) = 1, gave wrong Schur complements for the larger Hertz meshes with MUMPS 5.5.)
  id_.ICNTL(19) = 3;
  id_.nprow = 1, id_.npcol = 1, id_.mblock = 64, id_.nblock = 64;
  id_.ICNTL(24) = 1; // null-pivot detection
  id_.CNTL(3) = 1e-12;
  id_.ICNTL(14) = MUMPS_WORKSPACE_INCREASE; // see saddle_point.cpp
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::ApplyControls(const MumpsControls &controls, PetscInt N, PetscInt node_size,
                                         OrderingOptions &ordering) {
  PetscFunctionBeginUser;
  // The user's MUMPS controls (ReadMumpsControls), as PETSc's interface takes them, except the ones this class relies
  // on (input/Schur/right-hand-side layout).
  // Ordering: a nested dissection of the node graph, given to MUMPS (ICNTL(7) = 1; Debian's MUMPS has only AMD, AMF,
  // QAMD and PORD built in), unless -contact_mat_mumps_icntl_7 picks one of those. With a Schur complement MUMPS's
  // own choice (AMD) nearly doubles the elimination flops of the 2D Hertz matrices (3.8e8 at 20k rows, METIS 2.0e8).
  // METIS's is the better one, but on a small 2D matrix it takes longer than its smaller factor saves, so that gets
  // the coordinate cuts; in 3D METIS pays from a few thousand rows on (measurements: docs/performance.md).
  id_.ICNTL(7) = 1;
  if (ordering.graph == GraphOrdering::AUTO)
    ordering.graph = node_size == 3 || N >= METIS_MIN_ROWS_2D ? GraphOrdering::METIS : GraphOrdering::COORDINATES;
  for (const auto &[k, v] : controls.icntl) {
    PetscCheck(k != 18 && k != 19 && k != 20 && k != 21 && k != 26, comm_, PETSC_ERR_USER_INPUT,
               "-contact_mat_mumps_icntl_%d cannot be set with -contact_reuse_factorization (the solver sets it)", k);
    id_.ICNTL(k) = (MUMPS_INT)v;
  }
  for (const auto &[k, v] : controls.cntl) id_.CNTL(k) = v;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::Analyse(const FactorChoices &how, PetscInt N, PetscInt m_all, double &flops,
                                   double &entries) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  const MumpsControls &controls = how.controls;
  cholesky_in_use_ = how.solver == KeptSolver::CHOLESKY ||
                     (how.solver == KeptSolver::AUTO && how.symmetric && id_.ICNTL(7) == 1 && controls.icntl.empty() &&
                      controls.cntl.empty() && N <= (size == 1 ? CHOLESKY_MAX_ROWS : CHOLESKY_MAX_ROWS_GATHERED));
  if (cholesky_in_use_) {
    PetscCheck(how.symmetric && id_.ICNTL(7) == 1, comm_, PETSC_ERR_PLIB,
               "the supernodal Cholesky factorisation needs LDL^T and the given ordering");
    PetscCall(CholeskyAnalysis(N, m_all));
    flops = cholesky_flops_, entries = cholesky_entries_;
  } else {
    PetscCall(MumpsAnalysis());
    // The analysis' estimates (every rank has them): elimination flops RINFOG(1), factor entries INFOG(20)
    // (negative: in millions).
    flops = id_.rinfog[0], entries = id_.INFOG(20) >= 0 ? id_.INFOG(20) : -1e6 * id_.INFOG(20);
  }
  PetscFunctionReturn(0);
}

void MumpsSchur::FreeValues() {
  // The matrix values are no longer needed (no refactorisation).
  irn_.clear(), jcn_.clear(), val_.clear();
  irn_.shrink_to_fit(), jcn_.shrink_to_fit(), val_.shrink_to_fit();
  for (auto *v : {&root_irn_, &root_jcn_})
    std::vector<MUMPS_INT>().swap(*v);
  std::vector<double>().swap(root_val_);
}

PetscErrorCode MumpsSchur::CholeskyAnalysis(PetscInt N, PetscInt m) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  // The pivot order stays (perm_in_) for MUMPS, should the block turn out not to be positive definite. On several
  // ranks the entries go to rank 0, which factors alone (the right-hand side and the solution are there already).
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(PetscLogEventBegin(EV_CHOL_ANALYSIS, 0, 0, 0, 0));
  if (size > 1) PetscCall(GatherEntries(true));
  double cost[2] = {0, 0};
  PetscCall(RunOnRoot(comm_, [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(cholesky_.Analyse(N, m, CholeskyRows(), CholeskyCols(), perm_in_, 1));
    cost[0] = cholesky_.Flops(), cost[1] = cholesky_.Entries();
    PetscFunctionReturn(0);
  }));
  PetscCallMPI(MPI_Bcast(cost, 2, MPI_DOUBLE, 0, comm_));
  PetscCall(PetscLogEventEnd(EV_CHOL_ANALYSIS, 0, 0, 0, 0));
  cholesky_flops_ = cost[0], cholesky_entries_ = cost[1];
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::GatherEntries(bool pattern) {
  PetscMPIInt mine;
  PetscFunctionBeginUser;
  PetscCall(PetscMPIIntCast((PetscInt)val_.size(), &mine));
  if (pattern) {
    PetscCall(GatherLayout(comm_, mine, gather_counts_, gather_displs_,
                           "too many matrix entries to gather on rank 0 for the Cholesky factorisation; expected "
                           "-contact_kept_solver mumps"));
    gathered_ = true;
    const std::size_t total = rank_ == 0 ? (std::size_t)gather_displs_.back() : 0;
    root_irn_.resize(total), root_jcn_.resize(total), root_val_.resize(total);
    PetscCallMPI(MPI_Gatherv(irn_.data(), mine, MPI_INT, root_irn_.data(), gather_counts_.data(),
                             gather_displs_.data(), MPI_INT, 0, comm_));
    PetscCallMPI(MPI_Gatherv(jcn_.data(), mine, MPI_INT, root_jcn_.data(), gather_counts_.data(),
                             gather_displs_.data(), MPI_INT, 0, comm_));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Gatherv(val_.data(), mine, MPI_DOUBLE, root_val_.data(), gather_counts_.data(),
                           gather_displs_.data(), MPI_DOUBLE, 0, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::MumpsAnalysis() {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(EV_ANALYSIS, 0, 0, 0, 0));
  if (rank_ == 0 && id_.ICNTL(7) == 1) id_.perm_in = perm_in_.data();
  PetscCall(Call(1, "analysis"));
  perm_in_.clear();
  perm_in_.shrink_to_fit();
  PetscCall(PetscLogEventEnd(EV_ANALYSIS, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::Refactor(Mat A, const std::vector<PetscScalar> &d0) {
  PetscFunctionBeginUser;
  PetscCheck(initialised_ && keep_values_, comm_, PETSC_ERR_ORDER,
             "a refactorisation needs an earlier Factor that kept the pattern");
  PetscCall(ReadValues(A, false));
  PetscCall(FactorNumeric(d0));
  if (!rejected_.empty()) Release();
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::FactorNumeric(const std::vector<PetscScalar> &d0) {
  const PetscInt m = rank_ == 0 ? (PetscInt)listvar_.size() : 0;
  PetscFunctionBeginUser;
  schur_raw_.assign((std::size_t)m * m, 0.0);
  if (cholesky_in_use_) {
    int positive = 0;
    PetscCall(PetscLogEventBegin(EV_CHOL_FACTOR, 0, 0, 0, 0));
    if (gathered_) PetscCall(GatherEntries(false));
    PetscCall(RunOnRoot(comm_, [&]() -> PetscErrorCode {
      bool p;
      PetscFunctionBeginUser;
      PetscCall(cholesky_.Factor(CholeskyValues(), schur_raw_, p));
      positive = p;
      PetscFunctionReturn(0);
    }));
    PetscCallMPI(MPI_Bcast(&positive, 1, MPI_INT, 0, comm_));
    PetscCall(PetscLogEventEnd(EV_CHOL_FACTOR, 0, 0, 0, 0));
    if (positive) {
      PetscCall(PetscInfo(nullptr, "Cholesky factors (supernodal): ordering ICNTL(7) = 1 (%s), %.6g entries, %.6g "
                          "flops in the elimination\n", ordering_name_, cholesky_entries_, cholesky_flops_));
      null_pivots_ = 0;
    } else {
      // Not safely positive definite: MUMPS's LDL^T with its null-pivot detection decides, from the same order.
      PetscCall(PetscInfo(nullptr, "Cholesky factorisation: a pivot not above %g of the largest diagonal entry; "
                          "MUMPS factorises instead\n", SchurCholesky::PIVOT_TOLERANCE));
      cholesky_.Clear();
      cholesky_in_use_ = false;
      for (auto *v : {&root_irn_, &root_jcn_})
        std::vector<MUMPS_INT>().swap(*v);
      std::vector<double>().swap(root_val_);
      gathered_ = false;
      PetscCall(MumpsAnalysis());
      if (!rejected_.empty()) PetscFunctionReturn(0);
      schur_raw_.assign((std::size_t)m * m, 0.0);
    }
  }
  if (!cholesky_in_use_) {
    id_.a_loc = val_.data();
    id_.schur = schur_raw_.data();
    PetscCall(PetscLogEventBegin(EV_FACTOR, 0, 0, 0, 0));
    PetscCall(Call(2, "factorisation"));
    PetscCall(PetscLogEventEnd(EV_FACTOR, 0, 0, 0, 0));
    if (!rejected_.empty()) PetscFunctionReturn(0);
    PetscCall(PetscInfo(nullptr, "MUMPS factors: ordering ICNTL(7) = %d (%s), %.6g entries, %.6g flops in the "
                        "elimination\n", (int)id_.ICNTL(7), ordering_name_,
                        (double)(id_.INFOG(29) >= 0 ? id_.INFOG(29) : -1e6 * id_.INFOG(29)), (double)id_.rinfog[2]));
    null_pivots_ = id_.INFOG(28);
  }
  // The Schur complement is complete for ICNTL(19) = 3; should a MUMPS version return only one triangle (the other
  // then stays zero), the full matrix is rebuilt from the filled one.
  s0_.assign((std::size_t)m * m, 0.0);
  double lower = 0, upper = 0;
  for (PetscInt j = 0; j < m; ++j)
    for (PetscInt i = 0; i < m; ++i)
      if (i != j) (i > j ? lower : upper) += std::abs(schur_raw_[i + j * m]);
  const bool use_lower = lower >= upper;
  for (PetscInt j = 0; j < m; ++j)
    for (PetscInt i = 0; i < m; ++i) {
      const PetscInt hi = std::max(i, j), lo = std::min(i, j);
      s0_[i + j * m] = use_lower ? schur_raw_[hi + lo * m] : schur_raw_[lo + hi * m];
    }
  schur_raw_.clear();
  schur_raw_.shrink_to_fit();
  d0_ = d0;
  s_factored_ = false;
  condensed_ = false;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::FactorSchur(const std::vector<PetscScalar> &d) {
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(EV_SCHUR, 0, 0, 0, 0));
  PetscCall(RunOnRoot(comm_, [&] { return FactorSchurOnRoot(d); }));
  PetscCall(PetscLogEventEnd(EV_SCHUR, 0, 0, 0, 0));
  s_factored_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::FactorSchurOnRoot(const std::vector<PetscScalar> &d) {
  const PetscInt m = (PetscInt)d0_.size();
  PetscBLASInt n, lwork = -1, info;
  PetscFunctionBeginUser;
  if (m == 0 || (s_factored_ && d == d_current_ && off_ == off_current_)) PetscFunctionReturn(0);
  if (coupled_ && s_factored_) {
    bool updated;
    PetscCall(UpdateSchur(d, updated));
    if (updated) {
      d_current_ = d, off_current_ = off_;
      PetscFunctionReturn(0);
    }
  }
  s_factored_ = false; // s_ is overwritten: until its factorisation succeeds, no factors exist (FactorSchur)
  update_rows_.clear(), w_index_.clear(), w_cache_.clear();
  s_ = s0_;
  for (PetscInt i = 0; i < m; ++i) s_[i + i * m] += d[i] - d0_[i];
  for (const Coupling &c : off_) s_[c.i + c.j * m] += c.v;
  dense_lu_ = !symmetric_ || !off_.empty();
  PetscCall(PetscBLASIntCast(m, &n));
  ipiv_.resize(m);
  double query;
  if (!dense_lu_) {
    LAPACKsytrf_("L", &n, s_.data(), &n, ipiv_.data(), &query, &lwork, &info);
    lwork = std::max<PetscBLASInt>(1, (PetscBLASInt)query);
    work_.resize(lwork);
    LAPACKsytrf_("L", &n, s_.data(), &n, ipiv_.data(), work_.data(), &lwork, &info);
  } else {
    LAPACKgetrf_(&n, &n, s_.data(), &n, ipiv_.data(), &info);
  }
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
             "the saddle-point system is singular (zero pivot %d in the Schur complement on the multipliers): the "
             "body is not held, or two active constraints coincide; add Dirichlet conditions or check that the "
             "obstacle touches it", (int)info);
  s_factored_ = true;
  d_factored_ = d_current_ = d;
  off_factored_ = off_current_ = off_;
  dense_factorisations_++;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::UpdateSchur(const std::vector<PetscScalar> &d, bool &updated) {
  const PetscInt m = (PetscInt)d0_.size();
  PetscFunctionBeginUser;
  updated = false;
  // The change from the factored S: D - D_f on the diagonal, the entries off it now less those factored.
  std::map<std::pair<PetscInt, PetscInt>, double> delta;
  for (PetscInt i = 0; i < m; ++i)
    if (d[i] != d_factored_[i]) delta[{i, i}] += d[i] - d_factored_[i];
  for (const Coupling &c : off_) delta[{c.i, c.j}] += c.v;
  for (const Coupling &c : off_factored_) delta[{c.i, c.j}] -= c.v;
  std::vector<PetscInt> rows;
  std::vector<std::vector<std::pair<PetscInt, double>>> entries;
  for (const auto &[ij, v] : delta) {
    if (v == 0) continue;
    if (rows.empty() || rows.back() != ij.first) rows.push_back(ij.first), entries.emplace_back();
    entries.back().emplace_back(ij.second, v);
  }
  // W = S_f^-1 E_R column by column: a row's column stays while S_f does (cached), so that only the rows new to the
  // update cost solves with the factors (2 m^2 flops each); taken while the new solves and the LU of the k x k
  // capacitance matrix cost at most half a new LU of S, and the cache holds at most half of S's columns.
  std::vector<PetscInt> fresh;
  for (PetscInt r : rows)
    if (!w_index_.count(r)) fresh.push_back(r);
  const double k = (double)rows.size(), mm = (double)m, kf = (double)fresh.size();
  if (2 * mm * mm * kf + 2 * k * k * k / 3 > 0.5 * 2 * mm * mm * mm / 3 ||
      (double)(w_index_.size() + fresh.size()) > 0.5 * mm)
    PetscFunctionReturn(0);
  if (!fresh.empty()) {
    const PetscInt kf_int = (PetscInt)fresh.size();
    std::vector<double> w((std::size_t)m * kf_int, 0.0);
    for (PetscInt a = 0; a < kf_int; ++a) w[fresh[a] + a * m] = 1.0;
    PetscCall(ReferenceSolve(w.data(), kf_int));
    for (PetscInt a = 0; a < kf_int; ++a) w_index_[fresh[a]] = (PetscInt)(w_cache_.size() / m) + a;
    w_cache_.insert(w_cache_.end(), w.begin(), w.end());
  }
  const PetscInt kk = (PetscInt)rows.size();
  std::vector<const double *> col(kk);
  for (PetscInt b = 0; b < kk; ++b) col[b] = &w_cache_[(std::size_t)w_index_[rows[b]] * m];
  std::vector<double> c((std::size_t)kk * kk, 0.0);
  for (PetscInt a = 0; a < kk; ++a)
    for (PetscInt b = 0; b < kk; ++b) {
      double v = a == b ? 1.0 : 0.0;
      for (const auto &[j, x] : entries[a]) v += x * col[b][j];
      c[a + b * kk] = v;
    }
  std::vector<PetscBLASInt> ipiv(kk);
  PetscBLASInt n, info = 0;
  PetscCall(PetscBLASIntCast(kk, &n));
  if (kk > 0) LAPACKgetrf_(&n, &n, c.data(), &n, ipiv.data(), &info);
  if (info != 0) PetscFunctionReturn(0); // a singular capacitance matrix: a new LU decides
  update_rows_ = std::move(rows), update_entries_ = std::move(entries);
  update_c_ = std::move(c), update_ipiv_ = std::move(ipiv);
  updated = true;
  dense_updates_++;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::ReferenceSolve(double *y, PetscInt nrhs) const {
  const PetscInt m = (PetscInt)d0_.size();
  PetscBLASInt n, k, info;
  PetscFunctionBeginUser;
  if (m == 0 || nrhs == 0) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(m, &n));
  PetscCall(PetscBLASIntCast(nrhs, &k));
  std::vector<PetscBLASInt> ipiv(ipiv_);
  if (!dense_lu_) LAPACKsytrs_("L", &n, &k, s_.data(), &n, ipiv.data(), y, &n, &info);
  else LAPACKgetrs_("N", &n, &k, s_.data(), &n, ipiv.data(), y, &n, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK solve with the Schur complement failed: info %d",
             (int)info);
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::DenseSolve(std::vector<PetscScalar> &y) const {
  const PetscInt m = (PetscInt)d0_.size();
  PetscFunctionBeginUser;
  if (m == 0) PetscFunctionReturn(0);
  PetscCall(ReferenceSolve(y.data(), 1));
  if (update_rows_.empty()) PetscFunctionReturn(0);
  // Woodbury: S = S_f + E_R Delta_R, so S^-1 y = z - W C^-1 Delta_R z with z = S_f^-1 y, W = S_f^-1 E_R and
  // C = I + Delta_R W.
  const PetscInt kk = (PetscInt)update_rows_.size();
  std::vector<double> t(kk, 0.0);
  for (PetscInt a = 0; a < kk; ++a)
    for (const auto &[j, x] : update_entries_[a]) t[a] += x * y[j];
  PetscBLASInt n, one = 1, info;
  PetscCall(PetscBLASIntCast(kk, &n));
  std::vector<PetscBLASInt> ipiv(update_ipiv_);
  LAPACKgetrs_("N", &n, &one, update_c_.data(), &n, ipiv.data(), t.data(), &n, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK solve with the capacitance matrix failed: info %d",
             (int)info);
  for (PetscInt b = 0; b < kk; ++b) {
    const double *w = &w_cache_[(std::size_t)w_index_.at(update_rows_[b]) * m];
    for (PetscInt j = 0; j < m; ++j) y[j] -= w[j] * t[b];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::CheckedDenseSolve(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y) {
  const PetscInt m = (PetscInt)d0_.size();
  PetscFunctionBeginUser;
  const std::vector<PetscScalar> rhs = y;
  PetscCall(DenseSolve(y));
  if (update_rows_.empty()) PetscFunctionReturn(0);
  // An updated solve is checked against S = S0 + (D - D0) + the entries off the diagonal; a residual above
  // UPDATE_RESIDUAL of the right-hand side refactors S and solves again.
  std::vector<double> r(rhs.begin(), rhs.end());
  for (PetscInt j = 0; j < m; ++j)
    for (PetscInt i = 0; i < m; ++i) r[i] -= s0_[i + j * m] * y[j];
  for (PetscInt i = 0; i < m; ++i) r[i] -= (d[i] - d0_[i]) * y[i];
  for (const Coupling &c : off_) r[c.i] -= c.v * y[c.j];
  double r2 = 0, b2 = 0;
  for (PetscInt i = 0; i < m; ++i) r2 += r[i] * r[i], b2 += rhs[i] * rhs[i];
  if (std::isfinite(r2) && std::sqrt(r2) <= UPDATE_RESIDUAL * std::sqrt(b2)) PetscFunctionReturn(0);
  PetscCall(PetscInfo(nullptr, "dense update of the Schur complement: residual %.3g of the right-hand side; "
                      "refactored\n", std::sqrt(r2 / std::max(b2, 1e-300))));
  s_factored_ = false;
  PetscCall(FactorSchurOnRoot(d_current_));
  y = rhs;
  PetscCall(DenseSolve(y));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::SolveReduced(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y,
                                        double &residual) {
  PetscFunctionBeginUser;
  PetscCheck(condensed_, comm_, PETSC_ERR_ORDER, "SolveReduced needs an earlier Condense");
  PetscCall(FactorSchur(d));
  PetscCall(PetscLogEventBegin(EV_REDUCED, 0, 0, 0, 0));
  residual = 0;
  PetscCall(RunOnRoot(comm_, [&] { return SolveReducedOnRoot(d, y, residual); }));
  PetscCallMPI(MPI_Bcast(&residual, 1, MPI_DOUBLE, 0, comm_));
  PetscCall(PetscLogEventEnd(EV_REDUCED, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::SolveReducedOnRoot(const std::vector<PetscScalar> &d, std::vector<PetscScalar> &y,
                                              double &residual) {
  const PetscInt m = (PetscInt)d0_.size();
  PetscFunctionBeginUser;
  PetscCheck(off_.empty(), PETSC_COMM_SELF, PETSC_ERR_ORDER, "a reduced solve with entries off the diagonal of D");
  for (PetscInt i = 0; i < m; ++i) y[i] -= condensed_u_[i];
  const std::vector<PetscScalar> rhs = y;
  PetscCall(DenseSolve(y));
  // ||rhs - S y||, S = S0 + (D - D0): the residual of the reduced system.
  residual = 0;
  for (PetscInt i = 0; i < m; ++i) {
    double r = rhs[i] - (d[i] - d0_[i]) * y[i];
    for (PetscInt j = 0; j < m; ++j) r -= s0_[i + j * m] * y[j];
    residual += r * r;
  }
  residual = std::sqrt(residual);
  reduced_ = y;
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::Condense(Vec b) {
  const PetscInt m = (PetscInt)d0_.size();
  const PetscLogEvent event = cholesky_in_use_ ? EV_CHOL_SOLVE : EV_SOLVE;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(event, 0, 0, 0, 0));
  PetscCall(VecScatterBegin(to_root_, b, root_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_root_, b, root_, INSERT_VALUES, SCATTER_FORWARD));
  PetscScalar *r;
  PetscCall(VecGetArray(root_, &r));
  if (cholesky_in_use_) {
    PetscCall(RunOnRoot(comm_, [&] { return cholesky_.Forward(r, redrhs_.data()); }));
  } else {
    id_.rhs = r;
    id_.nrhs = 1;
    id_.lrhs = id_.n;
    id_.redrhs = redrhs_.data();
    id_.lredrhs = (MUMPS_INT)std::max<PetscInt>(1, m);
    id_.ICNTL(20) = 0; // dense right-hand side on the host
    id_.ICNTL(21) = 0; // solution on the host
    id_.ICNTL(26) = 1; // the forward elimination, which MUMPS keeps for the expansion, and the reduced right-hand side
    PetscCall(Call(3, "solve (condensation)"));
  }
  // The part of the reduced right-hand side that comes from the displacement rows, A21 A11^-1 b_u, for SolveReduced.
  if (rank_ == 0) {
    condensed_u_.resize(m);
    for (PetscInt i = 0; i < m; ++i) condensed_u_[i] = r[listvar_[i] - 1] - redrhs_[i];
  }
  PetscCall(VecRestoreArray(root_, &r));
  condensed_ = true;
  reduced_.clear();
  PetscCall(PetscLogEventEnd(event, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

void MumpsSchur::ReducedOperator(std::vector<double> &h, std::vector<double> &condensed) const {
  const std::size_t m = d0_.size();
  h.clear();
  condensed.clear();
  if (rank_ != 0 || !condensed_) return;
  h.assign(m * m, 0.0);
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < m; ++i) h[i + j * m] = -0.5 * (s0_[i + j * m] + s0_[j + i * m]);
  for (std::size_t i = 0; i < m; ++i) h[i + i * m] += d0_[i];
  condensed = condensed_u_;
}

PetscErrorCode MumpsSchur::Expand(Vec x) {
  const PetscInt m = (PetscInt)d0_.size();
  PetscFunctionBeginUser;
  PetscCheck(condensed_ && (rank_ != 0 || reduced_.size() == (std::size_t)m), comm_, PETSC_ERR_ORDER,
             "Expand needs a Condense and a reduced solution after it");
  const PetscLogEvent event = cholesky_in_use_ ? EV_CHOL_SOLVE : EV_SOLVE;
  PetscCall(PetscLogEventBegin(event, 0, 0, 0, 0));
  PetscScalar *r;
  PetscCall(VecGetArray(root_, &r));
  if (cholesky_in_use_) {
    PetscCall(RunOnRoot(comm_, [&] { return cholesky_.Backward(reduced_.data(), r); }));
  } else {
    if (rank_ == 0) std::copy(reduced_.begin(), reduced_.end(), redrhs_.begin());
    id_.rhs = r;
    id_.redrhs = redrhs_.data();
    id_.ICNTL(26) = 2; // the backward substitution from the kept forward elimination and the reduced solution
    PetscCall(Call(3, "solve (expansion)"));
  }
  if (rank_ == 0)
    for (PetscInt i = 0; i < m; ++i) r[listvar_[i] - 1] = reduced_[i];
  PetscCall(VecRestoreArray(root_, &r));
  PetscCall(VecScatterBegin(to_root_, root_, x, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(to_root_, root_, x, INSERT_VALUES, SCATTER_REVERSE));
  condensed_ = false;
  PetscCall(PetscLogEventEnd(event, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::Solve(const std::vector<PetscScalar> &d, Vec b, Vec x) {
  PetscFunctionBeginUser;
  PetscCall(FactorSchur(d));
  PetscCall(Condense(b));
  // The reduced system with the reduced right-hand side of the condensation as it is, then the expansion.
  reduced_ = redrhs_;
  PetscCall(RunOnRoot(comm_, [&] { return CheckedDenseSolve(d, reduced_); }));
  PetscCall(Expand(x));
  PetscFunctionReturn(0);
}

PetscErrorCode MumpsSchur::View(PetscViewer viewer) const {
  PetscFunctionBeginUser;
  if (!initialised_) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "no factorisation (released or not made)\n"));
    PetscFunctionReturn(0);
  }
  double entries, flops;
  if (cholesky_in_use_) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "factored by: signorini's supernodal Cholesky on rank 0%s\n",
                                     gathered_ ? " (the matrix gathered from every rank)" : ""));
    entries = cholesky_entries_, flops = cholesky_flops_;
  } else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "factored by: MUMPS %s, called directly\n",
                                     symmetric_ ? "LDL^T (SYM = 2)" : "LU (SYM = 0)"));
    entries = id_.INFOG(29) >= 0 ? id_.INFOG(29) : -1e6 * id_.INFOG(29), flops = id_.rinfog[2];
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "rows: %d, of which %d multipliers in the Schur complement (dense %s on "
                                   "rank 0, %s when D changes)\n", (int)id_.n, (int)id_.size_schur,
                                   dense_lu_ ? "LU" : "LDL^T", coupled_ ? "updated at low rank or refactored" :
                                   "refactored"));
  if (id_.ICNTL(7) == 1)
    PetscCall(PetscViewerASCIIPrintf(viewer, "ordering: nested dissection of the node graph (%s)\n", ordering_name_));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "ordering: MUMPS's own (ICNTL(7) = %d)\n", (int)id_.ICNTL(7)));
  PetscCall(PetscViewerASCIIPrintf(viewer, "factor entries: %.6g, elimination flops: %.6g, null pivots: %d\n", entries,
                                   flops, (int)null_pivots_));
  if (coupled_)
    PetscCall(PetscViewerASCIIPrintf(viewer, "Schur complement: %d dense LU(s), %d low-rank update(s) so far\n",
                                     (int)dense_factorisations_, (int)dense_updates_));
  PetscFunctionReturn(0);
}

} // namespace signorini
