// HDF5/XDMF, CSV and JSON output through a staging directory.
#include "signorini/io/output.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/core/options.hpp"

#include <hdf5.h>

#include <algorithm>
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
  PetscCall(OptionsString(PetscOptionsObject, "-output_dir", "Directory for solution.h5/.xdmf, nodes.csv and "
                          "summary.json (default: no files)", "a directory path", opts.dir));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode GatherToRoot(const Mesh &mesh, const Field &field, std::vector<double> &out) {
  MPI_Comm comm = mesh.Comm();
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscInt n = field.on_cells ? mesh.NumLocalCells() : mesh.NumLocalVertices();
  const int nc = field.ncomp;
  std::vector<double> send;
  for (PetscInt i = 0; i < n; ++i) {
    if (!field.on_cells && !mesh.Owned(i)) continue;
    send.push_back((double)(field.on_cells ? mesh.CellOriginal(i) : mesh.VertexOriginal(i)));
    for (int k = 0; k < nc; ++k) send.push_back(field.values[i * nc + k]);
  }
  int count = (int)send.size();
  std::vector<int> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  std::vector<double> recv;
  if (rank == 0) {
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    recv.resize(displs[size - 1] + counts[size - 1]);
  }
  PetscCallMPI(MPI_Gatherv(send.data(), count, MPI_DOUBLE, recv.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
                           comm));
  if (rank == 0) {
    const PetscInt total = field.on_cells ? mesh.NumGlobalCells() : mesh.NumGlobalNodes();
    out.assign(total * nc, 0.0);
    for (std::size_t i = 0; i + nc < recv.size() + 1; i += nc + 1) {
      const PetscInt orig = (PetscInt)recv[i];
      for (int k = 0; k < nc; ++k) out[orig * nc + k] = recv[i + 1 + k];
    }
  }
  PetscFunctionReturn(0);
}

namespace {

bool UniformCells(const SerialMesh &sm) {
  for (int c = 1; c < sm.NumCells(); ++c)
    if (sm.CellSize(c) != sm.CellSize(0)) return false;
  return true;
}

std::string HdfError(const std::string &path) { return "cannot write HDF5 file '" + path + "'"; }

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

/// Writes a 2D dataset (rows x cols) of doubles or ints into an open HDF5 location.
template <typename T>
bool WriteDataset(hid_t loc, const std::string &name, const std::vector<T> &data, hsize_t cols) {
  const hsize_t dims[2] = {cols ? data.size() / cols : 0, cols};
  const hid_t type = std::is_same<T, double>::value ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
  hid_t space = H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr);
  if (space < 0) return false;
  hid_t set = H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool ok = set >= 0 && H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0;
  if (set >= 0) H5Dclose(set);
  H5Sclose(space);
  return ok;
}

} // namespace

PetscErrorCode OutputWriter::Open(const Mesh &mesh, const OutputOptions &opts) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  mesh_ = &mesh;
  opts_ = opts;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(mesh.Comm(), &rank));
  std::string error;
  if (rank == 0) error = PrepareOutputDirectory(opts_.dir);
  PetscCall(RaiseFromRoot(mesh.Comm(), error));
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
  // quadrilaterals in 3D; per face its vertex count, then its vertices (file order).
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
  contact_nodes_.clear();
  contact_faces_.clear();
  contact_num_faces_ = 0;
  int size_seen = -1;
  bool uniform = true;
  for (std::size_t k = 0; k < all.size(); k += all[k] + 1) {
    contact_nodes_.insert(contact_nodes_.end(), all.begin() + k + 1, all.begin() + k + 1 + all[k]);
    uniform = uniform && (size_seen < 0 || size_seen == (int)all[k]);
    size_seen = (int)all[k];
  }
  std::sort(contact_nodes_.begin(), contact_nodes_.end());
  contact_nodes_.erase(std::unique(contact_nodes_.begin(), contact_nodes_.end()), contact_nodes_.end());
  // XDMF: a uniform topology, or a Mixed one with the cell type before each face's vertices.
  contact_face_size_ = uniform ? std::max(size_seen, 0) : 0;
  for (std::size_t k = 0; k < all.size(); k += all[k] + 1, ++contact_num_faces_) {
    if (!uniform) contact_faces_.push_back(XdmfCellId(2, (int)all[k]));
    for (PetscInt a = 0; a < all[k]; ++a)
      contact_faces_.push_back(std::lower_bound(contact_nodes_.begin(), contact_nodes_.end(), all[k + 1 + a]) -
                               contact_nodes_.begin());
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::GatherFields(const std::vector<Field> &fields, std::vector<std::vector<double>> &gathered,
                                          PetscMPIInt &rank) const {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  gathered.resize(fields.size());
  for (std::size_t f = 0; f < fields.size(); ++f) PetscCall(GatherToRoot(*mesh_, fields[f], gathered[f]));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteStep(PetscInt step, double t, const std::vector<Field> &fields) {
  PetscMPIInt rank;
  std::vector<std::vector<double>> gathered;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCall(GatherFields(fields, gathered, rank));
  std::string error;
  if (rank == 0) {
    const std::string path = Staging() + "/solution.h5";
    const bool first = steps_.empty();
    hid_t file = first ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)
                       : H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    bool ok = file >= 0;
    ok = ok && (!first || WriteGeometry(file));
    char name[32];
    std::snprintf(name, sizeof(name), "step_%06d", (int)step);
    hid_t g = ok ? H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    ok = ok && g >= 0;
    for (std::size_t f = 0; ok && f < fields.size(); ++f)
      ok = WriteDataset(g, fields[f].name, gathered[f], (hsize_t)fields[f].ncomp);
    hid_t boundary = ok && !contact_nodes_.empty()
                         ? H5Gcreate2(g, "contact_boundary", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    for (std::size_t f = 0; boundary >= 0 && ok && f < fields.size(); ++f) {
      if (!fields[f].on_contact) continue;
      const int nc = fields[f].ncomp;
      std::vector<double> restricted;
      for (PetscInt v : contact_nodes_)
        restricted.insert(restricted.end(), gathered[f].begin() + v * nc, gathered[f].begin() + (v + 1) * nc);
      ok = WriteDataset(boundary, fields[f].name, restricted, (hsize_t)nc);
    }
    if (boundary >= 0) H5Gclose(boundary);
    if (g >= 0) H5Gclose(g);
    if (file >= 0) ok = H5Fclose(file) >= 0 && ok;
    if (!ok) error = HdfError(path);
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  StepInfo info{step, t, {}};
  for (const auto &f : fields) info.layout.push_back({f.name, f.ncomp, f.on_cells, {}, f.on_contact});
  steps_.push_back(info);
  PetscCall(WriteXdmf());
  PetscFunctionReturn(0);
}

bool OutputWriter::WriteGeometry(std::int64_t file) const {
  const SerialMesh &sm = mesh_->Serial();
  hid_t g = H5Gcreate2(file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  std::vector<double> coords(3 * sm.NumNodes(), 0.0);
  for (int i = 0; i < sm.NumNodes(); ++i)
    for (int d = 0; d < sm.dim; ++d) coords[3 * i + d] = sm.coords[sm.dim * i + d];
  const bool uniform = UniformCells(sm);
  std::vector<long long> topo, ntags(sm.node_tags.begin(), sm.node_tags.end()),
      ctags(sm.cell_tags.begin(), sm.cell_tags.end());
  for (int c = 0; c < sm.NumCells(); ++c) {
    if (!uniform) topo.push_back(XdmfCellId(sm.dim, sm.CellSize(c)));
    for (int k = sm.cell_offsets[c]; k < sm.cell_offsets[c + 1]; ++k) topo.push_back(sm.cell_nodes[k]);
  }
  bool ok = g >= 0 && WriteDataset(g, "coordinates", coords, 3) &&
            WriteDataset(g, "topology", topo, uniform ? (hsize_t)sm.CellSize(0) : 1) &&
            WriteDataset(g, "node_tags", ntags, 1) && WriteDataset(g, "cell_tags", ctags, 1);
  if (g >= 0) H5Gclose(g);
  if (ok && !obstacle_points_.empty()) {
    std::vector<long long> cells(obstacle_points_.size());
    for (std::size_t k = 0; k < cells.size(); ++k) cells[k] = (long long)k;
    g = H5Gcreate2(file, "obstacle", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<double> coords;
    for (const auto &p : obstacle_points_) coords.insert(coords.end(), p.begin(), p.end());
    ok = g >= 0 && WriteDataset(g, "coordinates", coords, 3) &&
         WriteDataset(g, "topology", cells, (hsize_t)obstacle_cell_size_);
    if (g >= 0) H5Gclose(g);
  }
  if (ok && !contact_nodes_.empty()) {
    std::vector<double> contact_coords;
    std::vector<long long> tags;
    for (PetscInt v : contact_nodes_)
      contact_coords.insert(contact_coords.end(), coords.begin() + 3 * v, coords.begin() + 3 * v + 3),
          tags.push_back((long long)sm.node_tags[v]);
    g = H5Gcreate2(file, "contact_boundary", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ok = g >= 0 && WriteDataset(g, "coordinates", contact_coords, 3) &&
         WriteDataset(g, "topology", contact_faces_, contact_face_size_ ? (hsize_t)contact_face_size_ : 1) &&
         WriteDataset(g, "node_tags", tags, 1);
    if (g >= 0) H5Gclose(g);
  }
  return ok;
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

PetscErrorCode OutputWriter::WriteXdmf() const {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  std::string error;
  if (rank == 0) {
    const SerialMesh &sm = mesh_->Serial();
    const bool uniform = UniformCells(sm);
    std::size_t topo_size = 0;
    for (int c = 0; c < sm.NumCells(); ++c) topo_size += sm.CellSize(c) + 1;
    const int nn = sm.NumNodes(), nc = sm.NumCells(), nb = (int)contact_nodes_.size();
    std::ostringstream x;
    x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
      << "  <Grid Name=\"signorini\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto &s : steps_) {
      char group[32];
      std::snprintf(group, sizeof(group), "step_%06d", (int)s.step);
      x << "   <Grid Name=\"" << group << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
        << "    <Time Value=\"" << s.t << "\"/>\n    <Grid Name=\"body\" GridType=\"Uniform\">\n"
        << Shape("mesh", uniform ? XdmfCellName(sm.dim, sm.CellSize(0)) : "Mixed", nc,
                 sm.CellSize(0), uniform ? 0 : topo_size, nn)
        << Attribute("node_tags", 1, false, nn, true, "/mesh/node_tags")
        << Attribute("cell_tags", 1, true, nc, true, "/mesh/cell_tags");
      for (const auto &f : s.layout)
        x << Attribute(f.name, f.ncomp, f.on_cells, f.on_cells ? nc : nn, false, "/" + std::string(group) + "/" + f.name);
      x << "    </Grid>\n";
      if (!obstacle_points_.empty())
        x << "    <Grid Name=\"obstacle\" GridType=\"Uniform\">\n"
          << Shape("obstacle", obstacle_cell_size_ == 3 ? "Triangle" : "Polyline",
                   (int)obstacle_points_.size() / obstacle_cell_size_, obstacle_cell_size_, 0,
                   (int)obstacle_points_.size())
          << "    </Grid>\n";
      if (nb > 0) {
        x << "    <Grid Name=\"contact_boundary\" GridType=\"Uniform\">\n"
          << Shape("contact_boundary",
                   contact_face_size_ == 2   ? "Polyline"
                   : contact_face_size_ == 3 ? "Triangle"
                   : contact_face_size_ == 4 ? "Quadrilateral"
                                             : "Mixed",
                   contact_num_faces_, contact_face_size_, contact_face_size_ ? 0 : contact_faces_.size(), nb)
          << Attribute("node_tags", 1, false, nb, true, "/contact_boundary/node_tags");
        for (const auto &f : s.layout)
          if (f.on_contact)
            x << Attribute(f.name, f.ncomp, false, nb, false, "/" + std::string(group) + "/contact_boundary/" + f.name);
        x << "    </Grid>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n </Domain>\n</Xdmf>\n";
    const std::string path = Staging() + "/solution.xdmf";
    std::ofstream out(path + ".tmp");
    out << x.str();
    out.close();
    std::error_code ec;
    if (!out) error = "cannot write '" + path + "'";
    else fs::rename(path + ".tmp", path, ec);
    if (ec) error = "cannot write '" + path + "': " + ec.message();
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteNodeTable(const std::vector<Field> &fields) {
  PetscMPIInt rank;
  std::vector<std::vector<double>> gathered;
  PetscFunctionBeginUser;
  if (!Enabled()) PetscFunctionReturn(0);
  PetscCall(GatherFields(fields, gathered, rank));
  std::string error;
  if (rank == 0) {
    const SerialMesh &sm = mesh_->Serial();
    const std::string path = Staging() + "/nodes.csv";
    FILE *out = std::fopen(path.c_str(), "w");
    if (!out) error = "cannot write '" + path + "'";
    else {
      std::fprintf(out, sm.dim == 2 ? "node_tag,x,y" : "node_tag,x,y,z");
      for (const auto &f : fields) {
        if (f.ncomp == 1) std::fprintf(out, ",%s", f.name.c_str());
        else
          for (int k = 0; k < f.ncomp; ++k) std::fprintf(out, ",%s_%c", f.name.c_str(), "xyz"[k]);
      }
      std::fprintf(out, "\n");
      for (int i = 0; i < sm.NumNodes(); ++i) {
        std::fprintf(out, "%zu", sm.node_tags[i]);
        for (int d = 0; d < sm.dim; ++d) std::fprintf(out, ",%.17g", sm.coords[sm.dim * i + d]);
        for (std::size_t f = 0; f < fields.size(); ++f)
          for (int k = 0; k < fields[f].ncomp; ++k) {
            const double v = gathered[f][i * fields[f].ncomp + k];
            if (std::isnan(v)) std::fprintf(out, ",nan");
            else std::fprintf(out, ",%.17g", v);
          }
        std::fprintf(out, "\n");
      }
      if (std::fclose(out) != 0) error = "cannot write '" + path + "'";
    }
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
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
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  PetscFunctionReturn(0);
}

} // namespace signorini
