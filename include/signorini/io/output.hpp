// Output (prefix -output_): HDF5 + XDMF for ParaView (one step per load step; the body, the obstacle and the contact
// boundary as three grids of solution.xdmf, and each in an XDMF file of its own), the per-node CSV table keyed by the
// mesh file's node tags, and summary.json. Everything is written into DIR/incomplete/ and published with one rename
// only when the run succeeds (output_directory.hpp), so a failed or killed run never leaves files that look complete
// nor replaces a good earlier output. Every rank writes its block of the file's node and cell order (HDF5 collectively
// through MPI-IO, nodes.csv with MPI-IO), so the files are the same for any number of ranks and no rank holds a whole
// table; the obstacle and the contact boundary are small and rank 0 writes them.
#pragma once

#include "signorini/io/file_rows.hpp"
#include "signorini/io/hdf5_file.hpp"
#include "signorini/io/output_directory.hpp"
#include "signorini/mesh/mesh.hpp"
#include "signorini/obstacles/obstacle.hpp"

#include <petscsys.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace signorini {

struct OutputOptions {
  std::string dir; ///< -output_dir: where to write (default: nothing is written)
};

[[nodiscard]] PetscErrorCode ReadOutputOptions(MPI_Comm comm, OutputOptions &opts);

/// A field on the vertices or the cells, ncomp values per local vertex (cell), named as in the HDF5 file. A vertex
/// field with on_contact is written on the contact-boundary grid too. A field with fill has its values made by it when
/// it is written (WriteStep), so that a step's fields are in memory one at a time (the cell fields of 1M cells take
/// 100 MB together); fill is collective when the writer's caller is.
struct Field {
  std::string name;
  int ncomp = 1;
  bool on_cells = false;
  std::vector<double> values;
  bool on_contact = false;
  std::function<PetscErrorCode(std::vector<double> &)> fill = nullptr;
};

class OutputWriter {
public:
  /// Prepares DIR/incomplete (removing a stale one); checks that DIR can be written. Collective.
  [[nodiscard]] PetscErrorCode Open(const Mesh &mesh, const OutputOptions &opts);
  bool Enabled() const { return !opts_.dir.empty(); }
  /// Records the obstacle's facets for the obstacle grid: polylines in 2D, triangulated surfaces in 3D (the triangles
  /// of meshed surfaces; planes and cylinders over the extent of the body's bounding box `body`, spheres whole). Call
  /// on every rank before WriteStep.
  void SetObstacle(const Obstacle &obstacle, const Box &body);
  /// Records the contact boundary: the boundary edges whose two vertices are candidates (candidate: per local
  /// vertex), the edges that carry contact pressure, gathered on rank 0 in the order of their vertices' file indices.
  /// Collective; call before WriteStep.
  [[nodiscard]] PetscErrorCode SetContactBoundary(const std::vector<char> &candidate);
  /// Writes the fields of one load step (load factor t) and rewrites the XDMF files. Collective.
  [[nodiscard]] PetscErrorCode WriteStep(PetscInt step, double t, const std::vector<Field> &fields);
  /// Writes the node table (vertex fields: name, ncomp) of the final state. Collective.
  [[nodiscard]] PetscErrorCode WriteNodeTable(const std::vector<Field> &fields);
  /// Writes summary.json (its text is given) and moves everything into DIR. Collective.
  [[nodiscard]] PetscErrorCode Publish(const std::string &summary_json);
  /// Path of the staging directory (for messages).
  std::string Staging() const { return StagingDirectory(opts_.dir); }

private:
  /// Sets up the moves of vertex and cell rows to the blocks of the file's order, and the shape of the topology.
  /// Collective.
  [[nodiscard]] PetscErrorCode BuildRows();
  [[nodiscard]] PetscErrorCode WriteXdmf() const;
  /// Writes the mesh, the obstacle and the contact boundary into the new HDF5 file. Collective.
  [[nodiscard]] PetscErrorCode WriteGeometry(Hdf5File &file) const;
  /// Writes /mesh/topology: the cells' vertices in the file's node numbering, each preceded by its XDMF type when the
  /// mesh mixes cell types. Collective.
  [[nodiscard]] PetscErrorCode WriteTopology(Hdf5File &file) const;
  /// This rank's block of the nodes: coordinates (three per node) and file tags. Collective.
  [[nodiscard]] PetscErrorCode NodeBlocks(std::vector<double> &xyz, std::vector<long long> &tags) const;
  const Mesh *mesh_ = nullptr;
  OutputOptions opts_;
  struct StepInfo {
    PetscInt step;
    double t;
    std::vector<Field> layout; // names and sizes only
  };
  std::vector<StepInfo> steps_;
  /// The XDMF of one grid named `name` (its Uniform Grid element, open: the caller adds what else the grid holds and
  /// closes it): the body with the fields of step s, the obstacle, the contact boundary with its fields of step s.
  std::string BodyGrid(const std::string &name, const StepInfo &s) const;
  std::string ObstacleGrid(const std::string &name) const;
  std::string ContactGrid(const std::string &name, const StepInfo &s) const;
  std::vector<std::array<double, 3>> obstacle_points_; ///< the corners of each obstacle cell (x, y, z)
  int obstacle_cell_size_ = 2;                         ///< 2: segments of polylines (2D), 3: triangles (3D)
  FileRows node_rows_, cell_rows_;                     ///< owned vertices and cells to the blocks of the file's order
  FileRows contact_rows_;                              ///< the blocks' rows of the contact-boundary nodes to rank 0
  bool uniform_ = true;                 ///< every cell has cell_size_ vertices (else: an XDMF Mixed topology)
  int cell_size_ = 0;                   ///< vertices of the smallest cell
  PetscInt mixed_topology_size_ = 0;    ///< the length of a Mixed topology: the cells' vertices + 1 each
  std::vector<PetscInt> contact_nodes_; ///< rank 0: file indices of the contact-boundary nodes
  PetscInt contact_num_nodes_ = 0, contact_topology_size_ = 0; ///< every rank: contact nodes, length of the topology
  std::vector<long long> contact_faces_; ///< rank 0: the contact faces' vertices (positions in contact_nodes_), each
                                         ///< preceded by its XDMF type when contact_face_size_ is 0 (mixed sizes)
  /// Every rank: vertices per contact face (2 edges, 3 triangles, 4 quadrilaterals; 0 when mixed), number of faces.
  int contact_face_size_ = 0, contact_num_faces_ = 0;
};

} // namespace signorini
