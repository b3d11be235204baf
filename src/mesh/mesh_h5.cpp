// Writing the distributed mesh to PETSc's DMPlex HDF5 format with signorini's own blocks (-mesh_save) and reading those
// back on any number of ranks, every rank its part (a .h5 -mesh_file), then partitioned by PTScotch.
//
// Why signorini reads its own blocks and not PETSc's DMPlex: PETSc 3.18's DMPlexTopologyLoad reads the whole topology
// on rank 0 (its source: "Force serial load"), and the coordinates, labels and point data follow it. The 3.9M-dof
// octant on 2 ranks: rank 0 held 3.0 GB after the load where rank 1 held 0.5 GB, 3.9 GB after the distribution, and
// kept rank 0's peak at 0.67 of the one-rank run's (docs/performance.md, twenty-seventh session). PETSc 3.18's
// parallel builder from a cell list (DMPlexCreateFromCellListParallelPetsc) takes one cell type; signorini's meshes
// mix tetrahedra, pyramids and hexahedra.
#include "signorini/mesh/mesh_h5.hpp"

#include "signorini/core/blocks.hpp"
#include "signorini/core/errors.hpp"
#include "signorini/core/handle.hpp"
#include "signorini/core/parse.hpp"
#include "signorini/core/progress.hpp"
#include "signorini/mesh/cell_faces.hpp"
#include "signorini/mesh/mesh.hpp"

#include <petscviewerhdf5.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace signorini {

namespace {

/// Removes a temporary file on rank 0 when it goes out of scope, unless Keep() was called: a write that fails leaves
/// no half-written file.
class TemporaryFile {
public:
  TemporaryFile(PetscMPIInt rank, std::string path) : rank_(rank), path_(std::move(path)) {}
  TemporaryFile(const TemporaryFile &) = delete;
  TemporaryFile &operator=(const TemporaryFile &) = delete;
  ~TemporaryFile() {
    if (rank_ == 0 && !kept_) std::remove(path_.c_str());
  }
  void Keep() { kept_ = true; }

private:
  PetscMPIInt rank_;
  std::string path_;
  bool kept_ = false;
};

/// The physical groups as the "groups" attribute holds them: "count\n", then "<dim><name>\n" for each.
std::string PackGroups(const std::vector<std::string> &names, const std::vector<int> &dims) {
  std::string packed = std::to_string(names.size()) + "\n";
  for (std::size_t g = 0; g < names.size(); ++g) packed += std::to_string(dims[g]) + names[g] + "\n";
  return packed;
}

bool UnpackGroups(const std::string &packed, std::vector<std::string> &names, std::vector<int> &dims) {
  names.clear();
  dims.clear();
  const std::vector<std::string> lines = Split(packed, '\n');
  if (lines.empty()) return false;
  std::size_t count = 0;
  try {
    count = std::stoul(lines[0]);
  } catch (...) {
    return false;
  }
  if (lines.size() < count + 1) return false;
  for (std::size_t g = 1; g <= count; ++g) {
    if (lines[g].size() < 2 || lines[g][0] < '0' || lines[g][0] > '3') return false;
    dims.push_back(lines[g][0] - '0');
    names.push_back(lines[g].substr(1));
  }
  return true;
}

/// Writes values (this rank's block of a table in the file's order, BlockOf over n) as the vector name of the current
/// group. Collective.
PetscErrorCode ViewBlock(MPI_Comm comm, PetscViewer viewer, const char *name, PetscInt n,
                         const std::vector<std::size_t> &values) {
  VecH v;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, (PetscInt)values.size(), n, v.out()));
  PetscCall(PetscObjectSetName((PetscObject)v.get(), name));
  PetscCall(VecGetArray(v, &a));
  for (std::size_t i = 0; i < values.size(); ++i) a[i] = (PetscScalar)values[i];
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecView(v, viewer));
  PetscFunctionReturn(0);
}

/// Reads the vector name of the current group, n values, this rank's block (BlockOf) into values. Collective.
PetscErrorCode LoadBlock(MPI_Comm comm, PetscViewer viewer, const char *name, PetscInt n,
                         std::vector<std::size_t> &values) {
  PetscInt start, size;
  VecH v;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(BlockOf(comm, n, start, size));
  PetscCall(VecCreateMPI(comm, size, n, v.out()));
  PetscCall(PetscObjectSetName((PetscObject)v.get(), name));
  PetscCall(VecLoad(v, viewer));
  PetscCall(VecGetArrayRead(v, &a));
  values.resize(size);
  for (PetscInt i = 0; i < size; ++i) values[i] = (std::size_t)PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

using PartitionerH = Handle<PetscPartitioner, PetscPartitionerDestroy>;

/// Sends each rank r the values out[r] and returns what every rank sent here, in rank order: rank r's from from[r] to
/// from[r + 1] (values of a trivially copyable type, sent as one MPI type of their size). Collective.
template <typename T>
PetscErrorCode ExchangeBySource(MPI_Comm comm, const std::vector<std::vector<T>> &out, std::vector<T> &in,
                                std::vector<int> &from) {
  static_assert(std::is_trivially_copyable<T>::value, "ExchangeBySource sends values as bytes");
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> send_counts(size), recv_counts(size), send_offsets(size + 1, 0);
  for (int r = 0; r < size; ++r) send_counts[r] = (int)out[r].size();
  PetscCallMPI(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm));
  from.assign(size + 1, 0);
  for (int r = 0; r < size; ++r) {
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
    from[r + 1] = from[r] + recv_counts[r];
  }
  std::vector<T> send(send_offsets[size]);
  for (int r = 0; r < size; ++r) std::copy(out[r].begin(), out[r].end(), send.begin() + send_offsets[r]);
  in.resize(from[size]);
  MPI_Datatype type;
  PetscCallMPI(MPI_Type_contiguous((int)sizeof(T), MPI_BYTE, &type));
  PetscCallMPI(MPI_Type_commit(&type));
  PetscCallMPI(MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), type, in.data(), recv_counts.data(),
                             from.data(), type, comm));
  PetscCallMPI(MPI_Type_free(&type));
  PetscFunctionReturn(0);
}

/// Sends each rank its records (rec values each) from out[rank] and returns what every rank sent here. Collective.
PetscErrorCode Exchange(MPI_Comm comm, int rec, const std::vector<std::vector<PetscInt>> &out,
                        std::vector<PetscInt> &in) {
  std::vector<int> from;
  PetscFunctionBeginUser;
  PetscCall(ExchangeBySource(comm, out, in, from));
  PetscAssert(in.size() % rec == 0, comm, PETSC_ERR_PLIB, "incomplete records");
  PetscFunctionReturn(0);
}

/// Writes values (this rank's part, the parts in rank order) as the vector name of the current group; nothing when
/// no rank has any. Collective.
PetscErrorCode ViewValues(MPI_Comm comm, PetscViewer viewer, const char *name, const std::vector<double> &values,
                          PetscInt bs = 1) {
  VecH v;
  PetscScalar *a;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, (PetscInt)values.size(), PETSC_DETERMINE, v.out()));
  PetscCall(VecSetBlockSize(v, bs));
  PetscCall(VecGetSize(v, &n));
  if (n == 0) PetscFunctionReturn(0);
  PetscCall(PetscObjectSetName((PetscObject)v.get(), name));
  PetscCall(VecGetArray(v, &a));
  std::copy(values.begin(), values.end(), a);
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecView(v, viewer));
  PetscFunctionReturn(0);
}

/// Reads n values of the vector name of the current group, this rank's part of the parts in rank order (nothing when
/// the ranks' n add up to 0). Collective.
PetscErrorCode LoadValues(MPI_Comm comm, PetscViewer viewer, const char *name, PetscInt n, std::vector<double> &values,
                          PetscInt bs = 1) {
  VecH v;
  const PetscScalar *a;
  PetscInt total;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, n, PETSC_DETERMINE, v.out()));
  PetscCall(VecSetBlockSize(v, bs));
  PetscCall(VecGetSize(v, &total));
  values.assign(n, 0.0);
  if (total == 0) PetscFunctionReturn(0);
  PetscCall(PetscObjectSetName((PetscObject)v.get(), name));
  PetscCall(VecLoad(v, viewer));
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; ++i)
    values[i] = PetscRealPart(a[i]);
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(0);
}

/// The sum of values (counts stored as doubles), as an integer.
PetscInt SumOf(const std::vector<double> &values) {
  double s = 0;
  for (double v : values)
    s += v;
  return (PetscInt)s;
}

} // namespace

PetscErrorCode Mesh::DualGraph(std::vector<PetscInt> &offsets, std::vector<PetscInt> &adjacency) const {
  constexpr int KEY = 4, REC = KEY + 1; // a face's sorted file vertices (padded with -1), then its cell
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  const PetscInt nc = (PetscInt)cell_offsets_.size() - 1;
  std::vector<PetscInt> first(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&nc, 1, MPIU_INT, &first[1], 1, MPIU_INT, comm_));
  for (int r = 0; r < size; ++r) first[r + 1] += first[r];
  // Each face goes to a rank chosen by a hash of its vertices, which pairs the two cells around it.
  std::vector<std::vector<PetscInt>> out(size);
  for (PetscInt c = 0; c < nc; ++c) {
    const PetscInt *cv = &cell_vertices_[cell_offsets_[c]];
    const CellFaceTable &cf = CellFaces(dim_, (int)(cell_offsets_[c + 1] - cell_offsets_[c]));
    for (int f = 0; f < cf.count; ++f) {
      std::array<PetscInt, KEY> key{-1, -1, -1, -1};
      for (int k = 0; k < cf.size[f]; ++k) { // insertion sort of at most 4 values
        int j = k;
        for (; j > 0 && key[j - 1] > cv[cf.v[f][k]]; --j) key[j] = key[j - 1];
        key[j] = cv[cf.v[f][k]];
      }
      std::uint64_t hash = 1469598103934665603ull; // FNV-1a over the key: faces spread evenly over the ranks
      for (PetscInt k : key) hash = (hash ^ (std::uint64_t)(std::uint32_t)k) * 1099511628211ull;
      auto &to = out[(PetscMPIInt)(hash % (std::uint64_t)size)];
      to.insert(to.end(), key.begin(), key.end());
      to.push_back(first[rank] + c);
    }
  }
  std::vector<PetscInt> faces;
  PetscCall(Exchange(comm_, REC, out, faces));
  // Pairs of cells around one face, sent to the rank of each cell as (its cell, the neighbour).
  std::vector<std::size_t> order(faces.size() / REC);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key_of = [&](std::size_t i) { return &faces[REC * i]; };
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return std::lexicographical_compare(key_of(i), key_of(i) + KEY, key_of(j), key_of(j) + KEY);
  });
  for (auto &o : out) o.clear();
  const auto owner = [&](PetscInt cell) {
    return (PetscMPIInt)(std::upper_bound(first.begin(), first.end(), cell) - first.begin() - 1);
  };
  for (std::size_t i = 0; i + 1 < order.size(); ++i) {
    const PetscInt *a = key_of(order[i]), *b = key_of(order[i + 1]);
    if (!std::equal(a, a + KEY, b)) continue;
    out[owner(a[KEY])].insert(out[owner(a[KEY])].end(), {a[KEY], b[KEY]});
    out[owner(b[KEY])].insert(out[owner(b[KEY])].end(), {b[KEY], a[KEY]});
  }
  std::vector<PetscInt> pairs;
  PetscCall(Exchange(comm_, 2, out, pairs));
  offsets.assign(nc + 1, 0);
  for (std::size_t i = 0; i < pairs.size(); i += 2) offsets[pairs[i] - first[rank] + 1]++;
  for (PetscInt c = 0; c < nc; ++c) offsets[c + 1] += offsets[c];
  adjacency.resize(offsets[nc]);
  std::vector<PetscInt> next(offsets.begin(), offsets.end() - 1);
  for (std::size_t i = 0; i < pairs.size(); i += 2) adjacency[next[pairs[i] - first[rank]]++] = pairs[i + 1];
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::ParallelPartition(DM dm, const std::string &partitioner) const {
  PetscMPIInt size;
  PetscPartitioner part;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(DMPlexGetPartitioner(dm, &part));
  if (size == 1 || partitioner == "simple") {
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscFunctionReturn(0);
  }
  // PTScotch on the graph of cells sharing a face, built here (PETSc builds it in parallel for an interpolated DMPlex
  // only, and interpolating took 16 s at 97k vertices on 2 ranks), handed to DMPlexDistribute as a shell partition.
  std::vector<PetscInt> sizes(size), points;
  {
    std::vector<PetscInt> offsets, adjacency;
    PartitionerH scotch;
    SectionH part_section;
    ISH partition;
    PetscCall(DualGraph(offsets, adjacency));
    PetscCall(PetscPartitionerCreate(comm_, scotch.out()));
    PetscCall(PetscPartitionerSetType(scotch, PETSCPARTITIONERPTSCOTCH));
    SingleThreadScotch();
    PetscCall(PetscSectionCreate(comm_, part_section.out()));
    PetscCall(PetscPartitionerPartition(scotch, size, (PetscInt)offsets.size() - 1, offsets.data(), adjacency.data(),
                                        nullptr, nullptr, part_section, partition.out()));
    for (PetscMPIInt r = 0; r < size; ++r) PetscCall(PetscSectionGetDof(part_section, r, &sizes[r]));
    PetscInt n, cstart, cend;
    const PetscInt *p;
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cstart, &cend));
    PetscCall(ISGetLocalSize(partition, &n));
    PetscCall(ISGetIndices(partition, &p));
    for (PetscInt i = 0; i < n; ++i) points.push_back(cstart + p[i]); // the graph's vertices are the local cells
    PetscCall(ISRestoreIndices(partition, &p));
  }
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes.data(), points.data()));
  PetscFunctionReturn(0);
}

std::string MeshSaveTemporaryName(const std::string &path) {
  const std::filesystem::path p(path);
  return (p.parent_path() / ("." + p.filename().string() + "." + std::to_string(getpid()) + ".incomplete")).string();
}

std::string CheckHdf5Signature(const std::string &path) {
  static const unsigned char SIGNATURE[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
  FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) return std::string("cannot open it (") + std::strerror(errno) + ")";
  unsigned char head[8] = {0};
  const std::size_t n = std::fread(head, 1, sizeof(head), f);
  const bool unreadable = std::ferror(f) != 0;
  std::fclose(f);
  if (unreadable) return "cannot read it (a directory?)";
  if (n < sizeof(head) || std::memcmp(head, SIGNATURE, sizeof(head)) != 0) return "it is no HDF5 file";
  return "";
}

PetscErrorCode CheckMeshSavePath(MPI_Comm comm, const std::string &path) {
  PetscMPIInt rank;
  std::string error;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    const std::string tmp = MeshSaveTemporaryName(path);
    if (std::filesystem::is_directory(path, ec)) error = "it is a directory";
    else if (FILE *f = std::fopen(tmp.c_str(), "wb")) {
      std::fclose(f);
      std::remove(tmp.c_str());
    } else
      error = std::string("cannot create a file there (") + std::strerror(errno) + ")";
    if (!error.empty())
      error = "-mesh_save '" + path + "': " + error + "; expected a writable .h5 path in an existing directory";
  }
  PetscCall(RaiseFromRoot(comm, error));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::SaveH5(const std::string &path) const {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  ProgressBegin(("writing the mesh to " + path).c_str());
  std::string tmp = rank == 0 ? MeshSaveTemporaryName(path) : "";
  PetscCall(Broadcast(comm_, 0, tmp));
  TemporaryFile guard(rank, tmp);
  {
    ViewerH viewer;
    PetscCall(PetscViewerHDF5Open(comm_, tmp.c_str(), FILE_MODE_WRITE, viewer.out()));
    PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_PETSC));
    PetscCall(PetscObjectSetName((PetscObject)dm_.get(), MESH_H5_DM));
    PetscCall(DMPlexTopologyView(dm_, viewer));
    PetscCall(DMPlexCoordinatesView(dm_, viewer));
    PetscCall(DMPlexLabelsView(dm_, viewer));
    // What rebuilds the mesh on any number of ranks, each reading its part (LoadH5Blocks), the file's tags in the
    // file's order, and what the DMPlex does not say.
    PetscCall(PetscViewerHDF5PushGroup(viewer, MESH_H5_GROUP));
    PetscCall(ViewH5Blocks(viewer));
    PetscCall(ViewBlock(comm_, viewer, "node_tags", num_global_nodes_, node_tags_));
    PetscCall(ViewBlock(comm_, viewer, "cell_tags", num_global_cells_, cell_tags_));
    PetscCall(PetscViewerHDF5PopGroup(viewer));
    const PetscInt dim = dim_;
    const std::string groups = PackGroups(group_names_, group_dims_);
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "format", PETSC_STRING, MESH_H5_FORMAT));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "dim", PETSC_INT, &dim));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "nodes", PETSC_INT, &num_global_nodes_));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "cells", PETSC_INT, &num_global_cells_));
    PetscInt vertices = 0;
    for (char owned : vertex_owned_)
      vertices += owned ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &vertices, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "vertices", PETSC_INT, &vertices));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "groups", PETSC_STRING, groups.c_str()));
    PetscCall(PetscViewerPopFormat(viewer));
  }
  std::string error;
  if (rank == 0 && std::rename(tmp.c_str(), path.c_str()) != 0)
    error = "-mesh_save '" + path + "': cannot rename '" + tmp + "' to it (" + std::strerror(errno) +
            "); expected a writable .h5 path";
  ProgressEnd();
  PetscCall(RaiseFromRoot(comm_, error));
  guard.Keep();
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::ReadH5Header(PetscViewer viewer, const std::string &path) {
  const std::string expected = "; expected a mesh written by -mesh_save";
  PetscFunctionBeginUser;
  PetscBool has_format = PETSC_FALSE, has_blocks = PETSC_FALSE;
  std::string format;
  PetscCall(PetscViewerHDF5HasAttribute(viewer, MESH_H5_GROUP, "format", &has_format));
  if (has_format) {
    char *value = nullptr;
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "format", PETSC_STRING, nullptr, &value));
    format = value;
    PetscCall(PetscFree(value));
  }
  const std::string blocks = std::string(MESH_H5_GROUP) + "/cell_sizes";
  PetscCall(PetscViewerHDF5HasDataset(viewer, blocks.c_str(), &has_blocks));
  // A file of signorini's first format (PETSc's DMPlex and point data, which PETSc 3.18 loads on rank 0) is read no
  // more.
  const std::string why = !has_format                    ? "no attribute 'format' in /signorini"
                          : format == "signorini mesh 1" ? "format 'signorini mesh 1', written by an earlier "
                                                           "signorini: write it again with -mesh_save"
                          : format != MESH_H5_FORMAT     ? "format '" + format + "', not '" + MESH_H5_FORMAT + "'"
                                                         : "no dataset /signorini/cell_sizes";
  PetscCheck(format == MESH_H5_FORMAT && has_blocks, comm_, PETSC_ERR_USER_INPUT,
             "-mesh_file '%s' is an HDF5 file but no signorini mesh (%s)%s", path.c_str(), why.c_str(),
             expected.c_str());
  PetscInt dim = 0;
  char *groups = nullptr;
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "dim", PETSC_INT, nullptr, &dim));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "nodes", PETSC_INT, nullptr, &num_global_nodes_));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "cells", PETSC_INT, nullptr, &num_global_cells_));
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "groups", PETSC_STRING, nullptr, &groups));
  const bool groups_ok = UnpackGroups(groups, group_names_, group_dims_);
  PetscCall(PetscFree(groups));
  PetscCheck(groups_ok && (dim == 2 || dim == 3), comm_, PETSC_ERR_USER_INPUT,
             "-mesh_file '%s': its /signorini attributes are damaged (dim %" PetscInt_FMT ")%s", path.c_str(), dim,
             expected.c_str());
  dim_ = (int)dim;
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::ViewH5Blocks(PetscViewer viewer) const {
  PetscFunctionBeginUser;
  const PetscInt nc = NumLocalCells(), nv = NumLocalVertices();
  PetscInt pstart, pend;
  PetscCall(DMPlexGetChart(dm_, &pstart, &pend));
  // The vertices' numbers in the file: the ranks' owned vertices in rank order, each rank's in its local order (on
  // one rank the DMPlex's own order, so that a run from the file on one rank is the run that wrote it).
  IS numbering; // the DMPlex's own, not ours to destroy
  const PetscInt *number;
  PetscCall(DMPlexGetVertexNumbering(dm_, &numbering));
  PetscCall(ISGetIndices(numbering, &number));
  std::vector<PetscInt> label_offsets;
  std::vector<int> labels;
  PetscCall(PointLabels(label_offsets, labels));
  const auto stored = [&](PetscInt v) { return (double)(number[v] >= 0 ? number[v] : -(number[v] + 1)); };
  std::vector<double> sizes, nodes, orig, face_sizes, faces, label_sizes, label_values;
  const auto add_labels = [&](PetscInt point) { // point's labels, as a count and the list
    const PetscInt p = point - pstart;
    label_sizes.push_back((double)(label_offsets[p + 1] - label_offsets[p]));
    for (PetscInt k = label_offsets[p]; k < label_offsets[p + 1]; ++k)
      label_values.push_back((double)labels[k]);
  };
  for (PetscInt c = 0; c < nc; ++c) {
    PetscInt n;
    const PetscInt *cv = CellVertices(c, n);
    sizes.push_back((double)n);
    for (PetscInt k = 0; k < n; ++k)
      nodes.push_back(stored(cv[k]));
    orig.push_back((double)cell_orig_[c]);
    face_sizes.push_back((double)(cell_face_offsets_[c + 1] - cell_face_offsets_[c]));
    for (PetscInt k = cell_face_offsets_[c]; k < cell_face_offsets_[c + 1]; ++k)
      faces.push_back((double)cell_face_codes_[k]);
    add_labels(cstart_ + c);
  }
  PetscCall(ViewValues(comm_, viewer, "cell_sizes", sizes));
  PetscCall(ViewValues(comm_, viewer, "cell_vertices", nodes));
  PetscCall(ViewValues(comm_, viewer, "cell_orig", orig));
  PetscCall(ViewValues(comm_, viewer, "cell_face_sizes", face_sizes));
  PetscCall(ViewValues(comm_, viewer, "cell_faces", faces));
  PetscCall(ViewValues(comm_, viewer, "cell_label_sizes", label_sizes));
  PetscCall(ViewValues(comm_, viewer, "cell_labels", label_values));
  std::vector<double> coords;
  orig.clear(), label_sizes.clear(), label_values.clear();
  for (PetscInt v = 0; v < nv; ++v) {
    if (number[v] < 0) continue;
    orig.push_back((double)vertex_orig_[v]);
    for (int d = 0; d < dim_; ++d)
      coords.push_back(X(v)[d]);
    add_labels(vstart_ + v);
  }
  PetscCall(ISRestoreIndices(numbering, &number));
  PetscCall(ViewValues(comm_, viewer, "vertex_orig", orig));
  PetscCall(ViewValues(comm_, viewer, "vertex_coordinates", coords, dim_));
  PetscCall(ViewValues(comm_, viewer, "vertex_label_sizes", label_sizes));
  PetscCall(ViewValues(comm_, viewer, "vertex_labels", label_values));
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::LoadH5Blocks(PetscViewer viewer, DMH &out) {
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscInt nvertices = 0;
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "vertices", PETSC_INT, nullptr, &nvertices));
  PetscCall(PetscViewerHDF5PushGroup(viewer, MESH_H5_GROUP));
  // This rank's block of the cells.
  PetscInt c0, nc;
  PetscCall(BlockOf(comm_, num_global_cells_, c0, nc));
  std::vector<double> sizes, nodes, orig, face_sizes, faces, label_sizes, label_values;
  PetscCall(LoadValues(comm_, viewer, "cell_sizes", nc, sizes));
  PetscCall(LoadValues(comm_, viewer, "cell_vertices", SumOf(sizes), nodes));
  PetscCall(LoadValues(comm_, viewer, "cell_orig", nc, orig));
  PetscCall(LoadValues(comm_, viewer, "cell_face_sizes", nc, face_sizes));
  PetscCall(LoadValues(comm_, viewer, "cell_faces", SumOf(face_sizes), faces));
  PetscCall(LoadValues(comm_, viewer, "cell_label_sizes", nc, label_sizes));
  PetscCall(LoadValues(comm_, viewer, "cell_labels", SumOf(label_sizes), label_values));
  // This rank's block of the vertices: it answers for them (their owner, file index, coordinates and labels).
  PetscInt v0, nb;
  PetscCall(BlockOf(comm_, nvertices, v0, nb));
  std::vector<double> vorig, vcoords, vlabel_sizes, vlabels;
  PetscCall(LoadValues(comm_, viewer, "vertex_orig", nb, vorig));
  PetscCall(LoadValues(comm_, viewer, "vertex_coordinates", nb * dim_, vcoords, dim_));
  PetscCall(LoadValues(comm_, viewer, "vertex_label_sizes", nb, vlabel_sizes));
  PetscCall(LoadValues(comm_, viewer, "vertex_labels", SumOf(vlabel_sizes), vlabels));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  std::vector<PetscInt> vlabel_offsets(nb + 1, 0);
  for (PetscInt i = 0; i < nb; ++i)
    vlabel_offsets[i + 1] = vlabel_offsets[i] + (PetscInt)vlabel_sizes[i];
  std::vector<PetscInt> first(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&v0, 1, MPIU_INT, first.data(), 1, MPIU_INT, comm_));
  first[size] = nvertices;
  const auto block_of = [&](PetscInt u) {
    return (PetscMPIInt)(std::upper_bound(first.begin(), first.end() - 1, u) - first.begin() - 1);
  };
  // A damaged file is refused on every rank, with the first rank's finding.
  {
    std::string bad;
    const double nlabels = (double)group_names_.size() + 1;
    const auto text = [](double x) {
      char t[32];
      std::snprintf(t, sizeof(t), "%g", x);
      return std::string(t);
    };
    for (PetscInt c = 0; c < nc && bad.empty(); ++c)
      if (!(sizes[c] >= dim_ + 1 && sizes[c] <= MAX_CELL_VERTICES))
        bad = "cell " + std::to_string(c0 + c) + " has " + text(sizes[c]) + " vertices";
    for (std::size_t k = 0; k < nodes.size() && bad.empty(); ++k)
      if (!(nodes[k] >= 0 && nodes[k] < (double)nvertices))
        bad = "a cell's vertex " + text(nodes[k]) + " is not one of its " + std::to_string(nvertices) + " vertices";
    for (const std::vector<double> *values : {&label_values, &vlabels})
      for (std::size_t k = 0; k < values->size() && bad.empty(); ++k)
        if (!((*values)[k] >= 0 && (*values)[k] < nlabels))
          bad = "it names label " + text((*values)[k]) + " of " + text(nlabels);
    PetscMPIInt who = bad.empty() ? size : rank;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &who, 1, MPI_INT, MPI_MIN, comm_));
    if (who < size) {
      PetscCall(Broadcast(comm_, who, bad));
      PetscCheck(false, comm_, PETSC_ERR_FILE_UNEXPECTED,
                 "-mesh_file '%s' is damaged: %s; expected a mesh written by -mesh_save", path_.c_str(), bad.c_str());
    }
  }
  std::vector<PetscInt> cell_nodes(nodes.begin(), nodes.end());
  nodes.clear();
  nodes.shrink_to_fit();

  // 1. The vertices this rank's cells use, asked of the ranks whose blocks hold them; a shared vertex is owned by the
  // lowest rank that uses it, a vertex no cell uses by the rank whose block holds it (as on one rank: the DMPlex of a
  // gmsh file has every node).
  std::vector<PetscInt> used(cell_nodes);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<std::vector<PetscInt>> ask(size);
  for (PetscInt u : used)
    ask[block_of(u)].push_back(u);
  std::vector<PetscInt> asked;
  std::vector<int> from;
  PetscCall(ExchangeBySource(comm_, ask, asked, from));
  std::vector<PetscMPIInt> owner(nb, size);
  for (PetscMPIInt r = 0; r < size; ++r)
    for (int i = from[r]; i < from[r + 1]; ++i)
      owner[asked[i] - v0] = std::min(owner[asked[i] - v0], r);
  std::vector<PetscInt> unused;
  for (PetscInt i = 0; i < nb; ++i)
    if (owner[i] == size) owner[i] = rank, unused.push_back(v0 + i);
  // This rank's vertices: those its cells use and its unused ones, in the file's order (the DMPlex's points nc on).
  std::vector<PetscInt> local(used);
  local.insert(local.end(), unused.begin(), unused.end());
  std::sort(local.begin(), local.end());
  const auto local_of = [&](PetscInt u) {
    return (PetscInt)(std::lower_bound(local.begin(), local.end(), u) - local.begin());
  };
  const PetscInt nv = (PetscInt)local.size();

  // 2. The owners tell the blocks' ranks their point of each vertex they own, for the other ranks' point SF.
  std::vector<std::vector<PetscInt>> owners_send(size);
  std::vector<std::vector<PetscInt>> reply(size);
  for (PetscMPIInt r = 0; r < size; ++r)
    for (int i = from[r]; i < from[r + 1]; ++i)
      reply[r].push_back(owner[asked[i] - v0]);
  std::vector<PetscInt> owner_of_used;
  std::vector<int> from_reply;
  PetscCall(ExchangeBySource(comm_, reply, owner_of_used, from_reply));
  // owner_of_used follows ask's order: block by block, each block's in used's order.
  std::vector<PetscMPIInt> vertex_owner(nv, rank);
  {
    std::size_t k = 0;
    for (PetscMPIInt r = 0; r < size; ++r)
      for (PetscInt u : ask[r])
        vertex_owner[local_of(u)] = (PetscMPIInt)owner_of_used[k++];
  }
  for (PetscInt i = 0; i < nv; ++i)
    if (vertex_owner[i] == rank)
      owners_send[block_of(local[i])].insert(owners_send[block_of(local[i])].end(), {local[i], nc + i});
  std::vector<PetscInt> owned_points;
  PetscCall(ExchangeBySource(comm_, owners_send, owned_points, from_reply));
  std::vector<PetscInt> owner_point(nb, -1);
  for (std::size_t i = 0; i < owned_points.size(); i += 2)
    owner_point[owned_points[i] - v0] = owned_points[i + 1];

  // 3. Each asking rank gets, in the order it asked, the owner's point, the file index and the labels (integers), and
  // the coordinates.
  std::vector<std::vector<PetscInt>> info(size);
  std::vector<std::vector<double>> xyz(size);
  for (PetscMPIInt r = 0; r < size; ++r)
    for (int i = from[r]; i < from[r + 1]; ++i) {
      const PetscInt b = asked[i] - v0;
      info[r].insert(info[r].end(), {owner_point[b], (PetscInt)vorig[b], vlabel_offsets[b + 1] - vlabel_offsets[b]});
      for (PetscInt k = vlabel_offsets[b]; k < vlabel_offsets[b + 1]; ++k)
        info[r].push_back((PetscInt)vlabels[k]);
      for (int d = 0; d < dim_; ++d)
        xyz[r].push_back(vcoords[dim_ * b + d]);
    }
  std::vector<PetscInt> got;
  std::vector<double> got_xyz;
  PetscCall(ExchangeBySource(comm_, info, got, from_reply));
  PetscCall(ExchangeBySource(comm_, xyz, got_xyz, from_reply));
  std::vector<PetscInt> remote_point(nv, -1);
  vertex_orig_.assign(nv, -1);
  coords_.assign((std::size_t)dim_ * nv, 0.0);
  std::vector<std::vector<PetscInt>> label_points(group_names_.size() + 1);
  const auto add_labels = [&](PetscInt point, const auto *g, PetscInt n) { // labels as read (double) or sent
    for (PetscInt k = 0; k < n; ++k)
      label_points[(std::size_t)g[k]].push_back(point);
  };
  {
    std::size_t k = 0, x = 0;
    for (PetscMPIInt r = 0; r < size; ++r)
      for (PetscInt u : ask[r]) {
        const PetscInt i = local_of(u), n = got[k + 2];
        remote_point[i] = got[k], vertex_orig_[i] = got[k + 1];
        add_labels(nc + i, got.data() + k + 3, n);
        k += 3 + n;
        for (int d = 0; d < dim_; ++d)
          coords_[dim_ * i + d] = got_xyz[x++];
      }
  }
  for (PetscInt u : unused) {
    const PetscInt i = local_of(u), b = u - v0;
    vertex_orig_[i] = (PetscInt)vorig[b];
    add_labels(nc + i, vlabels.data() + vlabel_offsets[b], vlabel_offsets[b + 1] - vlabel_offsets[b]);
    for (int d = 0; d < dim_; ++d)
      coords_[dim_ * i + d] = vcoords[dim_ * b + d];
  }

  PetscCall(PetscInfo(nullptr,
                      "read cells %" PetscInt_FMT " to %" PetscInt_FMT " of %" PetscInt_FMT ", vertices %" PetscInt_FMT
                      " to %" PetscInt_FMT " of %" PetscInt_FMT "; %" PetscInt_FMT " vertices local (LoadH5Blocks)\n",
                      c0, c0 + nc, num_global_cells_, v0, v0 + nb, nvertices, nv));
  // 4. The DMPlex of this rank's cells and vertices (as BuildSerialDM), its point SF to the vertices' owners.
  DMH dm;
  PetscCall(DMPlexCreate(comm_, dm.out()));
  PetscCall(DMSetDimension(dm, dim_));
  PetscCall(DMPlexSetChart(dm, 0, nc + nv));
  for (PetscInt c = 0; c < nc; ++c)
    PetscCall(DMPlexSetConeSize(dm, c, (PetscInt)sizes[c]));
  PetscCall(DMSetUp(dm));
  cell_offsets_.assign(1, 0);
  cell_vertices_.clear();
  std::vector<PetscInt> cone(MAX_CELL_VERTICES);
  for (PetscInt c = 0, k = 0; c < nc; ++c) {
    const int n = (int)sizes[c];
    for (int j = 0; j < n; ++j, ++k) {
      const PetscInt i = local_of(cell_nodes[k]);
      cone[j] = nc + i;
      cell_vertices_.push_back(vertex_orig_[i]);
    }
    cell_offsets_.push_back((PetscInt)cell_vertices_.size());
    if (dim_ == 3) PetscCall(DMPlexInvertCell(CellPolytope3D(n), cone.data()));
    PetscCall(DMPlexSetCone(dm, c, cone.data()));
  }
  PetscCall(DMPlexSymmetrize(dm));
  PetscCall(DMPlexStratify(dm));
  PetscCall(DMPlexComputeCellTypes(dm));
  PetscCall(DMPlexBuildCoordinatesFromCellList(dm, dim_, coords_.data()));
  {
    std::vector<PetscInt> leaves;
    std::vector<PetscSFNode> roots;
    for (PetscInt i = 0; i < nv; ++i)
      if (vertex_owner[i] != rank) {
        leaves.push_back(nc + i);
        roots.push_back({vertex_owner[i], remote_point[i]});
      }
    PetscSF sf;
    PetscCall(PetscSFCreate(comm_, &sf));
    PetscCall(PetscSFSetGraph(sf, nc + nv, (PetscInt)leaves.size(), leaves.data(), PETSC_COPY_VALUES, roots.data(),
                              PETSC_COPY_VALUES));
    PetscCall(DMSetPointSF(dm, sf));
    PetscCall(PetscSFDestroy(&sf));
  }
  for (PetscInt c = 0, k = 0; c < nc; ++c) {
    add_labels(c, label_values.data() + k, (PetscInt)label_sizes[c]);
    k += (PetscInt)label_sizes[c];
  }
  PetscCall(SetGroupLabels(dm, label_points));
  // The point arrays PackPointData carries through the distribution.
  vstart_ = nc;
  cstart_ = 0;
  cell_orig_.resize(nc);
  for (PetscInt c = 0; c < nc; ++c)
    cell_orig_[c] = (PetscInt)orig[c];
  cell_face_offsets_.assign(1, 0);
  cell_face_codes_.clear();
  for (PetscInt c = 0, k = 0; c < nc; ++c) {
    for (PetscInt j = 0; j < (PetscInt)face_sizes[c]; ++j)
      cell_face_codes_.push_back((PetscInt)faces[k++]);
    cell_face_offsets_.push_back((PetscInt)cell_face_codes_.size());
  }
  coords_.clear();
  out = std::move(dm);
  PetscFunctionReturn(0);
}

PetscErrorCode Mesh::LoadH5(const MeshOptions &opts) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::string path, error;
  const std::string expected = "; expected a mesh written by -mesh_save";
  if (rank == 0) {
    path = FindMeshFile(opts, path_, error);
    if (!path.empty()) {
      const std::string why = CheckHdf5Signature(path);
      if (!why.empty()) error = "-mesh_file '" + path + "': " + why + expected;
    }
  }
  PetscCall(RaiseFromRoot(comm_, error));
  ProgressBegin(("reading " + opts.file + " (every rank its part)").c_str());
  PetscCall(Broadcast(comm_, 0, path));
  PetscCall(Broadcast(comm_, 0, path_));

  ViewerH viewer;
  PetscCall(PetscViewerHDF5Open(comm_, path.c_str(), FILE_MODE_READ, viewer.out()));
  PetscCall(ReadH5Header(viewer, path));

  DMH dm;
  PetscCall(LoadH5Blocks(viewer, dm));
  PetscCall(PetscViewerHDF5PushGroup(viewer, MESH_H5_GROUP));
  PetscCall(LoadBlock(comm_, viewer, "node_tags", num_global_nodes_, node_tags_));
  PetscCall(LoadBlock(comm_, viewer, "cell_tags", num_global_cells_, cell_tags_));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  viewer.Reset();
  ProgressEnd();

  // Partitioned in parallel: METIS (the default for a gmsh file) would need the whole mesh on one rank.
  ProgressBegin("partition and distribution");
  PetscCall(ParallelPartition(dm, opts.partitioner));
  PetscCall(Distribute(dm));
  ProgressEnd();
  PetscCall(KeepDistributed(dm));
  PetscFunctionReturn(0);
}

} // namespace signorini
