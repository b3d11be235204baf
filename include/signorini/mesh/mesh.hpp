// The distributed mesh: a DMPlex built from the gmsh file, labelled by physical-group names, partitioned and
// distributed, with the per-rank arrays the element loops use.
#pragma once

#include "signorini/core/handle.hpp"
#include "signorini/options/option_paths.hpp"
#include "signorini/mesh/serial_mesh.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

/// Most vertices of a cell (the hexahedron).
constexpr int MAX_CELL_VERTICES = 8;
/// The DMPlex polytope of a 3D cell of n vertices (a tetrahedron, a pyramid or a hexahedron).
inline DMPolytopeType CellPolytope3D(int n) {
  return n == 4 ? DM_POLYTOPE_TETRAHEDRON : n == 5 ? DM_POLYTOPE_PYRAMID : DM_POLYTOPE_HEXAHEDRON;
}

/// A face of the cells (codimension 1) as local vertex indices, oriented outwards: an edge in 2D with the body on the
/// left of v[0] -> v[1]; a triangle or quadrilateral in 3D, vertices in cyclic order, its right-hand normal pointing
/// out of the body.
struct Face {
  int n = 0;
  std::array<PetscInt, 4> v{};
  PetscInt cell = -1; ///< the local cell whose face it is
};

/// Mesh options (prefix -mesh_), read by Mesh::Create.
struct MeshOptions {
  std::string file;               ///< -mesh_file: gmsh .msh or .geo, or a .h5 written by -mesh_save, as given
  PathCandidates file_candidates; ///< where file is looked for (relative to the options file that set it, then here)
  double size_factor = 1.0;       ///< -mesh_size_factor: scales the mesh size of a .geo
  double max_cells = 0;           ///< -mesh_max_cells: a .geo estimated to mesh into more cells is refused
  std::string partitioner = "metis"; ///< -mesh_partitioner: metis | ptscotch | simple
  bool partitioner_set = false;      ///< -mesh_partitioner was given (a .h5 replaces the default metis by ptscotch)
  std::string save;                  ///< -mesh_save: the .h5 file the distributed mesh is written to ("" for none)
};

[[nodiscard]] PetscErrorCode ReadMeshOptions(MPI_Comm comm, const std::string &default_file, MeshOptions &opts);

/// The file opts.file names (looked for in opts.file_candidates), as found, and absolute_path; "" and error set when
/// there is none. Local.
std::string FindMeshFile(const MeshOptions &opts, std::string &absolute_path, std::string &error);

class Mesh {
public:
  /// Reads the gmsh file on rank 0, builds, labels, partitions and distributes the DMPlex; or reads a .h5 written by
  /// -mesh_save, every rank its part (LoadH5), and partitions it with PTScotch. Then writes -mesh_save if given
  /// (SaveH5).
  /// Collective.
  [[nodiscard]] PetscErrorCode Create(MPI_Comm comm, const MeshOptions &opts);

  MPI_Comm Comm() const { return comm_; }
  /// The distributed DMPlex, until ReleaseDM().
  DM Dm() const { return dm_; }
  /// Frees the DMPlex (80 MB at 1M cells in 2D): nothing after the set-up needs it, since the local arrays, the
  /// vertex SF and the groups' vertices and faces are the mesh's own. Collective.
  void ReleaseDM() { dm_.Reset(); }
  /// Shared vertices: a root on the rank that owns a vertex, a leaf on every rank that has it as a ghost, both indexed
  /// by local vertex.
  PetscSF VertexSF() const { return vertex_sf_; }
  int Dim() const { return dim_; }
  /// The file read (absolute, after the options file's directory and the current one were tried), on every rank.
  const std::string &Path() const { return path_; }
  PetscInt NumLocalVertices() const { return (PetscInt)vertex_owned_.size(); }
  PetscInt NumLocalCells() const { return (PetscInt)cell_orig_.size(); }
  PetscInt NumGlobalNodes() const { return num_global_nodes_; }
  PetscInt NumGlobalCells() const { return num_global_cells_; }
  bool Owned(PetscInt v) const { return vertex_owned_[v]; }
  /// Index of local vertex v (or cell c) in the file's node (cell) order.
  PetscInt VertexOriginal(PetscInt v) const { return vertex_orig_[v]; }
  PetscInt CellOriginal(PetscInt c) const { return cell_orig_[c]; }
  const double *X(PetscInt v) const { return &coords_[dim_ * v]; }
  /// Local vertex indices of cell c in gmsh's order (counter-clockwise in 2D; positive Jacobian in 3D).
  const PetscInt *CellVertices(PetscInt c, PetscInt &n) const {
    n = cell_offsets_[c + 1] - cell_offsets_[c];
    return &cell_vertices_[cell_offsets_[c]];
  }
  const std::vector<std::string> &GroupNames() const { return group_names_; }
  /// Dimension of each group of GroupNames().
  const std::vector<int> &GroupDims() const { return group_dims_; }
  /// The groups of the mesh's dimension (physical surfaces in 2D, volumes in 3D) that hold local cell c, as indices
  /// into GroupNames(), ascending: n of them (none, one, or several when the file lists a cell in several groups).
  const int *CellGroups(PetscInt c, int &n) const {
    n = cell_group_offsets_[c + 1] - cell_group_offsets_[c];
    return &cell_groups_[cell_group_offsets_[c]];
  }
  /// Bodies: the connected components of the cells (cells sharing a vertex are in one body), numbered 0, 1, ... by
  /// the smallest file cell index they hold, the same on any number of ranks. A one-body mesh has body 0 only.
  PetscInt NumBodies() const { return num_bodies_; }
  PetscInt CellBody(PetscInt c) const { return cell_body_[c]; }
  /// The body of local vertex v (owned or ghost).
  PetscInt VertexBody(PetscInt v) const { return vertex_body_[v]; }
  /// The file's tags of the nodes (cells) of this rank's block of file indices (BlockOf over NumGlobalNodes(),
  /// NumGlobalCells()): NodeTagsBlock()[i] is the tag of the file's node start + i.
  const std::vector<std::size_t> &NodeTagsBlock() const { return node_tags_; }
  const std::vector<std::size_t> &CellTagsBlock() const { return cell_tags_; }

  /// Local vertices (owned and ghost) of the physical group `name` (kept since Create); an unknown name is an error
  /// listing the names, which starts with `input` (the option and item that named the group) when given. Collective.
  [[nodiscard]] PetscErrorCode GroupVertices(const std::string &name, std::vector<PetscInt> &vertices,
                                             const std::string &input = "") const;
  /// Owned faces of a physical curve (2D) or surface (3D), oriented outwards (Face); error if the group has another
  /// dimension (starting with `input`, as GroupVertices'). Collective.
  [[nodiscard]] PetscErrorCode GroupFaces(const std::string &name, std::vector<Face> &faces,
                                          const std::string &input = "") const;
  /// Local vertices on the boundary of the body. Collective.
  [[nodiscard]] PetscErrorCode BoundaryVertices(std::vector<PetscInt> &vertices) const;
  /// Owned faces on the boundary of the body, oriented outwards (Face). Collective.
  [[nodiscard]] PetscErrorCode BoundaryFaces(std::vector<Face> &faces) const;
  /// Outward normal of a face scaled by its length (2D) or its area (3D; exact for a planar face).
  void FaceNormal(const Face &f, double *normal) const;
  /// The bounding box of the whole body: lo and hi, three values each (0 for z in 2D). Collective.
  [[nodiscard]] PetscErrorCode BoundingBox(double *lo, double *hi) const;
  /// Sums a per-vertex quantity over the ranks that share a vertex, so that every copy holds the total. Collective.
  [[nodiscard]] PetscErrorCode SumShared(std::vector<double> &per_vertex) const;

private:
  /// Builds the DMPlex (cells and vertices) of the serial mesh on rank 0 (empty elsewhere), with vertex and cell
  /// labels, and the faces each cell carries; errors name file. Collective.
  [[nodiscard]] PetscErrorCode BuildSerialDM(const std::string &file, DM *dm);
  /// The faces of the serial mesh that the program needs, as (cell, code) with code = local face * (groups + 1) +
  /// label (a group's index, or the number of groups for the boundary): boundary faces (of one cell), and the
  /// elements of each group of dimension dim-1, each matched to a face of a cell. error: the first group element
  /// that is no cell face, or the first pair of folded cells. Rank 0.
  [[nodiscard]] PetscErrorCode FaceTable(std::vector<std::pair<int, PetscInt>> &tags, std::string &error) const;
  /// The faces each cell carries (cell_face_offsets_, cell_face_codes_ from FaceTable) and the points of each vertex
  /// label (label_points: a group's, then the boundary's) of the serial mesh; raises FaceTable's error naming file.
  /// Rank 0 (RunOnRoot).
  [[nodiscard]] PetscErrorCode SerialFaces(const std::string &file, std::vector<std::vector<PetscInt>> &label_points);
  [[nodiscard]] PetscErrorCode Partition(DM dm, const std::string &partitioner);
  /// METIS's partition of the serial mesh's dual graph into sizes.size() parts as PetscPartitionerShellSetPartition
  /// takes it: sizes (zero on entry) the cells of each part, points the cells part by part. Rank 0 (RunOnRoot).
  [[nodiscard]] PetscErrorCode MetisPartition(std::vector<PetscInt> &sizes, std::vector<PetscInt> &points) const;
  [[nodiscard]] PetscErrorCode Distribute(DMH &dm);
  /// Scotch on one thread, before each of PTScotch's partitions: the same partition every run.
  static void SingleThreadScotch();
  /// The data each point of dm carries (the file's index of a vertex; of a cell: its file index, its vertex count, its
  /// vertices in gmsh's order as file indices, then its face codes), as a section over dm's chart and a sequential
  /// vector (before BuildLocalArrays, while cell_vertices_ holds file indices).
  [[nodiscard]] PetscErrorCode PackPointData(DM dm, SectionH &sec, VecH &data) const;
  /// The point arrays (vstart_, cstart_, vertex_orig_, cell_orig_, cell vertices as file indices, face codes) from
  /// PackPointData's section and vector over dm.
  [[nodiscard]] PetscErrorCode UnpackPointData(DM dm, PetscSection sec, Vec data);
  /// Writes the distributed mesh to path in PETSc's DMPlex HDF5 format with signorini's blocks (ViewH5Blocks), the
  /// groups and the file's tags (mesh_h5.cpp), through a temporary file renamed at the end. Collective.
  [[nodiscard]] PetscErrorCode SaveH5(const std::string &path) const;
  /// SaveH5's blocks of signorini's own (format 2; mesh_h5.hpp): this rank's cells, then its owned vertices, each
  /// with what rebuilds them, in the DMPlex's order. Collective.
  [[nodiscard]] PetscErrorCode ViewH5Blocks(PetscViewer viewer) const;
  /// LoadH5's part that reads: every rank a block of the cells (BlockOf) and of the vertices, the vertices its cells
  /// use gathered from the ranks whose blocks hold them (the lowest such rank owns a shared vertex), and dm built
  /// from them with its point SF, coordinates, labels and point arrays (PackPointData's). Collective.
  [[nodiscard]] PetscErrorCode LoadH5Blocks(PetscViewer viewer, DMH &dm);
  /// The label of group g (LABEL_PREFIX + its name), or for g = the number of groups the boundary's.
  std::string GroupLabelName(std::size_t g) const;
  /// Creates on dm the labels of the groups and of the boundary (GroupLabelName) with value 1 on label_points[g]
  /// (sorted and made unique here). Local.
  [[nodiscard]] PetscErrorCode SetGroupLabels(DM dm, std::vector<std::vector<PetscInt>> &label_points) const;
  /// For each point of dm_'s chart (from its start), the labels (GroupLabelName's g) that hold it: labels from
  /// offsets[p] to offsets[p + 1]. Local.
  [[nodiscard]] PetscErrorCode PointLabels(std::vector<PetscInt> &offsets, std::vector<int> &labels) const;
  /// Reads a file written by SaveH5 (opts.file), every rank a part, and partitions and distributes it with
  /// opts.partitioner (ptscotch for the default metis, or simple). Collective.
  [[nodiscard]] PetscErrorCode LoadH5(const MeshOptions &opts);
  /// The graph of this rank's cells (before distribution) sharing a face, for a parallel partitioner: CSR over the
  /// local cells, neighbours numbered globally (rank by rank in rank order). Faces are matched on a rank chosen by a
  /// hash of their vertices' file indices. Collective.
  [[nodiscard]] PetscErrorCode DualGraph(std::vector<PetscInt> &offsets, std::vector<PetscInt> &adjacency) const;
  /// Sets the partitioner of dm (its cells spread over the ranks, PackPointData's arrays set): PETSc's simple split
  /// for "simple", else PTScotch on DualGraph, as a shell partition. Collective.
  [[nodiscard]] PetscErrorCode ParallelPartition(DM dm, const std::string &partitioner) const;
  /// Checks that viewer's file (path, for messages) is a signorini mesh and reads its /signorini attributes (dim_,
  /// the global counts, the groups). Collective.
  [[nodiscard]] PetscErrorCode ReadH5Header(PetscViewer viewer, const std::string &path);
  /// Create's path for a gmsh file (.msh, .geo): read on rank 0, labelled, partitioned, distributed. Collective.
  [[nodiscard]] PetscErrorCode ReadGmshMesh(const MeshOptions &opts);
  /// Takes the distributed dm as dm_ and builds the per-rank arrays (local arrays, vertex SF, the labels' vertices).
  /// Collective.
  [[nodiscard]] PetscErrorCode KeepDistributed(DMH &dm);
  [[nodiscard]] PetscErrorCode BuildLocalArrays();
  /// vertex_sf_ from the point SF of dm_. Collective.
  [[nodiscard]] PetscErrorCode BuildVertexSF();
  /// label_vertices_ for every group and the boundary (LabelVertices). Collective.
  [[nodiscard]] PetscErrorCode CacheLabelVertices();
  /// Local vertices of a label; cells: the label holds cells (a group of the mesh's dimension, not completed to its
  /// closure), whose vertices are gathered over the ranks. Collective when cells.
  [[nodiscard]] PetscErrorCode LabelVertices(const std::string &label, bool cells, std::vector<PetscInt> &vertices) const;
  [[nodiscard]] PetscErrorCode CheckGroup(const std::string &name, int required_dim, const std::string &input) const;
  /// cell_group_offsets_, cell_groups_ from the labels of the groups of the mesh's dimension on dm_. Local.
  [[nodiscard]] PetscErrorCode BuildCellGroups();
  /// cell_body_, vertex_body_, num_bodies_ (mesh_bodies.cpp). Collective.
  [[nodiscard]] PetscErrorCode BuildBodies();

  MPI_Comm comm_ = MPI_COMM_NULL;
  DMH dm_;
  int dim_ = 2;
  std::string path_;
  PetscInt vstart_ = 0, cstart_ = 0;
  PetscInt num_global_nodes_ = 0, num_global_cells_ = 0;
  std::vector<PetscInt> vertex_orig_, cell_orig_;
  std::vector<char> vertex_owned_;
  std::vector<double> coords_;
  std::vector<PetscInt> cell_offsets_, cell_vertices_;
  /// Faces each local cell carries (FaceTable's codes, CSR), and the faces of each label built from them (a group's
  /// index, then the boundary), on this rank's cells.
  std::vector<PetscInt> cell_face_offsets_, cell_face_codes_;
  std::vector<std::vector<Face>> label_faces_;
  std::vector<std::vector<PetscInt>> label_vertices_; ///< local vertices of each group, then of the boundary
  std::vector<int> cell_group_offsets_{0}, cell_groups_; ///< CellGroups, CSR over the local cells
  PetscInt num_bodies_ = 0;
  std::vector<PetscInt> cell_body_, vertex_body_;
  SFH vertex_sf_;
  std::vector<std::string> group_names_;
  std::vector<int> group_dims_;
  SerialMesh serial_; ///< the mesh as read, on rank 0 while Create runs
  std::vector<std::size_t> node_tags_, cell_tags_;
};

} // namespace signorini
