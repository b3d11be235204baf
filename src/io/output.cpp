// HDF5/XDMF, CSV and JSON output through a staging directory: every rank writes its block of the file's order.
#include "signorini/io/output.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/options/readers.hpp"
#include "signorini/io/ordered_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace signorini {

namespace fs = std::filesystem;

PetscErrorCode ReadOutputOptions(MPI_Comm comm, OutputOptions &opts) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Output", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsString(PetscOptionsObject, "-output_dir", "Directory for solution.h5/.xdmf, an .xdmf per block, "
                          "nodes.csv and summary.json (default: no files)", "a directory path", opts.dir));
  PetscOptionsEnd();
  // A directory that cannot be made is reported now, not after the mesh and the set-up (it is opened after them).
  PetscMPIInt rank;
  PetscBool help;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscOptionsHasHelp(nullptr, &help));
  std::string error;
  if (rank == 0 && !opts.dir.empty() && !help) error = OutputDirectoryProblem(opts.dir);
  PetscCall(RaiseFromRoot(comm, error));
  PetscFunctionReturn(0);
}

namespace {

PetscLogEvent EV_HDF5 = 0, EV_XDMF = 0, EV_CSV = 0;
PetscErrorCode RegisterEvents() {
  PetscClassId id;
  PetscFunctionBeginUser;
  if (EV_HDF5) PetscFunctionReturn(0);
  PetscCall(PetscClassIdRegister("signorini output", &id));
  PetscCall(PetscLogEventRegister("SigWriteHDF5", id, &EV_HDF5));
  PetscCall(PetscLogEventRegister("SigWriteXDMF", id, &EV_XDMF));
  PetscCall(PetscLogEventRegister("SigWriteCSV", id, &EV_CSV));
  PetscFunctionReturn(0);
}

std::string HdfError(const Hdf5File &file) {
  return "cannot write HDF5 file '" + file.Path() + "'" + (file.Reason().empty() ? "" : " (" + file.Reason() + ")") +
         "; expected a writable output directory with room for the file";
}

/// XDMF name and mixed-topology id of a cell with n vertices in dimension dim. XDMF's pyramid (VTK's) has gmsh's
/// vertex order: the base, then the apex.
const char *XdmfCellName(int dim, int n) {
  if (dim == 2) return n == 3 ? "Triangle" : "Quadrilateral";
  return n == 4 ? "Tetrahedron" : n == 5 ? "Pyramid" : "Hexahedron";
}
int XdmfCellId(int dim, int n) {
  // XDMF: 4 triangle, 5 quadrilateral, 6 tetrahedron, 7 pyramid, 9 hexahedron.
  if (dim == 2) return n == 3 ? 4 : 5;
  return n == 4 ? 6 : n == 5 ? 7 : 9;
}

/// Appends v as printf's "%.17g" writes it (std::to_chars is specified so), "nan" for every NaN.
void AppendNumber(std::string &out, double v) {
  char buf[32];
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  const auto end = std::to_chars(buf, buf + sizeof(buf), v, std::chars_format::general, 17).ptr;
  out.append(buf, end);
}

} // namespace

PetscErrorCode OutputWriter::Open(const Mesh &mesh, const OutputOptions &opts) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  mesh_ = &mesh;
  opts_ = opts;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCall(RegisterEvents());
  PetscCallMPI(MPI_Comm_rank(mesh.Comm(), &rank));
  std::string error;
  if (rank == 0) {
    int made;
    error = PrepareOutputDirectory(opts_.dir, made);
    // From here on, a failed run removes what it wrote (main, the error handler), and the directories it made.
    if (error.empty()) RemoveOnFailure(Staging(), made);
  }
  PetscCall(RaiseFromRoot(mesh.Comm(), error));
  PetscCall(BuildRows());
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::BuildRows() {
  const Mesh &mesh = *mesh_;
  MPI_Comm comm = mesh.Comm();
  PetscFunctionBeginUser;
  // Each vertex is written by the rank that owns it, each cell by its rank, at their places in the file's order.
  std::vector<PetscInt> local, file;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v)
    if (mesh.Owned(v)) local.push_back(v), file.push_back(mesh.VertexOriginal(v));
  PetscCall(node_rows_.Create(comm, mesh.NumGlobalNodes(), local, file));
  file.clear();
  PetscInt sizes[2] = {MAX_CELL_VERTICES, 0}, topology = 0;
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) {
    PetscInt n;
    (void)mesh.CellVertices(c, n);
    sizes[0] = std::min(sizes[0], n), sizes[1] = std::min(sizes[1], -n); // min and -max
    topology += n + 1;
    file.push_back(mesh.CellOriginal(c));
  }
  PetscCall(cell_rows_.Create(comm, mesh.NumGlobalCells(), {}, file));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sizes, 2, MPIU_INT, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(&topology, &mixed_topology_size_, 1, MPIU_INT, MPI_SUM, comm));
  cell_size_ = (int)sizes[0];
  uniform_ = sizes[0] == -sizes[1];
  PetscCheck((PetscInt)mesh.NodeTagsBlock().size() == node_rows_.Size() &&
                 (PetscInt)mesh.CellTagsBlock().size() == cell_rows_.Size(),
             PETSC_COMM_SELF, PETSC_ERR_PLIB, "the mesh's blocks of tags are not the output's blocks");
  PetscFunctionReturn(0);
}

void OutputWriter::SetObstacle(const Obstacle &obstacle, const Box &body) {
  obstacle_points_.clear();
  obstacle_cell_size_ = mesh_ && mesh_->Dim() == 3 ? 3 : 2;
  for (const auto &facet : obstacle.facets) {
    if (obstacle_cell_size_ == 3) {
      const auto corners = facet->Surface(body);
      obstacle_points_.insert(obstacle_points_.end(), corners.begin(), corners.end());
      continue;
    }
    const auto line = facet->Polyline();
    for (std::size_t k = 0; k + 1 < line.size(); ++k)
      obstacle_points_.insert(obstacle_points_.end(),
                              {{line[k][0], line[k][1], 0.0}, {line[k + 1][0], line[k + 1][1], 0.0}});
  }
}

PetscErrorCode OutputWriter::SetContactBoundary(const std::vector<char> &candidate) {
  std::vector<Face> faces;
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  MPI_Comm comm = mesh_->Comm();
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // The contact boundary: the boundary faces whose every vertex is a candidate, edges in 2D, triangles and
  // quadrilaterals in 3D; per face its vertex count, then its vertices (file order). It is small: rank 0 holds it.
  PetscCall(mesh_->BoundaryFaces(faces));
  std::vector<PetscInt> send;
  for (const auto &f : faces) {
    bool all = true;
    for (int a = 0; a < f.n; ++a) all = all && candidate[f.v[a]];
    if (!all) continue;
    send.push_back(f.n);
    for (int a = 0; a < f.n; ++a) send.push_back(mesh_->VertexOriginal(f.v[a]));
  }
  PetscMPIInt count = (PetscMPIInt)send.size();
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  std::vector<PetscInt> all;
  if (rank == 0) {
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    all.resize(displs[size - 1] + counts[size - 1]);
  }
  PetscCallMPI(MPI_Gatherv(send.data(), count, MPIU_INT, all.data(), counts.data(), displs.data(), MPIU_INT, 0, comm));
  // The faces in the order of their vertices' file indices, whichever ranks held them.
  std::vector<std::vector<PetscInt>> sorted;
  for (std::size_t k = 0; k < all.size(); k += all[k] + 1)
    sorted.emplace_back(all.begin() + k + 1, all.begin() + k + 1 + all[k]);
  std::sort(sorted.begin(), sorted.end());
  contact_nodes_.clear();
  contact_faces_.clear();
  contact_num_faces_ = (int)sorted.size();
  int size_seen = -1;
  bool uniform = true;
  for (const auto &face : sorted) {
    contact_nodes_.insert(contact_nodes_.end(), face.begin(), face.end());
    uniform = uniform && (size_seen < 0 || size_seen == (int)face.size());
    size_seen = (int)face.size();
  }
  std::sort(contact_nodes_.begin(), contact_nodes_.end());
  contact_nodes_.erase(std::unique(contact_nodes_.begin(), contact_nodes_.end()), contact_nodes_.end());
  // XDMF: a uniform topology, or a Mixed one with the cell type before each face's vertices.
  contact_face_size_ = uniform ? std::max(size_seen, 0) : 0;
  for (const auto &face : sorted) {
    if (!uniform) contact_faces_.push_back(XdmfCellId(2, (int)face.size()));
    for (PetscInt v : face)
      contact_faces_.push_back(std::lower_bound(contact_nodes_.begin(), contact_nodes_.end(), v) -
                               contact_nodes_.begin());
  }
  // Every rank takes part in writing the contact boundary's datasets (rank 0's rows): they need their shapes.
  PetscInt shape[4] = {(PetscInt)contact_nodes_.size(), (PetscInt)contact_faces_.size(), contact_face_size_,
                       contact_num_faces_};
  PetscCallMPI(MPI_Bcast(shape, 4, MPIU_INT, 0, comm));
  contact_num_nodes_ = shape[0], contact_topology_size_ = shape[1];
  contact_face_size_ = (int)shape[2], contact_num_faces_ = (int)shape[3];
  PetscCall(contact_rows_.Create(comm, mesh_->NumGlobalNodes(), {}, contact_nodes_));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteStep(PetscInt step, double t, const std::vector<Field> &fields) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  MPI_Comm comm = mesh_->Comm();
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscLogEventBegin(EV_HDF5, 0, 0, 0, 0));
  Hdf5File file;
  PetscCall(file.Open(comm, Staging() + "/solution.h5", steps_.empty()));
  if (steps_.empty()) PetscCall(WriteGeometry(file));
  char name[32];
  std::snprintf(name, sizeof(name), "/step_%06d", (int)step);
  const std::string group = name, boundary = group + "/contact_boundary";
  PetscCall(file.CreateGroup(group));
  if (contact_num_nodes_ > 0) PetscCall(file.CreateGroup(boundary));
  for (const auto &f : fields) {
    const FileRows &rows = f.on_cells ? cell_rows_ : node_rows_;
    std::vector<double> made, block, restricted;
    if (f.fill) PetscCall(f.fill(made));
    PetscCall(rows.ToBlocks(f.fill ? made : f.values, f.ncomp, block));
    made = std::vector<double>(); // freed before the write
    PetscCall(file.WriteRows(group + "/" + f.name, rows.Global(), f.ncomp, rows.Start(), block));
    if (!f.on_contact || contact_num_nodes_ == 0) continue;
    PetscCall(contact_rows_.FromBlocks(block, f.ncomp, restricted));
    PetscCall(file.WriteRows(boundary + "/" + f.name, contact_num_nodes_, f.ncomp, 0, restricted));
  }
  PetscCall(file.Close());
  // The message comes from the first rank where the write failed (Agree marks it), with HDF5's reason.
  PetscCall(CheckCollective(comm, !file.FailedHere(), HdfError(file)));
  PetscCall(PetscLogEventEnd(EV_HDF5, 0, 0, 0, 0));
  StepInfo info{step, t, {}};
  for (const auto &f : fields) info.layout.push_back({f.name, f.ncomp, f.on_cells, {}, f.on_contact});
  steps_.push_back(info);
  PetscCall(PetscLogEventBegin(EV_XDMF, 0, 0, 0, 0));
  PetscCall(WriteXdmf());
  PetscCall(PetscLogEventEnd(EV_XDMF, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::NodeBlocks(std::vector<double> &xyz, std::vector<long long> &tags) const {
  PetscFunctionBeginUser;
  std::vector<double> local(3 * mesh_->NumLocalVertices(), 0.0);
  for (PetscInt v = 0; v < mesh_->NumLocalVertices(); ++v)
    for (int d = 0; d < mesh_->Dim(); ++d) local[3 * v + d] = mesh_->X(v)[d];
  PetscCall(node_rows_.ToBlocks(local, 3, xyz));
  tags.assign(mesh_->NodeTagsBlock().begin(), mesh_->NodeTagsBlock().end());
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteTopology(Hdf5File &file) const {
  const Mesh &mesh = *mesh_;
  PetscFunctionBeginUser;
  // Rows of the cells' vertices in the file's node numbering; for a mixed mesh each row starts with the cell's XDMF
  // type and is padded with -1 to the largest cell, and the rows of the blocks are then joined end to end.
  const int width = uniform_ ? cell_size_ : MAX_CELL_VERTICES + 1;
  std::vector<long long> local(mesh.NumLocalCells() * width, -1), block;
  for (PetscInt c = 0; c < mesh.NumLocalCells(); ++c) {
    PetscInt n;
    const PetscInt *cv = mesh.CellVertices(c, n);
    long long *row = &local[c * width];
    if (!uniform_) *row++ = XdmfCellId(mesh.Dim(), (int)n);
    for (PetscInt k = 0; k < n; ++k) row[k] = mesh.VertexOriginal(cv[k]);
  }
  PetscCall(cell_rows_.ToBlocks(local, width, block));
  if (uniform_) {
    PetscCall(file.WriteRows("/mesh/topology", cell_rows_.Global(), width, cell_rows_.Start(), block));
    PetscFunctionReturn(0);
  }
  block.erase(std::remove(block.begin(), block.end(), -1LL), block.end());
  long long size = (long long)block.size(), offset = 0;
  PetscCallMPI(MPI_Exscan(&size, &offset, 1, MPI_LONG_LONG, MPI_SUM, mesh.Comm()));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(mesh.Comm(), &rank));
  if (rank == 0) offset = 0; // MPI_Exscan leaves rank 0's result undefined
  PetscCall(file.WriteRows("/mesh/topology", mixed_topology_size_, 1, offset, block));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteGeometry(Hdf5File &file) const {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  std::vector<double> xyz;
  std::vector<long long> node_tags;
  PetscCall(NodeBlocks(xyz, node_tags));
  const std::vector<long long> cell_tags(mesh_->CellTagsBlock().begin(), mesh_->CellTagsBlock().end());
  PetscCall(file.CreateGroup("/mesh"));
  PetscCall(file.WriteRows("/mesh/coordinates", node_rows_.Global(), 3, node_rows_.Start(), xyz));
  PetscCall(WriteTopology(file));
  PetscCall(file.WriteRows("/mesh/node_tags", node_rows_.Global(), 1, node_rows_.Start(), node_tags));
  PetscCall(file.WriteRows("/mesh/cell_tags", cell_rows_.Global(), 1, cell_rows_.Start(), cell_tags));
  // The body of each cell (Mesh::CellBody: connected groups of cells, numbered by their smallest file cell index).
  std::vector<long long> body(mesh_->NumLocalCells()), body_block;
  for (PetscInt c = 0; c < mesh_->NumLocalCells(); ++c) body[c] = mesh_->CellBody(c);
  PetscCall(cell_rows_.ToBlocks(body, 1, body_block));
  PetscCall(file.WriteRows("/mesh/body", cell_rows_.Global(), 1, cell_rows_.Start(), body_block));
  // The obstacle (known on every rank) and the contact boundary (gathered on rank 0) are small: rank 0 writes them.
  if (!obstacle_points_.empty()) {
    std::vector<double> coords;
    std::vector<long long> cells;
    if (rank == 0) {
      for (const auto &p : obstacle_points_) coords.insert(coords.end(), p.begin(), p.end());
      for (std::size_t k = 0; k < obstacle_points_.size(); ++k) cells.push_back((long long)k);
    }
    const PetscInt n = (PetscInt)obstacle_points_.size();
    PetscCall(file.CreateGroup("/obstacle"));
    PetscCall(file.WriteRows("/obstacle/coordinates", n, 3, 0, coords));
    PetscCall(file.WriteRows("/obstacle/topology", n / obstacle_cell_size_, obstacle_cell_size_, 0, cells));
  }
  if (contact_num_nodes_ > 0) {
    std::vector<double> contact_xyz;
    std::vector<long long> contact_tags;
    PetscCall(contact_rows_.FromBlocks(xyz, 3, contact_xyz));
    PetscCall(contact_rows_.FromBlocks(node_tags, 1, contact_tags));
    const int cols = contact_face_size_ ? contact_face_size_ : 1;
    PetscCall(file.CreateGroup("/contact_boundary"));
    PetscCall(file.WriteRows("/contact_boundary/coordinates", contact_num_nodes_, 3, 0, contact_xyz));
    PetscCall(file.WriteRows("/contact_boundary/topology", contact_topology_size_ / cols, cols, 0, contact_faces_));
    PetscCall(file.WriteRows("/contact_boundary/node_tags", contact_num_nodes_, 1, 0, contact_tags));
  }
  PetscFunctionReturn(0);
}

namespace {

/// An HDF5 DataItem of solution.h5 (dims: "n" or "n m").
std::string DataItem(const std::string &dims, bool integer, const std::string &dataset) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + (integer ? "Int" : "Float") +
         "\" Precision=\"8\" Format=\"HDF\">solution.h5:" + dataset + "</DataItem>";
}

/// An attribute of n nodes or cells with ncomp values each; three components are a vector. Six are a symmetric
/// tensor in VTK's order (xx, yy, zz, xy, yz, xz), declared as a plain matrix so that every ParaView XDMF reader
/// passes them through and names them XX, YY, ZZ, XY, YZ, XZ: the legacy XDMFReader would expand an XDMF Tensor6
/// (xx, xy, xz, yy, yz, zz) to nine, while the Xdmf3 readers pass it through under VTK's names, in the wrong order.
std::string Attribute(const std::string &name, int ncomp, bool on_cells, int n, bool integer,
                      const std::string &dataset) {
  const char *type = ncomp == 1 ? "Scalar" : ncomp == 3 ? "Vector" : "Matrix";
  const std::string dims = std::to_string(n) + (ncomp > 1 ? " " + std::to_string(ncomp) : "");
  return "     <Attribute Name=\"" + name + "\" AttributeType=\"" + type + "\" Center=\"" +
         (on_cells ? "Cell" : "Node") + "\">\n      " + DataItem(dims, integer, dataset) + "\n     </Attribute>\n";
}

/// Topology and geometry of a grid whose datasets live in group (cells of `nodes_per_cell` nodes, or mixed).
std::string Shape(const std::string &group, const char *type, int cells, int nodes_per_cell, std::size_t mixed_size,
                  int nodes) {
  std::ostringstream x;
  x << "     <Topology TopologyType=\"" << type << "\" NumberOfElements=\"" << cells << "\"";
  if (std::string(type) == "Polyline") x << " NodesPerElement=\"2\"";
  x << ">\n      "
    << DataItem(mixed_size ? std::to_string(mixed_size) : std::to_string(cells) + " " + std::to_string(nodes_per_cell),
                true, "/" + group + "/topology")
    << "\n     </Topology>\n     <Geometry GeometryType=\"XYZ\">\n      "
    << DataItem(std::to_string(nodes) + " 3", false, "/" + group + "/coordinates") << "\n     </Geometry>\n";
  return x.str();
}

} // namespace

std::string OutputWriter::BodyGrid(const std::string &name, const StepInfo &s) const {
  const int nn = (int)mesh_->NumGlobalNodes(), nc = (int)mesh_->NumGlobalCells();
  char group[32];
  std::snprintf(group, sizeof(group), "/step_%06d/", (int)s.step);
  std::ostringstream x;
  x << "    <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
    << Shape("mesh", uniform_ ? XdmfCellName(mesh_->Dim(), cell_size_) : "Mixed", nc, cell_size_,
             uniform_ ? 0 : (std::size_t)mixed_topology_size_, nn)
    << Attribute("node_tags", 1, false, nn, true, "/mesh/node_tags")
    << Attribute("cell_tags", 1, true, nc, true, "/mesh/cell_tags")
    << Attribute("body", 1, true, nc, true, "/mesh/body");
  for (const auto &f : s.layout)
    x << Attribute(f.name, f.ncomp, f.on_cells, f.on_cells ? nc : nn, false, group + f.name);
  return x.str();
}

std::string OutputWriter::ObstacleGrid(const std::string &name) const {
  return "    <Grid Name=\"" + name + "\" GridType=\"Uniform\">\n" +
         Shape("obstacle", obstacle_cell_size_ == 3 ? "Triangle" : "Polyline",
               (int)obstacle_points_.size() / obstacle_cell_size_, obstacle_cell_size_, 0,
               (int)obstacle_points_.size());
}

std::string OutputWriter::ContactGrid(const std::string &name, const StepInfo &s) const {
  const int nb = (int)contact_num_nodes_;
  char group[48];
  std::snprintf(group, sizeof(group), "/step_%06d/contact_boundary/", (int)s.step);
  std::ostringstream x;
  x << "    <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
    << Shape("contact_boundary",
             contact_face_size_ == 2   ? "Polyline"
             : contact_face_size_ == 3 ? "Triangle"
             : contact_face_size_ == 4 ? "Quadrilateral"
                                       : "Mixed",
             contact_num_faces_, contact_face_size_, contact_face_size_ ? 0 : (std::size_t)contact_topology_size_, nb)
    << Attribute("node_tags", 1, false, nb, true, "/contact_boundary/node_tags");
  for (const auto &f : s.layout)
    if (f.on_contact) x << Attribute(f.name, f.ncomp, false, nb, false, group + f.name);
  return x.str();
}

PetscErrorCode OutputWriter::WriteXdmf() const {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  std::string error;
  if (rank == 0) {
    const bool obstacle = !obstacle_points_.empty(), contact = contact_num_nodes_ > 0;
    const char *head = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
    const char *tail = "  </Grid>\n </Domain>\n</Xdmf>\n";
    const auto temporal = [](const std::string &name) {
      return "  <Grid Name=\"" + name + "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    };
    // solution.xdmf: per step a spatial collection of the three grids. Each block also gets a file of its own, a
    // temporal collection of one grid per step: every ParaView reader opens that as a plain dataset with all steps,
    // where the Xdmf3 readers name the blocks of solution.xdmf body[1], ... from the second step on, or not at all.
    std::ostringstream all, body, obstacles, boundary;
    all << head << temporal("signorini");
    body << head << temporal("body");
    obstacles << head << temporal("obstacle");
    boundary << head << temporal("contact_boundary");
    for (const auto &s : steps_) {
      char group[32];
      std::snprintf(group, sizeof(group), "step_%06d", (int)s.step);
      std::ostringstream t;
      t << "     <Time Value=\"" << s.t << "\"/>\n";
      const std::string time = t.str(), end = "    </Grid>\n";
      all << "   <Grid Name=\"" << group << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
          << "    <Time Value=\"" << s.t << "\"/>\n"
          << BodyGrid("body", s) << end;
      body << BodyGrid(group, s) << time << end;
      if (obstacle) all << ObstacleGrid("obstacle") << end, obstacles << ObstacleGrid(group) << time << end;
      if (contact) all << ContactGrid("contact_boundary", s) << end, boundary << ContactGrid(group, s) << time << end;
      all << "   </Grid>\n";
    }
    std::vector<std::pair<std::string, std::string>> files = {{"solution.xdmf", all.str() + tail},
                                                              {"body.xdmf", body.str() + tail}};
    if (obstacle) files.emplace_back("obstacle.xdmf", obstacles.str() + tail);
    if (contact) files.emplace_back("contact_boundary.xdmf", boundary.str() + tail);
    for (const auto &[name, text] : files) {
      const std::string path = Staging() + "/" + name;
      std::ofstream out(path + ".tmp");
      out << text;
      out.close();
      std::error_code ec;
      if (!out) error = "cannot write '" + path + "'";
      else fs::rename(path + ".tmp", path, ec);
      if (ec) error = "cannot write '" + path + "': " + ec.message();
      if (!error.empty()) break;
    }
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteNodeTable(const std::vector<Field> &fields) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(EV_CSV, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  // Each rank formats the rows of its block of the file's node order; the blocks join in rank order.
  std::vector<double> xyz;
  std::vector<long long> tags;
  PetscCall(NodeBlocks(xyz, tags));
  std::vector<std::vector<double>> blocks(fields.size());
  for (std::size_t f = 0; f < fields.size(); ++f)
    PetscCall(node_rows_.ToBlocks(fields[f].values, fields[f].ncomp, blocks[f]));
  std::string text;
  if (rank == 0) {
    text = mesh_->Dim() == 2 ? "node_tag,x,y" : "node_tag,x,y,z";
    for (const auto &f : fields) {
      if (f.ncomp == 1) text += "," + f.name;
      else
        for (int k = 0; k < f.ncomp; ++k) text += "," + f.name + "_" + "xyz"[k];
    }
    text += "\n";
  }
  for (PetscInt i = 0; i < node_rows_.Size(); ++i) {
    char buf[24];
    text.append(buf, std::to_chars(buf, buf + sizeof(buf), (unsigned long long)tags[i]).ptr);
    for (int d = 0; d < mesh_->Dim(); ++d) text += ',', AppendNumber(text, xyz[3 * i + d]);
    for (std::size_t f = 0; f < fields.size(); ++f)
      for (int k = 0; k < fields[f].ncomp; ++k) text += ',', AppendNumber(text, blocks[f][i * fields[f].ncomp + k]);
    text += '\n';
  }
  PetscCall(WriteInRankOrder(mesh_->Comm(), Staging() + "/nodes.csv", text));
  PetscCall(PetscLogEventEnd(EV_CSV, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::Publish(const std::string &summary_json) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  std::string error;
  if (rank == 0) {
    const std::string path = Staging() + "/summary.json";
    std::ofstream out(path);
    out << summary_json;
    out.close();
    if (!out) error = "cannot write '" + path + "'";
    else error = PublishOutputDirectory(opts_.dir);
    if (error.empty()) RemoveOnFailure("");
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  PetscFunctionReturn(0);
}

} // namespace signorini
