// Building, labelling, partitioning and distributing the DMPlex, and the per-rank arrays of the element loops.
#include "signorini/mesh/mesh.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/core/errors.hpp"
#include "signorini/core/options.hpp"
#include "signorini/core/parse.hpp"
#include "signorini/core/progress.hpp"
#include "signorini/mesh/geo_mesher.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace signorini {

namespace {

const std::string LABEL_PREFIX = "phys_";
const char *BOUNDARY_LABEL = "signorini_boundary";

/// Sends the group names and dimensions of rank 0 to every rank.
PetscErrorCode BroadcastGroups(MPI_Comm comm, const SerialMesh &serial, std::vector<std::string> &names,
                               std::vector<int> &dims) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string packed;
  if (rank == 0)
    for (const auto &g : serial.groups) packed += std::to_string(g.dim) + g.name + '\n';
  int len = (int)packed.size();
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  packed.resize(len);
  PetscCallMPI(MPI_Bcast(packed.data(), len, MPI_CHAR, 0, comm));
  names.clear();
  dims.clear();
  for (const auto &line : Split(packed, '\n')) {
    if (line.empty()) continue;
    dims.push_back(line[0] - '0');
    names.push_back(line.substr(1));
  }
  PetscFunctionReturn(0);
}

/// The vertices of face `face` of an interpolated DMPlex in cyclic order, as vertex indices (point - vstart): the two
/// ends of an edge in 2D; in 3D the face's edges chained into a cycle (its orientation is the caller's to fix).
PetscErrorCode FaceCycle(DM dm, int dim, PetscInt vstart, PetscInt face, Face &f) {
  const PetscInt *cone;
  PetscInt ncone;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetConeSize(dm, face, &ncone));
  PetscCall(DMPlexGetCone(dm, face, &cone));
  if (dim == 2) {
    f.n = 2, f.v[0] = cone[0] - vstart, f.v[1] = cone[1] - vstart;
    PetscFunctionReturn(0);
  }
  std::array<std::array<PetscInt, 2>, 4> edges;
  PetscCheck(ncone == 3 || ncone == 4, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a face with %" PetscInt_FMT " edges", ncone);
  for (PetscInt k = 0; k < ncone; ++k) {
    const PetscInt *ev;
    PetscCall(DMPlexGetCone(dm, cone[k], &ev));
    edges[k] = {ev[0] - vstart, ev[1] - vstart};
  }
  f.n = (int)ncone;
  f.v[0] = edges[0][0], f.v[1] = edges[0][1];
  std::array<char, 4> used{1, 0, 0, 0};
  for (int k = 2; k < f.n; ++k)
    for (PetscInt e = 0; e < ncone; ++e) {
      if (used[e] || (edges[e][0] != f.v[k - 1] && edges[e][1] != f.v[k - 1])) continue;
      f.v[k] = edges[e][0] == f.v[k - 1] ? edges[e][1] : edges[e][0];
      used[e] = 1;
      break;
    }
  PetscFunctionReturn(0);
}

/// Normal of a face with vertices x(f.v[k]) (dim values each), scaled by its length (2D: the right normal of
/// v0 -> v1) or area (3D: Newell's vector area, of the projections for a warped quadrilateral).
template <typename Coordinates>
void FaceVectorArea(int dim, const Face &f, const Coordinates &x, double *normal) {
  normal[0] = normal[1] = normal[2] = 0;
  if (dim == 2) {
    const double *a = x(f.v[0]), *b = x(f.v[1]);
    normal[0] = b[1] - a[1], normal[1] = -(b[0] - a[0]);
    return;
  }
  for (int k = 0; k < f.n; ++k) {
    const double *a = x(f.v[k]), *b = x(f.v[(k + 1) % f.n]);
    normal[0] += 0.5 * (a[1] - b[1]) * (a[2] + b[2]);
    normal[1] += 0.5 * (a[2] - b[2]) * (a[0] + b[0]);
    normal[2] += 0.5 * (a[0] - b[0]) * (a[1] + b[1]);
  }
}

} // namespace

/// Bounds of -mesh_size_factor: 1e-3 already multiplies the element count of a .geo by a million.
constexpr double MESH_SIZE_FACTOR_MIN = 1e-3, MESH_SIZE_FACTOR_MAX = 1e3;

PetscErrorCode ReadMeshOptions(MPI_Comm comm, const std::string &default_file, MeshOptions &opts) {
  PetscFunctionBeginUser;
  opts.file = default_file;
  PetscOptionsBegin(comm, nullptr, "Mesh options", "signorini");
  PetscCall(OptionsString(PetscOptionsObject, "-mesh_file", "gmsh mesh (.msh 2.2/4.1) or geometry (.geo, meshed "
                          "in-process)", "a .msh or .geo path", opts.file));
  PetscCall(OptionsReal(PetscOptionsObject, "-mesh_size_factor", "Mesh size factor applied when meshing a .geo file",
                        {MESH_SIZE_FACTOR_MIN, MESH_SIZE_FACTOR_MAX}, opts.size_factor));
  opts.max_cells = DefaultMaxCells();
  PetscCall(OptionsReal(PetscOptionsObject, "-mesh_max_cells", "Refuse a .geo whose mesh is estimated to have more "
                        "cells (default: physical memory / 3.2 kB per cell)", {1, 1e12}, opts.max_cells));
  PetscCall(OptionsString(PetscOptionsObject, "-mesh_partitioner", "Partitioner: metis, ptscotch or simple",
                          "metis, ptscotch or simple", opts.partitioner));
  PetscOptionsEnd();
  PetscCheck(!opts.file.empty(), comm, PETSC_ERR_USER_INPUT, "-mesh_file is empty; expected a .msh or .geo path");
  PetscCall(PathCandidatesFor("-mesh_file", opts.file, opts.file_candidates));
  PetscCheck(opts.partitioner == "metis" || opts.partitioner == "ptscotch" || opts.partitioner == "simple", comm,
             PETSC_ERR_USER_INPUT, "-mesh_partitioner '%s' is unknown; expected metis, ptscotch or simple",
             opts.partitioner.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::Create(MPI_Comm comm, const MeshOptions &opts) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  comm_ = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string error;
  ProgressBegin(("reading " + opts.file + (opts.file.size() > 4 && opts.file.substr(opts.file.size() - 4) == ".geo"
                                                ? " (meshing with gmsh)" : "")).c_str());
  if (rank == 0) {
    std::string looked;
    // Options not read by ReadMeshOptions (unit tests) name the file as it is.
    const PathCandidates as_given{{opts.file}, {"relative to the current directory"}};
    const std::string path = FirstExisting(opts.file_candidates.paths.empty() ? as_given : opts.file_candidates, looked);
    if (path.empty())
      error = "cannot open mesh file '" + opts.file + "': not found at " + looked +
              "; expected a readable gmsh .msh or .geo file";
    else
      error = ReadGmsh(path, opts.size_factor, serial_, opts.max_cells);
  }
  ProgressEnd();
  PetscCall(RaiseFromRoot(comm, error));
  dim_ = serial_.dim;
  PetscCallMPI(MPI_Bcast(&dim_, 1, MPI_INT, 0, comm));
  PetscCall(BroadcastGroups(comm, serial_, group_names_, group_dims_));
  DMH dm;
  PetscCall(BuildSerialDM(opts.file, dm.out()));
  ProgressBegin("partition and distribution");
  PetscCall(Partition(dm, opts.partitioner));
  PetscCall(Distribute(dm));
  ProgressEnd();
  dm_ = std::move(dm);
  PetscCall(BuildLocalArrays());
  // The file's tags in blocks of file indices (written with the output); nothing needs the serial mesh any more.
  PetscCall(ScatterBlocks(comm, serial_.node_tags, node_tags_));
  PetscCall(ScatterBlocks(comm, serial_.cell_tags, cell_tags_));
  serial_ = SerialMesh{};
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BuildSerialDM(const std::string &file, DM *out) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  const PetscInt nc = serial_.NumCells(), nv = serial_.NumNodes();
  DMH dm;
  PetscCall(DMPlexCreate(comm_, dm.out()));
  PetscCall(DMSetDimension(dm, dim_));
  PetscCall(DMPlexSetChart(dm, 0, nc + nv));
  for (PetscInt c = 0; c < nc; ++c) PetscCall(DMPlexSetConeSize(dm, c, serial_.CellSize(c)));
  PetscCall(DMSetUp(dm));
  std::vector<PetscInt> cone(MAX_CELL_VERTICES);
  for (PetscInt c = 0; c < nc; ++c) {
    const int n = serial_.CellSize(c);
    for (int j = 0; j < n; ++j) cone[j] = nc + serial_.cell_nodes[serial_.cell_offsets[c] + j];
    // DMPlex orders the vertices of a tetrahedron, a pyramid and a hexahedron differently from gmsh (its first face
    // points inwards: the base of a pyramid clockwise seen from the apex); the element loops keep gmsh's order
    // (cell_vertices_).
    if (dim_ == 3)
      PetscCall(DMPlexInvertCell(n == 4   ? DM_POLYTOPE_TETRAHEDRON
                                 : n == 5 ? DM_POLYTOPE_PYRAMID
                                          : DM_POLYTOPE_HEXAHEDRON,
                                 cone.data()));
    PetscCall(DMPlexSetCone(dm, c, cone.data()));
  }
  PetscCall(DMPlexSymmetrize(dm));
  PetscCall(DMPlexStratify(dm));
  PetscCall(DMPlexComputeCellTypes(dm));
  DMH idm;
  PetscCall(DMPlexInterpolate(dm, idm.out()));
  PetscCall(DMPlexBuildCoordinatesFromCellList(idm, dim_, serial_.coords.data()));
  PetscInt vstart, vend, cstart, cend;
  PetscCall(DMPlexGetDepthStratum(idm, 0, &vstart, &vend));
  PetscCall(DMPlexGetHeightStratum(idm, 0, &cstart, &cend));
  PetscCheck(vend - vstart == nv && cend - cstart == nc, comm_, PETSC_ERR_PLIB, "interpolation changed the mesh");
  std::string folded;
  if (rank == 0) PetscCall(FindFoldedCells(idm, cstart, folded));
  PetscCall(RaiseFromRoot(comm_, folded.empty() ? "" : "mesh '" + file + "': " + folded));

  // One label per physical group, value 1, completed to the closure of what the group holds.
  for (std::size_t g = 0; g < group_names_.size(); ++g) {
    const std::string label_name = LABEL_PREFIX + group_names_[g];
    PetscCall(DMCreateLabel(idm, label_name.c_str()));
    DMLabel label;
    PetscCall(DMGetLabel(idm, label_name.c_str(), &label));
    if (rank == 0) {
      const PhysicalGroup &group = serial_.groups[g];
      for (int v : group.nodes) PetscCall(DMLabelSetValue(label, vstart + v, 1));
      for (int c : group.cells) PetscCall(DMLabelSetValue(label, cstart + c, 1));
      for (std::size_t e = 0; e + 1 < group.edges.size(); e += 2) {
        const PetscInt pts[2] = {vstart + group.edges[e], vstart + group.edges[e + 1]};
        PetscInt njoin;
        const PetscInt *join;
        PetscCall(DMPlexGetJoin(idm, 2, pts, &njoin, &join));
        const PetscInt edge = njoin == 1 ? join[0] : -1;
        PetscCall(DMPlexRestoreJoin(idm, 2, pts, &njoin, &join));
        PetscCheck(edge >= 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
                   "a line element of physical curve '%s' is not an edge of any cell; expected the lines of a "
                   "physical curve to be cell edges", group.name.c_str());
        PetscCall(DMLabelSetValue(label, edge, 1));
      }
      for (std::size_t f = 0; f + 1 < group.face_offsets.size(); ++f) {
        std::vector<PetscInt> pts;
        for (int k = group.face_offsets[f]; k < group.face_offsets[f + 1]; ++k)
          pts.push_back(vstart + group.face_nodes[k]);
        PetscInt njoin;
        const PetscInt *join;
        PetscCall(DMPlexGetFullJoin(idm, (PetscInt)pts.size(), pts.data(), &njoin, &join));
        const PetscInt face = njoin == 1 ? join[0] : -1;
        PetscCall(DMPlexRestoreJoin(idm, (PetscInt)pts.size(), pts.data(), &njoin, &join));
        PetscCheck(face >= 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT,
                   "a surface element of physical surface '%s' is not a face of any cell; expected the triangles and "
                   "quadrilaterals of a physical surface to be cell faces", group.name.c_str());
        PetscCall(DMLabelSetValue(label, face, 1));
      }
    }
    // A group of cells is not completed to its closure (for the body of a 1M-cell mesh that took 4.7 s of the mesh
    // set-up): LabelVertices finds its vertices through the cells.
    if (group_dims_[g] < dim_) PetscCall(DMPlexLabelComplete(idm, label));
  }
  PetscCall(DMCreateLabel(idm, BOUNDARY_LABEL));
  DMLabel boundary;
  PetscCall(DMGetLabel(idm, BOUNDARY_LABEL, &boundary));
  PetscCall(DMPlexMarkBoundaryFaces(idm, 1, boundary));
  PetscCall(DMPlexLabelComplete(idm, boundary));

  // The file's node and cell order travels with the points as a field: 1 dof on every cell and vertex.
  vertex_orig_.resize(nv);
  cell_orig_.resize(nc);
  for (PetscInt v = 0; v < nv; ++v) vertex_orig_[v] = v;
  for (PetscInt c = 0; c < nc; ++c) cell_orig_[c] = c;
  cell_offsets_.assign(serial_.cell_offsets.begin(), serial_.cell_offsets.end());
  cell_vertices_.assign(serial_.cell_nodes.begin(), serial_.cell_nodes.end());
  vstart_ = vstart;
  cstart_ = cstart;
  PetscInt ng[2] = {nv, nc};
  PetscCallMPI(MPI_Bcast(ng, 2, MPIU_INT, 0, comm_));
  num_global_nodes_ = ng[0];
  num_global_cells_ = ng[1];
  *out = idm.get();
  PetscCall(PetscObjectReference((PetscObject)*out));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::FindFoldedCells(DM dm, PetscInt cstart, std::string &error) const {
  PetscFunctionBeginUser;
  error.clear();
  const int dim = serial_.dim, nc = serial_.NumCells();
  const auto x = [&](int v) { return &serial_.coords[dim * v]; };
  std::vector<double> centroid(3 * nc, 0.0);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, diag2 = 0;
  for (int c = 0; c < nc; ++c) {
    const int n = serial_.CellSize(c);
    for (int k = serial_.cell_offsets[c]; k < serial_.cell_offsets[c + 1]; ++k)
      for (int d = 0; d < dim; ++d) centroid[3 * c + d] += x(serial_.cell_nodes[k])[d] / n;
  }
  for (int v = 0; v < serial_.NumNodes(); ++v)
    for (int d = 0; d < dim; ++d)
      lo[d] = v ? std::min(lo[d], x(v)[d]) : x(v)[d], hi[d] = v ? std::max(hi[d], x(v)[d]) : x(v)[d];
  for (int d = 0; d < dim; ++d) diag2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  // A distance below 1e-12 of the bounding box's diagonal counts as zero (a degenerate cell is caught before).
  const double tol = 1e-12 * std::sqrt(diag2);
  PetscInt fstart, fend;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fstart, &fend));
  for (PetscInt face = fstart; face < fend && error.empty(); ++face) {
    PetscInt nsupport;
    const PetscInt *support;
    PetscCall(DMPlexGetSupportSize(dm, face, &nsupport));
    if (nsupport != 2) continue;
    PetscCall(DMPlexGetSupport(dm, face, &support));
    const int a = (int)(support[0] - cstart), b = (int)(support[1] - cstart);
    // The face's first dim vertices (those the two cells share) span its plane (a warped quadrilateral's nearly).
    int p[3], np = 0;
    for (int i = serial_.cell_offsets[a]; i < serial_.cell_offsets[a + 1] && np < dim; ++i)
      for (int j = serial_.cell_offsets[b]; j < serial_.cell_offsets[b + 1]; ++j)
        if (serial_.cell_nodes[i] == serial_.cell_nodes[j]) {
          p[np++] = serial_.cell_nodes[i];
          break;
        }
    PetscCheck(np == dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cells sharing a face share fewer than %d vertices", dim);
    double n[3] = {0, 0, 0};
    if (dim == 2) {
      n[0] = x(p[1])[1] - x(p[0])[1], n[1] = -(x(p[1])[0] - x(p[0])[0]);
    } else {
      double e1[3], e2[3];
      for (int d = 0; d < 3; ++d) e1[d] = x(p[1])[d] - x(p[0])[d], e2[d] = x(p[2])[d] - x(p[0])[d];
      n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    }
    const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double side[2] = {0, 0};
    for (int s = 0; s < 2; ++s)
      for (int d = 0; d < dim; ++d) side[s] += n[d] * (centroid[3 * (s ? b : a) + d] - x(p[0])[d]) / norm;
    if (std::min(std::abs(side[0]), std::abs(side[1])) > tol && (side[0] > 0) == (side[1] > 0))
      error = "elements " + std::to_string(serial_.cell_tags[a]) + " and " + std::to_string(serial_.cell_tags[b]) +
              " overlap: they lie on the same side of the " + (dim == 2 ? "edge" : "face") +
              " they share (a folded mesh); expected the cells around each interior " + (dim == 2 ? "edge" : "face") +
              " on either side of it";
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::Partition(DM dm, const std::string &partitioner) {
  PetscMPIInt rank, size;
  PetscPartitioner part;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(DMPlexGetPartitioner(dm, &part));
  if (partitioner == "ptscotch") {
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
    PetscFunctionReturn(0);
  }
  if (partitioner == "simple" || size == 1) {
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscFunctionReturn(0);
  }
  // METIS on the dual graph of the serial mesh (cells sharing an edge), handed to DMPlex as a shell partition.
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  std::vector<PetscInt> sizes(size, 0), points;
  if (rank == 0) {
    // Cells are neighbours when they share a face: 2 nodes in 2D, 3 for a tetrahedron, 4 for a hexahedron (3 when
    // tetrahedra or pyramids are present, so that a mixed mesh connects through its triangular faces).
    bool triangles = false;
    for (int c = 0; c < serial_.NumCells(); ++c) triangles = triangles || serial_.CellSize(c) < 8;
    idx_t ne = serial_.NumCells(), nn = serial_.NumNodes(), nparts = size, objval = 0;
    idx_t ncommon = dim_ == 2 ? 2 : triangles ? 3 : 4;
    std::vector<idx_t> eptr(serial_.cell_offsets.begin(), serial_.cell_offsets.end());
    std::vector<idx_t> eind(serial_.cell_nodes.begin(), serial_.cell_nodes.end());
    std::vector<idx_t> epart(ne), npart(nn);
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 7;
    const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                                          nullptr, options, &objval, epart.data(), npart.data());
    PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartMeshDual failed (%d)", status);
    for (idx_t c = 0; c < ne; ++c) sizes[epart[c]]++;
    std::vector<PetscInt> start(size + 1, 0);
    for (int p = 0; p < size; ++p) start[p + 1] = start[p] + sizes[p];
    points.resize(ne);
    for (idx_t c = 0; c < ne; ++c) points[start[epart[c]]++] = c;
  }
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes.data(), points.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::Distribute(DMH &dm) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  if (size == 1) PetscFunctionReturn(0);
  // Section holding, on every vertex, its index in the file and, on every cell, its index in the file followed by
  // those of its vertices in gmsh's order.
  PetscInt pstart, pend;
  PetscCall(DMPlexGetChart(dm, &pstart, &pend));
  SectionH sec;
  PetscCall(PetscSectionCreate(PETSC_COMM_SELF, sec.out()));
  PetscCall(PetscSectionSetChart(sec, pstart, pend));
  const PetscInt nv = (PetscInt)vertex_orig_.size(), nc = (PetscInt)cell_orig_.size();
  for (PetscInt c = 0; c < nc; ++c)
    PetscCall(PetscSectionSetDof(sec, cstart_ + c, 1 + cell_offsets_[c + 1] - cell_offsets_[c]));
  for (PetscInt v = 0; v < nv; ++v) PetscCall(PetscSectionSetDof(sec, vstart_ + v, 1));
  PetscCall(PetscSectionSetUp(sec));
  VecH orig;
  PetscInt n;
  PetscCall(PetscSectionGetStorageSize(sec, &n));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, orig.out()));
  PetscScalar *a;
  PetscCall(VecGetArray(orig, &a));
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(sec, cstart_ + c, &off));
    a[off] = cell_orig_[c];
    for (PetscInt k = cell_offsets_[c]; k < cell_offsets_[c + 1]; ++k) a[off + 1 + k - cell_offsets_[c]] = cell_vertices_[k];
  }
  for (PetscInt v = 0; v < nv; ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(sec, vstart_ + v, &off));
    a[off] = vertex_orig_[v];
  }
  PetscCall(VecRestoreArray(orig, &a));

  SFH migration;
  DMH dist;
  PetscCall(DMPlexDistribute(dm, 0, migration.out(), dist.out()));
  if (!dist) PetscFunctionReturn(0);
  SectionH new_sec;
  VecH new_orig;
  PetscCall(PetscSectionCreate(PETSC_COMM_SELF, new_sec.out()));
  PetscCall(VecCreate(PETSC_COMM_SELF, new_orig.out()));
  PetscCall(DMPlexDistributeField(dm, migration, sec, orig, new_sec, new_orig));
  PetscCall(DMPlexGetDepthStratum(dist, 0, &vstart_, &pend));
  vertex_orig_.assign(pend - vstart_, -1);
  PetscCall(DMPlexGetHeightStratum(dist, 0, &cstart_, &pend));
  cell_orig_.assign(pend - cstart_, -1);
  const PetscScalar *b;
  PetscCall(VecGetArrayRead(new_orig, &b));
  for (PetscInt v = 0; v < (PetscInt)vertex_orig_.size(); ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(new_sec, vstart_ + v, &off));
    vertex_orig_[v] = (PetscInt)PetscRealPart(b[off]);
  }
  cell_offsets_.assign(1, 0);
  cell_vertices_.clear();
  for (PetscInt c = 0; c < (PetscInt)cell_orig_.size(); ++c) {
    PetscInt off, ndof;
    PetscCall(PetscSectionGetOffset(new_sec, cstart_ + c, &off));
    PetscCall(PetscSectionGetDof(new_sec, cstart_ + c, &ndof));
    cell_orig_[c] = (PetscInt)PetscRealPart(b[off]);
    for (PetscInt k = 1; k < ndof; ++k) cell_vertices_.push_back((PetscInt)PetscRealPart(b[off + k]));
    cell_offsets_.push_back((PetscInt)cell_vertices_.size());
  }
  PetscCall(VecRestoreArrayRead(new_orig, &b));
  dm = std::move(dist);
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BuildLocalArrays() {
  PetscInt pstart, pend, vend, cend;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  PetscCall(DMPlexGetDepthStratum(dm_, 0, &vstart_, &vend));
  PetscCall(DMPlexGetHeightStratum(dm_, 0, &cstart_, &cend));
  const PetscInt nv = vend - vstart_, nc = cend - cstart_;
  PetscCheck((PetscInt)vertex_orig_.size() == nv && (PetscInt)cell_orig_.size() == nc, comm_, PETSC_ERR_PLIB,
             "inconsistent distributed mesh");

  point_leaf_.assign(pend - pstart, 0);
  PetscSF sf;
  PetscInt nroots, nleaves;
  const PetscInt *ilocal;
  PetscCall(DMGetPointSF(dm_, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, nullptr));
  if (nroots >= 0)
    for (PetscInt i = 0; i < nleaves; ++i) point_leaf_[(ilocal ? ilocal[i] : i) - pstart] = 1;
  vertex_owned_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v) vertex_owned_[v] = !point_leaf_[vstart_ + v - pstart];

  Vec coords;
  PetscSection csec;
  const PetscScalar *x;
  PetscCall(DMGetCoordinatesLocal(dm_, &coords));
  PetscCall(DMGetCoordinateSection(dm_, &csec));
  PetscCall(VecGetArrayRead(coords, &x));
  coords_.resize(dim_ * nv);
  for (PetscInt v = 0; v < nv; ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(csec, vstart_ + v, &off));
    for (int d = 0; d < dim_; ++d) coords_[dim_ * v + d] = PetscRealPart(x[off + d]);
  }
  PetscCall(VecRestoreArrayRead(coords, &x));

  // The cells' vertices, in gmsh's order, from file indices to local ones.
  std::unordered_map<PetscInt, PetscInt> local_of;
  for (PetscInt v = 0; v < nv; ++v) local_of[vertex_orig_[v]] = v;
  for (auto &v : cell_vertices_) {
    const auto it = local_of.find(v);
    PetscCheck(it != local_of.end(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "a cell's vertex is not on its rank");
    v = it->second;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::LabelVertices(const std::string &label_name, bool cells, std::vector<PetscInt> &vertices) const {
  DMLabel label;
  PetscFunctionBeginUser;
  vertices.clear();
  PetscCall(DMGetLabel(dm_, label_name.c_str(), &label));
  const PetscInt nv = NumLocalVertices(), nc = NumLocalCells();
  std::vector<double> in_cells(cells ? nv : 0, 0.0);
  ISH is;
  if (label) PetscCall(DMLabelGetStratumIS(label, 1, is.out()));
  if (is) {
    PetscInt n;
    const PetscInt *pts;
    PetscCall(ISGetLocalSize(is, &n));
    PetscCall(ISGetIndices(is, &pts));
    for (PetscInt i = 0; i < n; ++i) {
      if (pts[i] >= vstart_ && pts[i] < vstart_ + nv) vertices.push_back(pts[i] - vstart_);
      if (cells && pts[i] >= cstart_ && pts[i] < cstart_ + nc) {
        PetscInt nn;
        const PetscInt *cv = CellVertices(pts[i] - cstart_, nn);
        for (PetscInt a = 0; a < nn; ++a) in_cells[cv[a]] = 1;
      }
    }
    PetscCall(ISRestoreIndices(is, &pts));
  }
  if (cells) {
    // A group of cells has no vertices in its label: they come from its local cells, and every rank sharing a vertex
    // learns it from the ranks whose cells hold it.
    PetscCall(SumShared(in_cells));
    for (PetscInt v = 0; v < nv; ++v)
      if (in_cells[v] > 0) vertices.push_back(v);
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::CheckGroup(const std::string &name, int required_dim) const {
  PetscFunctionBeginUser;
  const auto it = std::find(group_names_.begin(), group_names_.end(), name);
  PetscCheck(it != group_names_.end(), comm_, PETSC_ERR_USER_INPUT,
             "physical group '%s' is not in the mesh; the mesh has: %s", name.c_str(),
             group_names_.empty() ? "(no physical groups)" : Join(group_names_, ", ").c_str());
  const int dim = group_dims_[it - group_names_.begin()];
  PetscCheck(required_dim < 0 || dim == required_dim, comm_, PETSC_ERR_USER_INPUT,
             "physical group '%s' has dimension %d; expected a physical %s (dimension %d)", name.c_str(), dim,
             required_dim == 1 ? "curve" : "surface", required_dim);
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::GroupVertices(const std::string &name, std::vector<PetscInt> &vertices) const {
  PetscFunctionBeginUser;
  PetscCall(CheckGroup(name, -1));
  const int dim = group_dims_[std::find(group_names_.begin(), group_names_.end(), name) - group_names_.begin()];
  PetscCall(LabelVertices(LABEL_PREFIX + name, dim == dim_, vertices));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BoundaryVertices(std::vector<PetscInt> &vertices) const {
  PetscFunctionBeginUser;
  PetscCall(LabelVertices(BOUNDARY_LABEL, false, vertices));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::GroupFaces(const std::string &name, std::vector<Face> &faces) const {
  PetscFunctionBeginUser;
  PetscCall(CheckGroup(name, dim_ - 1));
  PetscCall(LabelFaces(LABEL_PREFIX + name, faces));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BoundaryFaces(std::vector<Face> &faces) const {
  PetscFunctionBeginUser;
  PetscCall(LabelFaces(BOUNDARY_LABEL, faces));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BoundingBox(double *lo, double *hi) const {
  double l[3] = {0, 0, 0}, h[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  for (int d = 0; d < dim_; ++d) l[d] = 1e300, h[d] = -1e300;
  for (PetscInt v = 0; v < NumLocalVertices(); ++v)
    for (int d = 0; d < dim_; ++d) l[d] = std::min(l[d], X(v)[d]), h[d] = std::max(h[d], X(v)[d]);
  PetscCallMPI(MPI_Allreduce(l, lo, 3, MPI_DOUBLE, MPI_MIN, comm_));
  PetscCallMPI(MPI_Allreduce(h, hi, 3, MPI_DOUBLE, MPI_MAX, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::SumShared(std::vector<double> &per_vertex) const {
  PetscInt pstart, pend, nroots;
  PetscSF sf;
  PetscFunctionBeginUser;
  PetscCall(DMGetPointSF(dm_, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, nullptr, nullptr, nullptr));
  if (nroots < 0) PetscFunctionReturn(0);
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  std::vector<double> root(pend - pstart, 0.0), leaf(pend - pstart, 0.0);
  for (PetscInt v = 0; v < NumLocalVertices(); ++v) {
    (Owned(v) ? root : leaf)[vstart_ + v - pstart] = per_vertex[v];
  }
  PetscCall(PetscSFReduceBegin(sf, MPI_DOUBLE, leaf.data(), root.data(), MPI_SUM));
  PetscCall(PetscSFReduceEnd(sf, MPI_DOUBLE, leaf.data(), root.data(), MPI_SUM));
  PetscCall(PetscSFBcastBegin(sf, MPI_DOUBLE, root.data(), leaf.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPI_DOUBLE, root.data(), leaf.data(), MPI_REPLACE));
  for (PetscInt v = 0; v < NumLocalVertices(); ++v) per_vertex[v] = (Owned(v) ? root : leaf)[vstart_ + v - pstart];
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::LabelFaces(const std::string &label_name, std::vector<Face> &faces) const {
  PetscFunctionBeginUser;
  faces.clear();
  DMLabel label;
  PetscCall(DMGetLabel(dm_, label_name.c_str(), &label));
  if (!label) PetscFunctionReturn(0);
  ISH is;
  PetscCall(DMLabelGetStratumIS(label, 1, is.out()));
  if (!is) PetscFunctionReturn(0);
  PetscInt n, fstart, fend, pstart, pend;
  const PetscInt *pts;
  PetscCall(DMPlexGetHeightStratum(dm_, 1, &fstart, &fend));
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  PetscCall(ISGetLocalSize(is, &n));
  PetscCall(ISGetIndices(is, &pts));
  for (PetscInt i = 0; i < n; ++i) {
    if (pts[i] < fstart || pts[i] >= fend || point_leaf_[pts[i] - pstart]) continue;
    const PetscInt *support;
    PetscInt nsupport;
    Face f;
    PetscCall(FaceCycle(dm_, dim_, vstart_, pts[i], f));
    PetscCall(DMPlexGetSupportSize(dm_, pts[i], &nsupport));
    PetscCall(DMPlexGetSupport(dm_, pts[i], &support));
    if (nsupport >= 1) {
      // Orient the face outwards: its outward normal (the right normal of v0 -> v1 in 2D, the right-hand normal
      // in 3D) points away from its cell's centroid.
      PetscInt nc;
      const PetscInt *cv = CellVertices(support[0] - cstart_, nc);
      double out[3] = {0, 0, 0}, normal[3];
      for (PetscInt k = 0; k < nc; ++k)
        for (int d = 0; d < dim_; ++d) out[d] -= X(cv[k])[d] / nc;
      for (int k = 0; k < f.n; ++k)
        for (int d = 0; d < dim_; ++d) out[d] += X(f.v[k])[d] / f.n;
      FaceNormal(f, normal);
      double dot = 0;
      for (int d = 0; d < dim_; ++d) dot += normal[d] * out[d];
      if (dot < 0) std::reverse(f.v.begin(), f.v.begin() + f.n);
    }
    faces.push_back(f);
  }
  PetscCall(ISRestoreIndices(is, &pts));
  PetscFunctionReturn(0);
}

void Mesh::FaceNormal(const Face &f, double *normal) const {
  FaceVectorArea(dim_, f, [this](PetscInt v) { return X(v); }, normal);
}

} // namespace signorini
