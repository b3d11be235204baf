// The mesh as read from a gmsh file on rank 0: nodes with their file tags, cells, named physical groups.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace signorini {

/// A physical group of the gmsh file: its name (or its number when unnamed), dimension, and what it holds, all as
/// indices into SerialMesh's node and cell arrays.
struct PhysicalGroup {
  std::string name;
  int dim = 0;
  int tag = 0;
  std::vector<int> nodes;          ///< every node of a group of points, curves or surfaces (sorted, unique; empty
                                   ///< for a group of cells, whose nodes are those of its cells)
  std::vector<int> edges;          ///< dim 1: node pairs of its line elements, flattened
  std::vector<int> cells;          ///< dimension of the mesh: cells of the group
  std::vector<int> face_offsets{0}; ///< dim 2 of a 3D mesh: CSR offsets into face_nodes
  std::vector<int> face_nodes;      ///< dim 2 of a 3D mesh: nodes of its triangles and quadrilaterals
};

/// The serial mesh. Nodes are the nodes used by cells, in the order gmsh returns them (the file order for format
/// 4.1, grouped by entity for 2.2); each keeps its file tag. Cells keep gmsh's vertex order, counter-clockwise in 2D and
/// with a positive Jacobian in 3D (tetrahedra; pyramids with their base counter-clockwise seen from the apex, the apex
/// last; hexahedra with two counter-clockwise quadrilaterals seen from above, bottom first).
struct SerialMesh {
  int dim = 2;
  std::vector<double> coords;              ///< dim values per node
  std::vector<std::size_t> node_tags;      ///< the file's own node tags
  std::vector<int> cell_offsets{0};        ///< CSR offsets into cell_nodes
  std::vector<int> cell_nodes;             ///< node indices of each cell, in gmsh's order (oriented)
  std::vector<std::size_t> cell_tags;      ///< the file's element tags
  std::vector<PhysicalGroup> groups;

  int NumNodes() const { return (int)node_tags.size(); }
  int NumCells() const { return (int)cell_tags.size(); }
  int CellSize(int c) const { return cell_offsets[c + 1] - cell_offsets[c]; }
};

/// Reads a gmsh .msh file (2.2 or 4.1, ASCII or binary) through the gmsh API, or meshes a .geo file with the given
/// size factor in a child process (MeshGeo: refused when estimated above max_cells, 0 for no limit). Serial: call on
/// one rank only. Returns an empty string on success, else the error message.
std::string ReadGmsh(const std::string &path, double size_factor, SerialMesh &mesh, double max_cells = 0);

/// Elements of one dimension read from a gmsh file (the facets of a meshed rigid obstacle): the nodes they use, with
/// three coordinates each, and the elements with their file tags and nodes in the file's order (which orients them).
struct ElementSet {
  std::vector<double> coords;         ///< 3 values per node
  std::vector<std::size_t> node_tags; ///< the file's node tags
  std::vector<int> offsets{0};        ///< CSR offsets into nodes
  std::vector<int> nodes;             ///< node indices of each element, in the file's order
  std::vector<std::size_t> tags;      ///< the file's element tags

  int NumElements() const { return (int)tags.size(); }
  int Size(int e) const { return offsets[e + 1] - offsets[e]; }
  const double *X(int node) const { return &coords[3 * node]; }
};

/// Reads the linear elements of dimension dim (1: 2-node lines; 2: 3-node triangles and 4-node quadrilaterals) of a
/// gmsh .msh file (or a .geo, meshed like ReadGmsh's), those of the physical group named group or, when group is
/// empty, every one. Errors (the returned message, empty on success, naming the file): an unreadable file, an unknown
/// group (listing the groups there are) or one of another dimension, elements of another type, and no element of
/// dimension dim (saying what the file holds instead). Serial: call on one rank only.
std::string ReadGmshElements(const std::string &path, int dim, const std::string &group, ElementSet &set);

/// Checks orientation and shape of every cell: a mesh whose cells are all clockwise (negative Jacobian in 3D) is
/// flipped; cells oriented against the rest, with zero area or volume, or not convex (a corner Jacobian of the other
/// sign) are errors. Returns an empty string on success.
std::string CheckAndOrientCells(SerialMesh &mesh);

} // namespace signorini
