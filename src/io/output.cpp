// HDF5/XDMF, CSV and JSON output through a staging directory.
#include "signorini/io/output.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/core/options.hpp"

#include <hdf5.h>

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

std::string HdfError(const std::string &path) { return "cannot write HDF5 file '" + path + "'"; }

/// XDMF name and mixed-topology id of a cell with n vertices in dimension dim.
const char *XdmfCellName(int dim, int n) {
  if (dim == 2) return n == 3 ? "Triangle" : "Quadrilateral";
  return n == 4 ? "Tetrahedron" : "Hexahedron";
}
int XdmfCellId(int dim, int n) {
  if (dim == 2) return n == 3 ? 4 : 5; // XDMF: 4 triangle, 5 quadrilateral, 6 tetrahedron, 9 hexahedron
  return n == 4 ? 6 : 9;
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
  if (rank == 0) {
    std::error_code ec;
    fs::create_directories(opts_.dir, ec);
    if (ec || !fs::is_directory(opts_.dir)) {
      error = "-output_dir '" + opts_.dir + "' cannot be created (" + ec.message() + "); expected a writable directory";
    } else {
      fs::remove_all(Staging(), ec);
      fs::create_directory(Staging(), ec);
      const std::string probe = Staging() + "/.probe";
      std::ofstream f(probe);
      if (ec || !f) error = "-output_dir '" + opts_.dir + "' is not writable; expected a writable directory";
      f.close();
      fs::remove(probe, ec);
    }
  }
  PetscCall(RaiseFromRoot(mesh.Comm(), error));
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
    if (ok && first) {
      const SerialMesh &sm = mesh_->Serial();
      hid_t g = H5Gcreate2(file, "mesh", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      std::vector<double> xyz(3 * sm.NumNodes(), 0.0);
      for (int i = 0; i < sm.NumNodes(); ++i)
        for (int d = 0; d < sm.dim; ++d) xyz[3 * i + d] = sm.coords[sm.dim * i + d];
      bool uniform = true;
      for (int c = 1; c < sm.NumCells(); ++c) uniform = uniform && sm.CellSize(c) == sm.CellSize(0);
      std::vector<long long> topo, ntags(sm.node_tags.begin(), sm.node_tags.end()),
          ctags(sm.cell_tags.begin(), sm.cell_tags.end());
      for (int c = 0; c < sm.NumCells(); ++c) {
        if (!uniform) topo.push_back(XdmfCellId(sm.dim, sm.CellSize(c)));
        for (int k = sm.cell_offsets[c]; k < sm.cell_offsets[c + 1]; ++k) topo.push_back(sm.cell_nodes[k]);
      }
      ok = g >= 0 && WriteDataset(g, "coordinates", xyz, 3) &&
           WriteDataset(g, "topology", topo, uniform ? (hsize_t)sm.CellSize(0) : 1) &&
           WriteDataset(g, "node_tags", ntags, 1) && WriteDataset(g, "cell_tags", ctags, 1);
      if (g >= 0) H5Gclose(g);
    }
    char name[32];
    std::snprintf(name, sizeof(name), "step_%06d", (int)step);
    hid_t g = ok ? H5Gcreate2(file, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT) : -1;
    ok = ok && g >= 0;
    for (std::size_t f = 0; ok && f < fields.size(); ++f)
      ok = WriteDataset(g, fields[f].name, gathered[f], (hsize_t)fields[f].ncomp);
    if (g >= 0) H5Gclose(g);
    if (file >= 0) ok = H5Fclose(file) >= 0 && ok;
    if (!ok) error = HdfError(path);
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  StepInfo info{step, t, {}};
  for (const auto &f : fields) info.layout.push_back({f.name, f.ncomp, f.on_cells, {}});
  steps_.push_back(info);
  PetscCall(WriteXdmf());
  PetscFunctionReturn(0);
}

PetscErrorCode OutputWriter::WriteXdmf() const {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(mesh_->Comm(), &rank));
  std::string error;
  if (rank == 0) {
    const SerialMesh &sm = mesh_->Serial();
    bool uniform = true;
    std::size_t topo_size = 0;
    for (int c = 0; c < sm.NumCells(); ++c) {
      uniform = uniform && sm.CellSize(c) == sm.CellSize(0);
      topo_size += sm.CellSize(c) + 1;
    }
    const int nn = sm.NumNodes(), nc = sm.NumCells();
    std::ostringstream x;
    x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
      << "  <Grid Name=\"signorini\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto &s : steps_) {
      char group[32];
      std::snprintf(group, sizeof(group), "step_%06d", (int)s.step);
      x << "   <Grid Name=\"" << group << "\" GridType=\"Uniform\">\n    <Time Value=\"" << s.t << "\"/>\n";
      if (uniform)
        x << "    <Topology TopologyType=\"" << XdmfCellName(sm.dim, sm.CellSize(0))
          << "\" NumberOfElements=\"" << nc << "\">\n     <DataItem Dimensions=\"" << nc << " " << sm.CellSize(0)
          << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">solution.h5:/mesh/topology</DataItem>\n";
      else
        x << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << nc << "\">\n     <DataItem Dimensions=\""
          << topo_size << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">solution.h5:/mesh/topology</DataItem>\n";
      x << "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"" << nn
        << " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">solution.h5:/mesh/coordinates</DataItem>\n"
        << "    </Geometry>\n";
      for (const auto &f : s.layout) {
        const char *type = f.ncomp == 1 ? "Scalar" : f.ncomp == 3 ? "Vector" : f.ncomp == 6 ? "Tensor6" : "Matrix";
        const int n = f.on_cells ? nc : nn;
        x << "    <Attribute Name=\"" << f.name << "\" AttributeType=\"" << type << "\" Center=\""
          << (f.on_cells ? "Cell" : "Node") << "\">\n     <DataItem Dimensions=\"" << n;
        if (f.ncomp > 1) x << " " << f.ncomp;
        x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">solution.h5:/" << group << "/" << f.name
          << "</DataItem>\n    </Attribute>\n";
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
    std::error_code ec;
    fs::remove(fs::path(opts_.dir) / "summary.json", ec);
    // summary.json moves last: its presence in DIR says that the other files are complete.
    for (const char *name : {"solution.h5", "solution.xdmf", "nodes.csv", "summary.json"}) {
      if (!error.empty()) break;
      const fs::path from = fs::path(Staging()) / name, to = fs::path(opts_.dir) / name;
      if (!fs::exists(from)) continue;
      fs::rename(from, to, ec);
      if (ec) error = "cannot move '" + from.string() + "' to '" + to.string() + "': " + ec.message();
    }
    if (error.empty()) fs::remove_all(Staging(), ec);
  }
  PetscCall(RaiseFromRoot(mesh_->Comm(), error));
  PetscFunctionReturn(0);
}

} // namespace signorini
