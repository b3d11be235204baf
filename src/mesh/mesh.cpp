// Building, labelling, partitioning and distributing the DMPlex, and the per-rank arrays of the element loops.
#include "signorini/mesh/mesh.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/core/errors.hpp"
#include "signorini/options/readers.hpp"
#include "signorini/core/parse.hpp"
#include "signorini/core/progress.hpp"
#include "signorini/mesh/cell_faces.hpp"
#include "signorini/mesh/geo_mesher.hpp"
#include "signorini/mesh/mesh_h5.hpp"

#include <metis.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <tuple>

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

/// A face of the serial mesh found through one of its cells: its sorted vertices (padded with INT_MAX), the cell and
/// the face's position in CellFaces.
struct FaceEntry {
  std::array<int, 4> key;
  int cell, local;
  bool operator<(const FaceEntry &o) const {
    return key != o.key ? key < o.key : cell != o.cell ? cell < o.cell : local < o.local;
  }
};

std::array<int, 4> FaceKey(const int *nodes, int n) {
  std::array<int, 4> key{INT_MAX, INT_MAX, INT_MAX, INT_MAX};
  for (int i = 0; i < n; ++i) { // insertion sort of at most 4 values
    int j = i;
    for (; j > 0 && key[j - 1] > nodes[i]; --j) key[j] = key[j - 1];
    key[j] = nodes[i];
  }
  return key;
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

/// The error naming the cells of a and b, two entries of one face of serial, if they lie on the same side of it (a
/// folded mesh), else empty.
std::string FoldedCells(const SerialMesh &serial, const FaceEntry &a, const FaceEntry &b) {
  // Both cells are positively oriented (CheckAndOrientCells) and their faces are listed outwards (CellFaces), so
  // cells on either side of their shared face run through it in opposite directions, and cells on the same side
  // (overlapping, each of them valid) in the same direction.
  const int dim = serial.dim;
  const CellFaceTable &fa = CellFaces(dim, serial.CellSize(a.cell)), &fb = CellFaces(dim, serial.CellSize(b.cell));
  const int n = fa.size[a.local];
  const auto vertex = [&](const FaceEntry &e, const CellFaceTable &t, int k) {
    return serial.cell_nodes[serial.cell_offsets[e.cell] + t.v[e.local][k % n]];
  };
  // The same direction: the same start in 2D, one a rotation of the other in 3D.
  int j = 0;
  while (vertex(b, fb, j) != vertex(a, fa, 0)) ++j;
  if (n == 2 ? j != 0 : vertex(b, fb, j + 1) != vertex(a, fa, 1)) return "";
  const char *what = dim == 2 ? "edge" : "face";
  const auto [first, second] = std::minmax(serial.cell_tags[a.cell], serial.cell_tags[b.cell]);
  return "elements " + std::to_string(first) + " and " + std::to_string(second) +
         " overlap: they lie on the same side of the " + what + " they share (a folded mesh); expected the cells " +
         "around each interior " + what + " on either side of it";
}

/// Renumbers the cells of serial along a Morton (Z-order) curve through their centroids and the nodes in the order
/// the cells first use them, so that the vertices of a cell, and the cells of a region, sit close together in every
/// array the element loops touch (the stiffness rows of one cell within a few cache lines). The file's numbering comes
/// out in file_node and file_cell (new index -> index in the file). Every index of serial (cells, groups) is
/// renumbered; the tags move with their nodes and cells.
void LocalityOrder(SerialMesh &serial, std::vector<PetscInt> &file_node, std::vector<PetscInt> &file_cell) {
  const int dim = serial.dim, nc = serial.NumCells(), nv = serial.NumNodes();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int v = 0; v < nv; ++v)
    for (int d = 0; d < dim; ++d)
      lo[d] = std::min(lo[d], serial.coords[v * dim + d]), hi[d] = std::max(hi[d], serial.coords[v * dim + d]);
  const int bits = dim == 2 ? 31 : 21;
  const double steps = std::ldexp(1.0, bits) * (1 - 1e-12);
  std::vector<std::pair<std::uint64_t, int>> keyed(nc);
  for (int c = 0; c < nc; ++c) {
    const int n = serial.CellSize(c);
    std::uint64_t key = 0;
    for (int d = 0; d < dim; ++d) {
      double x = 0;
      for (int k = 0; k < n; ++k) x += serial.coords[serial.cell_nodes[serial.cell_offsets[c] + k] * dim + d];
      const double t = hi[d] > lo[d] ? (x / n - lo[d]) / (hi[d] - lo[d]) : 0;
      const std::uint64_t q = (std::uint64_t)std::clamp(t * steps, 0.0, steps);
      for (int b = 0; b < bits; ++b) key |= ((q >> b) & 1u) << (b * dim + d);
    }
    keyed[c] = {key, c};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> new_node(nv, -1), new_cell(nc);
  file_node.assign(nv, -1);
  file_cell.resize(nc);
  std::vector<int> offsets(nc + 1, 0), nodes(serial.cell_nodes.size());
  std::vector<std::size_t> cell_tags(nc);
  int next = 0;
  for (int i = 0; i < nc; ++i) {
    const int c = keyed[i].second;
    new_cell[c] = i;
    file_cell[i] = c;
    cell_tags[i] = serial.cell_tags[c];
    offsets[i + 1] = offsets[i] + serial.CellSize(c);
    for (int k = 0; k < serial.CellSize(c); ++k) {
      int &v = new_node[serial.cell_nodes[serial.cell_offsets[c] + k]];
      if (v < 0) file_node[next] = serial.cell_nodes[serial.cell_offsets[c] + k], v = next++;
      nodes[offsets[i] + k] = v;
    }
  }
  for (int v = 0; v < nv; ++v) // nodes used by no cell (the reader keeps none; kept in file order all the same)
    if (new_node[v] < 0) file_node[next] = v, new_node[v] = next++;
  std::vector<double> coords(serial.coords.size());
  std::vector<std::size_t> node_tags(nv);
  for (int v = 0; v < nv; ++v) {
    std::copy_n(&serial.coords[file_node[v] * dim], dim, &coords[v * dim]);
    node_tags[v] = serial.node_tags[file_node[v]];
  }
  serial.coords = std::move(coords);
  serial.node_tags = std::move(node_tags);
  serial.cell_offsets = std::move(offsets);
  serial.cell_nodes = std::move(nodes);
  serial.cell_tags = std::move(cell_tags);
  for (auto &g : serial.groups) {
    for (int &v : g.nodes) v = new_node[v];
    std::sort(g.nodes.begin(), g.nodes.end());
    for (int &v : g.edges) v = new_node[v];
    for (int &v : g.face_nodes) v = new_node[v];
    for (int &c : g.cells) c = new_cell[c];
    std::sort(g.cells.begin(), g.cells.end());
  }
}

/// The file's tags in file order from those of a renumbered mesh (file: new index -> index in the file).
std::vector<std::size_t> InFileOrder(const std::vector<std::size_t> &tags, const std::vector<PetscInt> &file) {
  std::vector<std::size_t> out(tags.size());
  for (std::size_t i = 0; i < tags.size(); ++i) out[file[i]] = tags[i];
  return out;
}

} // namespace

/// Bounds of -mesh_size_factor: 1e-3 already multiplies the element count of a .geo by a million.
constexpr double MESH_SIZE_FACTOR_MIN = 1e-3, MESH_SIZE_FACTOR_MAX = 1e3;

PetscErrorCode ReadMeshOptions(MPI_Comm comm, const std::string &default_file, MeshOptions &opts) {
  PetscFunctionBeginUser;
  opts.file = default_file;
  PetscBool size_factor_set = PETSC_FALSE, max_cells_set = PETSC_FALSE;
  PetscOptionsBegin(comm, nullptr, "Mesh options", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsString(PetscOptionsObject, "-mesh_file",
                          "gmsh mesh (.msh 2.2/4.1), geometry (.geo, meshed by "
                          "gmsh in a child process of rank 0) or a mesh written by -mesh_save (.h5, read in parallel)",
                          "a .msh, .geo or .h5 path", opts.file));
  PetscCall(OptionsReal(PetscOptionsObject, "-mesh_size_factor", "Mesh size factor applied when meshing a .geo file",
                        {MESH_SIZE_FACTOR_MIN, MESH_SIZE_FACTOR_MAX}, opts.size_factor, &size_factor_set));
  opts.max_cells = DefaultMaxCells();
  PetscCall(OptionsReal(PetscOptionsObject, "-mesh_max_cells", "Refuse a .geo whose mesh is estimated to have more "
                        "cells (default: physical memory / 3.2 kB per cell)", RealRange::Whole(1, 1e12), opts.max_cells,
                        &max_cells_set));
  PetscBool partitioner_set = PETSC_FALSE;
  PetscCall(OptionsString(PetscOptionsObject, "-mesh_partitioner", "Partitioner: metis, ptscotch or simple (a .h5 "
                          "-mesh_file: ptscotch, in parallel)", "metis, ptscotch or simple", opts.partitioner,
                          &partitioner_set));
  opts.partitioner_set = partitioner_set;
  opts.save.clear();
  PetscCall(OptionsString(PetscOptionsObject, "-mesh_save", "Write the distributed mesh to this .h5 file (PETSc's "
                          "DMPlex HDF5 format), to be read by -mesh_file on any number of ranks", "a .h5 path",
                          opts.save));
  PetscOptionsEnd();
  PetscCheck(!opts.file.empty(), comm, PETSC_ERR_USER_INPUT,
             "-mesh_file is empty; expected a .msh, .geo or .h5 path");
  // Both only steer the meshing of a .geo (the reader decides by the same suffix): with a .msh they would be ignored.
  const bool geo = EndsWith(opts.file, ".geo");
  for (const auto &[set, name, value] : {std::make_tuple(size_factor_set, "-mesh_size_factor", opts.size_factor),
                                         std::make_tuple(max_cells_set, "-mesh_max_cells", opts.max_cells)})
    PetscCheck(geo || !set, comm, PETSC_ERR_USER_INPUT,
               "%s %s applies to meshing a .geo file only; -mesh_file '%s' is a mesh (expected a .geo -mesh_file, or "
               "no %s)", name, FormatNumber(value).c_str(), opts.file.c_str(), name);
  PetscCall(PathCandidatesFor("-mesh_file", opts.file, opts.file_candidates));
  PetscCheck(opts.partitioner == "metis" || opts.partitioner == "ptscotch" || opts.partitioner == "simple", comm,
             PETSC_ERR_USER_INPUT, "-mesh_partitioner '%s' is unknown; expected metis, ptscotch or simple",
             opts.partitioner.c_str());
  PetscCheck(!(EndsWith(opts.file, ".h5") && opts.partitioner_set && opts.partitioner == "metis"), comm,
             PETSC_ERR_USER_INPUT, "-mesh_partitioner metis partitions the whole mesh on rank 0, which a .h5 "
             "-mesh_file ('%s') never holds; expected ptscotch or simple", opts.file.c_str());
  PetscCheck(opts.save.empty() || (EndsWith(opts.save, ".h5") && opts.save.size() > 3), comm, PETSC_ERR_USER_INPUT,
             "-mesh_save '%s' is no .h5 file name; expected a path ending in .h5", opts.save.c_str());
  PetscFunctionReturn(0);
}

std::string FindMeshFile(const MeshOptions &opts, std::string &absolute_path, std::string &error) {
  std::string looked;
  // Options not read by ReadMeshOptions (unit tests) name the file as it is.
  const PathCandidates as_given{{opts.file}, {"relative to the current directory"}};
  const std::string path = FirstExisting(opts.file_candidates.paths.empty() ? as_given : opts.file_candidates, looked);
  if (path.empty()) {
    error = "cannot open mesh file '" + opts.file + "': not found at " + looked + "; expected a readable " +
            (EndsWith(opts.file, ".h5") ? "mesh written by -mesh_save" : "gmsh .msh or .geo file");
    return "";
  }
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  absolute_path = ec ? path : absolute.lexically_normal().string();
  return path;
}

PetscErrorCode Mesh::Create(MPI_Comm comm, const MeshOptions &opts) {
  PetscFunctionBeginUser;
  comm_ = comm;
  // An unwritable -mesh_save is reported before a large mesh is read.
  if (!opts.save.empty()) PetscCall(CheckMeshSavePath(comm, opts.save));
  if (EndsWith(opts.file, ".h5")) PetscCall(LoadH5(opts));
  else PetscCall(ReadGmshMesh(opts));
  if (!opts.save.empty()) PetscCall(SaveH5(opts.save));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::ReadGmshMesh(const MeshOptions &opts) {
  PetscMPIInt rank;
  MPI_Comm comm = comm_;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string error;
  ProgressBegin(("reading " + opts.file + (EndsWith(opts.file, ".geo") ? " (meshing with gmsh)" : "")).c_str());
  if (rank == 0) {
    const std::string path = FindMeshFile(opts, path_, error);
    if (!path.empty()) error = ReadGmsh(path, opts.size_factor, serial_, opts.max_cells);
  }
  ProgressEnd();
  PetscCall(RaiseFromRoot(comm, error));
  dim_ = serial_.dim;
  PetscCallMPI(MPI_Bcast(&dim_, 1, MPI_INT, 0, comm));
  PetscCall(Broadcast(comm, 0, path_));
  PetscCall(BroadcastGroups(comm, serial_, group_names_, group_dims_));
  std::vector<PetscInt> file_node, file_cell;
  if (rank == 0) LocalityOrder(serial_, file_node, file_cell);
  DMH dm;
  PetscCall(BuildSerialDM(opts.file, dm.out()));
  // The file's indices travel with the points (Distribute) and name the cells' vertices (BuildLocalArrays).
  for (std::size_t v = 0; v < file_node.size(); ++v) vertex_orig_[v] = file_node[v];
  for (std::size_t c = 0; c < file_cell.size(); ++c) cell_orig_[c] = file_cell[c];
  for (PetscInt &v : cell_vertices_) v = file_node[v];
  ProgressBegin("partition and distribution");
  PetscCall(Partition(dm, opts.partitioner));
  PetscCall(Distribute(dm));
  ProgressEnd();
  PetscCall(KeepDistributed(dm));
  // The file's tags in blocks of file indices (written with the output); nothing needs the serial mesh any more.
  if (rank == 0) {
    serial_.node_tags = InFileOrder(serial_.node_tags, file_node);
    serial_.cell_tags = InFileOrder(serial_.cell_tags, file_cell);
  }
  PetscCall(ScatterBlocks(comm, serial_.node_tags, node_tags_));
  PetscCall(ScatterBlocks(comm, serial_.cell_tags, cell_tags_));
  serial_ = SerialMesh{};
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BuildSerialDM(const std::string &file, DM *out) {
  PetscFunctionBeginUser;
  const PetscInt nc = serial_.NumCells(), nv = serial_.NumNodes();
  // Cells and vertices only: nothing uses the edges (and faces) of an interpolated DMPlex, whose construction took
  // 5 s of the mesh stage at 1M dofs. The faces the program needs (the boundary and the groups of dimension dim-1)
  // come from FaceTable and travel with their cells (Distribute).
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
    if (dim_ == 3) PetscCall(DMPlexInvertCell(CellPolytope3D(n), cone.data()));
    PetscCall(DMPlexSetCone(dm, c, cone.data()));
  }
  PetscCall(DMPlexSymmetrize(dm));
  PetscCall(DMPlexStratify(dm));
  PetscCall(DMPlexComputeCellTypes(dm));
  PetscCall(DMPlexBuildCoordinatesFromCellList(dm, dim_, serial_.coords.data()));
  vstart_ = nc;
  cstart_ = 0;

  // Faces: the boundary, the groups of dimension dim-1 (each element matched to a cell face), folded cells.
  std::vector<std::vector<PetscInt>> label_points(group_names_.size() + 1);
  cell_face_offsets_.assign(1, 0);
  cell_face_codes_.clear();
  PetscCall(RunOnRoot(comm_, [&] { return SerialFaces(file, label_points); }));
  PetscCall(SetGroupLabels(dm, label_points));

  // The file's node and cell order travels with the points as a field: 1 dof on every cell and vertex.
  vertex_orig_.resize(nv);
  cell_orig_.resize(nc);
  for (PetscInt v = 0; v < nv; ++v) vertex_orig_[v] = v;
  for (PetscInt c = 0; c < nc; ++c) cell_orig_[c] = c;
  cell_offsets_.assign(serial_.cell_offsets.begin(), serial_.cell_offsets.end());
  cell_vertices_.assign(serial_.cell_nodes.begin(), serial_.cell_nodes.end());
  PetscInt ng[2] = {nv, nc};
  PetscCallMPI(MPI_Bcast(ng, 2, MPIU_INT, 0, comm_));
  num_global_nodes_ = ng[0];
  num_global_cells_ = ng[1];
  *out = dm.get();
  PetscCall(PetscObjectReference((PetscObject)*out));
  PetscFunctionReturn(0);
}

std::string Mesh::GroupLabelName(std::size_t g) const {
  return g < group_names_.size() ? LABEL_PREFIX + group_names_[g] : std::string(BOUNDARY_LABEL);
}

PetscErrorCode Mesh::SetGroupLabels(DM dm, std::vector<std::vector<PetscInt>> &label_points) const {
  PetscFunctionBeginUser;
  for (std::size_t g = 0; g < label_points.size(); ++g) {
    const std::string name = GroupLabelName(g);
    PetscCall(DMCreateLabel(dm, name.c_str()));
    auto &pts = label_points[g];
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    if (pts.empty()) continue;
    DMLabel label;
    ISH is;
    PetscCall(DMGetLabel(dm, name.c_str(), &label));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)pts.size(), pts.data(), PETSC_COPY_VALUES, is.out()));
    PetscCall(DMLabelSetStratumIS(label, 1, is));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::PointLabels(std::vector<PetscInt> &offsets, std::vector<int> &labels) const {
  PetscInt pstart, pend;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  offsets.assign(pend - pstart + 1, 0);
  // Two passes over the labels' points: the counts, then the labels in the points' rows (in label order).
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<PetscInt> next;
    if (pass == 1) {
      for (PetscInt p = 0; p < pend - pstart; ++p)
        offsets[p + 1] += offsets[p];
      labels.resize(offsets.back());
      next.assign(offsets.begin(), offsets.end() - 1);
    }
    for (std::size_t g = 0; g <= group_names_.size(); ++g) {
      DMLabel label;
      ISH is;
      PetscCall(DMGetLabel(dm_, GroupLabelName(g).c_str(), &label));
      if (label) PetscCall(DMLabelGetStratumIS(label, 1, is.out()));
      if (!is) continue;
      PetscInt n;
      const PetscInt *pts;
      PetscCall(ISGetLocalSize(is, &n));
      PetscCall(ISGetIndices(is, &pts));
      for (PetscInt i = 0; i < n; ++i) {
        if (pass == 0)
          offsets[pts[i] - pstart + 1]++;
        else
          labels[next[pts[i] - pstart]++] = (int)g;
      }
      PetscCall(ISRestoreIndices(is, &pts));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::SerialFaces(const std::string &file, std::vector<std::vector<PetscInt>> &label_points) {
  const PetscInt nc = serial_.NumCells(), nlabels = (PetscInt)group_names_.size() + 1;
  std::vector<std::pair<int, PetscInt>> tags; // (cell, code)
  std::string error;
  PetscFunctionBeginUser;
  PetscCall(FaceTable(tags, error));
  PetscCheck(error.empty(), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "mesh '%s': %s", file.c_str(), error.c_str());
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  cell_face_offsets_.assign(nc + 1, 0);
  for (const auto &t : tags) cell_face_offsets_[t.first + 1]++;
  for (PetscInt c = 0; c < nc; ++c) cell_face_offsets_[c + 1] += cell_face_offsets_[c];
  for (const auto &t : tags) cell_face_codes_.push_back(t.second);
  // Vertex labels: the nodes of each group (the groups of cells are found through their cells, LabelVertices), and
  // the vertices of the boundary faces.
  for (std::size_t g = 0; g < serial_.groups.size(); ++g) {
    for (int v : serial_.groups[g].nodes) label_points[g].push_back(vstart_ + v);
    for (int c : serial_.groups[g].cells) label_points[g].push_back(cstart_ + c);
  }
  for (const auto &t : tags)
    if (t.second % nlabels == nlabels - 1) {
      const CellFaceTable &cf = CellFaces(dim_, serial_.CellSize(t.first));
      const int lf = (int)(t.second / nlabels);
      for (int k = 0; k < cf.size[lf]; ++k)
        label_points.back().push_back(vstart_ + serial_.cell_nodes[serial_.cell_offsets[t.first] + cf.v[lf][k]]);
    }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::FaceTable(std::vector<std::pair<int, PetscInt>> &tags, std::string &error) const {
  PetscFunctionBeginUser;
  const int nc = serial_.NumCells();
  const PetscInt nlabels = (PetscInt)group_names_.size() + 1;
  // Every face of every cell, sorted by its key: a counting sort on the smallest vertex, then each bucket (the few
  // faces around one vertex) sorted on its own.
  const auto each_face = [&](auto &&visit) {
    int nodes[4];
    for (int c = 0; c < nc; ++c) {
      const int *cv = &serial_.cell_nodes[serial_.cell_offsets[c]];
      const CellFaceTable &cf = CellFaces(dim_, serial_.CellSize(c));
      for (int f = 0; f < cf.count; ++f) {
        for (int k = 0; k < cf.size[f]; ++k) nodes[k] = cv[cf.v[f][k]];
        visit(FaceEntry{FaceKey(nodes, cf.size[f]), c, f});
      }
    }
  };
  std::vector<std::size_t> bucket(serial_.NumNodes() + 1, 0);
  each_face([&](const FaceEntry &e) { bucket[e.key[0] + 1]++; });
  for (int v = 0; v < serial_.NumNodes(); ++v) bucket[v + 1] += bucket[v];
  std::vector<FaceEntry> faces(bucket.back());
  {
    std::vector<std::size_t> next(bucket.begin(), bucket.end() - 1);
    each_face([&](const FaceEntry &e) { faces[next[e.key[0]]++] = e; });
  }
  for (int v = 0; v < serial_.NumNodes(); ++v) std::sort(faces.begin() + bucket[v], faces.begin() + bucket[v + 1]);
  // A face of one cell is on the boundary; a face of two must have them on either side (FoldedCells).
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) tags.emplace_back(faces[i].cell, faces[i].local * nlabels + nlabels - 1);
    else if (j == i + 2 && error.empty()) error = FoldedCells(serial_, faces[i], faces[i + 1]);
    i = j;
  }
  // Each element of a group of dimension dim-1 is a face of a cell (the first of the cells it bounds).
  for (std::size_t g = 0; g < serial_.groups.size() && error.empty(); ++g) {
    const PhysicalGroup &group = serial_.groups[g];
    if (group.dim != dim_ - 1) continue;
    const bool lines = dim_ == 2;
    const std::size_t count = lines ? group.edges.size() / 2 : group.face_offsets.size() - 1;
    for (std::size_t e = 0; e < count; ++e) {
      const int n = lines ? 2 : group.face_offsets[e + 1] - group.face_offsets[e];
      const int *en = lines ? &group.edges[2 * e] : &group.face_nodes[group.face_offsets[e]];
      const FaceEntry probe{FaceKey(en, n), -1, -1};
      const auto it = std::lower_bound(faces.begin(), faces.end(), probe);
      if (it == faces.end() || it->key != probe.key) {
        error = lines ? "a line element of physical curve '" + group.name +
                            "' is not an edge of any cell; expected the lines of a physical curve to be cell edges"
                      : "a surface element of physical surface '" + group.name +
                            "' is not a face of any cell; expected the triangles and quadrilaterals of a physical "
                            "surface to be cell faces";
        break;
      }
      tags.emplace_back(it->cell, it->local * nlabels + (PetscInt)g);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::Partition(DM dm, const std::string &partitioner) {
  PetscMPIInt size;
  PetscPartitioner part;
  PetscFunctionBeginUser;
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
  PetscCall(RunOnRoot(comm_, [&] { return MetisPartition(sizes, points); }));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes.data(), points.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::MetisPartition(std::vector<PetscInt> &sizes, std::vector<PetscInt> &points) const {
  PetscFunctionBeginUser;
  // Cells are neighbours when they share a face: 2 nodes in 2D, 3 for a tetrahedron, 4 for a hexahedron (3 when
  // tetrahedra or pyramids are present, so that a mixed mesh connects through its triangular faces).
  bool triangles = false;
  for (int c = 0; c < serial_.NumCells(); ++c) triangles = triangles || serial_.CellSize(c) < 8;
  idx_t ne = serial_.NumCells(), nn = serial_.NumNodes(), nparts = (idx_t)sizes.size(), objval = 0;
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
  std::vector<PetscInt> start(nparts + 1, 0);
  for (idx_t p = 0; p < nparts; ++p) start[p + 1] = start[p] + sizes[p];
  points.resize(ne);
  for (idx_t c = 0; c < ne; ++c) points[start[epart[c]]++] = c;
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::PackPointData(DM dm, SectionH &s, VecH &d) const {
  PetscInt pstart, pend, n;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pstart, &pend));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), s.out())); // collective views need dm's comm
  PetscCall(PetscSectionSetChart(s, pstart, pend));
  const PetscInt nv = (PetscInt)vertex_orig_.size(), nc = (PetscInt)cell_orig_.size();
  for (PetscInt c = 0; c < nc; ++c)
    PetscCall(PetscSectionSetDof(s, cstart_ + c, 2 + cell_offsets_[c + 1] - cell_offsets_[c] +
                                                     cell_face_offsets_[c + 1] - cell_face_offsets_[c]));
  for (PetscInt v = 0; v < nv; ++v) PetscCall(PetscSectionSetDof(s, vstart_ + v, 1));
  PetscCall(PetscSectionSetUp(s));
  PetscCall(PetscSectionGetStorageSize(s, &n));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, d.out()));
  PetscCall(PetscObjectSetName((PetscObject)d.get(), "point_data"));
  PetscScalar *a;
  PetscCall(VecGetArray(d, &a));
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, cstart_ + c, &off));
    a[off++] = cell_orig_[c];
    a[off++] = cell_offsets_[c + 1] - cell_offsets_[c];
    for (PetscInt k = cell_offsets_[c]; k < cell_offsets_[c + 1]; ++k)
      a[off++] = cell_vertices_[k];
    for (PetscInt k = cell_face_offsets_[c]; k < cell_face_offsets_[c + 1]; ++k) a[off++] = cell_face_codes_[k];
  }
  for (PetscInt v = 0; v < nv; ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, vstart_ + v, &off));
    a[off] = vertex_orig_[v];
  }
  PetscCall(VecRestoreArray(d, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::UnpackPointData(DM dm, PetscSection sec, Vec data) {
  PetscInt end;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vstart_, &end));
  vertex_orig_.assign(end - vstart_, -1);
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cstart_, &end));
  cell_orig_.assign(end - cstart_, -1);
  const PetscScalar *b;
  PetscCall(VecGetArrayRead(data, &b));
  for (PetscInt v = 0; v < (PetscInt)vertex_orig_.size(); ++v) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(sec, vstart_ + v, &off));
    vertex_orig_[v] = (PetscInt)PetscRealPart(b[off]);
  }
  cell_offsets_.assign(1, 0);
  cell_vertices_.clear();
  cell_face_offsets_.assign(1, 0);
  cell_face_codes_.clear();
  for (PetscInt c = 0; c < (PetscInt)cell_orig_.size(); ++c) {
    PetscInt off, ndof;
    PetscCall(PetscSectionGetOffset(sec, cstart_ + c, &off));
    PetscCall(PetscSectionGetDof(sec, cstart_ + c, &ndof));
    PetscCheck(ndof >= 2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %" PetscInt_FMT " carries no point data", c);
    cell_orig_[c] = (PetscInt)PetscRealPart(b[off]);
    const PetscInt nvert = (PetscInt)PetscRealPart(b[off + 1]);
    for (PetscInt k = 2; k < ndof; ++k)
      (k < 2 + nvert ? cell_vertices_ : cell_face_codes_).push_back((PetscInt)PetscRealPart(b[off + k]));
    cell_offsets_.push_back((PetscInt)cell_vertices_.size());
    cell_face_offsets_.push_back((PetscInt)cell_face_codes_.size());
  }
  PetscCall(VecRestoreArrayRead(data, &b));
  PetscFunctionReturn(0);
}

void Mesh::SingleThreadScotch() {
  // Debian's Scotch 7 partitions with threads, and its partition differed from run to run: the 290k-dof octant read
  // from its .h5 on 2 ranks: the ranks sent 217121 and 66384 of their cells to rank 0 in one run, 113215 and 168170
  // in another, and the runs took 7 13 10 18 or 7 12 8 8 14 CG iterations (the same state). One thread (Scotch's
  // SCOTCH_PTHREAD_NUMBER, read when it partitions; a value the user set stays) gave the same partition in every run
  // measured; seeding its random generator (SCOTCH_randomSeed, SCOTCH_randomReset) did not.
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 0);
}

PetscErrorCode Mesh::Distribute(DMH &dm) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  if (size == 1) PetscFunctionReturn(0);
  // The point data (PackPointData) travels with the points.
  SectionH sec;
  VecH orig;
  PetscCall(PackPointData(dm, sec, orig));
  SFH migration;
  DMH dist;
  SingleThreadScotch(); // -mesh_partitioner ptscotch partitions here
  PetscCall(DMPlexDistribute(dm, 0, migration.out(), dist.out()));
  if (!dist) PetscFunctionReturn(0);
  SectionH new_sec;
  VecH new_orig;
  PetscCall(PetscSectionCreate(PETSC_COMM_SELF, new_sec.out()));
  PetscCall(VecCreate(PETSC_COMM_SELF, new_orig.out()));
  PetscCall(DMPlexDistributeField(dm, migration, sec, orig, new_sec, new_orig));
  PetscCall(UnpackPointData(dist, new_sec, new_orig));
  dm = std::move(dist);
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::KeepDistributed(DMH &dm) {
  PetscFunctionBeginUser;
  dm_ = std::move(dm);
  PetscCall(BuildLocalArrays());
  PetscCall(BuildVertexSF());
  PetscCall(CacheLabelVertices());
  PetscCall(BuildCellGroups());
  PetscCall(BuildBodies());
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BuildCellGroups() {
  const PetscInt nc = NumLocalCells();
  PetscFunctionBeginUser;
  // The cell labels travel with the cells through distribution and the .h5 file alike, so both paths agree; they are
  // copied here because the DM is released after the set-up (ReleaseDM).
  std::vector<PetscInt> offsets;
  std::vector<int> labels;
  PetscInt pstart, pend;
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  PetscCall(PointLabels(offsets, labels));
  std::vector<std::vector<int>> groups(nc);
  for (PetscInt c = 0; c < nc; ++c)
    for (PetscInt k = offsets[cstart_ + c - pstart]; k < offsets[cstart_ + c - pstart + 1]; ++k)
      if (labels[k] < (int)group_names_.size() && group_dims_[labels[k]] == dim_) groups[c].push_back(labels[k]);
  cell_group_offsets_.assign(1, 0);
  cell_groups_.clear();
  for (const auto &cg : groups) {
    cell_groups_.insert(cell_groups_.end(), cg.begin(), cg.end());
    cell_group_offsets_.push_back((int)cell_groups_.size());
  }
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

  std::vector<char> point_leaf(pend - pstart, 0);
  PetscSF sf;
  PetscInt nroots, nleaves;
  const PetscInt *ilocal;
  PetscCall(DMGetPointSF(dm_, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, nullptr));
  if (nroots >= 0)
    for (PetscInt i = 0; i < nleaves; ++i) point_leaf[(ilocal ? ilocal[i] : i) - pstart] = 1;
  vertex_owned_.resize(nv);
  for (PetscInt v = 0; v < nv; ++v) vertex_owned_[v] = !point_leaf[vstart_ + v - pstart];

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
  std::vector<PetscInt> local_of(num_global_nodes_, -1);
  for (PetscInt v = 0; v < nv; ++v) local_of[vertex_orig_[v]] = v;
  for (auto &v : cell_vertices_) {
    v = local_of[v];
    PetscCheck(v >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a cell's vertex is not on its rank");
  }

  // The faces of each label, from the faces the cells carry, oriented outwards by CellFaces.
  const PetscInt nlabels = (PetscInt)group_names_.size() + 1;
  label_faces_.assign(nlabels, {});
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt n;
    const PetscInt *cv = CellVertices(c, n);
    const CellFaceTable &cf = CellFaces(dim_, (int)n);
    for (PetscInt k = cell_face_offsets_[c]; k < cell_face_offsets_[c + 1]; ++k) {
      const PetscInt code = cell_face_codes_[k], lf = code / nlabels;
      Face f;
      f.n = cf.size[lf];
      f.cell = c;
      for (int j = 0; j < f.n; ++j) f.v[j] = cv[cf.v[lf][j]];
      label_faces_[code % nlabels].push_back(f);
    }
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

PetscErrorCode Mesh::CheckGroup(const std::string &name, int required_dim, const std::string &input) const {
  const std::string where = input.empty() ? "" : input + ": ";
  PetscFunctionBeginUser;
  const auto it = std::find(group_names_.begin(), group_names_.end(), name);
  PetscCheck(it != group_names_.end(), comm_, PETSC_ERR_USER_INPUT,
             "%sphysical group '%s' is not in the mesh; %s", where.c_str(), name.c_str(),
             group_names_.empty() ? "the mesh has no physical groups"
                                  : ("expected one of the mesh's groups: " + Join(group_names_, ", ")).c_str());
  const int dim = group_dims_[it - group_names_.begin()];
  PetscCheck(required_dim < 0 || dim == required_dim, comm_, PETSC_ERR_USER_INPUT,
             "%sphysical group '%s' has dimension %d; expected a physical %s (dimension %d)", where.c_str(),
             name.c_str(), dim, required_dim == 1 ? "curve" : "surface", required_dim);
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::GroupVertices(const std::string &name, std::vector<PetscInt> &vertices,
                                   const std::string &input) const {
  PetscFunctionBeginUser;
  PetscCall(CheckGroup(name, -1, input));
  vertices = label_vertices_[std::find(group_names_.begin(), group_names_.end(), name) - group_names_.begin()];
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BoundaryVertices(std::vector<PetscInt> &vertices) const {
  PetscFunctionBeginUser;
  vertices = label_vertices_.back();
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::GroupFaces(const std::string &name, std::vector<Face> &faces, const std::string &input) const {
  PetscFunctionBeginUser;
  PetscCall(CheckGroup(name, dim_ - 1, input));
  faces = label_faces_[std::find(group_names_.begin(), group_names_.end(), name) - group_names_.begin()];
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BoundaryFaces(std::vector<Face> &faces) const {
  PetscFunctionBeginUser;
  faces = label_faces_.back();
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
  const PetscInt nv = NumLocalVertices();
  PetscFunctionBeginUser;
  std::vector<double> root(nv, 0.0), leaf(nv, 0.0);
  for (PetscInt v = 0; v < nv; ++v) (Owned(v) ? root : leaf)[v] = per_vertex[v];
  PetscCall(PetscSFReduceBegin(vertex_sf_, MPI_DOUBLE, leaf.data(), root.data(), MPI_SUM));
  PetscCall(PetscSFReduceEnd(vertex_sf_, MPI_DOUBLE, leaf.data(), root.data(), MPI_SUM));
  PetscCall(PetscSFBcastBegin(vertex_sf_, MPI_DOUBLE, root.data(), leaf.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(vertex_sf_, MPI_DOUBLE, root.data(), leaf.data(), MPI_REPLACE));
  for (PetscInt v = 0; v < nv; ++v) per_vertex[v] = (Owned(v) ? root : leaf)[v];
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::BuildVertexSF() {
  const PetscInt nv = NumLocalVertices();
  PetscInt pstart, pend, nroots, nleaves;
  const PetscInt *ilocal;
  const PetscSFNode *iremote;
  PetscSF sf;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  PetscCall(DMGetPointSF(dm_, &sf));
  PetscCall(PetscSFGetGraph(sf, &nroots, &nleaves, &ilocal, &iremote));
  std::vector<PetscInt> leaves;
  std::vector<PetscSFNode> remotes;
  if (nroots >= 0) {
    // Each point's vertex index on its own rank (-1: not a vertex), carried to the ranks that have it as a leaf.
    std::vector<PetscInt> own(pend - pstart, -1), remote(pend - pstart, -1);
    for (PetscInt v = 0; v < nv; ++v) own[vstart_ + v - pstart] = v;
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, own.data(), remote.data(), MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, own.data(), remote.data(), MPI_REPLACE));
    for (PetscInt i = 0; i < nleaves; ++i) {
      const PetscInt p = ilocal ? ilocal[i] : i;
      if (p < vstart_ || p >= vstart_ + nv) continue;
      PetscCheck(remote[p - pstart] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a ghost vertex is no vertex on its owner");
      leaves.push_back(p - vstart_);
      remotes.push_back({iremote[i].rank, remote[p - pstart]});
    }
  }
  PetscCall(PetscSFCreate(comm_, vertex_sf_.out()));
  PetscCall(PetscSFSetGraph(vertex_sf_, nv, (PetscInt)leaves.size(), leaves.data(), PETSC_COPY_VALUES,
                            remotes.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(vertex_sf_));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::CacheLabelVertices() {
  PetscFunctionBeginUser;
  label_vertices_.assign(group_names_.size() + 1, {});
  for (std::size_t g = 0; g < group_names_.size(); ++g)
    PetscCall(LabelVertices(LABEL_PREFIX + group_names_[g], group_dims_[g] == dim_, label_vertices_[g]));
  PetscCall(LabelVertices(BOUNDARY_LABEL, false, label_vertices_.back()));
  PetscFunctionReturn(0);
}

void Mesh::FaceNormal(const Face &f, double *normal) const {
  FaceVectorArea(dim_, f, [this](PetscInt v) { return X(v); }, normal);
}

} // namespace signorini
