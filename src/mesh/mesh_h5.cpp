// Writing the distributed mesh to PETSc's DMPlex HDF5 format (-mesh_save) and reading it back on any number of ranks
// (a .h5 -mesh_file): PETSc 3.18 loads its topology on rank 0, then PTScotch partitions it.
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

const char *const POINT_DATA = "point_data";

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

/// Sends each rank its records (rec values each) from out[rank] and returns what every rank sent here. Collective.
PetscErrorCode Exchange(MPI_Comm comm, int rec, const std::vector<std::vector<PetscInt>> &out,
                        std::vector<PetscInt> &in) {
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> send_counts(size), recv_counts(size), send_offsets(size + 1, 0), recv_offsets(size + 1, 0);
  for (int r = 0; r < size; ++r) send_counts[r] = (int)out[r].size();
  PetscCallMPI(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm));
  for (int r = 0; r < size; ++r) {
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
    recv_offsets[r + 1] = recv_offsets[r] + recv_counts[r];
  }
  std::vector<PetscInt> send(send_offsets[size]);
  for (int r = 0; r < size; ++r) std::copy(out[r].begin(), out[r].end(), send.begin() + send_offsets[r]);
  in.resize(recv_offsets[size]);
  PetscCallMPI(MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPIU_INT, in.data(),
                             recv_counts.data(), recv_offsets.data(), MPIU_INT, comm));
  PetscAssert(in.size() % rec == 0, comm, PETSC_ERR_PLIB, "incomplete records");
  PetscFunctionReturn(0);
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
    // The point data on a clone of the DM that carries its section.
    DMH point_dm;
    SectionH sec;
    VecH data;
    PetscCall(DMClone(dm_, point_dm.out()));
    PetscCall(PetscObjectSetName((PetscObject)point_dm.get(), MESH_H5_POINT_DM));
    PetscCall(PackPointData(dm_, true, sec, data));
    PetscCall(DMSetLocalSection(point_dm, sec));
    PetscCall(PetscObjectSetName((PetscObject)data.get(), POINT_DATA));
    PetscCall(DMPlexSectionView(dm_, viewer, point_dm));
    PetscCall(DMPlexLocalVectorView(dm_, viewer, point_dm, data));
    // The file's tags in the file's order, and what the DMPlex does not say.
    PetscCall(PetscViewerHDF5PushGroup(viewer, MESH_H5_GROUP));
    PetscCall(ViewBlock(comm_, viewer, "node_tags", num_global_nodes_, node_tags_));
    PetscCall(ViewBlock(comm_, viewer, "cell_tags", num_global_cells_, cell_tags_));
    PetscCall(PetscViewerHDF5PopGroup(viewer));
    const PetscInt dim = dim_;
    const std::string groups = PackGroups(group_names_, group_dims_);
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "format", PETSC_STRING, MESH_H5_FORMAT));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "dim", PETSC_INT, &dim));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "nodes", PETSC_INT, &num_global_nodes_));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, MESH_H5_GROUP, "cells", PETSC_INT, &num_global_cells_));
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
  PetscBool has_format = PETSC_FALSE, has_topology = PETSC_FALSE;
  std::string format;
  PetscCall(PetscViewerHDF5HasAttribute(viewer, MESH_H5_GROUP, "format", &has_format));
  if (has_format) {
    char *value = nullptr;
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, MESH_H5_GROUP, "format", PETSC_STRING, nullptr, &value));
    format = value;
    PetscCall(PetscFree(value));
  }
  const std::string point_data = std::string("/topologies/") + MESH_H5_DM + "/dms/" + MESH_H5_POINT_DM;
  PetscCall(PetscViewerHDF5HasGroup(viewer, point_data.c_str(), &has_topology));
  PetscCheck(format == MESH_H5_FORMAT && has_topology, comm_, PETSC_ERR_USER_INPUT,
             "-mesh_file '%s' is an HDF5 file but no signorini mesh (%s)%s", path.c_str(),
             !has_format ? "no attribute 'format' in /signorini"
             : format != MESH_H5_FORMAT ? ("format '" + format + "', not '" + MESH_H5_FORMAT + "'").c_str()
                                        : "no point data of DMPlex 'signorini_mesh'",
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
  ProgressBegin(("reading " + opts.file + " (PETSc's load: the topology on rank 0)").c_str());
  PetscCall(Broadcast(comm_, 0, path));
  PetscCall(Broadcast(comm_, 0, path_));

  ViewerH viewer;
  PetscCall(PetscViewerHDF5Open(comm_, path.c_str(), FILE_MODE_READ, viewer.out()));
  PetscCall(ReadH5Header(viewer, path));

  // PETSc's load. In PETSc 3.18 DMPlexTopologyLoad reads the whole topology on rank 0 (its source: "Force serial
  // load"), and the coordinates, labels and point data follow the points: rank 0 holds the whole mesh until it is
  // distributed, as from a .msh (the 3.9M-dof octant on 2 ranks: rank 0 906 MB after the topology, 3.0 GB after the
  // point data, rank 1 82 and 525 MB; docs/performance.md, twenty-seventh session). What the file saves is the
  // parsing of the .msh, the locality order and METIS on rank 0.
  DMH dm, point_dm;
  SFH file_to_local, point_data_sf;
  VecH data;
  PetscSection sec;
  PetscCall(PetscViewerPushFormat(viewer, PETSC_VIEWER_HDF5_PETSC));
  PetscCall(DMCreate(comm_, dm.out()));
  PetscCall(DMSetType(dm, DMPLEX));
  PetscCall(PetscObjectSetName((PetscObject)dm.get(), MESH_H5_DM));
  PetscCall(DMPlexTopologyLoad(dm, viewer, file_to_local.out()));
  PetscCall(DMPlexCoordinatesLoad(dm, viewer, file_to_local));
  PetscCall(DMPlexLabelsLoad(dm, viewer, file_to_local));
  PetscCall(DMClone(dm, point_dm.out()));
  PetscCall(PetscObjectSetName((PetscObject)point_dm.get(), MESH_H5_POINT_DM));
  {
    SectionH empty; // filled by DMPlexSectionLoad (a section of its own, not the clone's default)
    PetscCall(PetscSectionCreate(comm_, empty.out()));
    PetscCall(DMSetLocalSection(point_dm, empty));
  }
  PetscCall(DMPlexSectionLoad(dm, viewer, point_dm, file_to_local, nullptr, point_data_sf.out()));
  PetscCall(DMGetLocalSection(point_dm, &sec));
  PetscCall(DMCreateLocalVector(point_dm, data.out()));
  PetscCall(PetscObjectSetName((PetscObject)data.get(), POINT_DATA));
  PetscCall(DMPlexLocalVectorLoad(dm, viewer, point_dm, point_data_sf, data));
  PetscCall(PetscViewerHDF5PushGroup(viewer, MESH_H5_GROUP));
  PetscCall(LoadBlock(comm_, viewer, "node_tags", num_global_nodes_, node_tags_));
  PetscCall(LoadBlock(comm_, viewer, "cell_tags", num_global_cells_, cell_tags_));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerPopFormat(viewer));
  viewer.Reset();
  PetscInt file_dim;
  PetscCall(DMGetDimension(dm, &file_dim));
  PetscCheck(file_dim == dim_, comm_, PETSC_ERR_USER_INPUT,
             "-mesh_file '%s': a DMPlex of dimension %" PetscInt_FMT " where /signorini says %d%s", path.c_str(),
             file_dim, dim_, expected.c_str());
  PetscCall(UnpackPointData(dm, sec, data));
  data.Reset();
  point_data_sf.Reset();
  point_dm.Reset();
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
