// Global assembly over the local cells: stiffness, internal force, loads, Dirichlet data.
#include "signorini/fem/assembly.hpp"

#include "signorini/core/parse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace signorini {

PetscErrorCode BuildDirichlet(const Mesh &mesh, const BoundaryConditions &bc, DirichletData &data) {
  const int dim = mesh.Dim();
  const PetscInt nspec = (PetscInt)bc.dirichlet.size();
  PetscFunctionBeginUser;
  data.fixed.assign(mesh.NumLocalVertices() * dim, 0);
  data.value.assign(mesh.NumLocalVertices() * dim, 0.0);
  data.ramp.assign(mesh.NumLocalVertices() * dim, 0);
  data.ramps.assign(1, Ramp{});
  // Two items prescribing different values (or ramps, but for the value 0, fixed at any time) to one node component
  // would leave the last one silently in force. The first such conflict in (file node, component, item, item) order
  // is reported: the key is the same on every rank that sees the node, so the minimum over the ranks gives one
  // message whatever the partition.
  const auto differ = [](const DirichletSpec &a, const DirichletSpec &b) {
    return a.value != b.value || (a.ramp != b.ramp && a.value != 0);
  };
  std::vector<PetscInt> setter(mesh.NumLocalVertices() * dim, -1);
  PetscInt64 conflict = std::numeric_limits<PetscInt64>::max();
  std::vector<PetscInt> vertices;
  for (PetscInt i = 0; i < nspec; ++i) {
    const auto &d = bc.dirichlet[i];
    PetscCall(mesh.GroupVertices(d.group, vertices, "-bc_dirichlet " + d.item));
    for (PetscInt v : vertices) {
      const PetscInt r = v * dim + d.component;
      if (setter[r] >= 0 && differ(bc.dirichlet[setter[r]], d)) {
        const PetscInt64 node_comp = (PetscInt64)mesh.VertexOriginal(v) * dim + d.component;
        const PetscInt64 key = (node_comp * nspec + setter[r]) * nspec + i;
        conflict = std::min(conflict, key);
        continue;
      }
      if (setter[r] < 0) setter[r] = i;
      data.fixed[r] = 1;
      data.value[r] = d.value;
      data.ramp[r] = (int)(std::find(data.ramps.begin(), data.ramps.end(), d.ramp) - data.ramps.begin());
      if (data.ramp[r] == (int)data.ramps.size()) data.ramps.push_back(d.ramp);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &conflict, 1, MPIU_INT64, MPI_MIN, mesh.Comm()));
  if (conflict != std::numeric_limits<PetscInt64>::max()) {
    const PetscInt i = (PetscInt)(conflict % nspec), first = (PetscInt)(conflict / nspec % nspec);
    const PetscInt64 node_comp = conflict / nspec / nspec;
    const auto &a = bc.dirichlet[first], &b = bc.dirichlet[i];
    SETERRQ(mesh.Comm(), PETSC_ERR_USER_INPUT,
            "-bc_dirichlet prescribes two values to component %c of node %" PetscInt64_FMT " (in file order): %s by "
            "item '%s' and %s by item '%s'; expected one value per node component (the same value with the same ramp "
            "twice is allowed)",
            "xyz"[node_comp % dim], node_comp / dim + 1, (FormatNumber(a.value) + a.ramp.Suffix()).c_str(),
            a.item.c_str(), (FormatNumber(b.value) + b.ramp.Suffix()).c_str(), b.item.c_str());
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckLoadGroups(const Mesh &mesh, const BoundaryConditions &bc) {
  std::vector<Face> faces;
  std::vector<PetscInt> vertices;
  PetscFunctionBeginUser;
  for (const auto &t : bc.traction) PetscCall(mesh.GroupFaces(t.group, faces, "-bc_traction " + t.item));
  for (const auto &p : bc.pressure) PetscCall(mesh.GroupFaces(p.group, faces, "-bc_pressure " + p.item));
  for (const auto &f : bc.point_force) PetscCall(mesh.GroupVertices(f.group, vertices, "-bc_point_force " + f.item));
  PetscFunctionReturn(0);
}

namespace {
/// The element's values (dim per vertex) from a per-local-vertex array.
void GatherElement(const double *u_local, const PetscInt *v, PetscInt nn, int dim, double *ue) {
  for (PetscInt a = 0; a < nn; ++a)
    for (int k = 0; k < dim; ++k) ue[a * dim + k] = u_local[v[a] * dim + k];
}
} // namespace

Assembler::Assembler(const Mesh &mesh, const Material &material, const DofMap &dofs, const DirichletData &dirichlet)
    : mesh_(mesh), material_(material), dofs_(dofs), dirichlet_(dirichlet) {
  if (material.constants.empty()) parts_.push_back(material.With(material.E, material.nu));
  for (const auto &k : material.constants) parts_.push_back(material.With(k));
  part_D_.resize(parts_.size());
  for (std::size_t p = 0; p < parts_.size(); ++p) ElasticityMatrix(parts_[p], mesh.Dim(), part_D_[p].D);
}

bool Assembler::Geometry(PetscInt c, ElementGeometry &g, PetscInt &nn, const PetscInt *&vertices) const {
  const int dim = mesh_.Dim();
  vertices = mesh_.CellVertices(c, nn);
  double X[MAX_NODES * MAX_DIM];
  for (PetscInt a = 0; a < nn; ++a)
    for (int d = 0; d < dim; ++d) X[a * dim + d] = mesh_.X(vertices[a])[d];
  return ComputeGeometry(dim, (int)nn, X, parts_[Part(c)].thickness, g);
}

PetscErrorCode Assembler::CheckCells() const {
  PetscFunctionBeginUser;
  bool ok = true;
  PetscInt bad = -1;
  ElementGeometry g;
  for (PetscInt c = 0; c < mesh_.NumLocalCells() && ok; ++c) {
    PetscInt nn;
    const PetscInt *v;
    ok = Geometry(c, g, nn, v) && g.min_detJ * g.max_detJ > 0;
    if (!ok) bad = mesh_.CellOriginal(c);
  }
  PetscInt gbad;
  PetscCallMPI(MPI_Allreduce(&bad, &gbad, 1, MPIU_INT, MPI_MAX, mesh_.Comm()));
  PetscCheck(gbad < 0, mesh_.Comm(), PETSC_ERR_USER_INPUT,
             "element number %" PetscInt_FMT " (in file order) is degenerate or inverted", gbad + 1);
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::FirstRows(Mat A, const PetscInt *&first) const {
  PetscInt m;
  PetscFunctionBeginUser;
  PetscCall(MatGetSize(A, &m, nullptr));
  const bool block = m != dofs_.GlobalRows();
  PetscCheck(!block || m == dofs_.GlobalU(), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
             "a stiffness matrix of %" PetscInt_FMT " rows: neither the saddle-point system nor its displacement "
             "block", m);
  first = dofs_.FirstRows(block).data();
  PetscFunctionReturn(0);
}

namespace {

/// Calls f(w) once for each vertex w that the local cells of vertex v hold (v included); first and cells: the cells
/// of every vertex (Assembler::VertexCells); seen: one entry per local vertex, none of them v yet (-1 at the start of
/// a loop over increasing v).
template <class F>
void ForEachNeighbour(const Mesh &mesh, const std::vector<PetscInt> &first, const std::vector<PetscInt> &cells,
                      PetscInt v, std::vector<PetscInt> &seen, F &&f) {
  for (PetscInt i = first[v]; i < first[v + 1]; ++i) {
    PetscInt nn;
    const PetscInt *w = mesh.CellVertices(cells[i], nn);
    for (PetscInt a = 0; a < nn; ++a)
      if (seen[w[a]] != v) seen[w[a]] = v, f(w[a]);
  }
}

} // namespace

void Assembler::VertexCells(std::vector<PetscInt> &first, std::vector<PetscInt> &cells) const {
  const PetscInt nv = mesh_.NumLocalVertices(), nc = mesh_.NumLocalCells();
  first.assign(nv + 1, 0);
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt nn;
    const PetscInt *v = mesh_.CellVertices(c, nn);
    for (PetscInt a = 0; a < nn; ++a)
      ++first[v[a] + 1];
  }
  for (PetscInt v = 0; v < nv; ++v)
    first[v + 1] += first[v];
  cells.resize(first[nv]);
  std::vector<PetscInt> next(first.begin(), first.end() - 1);
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt nn;
    const PetscInt *v = mesh_.CellVertices(c, nn);
    for (PetscInt a = 0; a < nn; ++a)
      cells[next[v[a]]++] = c;
  }
}

PetscErrorCode Assembler::InsertPattern(Mat A) const {
  const int dim = mesh_.Dim();
  const PetscInt nv = mesh_.NumLocalVertices();
  const PetscInt *row_of;
  PetscFunctionBeginUser;
  PetscCall(FirstRows(A, row_of));
  // Row by row: each vertex's rows get the sorted free columns of the vertices its local cells share with it, once.
  // Cell by cell, every entry was set by each cell holding both its nodes (a 3D tetrahedral vertex: about 24 cells),
  // 2.1M calls of 12 x 12 at 1.07M dofs, 4.9 s of a 7 s set-up (perf). A ghost vertex's rows go to their owner as
  // before (the owner's counts hold every rank's columns, PatternCounts).
  std::vector<PetscInt> first, cells, cols, seen(nv, -1);
  VertexCells(first, cells);
  std::vector<PetscScalar> zeros;
  for (PetscInt v = 0; v < nv; ++v) {
    cols.clear();
    ForEachNeighbour(mesh_, first, cells, v, seen, [&](PetscInt w) {
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[w * dim + k]) cols.push_back(row_of[w] + k);
    });
    if (cols.empty()) continue;
    std::sort(cols.begin(), cols.end());
    if (zeros.size() < cols.size()) zeros.resize(cols.size(), 0.0);
    for (int k = 0; k < dim; ++k) {
      if (dirichlet_.fixed[v * dim + k]) continue;
      const PetscInt row = row_of[v] + k;
      PetscCall(MatSetValues(A, 1, &row, (PetscInt)cols.size(), cols.data(), zeros.data(), ADD_VALUES));
    }
  }
  for (PetscInt v = 0; v < nv; ++v)
    for (int k = 0; k < dim; ++k)
      if (mesh_.Owned(v) && dirichlet_.fixed[v * dim + k])
        PetscCall(MatSetValue(A, row_of[v] + k, row_of[v] + k, 0.0, ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::PatternCounts(std::vector<PetscInt> &d_nnz, std::vector<PetscInt> &o_nnz) const {
  const int dim = mesh_.Dim();
  const PetscInt nv = mesh_.NumLocalVertices();
  PetscFunctionBeginUser;
  std::vector<PetscInt> first, cells; // the local cells of every vertex (compressed rows)
  VertexCells(first, cells);
  // The rank that owns each local vertex: this one, or the root's of its leaf in the vertex SF.
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(mesh_.Comm(), &rank));
  std::vector<PetscMPIInt> owner(nv, rank);
  {
    PetscInt nroots, nleaves;
    const PetscInt *ilocal;
    const PetscSFNode *iremote;
    PetscCall(PetscSFGetGraph(mesh_.VertexSF(), &nroots, &nleaves, &ilocal, &iremote));
    for (PetscInt i = 0; i < nleaves; ++i)
      owner[ilocal ? ilocal[i] : i] = (PetscMPIInt)iremote[i].rank;
  }
  const auto free_dofs = [&](PetscInt w) {
    PetscInt n = 0;
    for (int k = 0; k < dim; ++k) n += !dirichlet_.fixed[w * dim + k];
    return n;
  };
  // For every local vertex, the free columns of its row that this rank's cells couple it to, split by the row
  // owner's blocks (a column of the owner's vertices: diagonal block; any other: off-diagonal). An owned vertex that
  // no other rank sees has all its cells here, so its counts are exact; a vertex on the partition's interface gets
  // the other ranks' counts of its row summed in (the vertex SF's reduction), which counts the columns of the
  // interface vertices that both sides' cells hold twice: an upper bound, so that no entry is allocated during the
  // assembly (the rows of the interface were counted as twice this rank's before: 555 and 6 reallocations of the
  // blocks of rank 1 at the 824k-dof cube on 2 ranks, 5 s of the set-up).
  std::vector<PetscInt> counts(2 * nv, 0), seen(nv, -1);
  for (PetscInt v = 0; v < nv; ++v)
    ForEachNeighbour(mesh_, first, cells, v, seen,
                     [&](PetscInt w) { counts[2 * v + (owner[w] == owner[v] ? 0 : 1)] += free_dofs(w); });
  {
    // Leaves send their counts (zeroed on the leaf side afterwards: only the owner's rows are preallocated here).
    MPI_Datatype pair;
    PetscCallMPI(MPI_Type_contiguous(2, MPIU_INT, &pair));
    PetscCallMPI(MPI_Type_commit(&pair));
    std::vector<PetscInt> sums(counts);
    PetscCall(PetscSFReduceBegin(mesh_.VertexSF(), pair, counts.data(), sums.data(), MPI_SUM));
    PetscCall(PetscSFReduceEnd(mesh_.VertexSF(), pair, counts.data(), sums.data(), MPI_SUM));
    PetscCallMPI(MPI_Type_free(&pair));
    counts.swap(sums);
  }
  d_nnz.assign(dofs_.OwnedU(), 0);
  o_nnz.assign(dofs_.OwnedU(), 0);
  const PetscInt owned_rows = dofs_.OwnedRows(), other_rows = dofs_.GlobalRows() - owned_rows;
  for (PetscInt v = 0; v < nv; ++v) {
    if (!mesh_.Owned(v)) continue;
    const PetscInt d = std::min(counts[2 * v], owned_rows), o = std::min(counts[2 * v + 1], other_rows);
    for (int k = 0; k < dim; ++k) {
      const PetscInt r = dofs_.LocalOffset(v, k);
      const bool fixed = dirichlet_.fixed[v * dim + k];
      d_nnz[r] = fixed ? 1 : d;
      o_nnz[r] = fixed ? 0 : o;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::AddLocal(const std::vector<double> &f_local, Vec f) const {
  const int dim = mesh_.Dim();
  PetscScalar *a;
  PetscFunctionBeginUser;
  // Owned rows straight into the array; the rows of ghost vertices through the stash to their owners.
  PetscCall(VecGetArray(f, &a));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (mesh_.Owned(v))
      for (int k = 0; k < dim; ++k) a[dofs_.LocalOffset(v, k)] += f_local[v * dim + k];
  PetscCall(VecRestoreArray(f, &a));
  for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
    if (!mesh_.Owned(v))
      for (int k = 0; k < dim; ++k)
        if (f_local[v * dim + k] != 0) PetscCall(VecSetValue(f, dofs_.Row(v, k), f_local[v * dim + k], ADD_VALUES));
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

namespace {
/// The element matrices of an assembly into an AIJ matrix whose nonzero pattern is final (assembled once): each
/// entry of an owned row is added in place into the values of the local diagonal or off-diagonal block, found in the
/// row's sorted columns; rows of other ranks go through MatSetValues (the stash). MatSetValues itself took three
/// quarters of the stiffness assembly at 20k dofs (its per-call checks and searches for six-entry rows). An
/// unassembled matrix (no pattern yet) gets MatSetValues throughout.
class ElementMatrixAdder {
public:
  [[nodiscard]] PetscErrorCode Begin(Mat A) {
    PetscBool assembled, mpi, seq;
    PetscFunctionBeginUser;
    A_ = A;
    PetscCall(MatAssembled(A, &assembled));
    PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
    PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
    direct_ = assembled && (mpi || seq);
    if (!direct_) PetscFunctionReturn(0);
    PetscCall(MatGetOwnershipRange(A, &rstart_, &rend_));
    PetscCall(MatGetOwnershipRangeColumn(A, &cstart_, &cend_));
    if (mpi) {
      PetscCall(MatMPIAIJGetSeqAIJ(A, &block_[0], &block_[1], &garray_));
      PetscCall(MatGetSize(block_[1], nullptr, &ngarray_));
    } else {
      block_[0] = A, block_[1] = nullptr;
    }
    for (int b = 0; b < 2; ++b) {
      if (!block_[b]) continue;
      PetscInt n;
      PetscBool done;
      PetscCall(MatGetRowIJ(block_[b], 0, PETSC_FALSE, PETSC_FALSE, &n, &ia_[b], &ja_[b], &done));
      PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no compressed rows of the stiffness matrix block");
      PetscCall(MatSeqAIJGetArray(block_[b], &va_[b]));
    }
    PetscFunctionReturn(0);
  }

  /// Adds the n x n row-major matrix Ke at the global rows and columns idx (-1: skipped).
  [[nodiscard]] PetscErrorCode Add(PetscInt n, const PetscInt *idx, const double *Ke) {
    PetscFunctionBeginUser;
    if (!direct_) {
      PetscCall(MatSetValues(A_, n, idx, n, idx, Ke, ADD_VALUES));
      PetscFunctionReturn(0);
    }
    bool owned = false;
    for (PetscInt i = 0; i < n; ++i) owned = owned || (idx[i] >= rstart_ && idx[i] < rend_);
    if (!owned) {
      // No row here (a cell of a ghost layer): its columns need not be in this rank's pattern.
      PetscCall(MatSetValues(A_, n, idx, n, idx, Ke, ADD_VALUES));
      PetscFunctionReturn(0);
    }
    // The element's columns once per element: their block (0: diagonal, 1: off-diagonal), local column, and order
    // in the block, so that each row is one forward walk over its sorted columns instead of a search per entry.
    std::array<Column, MAX_EDOF> cols;
    PetscInt m = 0;
    for (PetscInt j = 0; j < n; ++j) {
      const PetscInt c = idx[j];
      if (c < 0) continue;
      Column col{0, c - cstart_, j};
      if (c < cstart_ || c >= cend_) {
        PetscCheck(block_[1], PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "column %" PetscInt_FMT " outside the "
                   "stiffness pattern", c);
        const PetscInt *at = std::lower_bound(garray_, garray_ + ngarray_, c);
        PetscCheck(at != garray_ + ngarray_ && *at == c, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                   "column %" PetscInt_FMT " outside the stiffness pattern", c);
        col = Column{1, (PetscInt)(at - garray_), j};
      }
      PetscInt k = m++;
      for (; k > 0 && (cols[k - 1].b > col.b || (cols[k - 1].b == col.b && cols[k - 1].lc > col.lc)); --k)
        cols[k] = cols[k - 1];
      cols[k] = col;
    }
    for (PetscInt i = 0; i < n; ++i) {
      const PetscInt r = idx[i];
      if (r < 0) continue;
      if (r < rstart_ || r >= rend_) {
        PetscCall(MatSetValues(A_, 1, &r, n, idx, Ke + i * n, ADD_VALUES));
        continue;
      }
      const PetscInt lr = r - rstart_;
      const double *ke = Ke + i * n;
      int b = -1;
      const PetscInt *at = nullptr, *end = nullptr;
      for (PetscInt q = 0; q < m; ++q) {
        if (cols[q].b != b) {
          b = cols[q].b;
          at = ja_[b] + ia_[b][lr], end = ja_[b] + ia_[b][lr + 1];
        }
        while (at != end && *at < cols[q].lc) ++at;
        PetscCheck(at != end && *at == cols[q].lc, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                   "entry (%" PetscInt_FMT ", %" PetscInt_FMT ") outside the stiffness pattern", r, idx[cols[q].j]);
        va_[b][at - ja_[b]] += ke[cols[q].j];
      }
    }
    PetscFunctionReturn(0);
  }

  [[nodiscard]] PetscErrorCode End() {
    PetscFunctionBeginUser;
    if (!direct_) PetscFunctionReturn(0);
    for (int b = 0; b < 2; ++b) {
      if (!block_[b]) continue;
      PetscInt n;
      PetscBool done;
      PetscCall(MatSeqAIJRestoreArray(block_[b], &va_[b]));
      PetscCall(MatRestoreRowIJ(block_[b], 0, PETSC_FALSE, PETSC_FALSE, &n, &ia_[b], &ja_[b], &done));
    }
    PetscFunctionReturn(0);
  }

private:
  struct Column {
    int b;        ///< 0: the diagonal block, 1: the off-diagonal one
    PetscInt lc;  ///< the column in that block
    PetscInt j;   ///< the element's column
  };
  Mat A_ = nullptr, block_[2] = {nullptr, nullptr};
  bool direct_ = false;
  PetscInt rstart_ = 0, rend_ = 0, cstart_ = 0, cend_ = 0, ngarray_ = 0;
  const PetscInt *garray_ = nullptr, *ia_[2] = {nullptr, nullptr}, *ja_[2] = {nullptr, nullptr};
  PetscScalar *va_[2] = {nullptr, nullptr};
};
} // namespace

PetscErrorCode Assembler::Assemble(const double *u_local, Mat A, double dirichlet_diag, Vec fint,
                                   double *min_J) const {
  const int dim = mesh_.Dim();
  std::array<PetscInt, MAX_EDOF> rows;
  std::array<double, MAX_EDOF * MAX_EDOF> Ke;
  std::array<double, MAX_EDOF> fe, ue;
  std::vector<double> f_local(fint ? mesh_.NumLocalVertices() * dim : 0, 0.0);
  ElementGeometry g;
  ElementMatrixAdder adder;
  double jmin = 1e300;
  PetscFunctionBeginUser;
  if (!A) {
    // The force alone at u = 0 (every rank): F_int(0) = 0 and det F = 1 for both models, no pass over the cells.
    int zero = std::all_of(u_local, u_local + mesh_.NumLocalVertices() * dim, [](double x) { return x == 0; });
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &zero, 1, MPI_INT, MPI_LAND, mesh_.Comm()));
    if (zero) {
      if (min_J) *min_J = 1;
      PetscFunctionReturn(0);
    }
  }
  const PetscInt *first = nullptr;
  if (A) PetscCall(FirstRows(A, first));
  if (A) PetscCall(adder.Begin(A));
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    PetscInt nn;
    const PetscInt *v;
    Geometry(c, g, nn, v);
    GatherElement(u_local, v, nn, dim, ue.data());
    // det F at the quadrature points (svk): the deformation must stay invertible.
    const int p = Part(c);
    jmin = std::min(jmin, ElementTangentAndForce(parts_[p], part_D_[p].D, g, ue.data(), A ? Ke.data() : nullptr,
                                                 fe.data()));
    if (A) {
      for (PetscInt a = 0; a < nn; ++a)
        for (int k = 0; k < dim; ++k)
          rows[a * dim + k] = dirichlet_.fixed[v[a] * dim + k] ? -1 : first[v[a]] + k;
      PetscCall(adder.Add(nn * dim, rows.data(), Ke.data()));
    }
    if (fint)
      for (PetscInt a = 0; a < nn; ++a)
        for (int k = 0; k < dim; ++k) f_local[v[a] * dim + k] += fe[a * dim + k];
  }
  if (A) {
    for (PetscInt v = 0; v < mesh_.NumLocalVertices(); ++v)
      for (int k = 0; k < dim; ++k)
        if (mesh_.Owned(v) && dirichlet_.fixed[v * dim + k]) {
          const PetscInt r = first[v] + k;
          PetscCall(adder.Add(1, &r, &dirichlet_diag));
        }
    PetscCall(adder.End());
  }
  if (fint) PetscCall(AddLocal(f_local, fint));
  if (min_J) PetscCallMPI(MPI_Allreduce(&jmin, min_J, 1, MPI_DOUBLE, MPI_MIN, mesh_.Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::AddStiffnessTimes(const double *u_local, const double *v_local, Vec f) const {
  const int dim = mesh_.Dim();
  std::array<PetscInt, MAX_EDOF> rows;
  std::array<double, MAX_EDOF * MAX_EDOF> Ke;
  std::array<double, MAX_EDOF> fe, ue, ve, kv;
  ElementGeometry g;
  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    PetscInt nn;
    const PetscInt *v = mesh_.CellVertices(c, nn);
    GatherElement(v_local, v, nn, dim, ve.data());
    bool any = false;
    for (PetscInt i = 0; i < nn * dim; ++i) any = any || ve[i] != 0;
    if (!any) continue;
    Geometry(c, g, nn, v);
    GatherElement(u_local, v, nn, dim, ue.data());
    ElementTangentAndForce(parts_[Part(c)], part_D_[Part(c)].D, g, ue.data(), Ke.data(), fe.data());
    for (PetscInt i = 0; i < nn * dim; ++i) {
      kv[i] = 0;
      for (PetscInt j = 0; j < nn * dim; ++j) kv[i] += Ke[i * nn * dim + j] * ve[j];
    }
    // Free rows only (VecSetValues does not skip negative indices).
    PetscInt n = 0;
    for (PetscInt a = 0; a < nn; ++a)
      for (int k = 0; k < dim; ++k)
        if (!dirichlet_.fixed[v[a] * dim + k]) rows[n] = dofs_.Row(v[a], k), kv[n++] = kv[a * dim + k];
    PetscCall(VecSetValues(f, n, rows.data(), kv.data(), ADD_VALUES));
  }
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::AssembleLoads(const BoundaryConditions &bc, double time, Vec f) const {
  const int dim = mesh_.Dim();
  std::vector<Face> faces;
  std::vector<PetscInt> vertices;
  double factor = 0; // the ramp of the item being added, at time
  PetscFunctionBeginUser;
  auto add = [&](PetscInt v, const double *value, double scale) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (int k = 0; k < dim; ++k) PetscCall(VecSetValue(f, dofs_.Row(v, k), factor * scale * value[k], ADD_VALUES));
    PetscFunctionReturn(0);
  };
  // Tractions t and pressures p on faces: nodal forces int N_a t dA and -p int N_a n dA (n outward).
  auto face_loads = [&](const std::vector<LoadSpec> &loads, bool pressure) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (const auto &load : loads) {
      factor = load.ramp.At(time);
      const std::string input = std::string(pressure ? "-bc_pressure " : "-bc_traction ") + load.item;
      PetscCall(mesh_.GroupFaces(load.group, faces, input));
      for (const auto &face : faces) {
        double X[4 * MAX_DIM], w[4], an[4][3];
        for (int a = 0; a < face.n; ++a)
          for (int d = 0; d < dim; ++d) X[a * dim + d] = mesh_.X(face.v[a])[d];
        FaceIntegrals(dim, face.n, X, w, an);
        const double t = parts_[Part(face.cell)].thickness; // the face's cell's (2D; 1 in 3D)
        for (int a = 0; a < face.n; ++a) {
          if (pressure) {
            const double force[3] = {-load.value[0] * an[a][0], -load.value[0] * an[a][1], -load.value[0] * an[a][2]};
            PetscCall(add(face.v[a], force, t));
          } else {
            PetscCall(add(face.v[a], load.value.data(), w[a] * t));
          }
        }
      }
    }
    PetscFunctionReturn(0);
  };
  PetscCall(face_loads(bc.traction, false));
  PetscCall(face_loads(bc.pressure, true));
  for (const auto &pf : bc.point_force) {
    factor = pf.ramp.At(time);
    PetscCall(mesh_.GroupVertices(pf.group, vertices, "-bc_point_force " + pf.item));
    for (PetscInt v : vertices)
      if (mesh_.Owned(v)) PetscCall(add(v, pf.value.data(), 1.0));
  }
  if (!bc.body_force.empty()) {
    factor = bc.body_force_ramp.At(time);
    std::array<PetscInt, MAX_EDOF> rows;
    std::array<double, MAX_EDOF> fe;
    ElementGeometry g;
    for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
      PetscInt nn;
      const PetscInt *v;
      Geometry(c, g, nn, v);
      ElementBodyForce(g, bc.body_force.data(), fe.data());
      for (PetscInt a = 0; a < nn; ++a)
        for (int k = 0; k < dim; ++k) rows[a * dim + k] = dofs_.Row(v[a], k), fe[a * dim + k] *= factor;
      PetscCall(VecSetValues(f, nn * dim, rows.data(), fe.data(), ADD_VALUES));
    }
  }
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::CellResults(const double *u_local,
                                      const std::function<void(PetscInt, const CellStress &)> &use) const {
  const int dim = mesh_.Dim();
  std::array<double, MAX_EDOF> ue;
  PetscFunctionBeginUser;
  ElementGeometry g;
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    PetscInt nn;
    const PetscInt *v;
    Geometry(c, g, nn, v);
    GatherElement(u_local, v, nn, dim, ue.data());
    use(c, ElementStress(parts_[Part(c)], g, ue.data()));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Assembler::StiffnessScale(double &scale, double *abs_row_sum) const {
  const int dim = mesh_.Dim();
  std::array<double, MAX_EDOF * MAX_EDOF> Ke;
  std::array<double, MAX_EDOF> fe, ue{};
  double sum[3] = {0, 0, 0}, gsum[3];
  PetscFunctionBeginUser;
  std::vector<Material> linear = parts_;
  for (Material &m : linear) m.model = MaterialModel::LINEAR;
  ElementGeometry g;
  for (PetscInt c = 0; c < mesh_.NumLocalCells(); ++c) {
    PetscInt nn;
    const PetscInt *v;
    Geometry(c, g, nn, v);
    ElementTangentAndForce(linear[Part(c)], part_D_[Part(c)].D, g, ue.data(), Ke.data(), fe.data());
    for (PetscInt i = 0; i < nn * dim; ++i) sum[0] += Ke[i * nn * dim + i];
    sum[1] += nn * dim;
    if (abs_row_sum)
      for (PetscInt i = 0; i < nn * dim * nn * dim; ++i) sum[2] += std::abs(Ke[i]);
  }
  PetscCallMPI(MPI_Allreduce(sum, gsum, 3, MPI_DOUBLE, MPI_SUM, mesh_.Comm()));
  scale = gsum[1] > 0 ? gsum[0] / gsum[1] : 1.0;
  if (abs_row_sum) *abs_row_sum = gsum[2] / std::max<double>(1.0, (double)mesh_.Dim() * mesh_.NumGlobalNodes());
  PetscFunctionReturn(0);
}

} // namespace signorini
