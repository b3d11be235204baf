// The faces of each cell type, in gmsh's vertex order and oriented outwards.
#pragma once

#include <array>

namespace signorini {

/// The faces (codimension 1) of a cell with n vertices, as positions in gmsh's vertex order, each oriented outwards
/// for a cell of positive orientation (CheckAndOrientCells) as Face is: the edges of a counter-clockwise triangle or
/// quadrilateral; the triangles and quadrilaterals of a tetrahedron, pyramid (base 0-3, apex 4) or hexahedron (bottom
/// 0-3, top 4-7), in cyclic order with their right-hand normal pointing out of the cell.
struct CellFaceTable {
  int count;
  std::array<int, 6> size;
  std::array<std::array<int, 4>, 6> v;
};
inline const CellFaceTable &CellFaces(int dim, int n) {
  static const CellFaceTable triangle{3, {2, 2, 2}, {{{0, 1}, {1, 2}, {2, 0}}}};
  static const CellFaceTable quadrilateral{4, {2, 2, 2, 2}, {{{0, 1}, {1, 2}, {2, 3}, {3, 0}}}};
  static const CellFaceTable tetrahedron{4, {3, 3, 3, 3}, {{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}}};
  static const CellFaceTable pyramid{5, {4, 3, 3, 3, 3}, {{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}}};
  static const CellFaceTable hexahedron{
      6, {4, 4, 4, 4, 4, 4}, {{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}}};
  if (dim == 2) return n == 3 ? triangle : quadrilateral;
  return n == 4 ? tetrahedron : n == 5 ? pyramid : hexahedron;
}

} // namespace signorini
