// Meshing a gmsh .geo file in a child process, so that a gmsh crash or a mesh too large for memory is an input error.
#pragma once

#include <string>

namespace signorini {

/// What MeshGeo needs besides the file.
struct GeoMeshing {
  double size_factor = 1.0; ///< -mesh_size_factor (Mesh.MeshSizeFactor before the .geo is read)
  double max_cells = 0;     ///< -mesh_max_cells: refuse a mesh estimated larger (0: no limit)
};

/// Meshes the .geo file geo in a forked child process with gmsh and writes the mesh to a temporary binary .msh 4.1
/// (every element, physical groups and names kept), whose path is returned in msh; the caller removes it. Before
/// meshing the surfaces the child estimates the cell count from the 1D mesh (see EstimateCells) and refuses a mesh
/// above max_cells. Returns "" on success, else one error message naming the file: gmsh's own error, the estimate
/// and the limit, or the signal that ended gmsh with the meshing algorithm to change. Serial: call on one rank only;
/// the child calls no MPI.
std::string MeshGeo(const std::string &geo, const GeoMeshing &meshing, std::string &msh);

/// gmsh's last error message, or fallback when it has none. Call where gmsh is initialised.
std::string LastGmshError(const std::string &fallback);

/// Cell count of a 2D mesh of a region of area A whose boundary is divided into n segments of total length length:
/// triangles of side h = length / n (the mean boundary size) cover A with 4 A / (sqrt(3) h^2) cells.
double EstimateCells(double area, double length, double n);

/// The default of -mesh_max_cells: physical memory over the measured peak memory per cell of a whole run (3.2 kB,
/// the default solver on one rank at 2M cells), so a larger mesh cannot finish on this machine.
double DefaultMaxCells();

} // namespace signorini
