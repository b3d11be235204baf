// Boundary conditions and loads (prefix -bc_): Dirichlet per component on any physical group, tractions and
// pressure on physical curves (2D) or surfaces (3D), point forces on node sets, a body force.
#pragma once

#include <petscsys.h>

#include <string>
#include <vector>

namespace signorini {

struct DirichletSpec {
  std::string group;
  int component = 0;
  double value = 0;
  std::string item; ///< the -bc_dirichlet item as written, for messages
};

/// A load on a physical group: a vector (traction, point force) or a scalar (pressure).
struct LoadSpec {
  std::string group;
  std::vector<double> value;
  std::string item; ///< the item as written, for messages
};

struct BoundaryConditions {
  std::vector<DirichletSpec> dirichlet; ///< -bc_dirichlet GROUP:x[=v][:y[=v]][:z[=v]],...
  std::vector<LoadSpec> traction;       ///< -bc_traction GROUP:tx:ty[:tz],... (force per unit area, reference config.)
  std::vector<LoadSpec> pressure;       ///< -bc_pressure GROUP:p,...          (along the inward normal)
  std::vector<LoadSpec> point_force;    ///< -bc_point_force GROUP:fx:fy[:fz],... (force on every node of the group)
  std::vector<double> body_force;       ///< -bc_body_force bx,by[,bz]         (force per unit volume)
};

/// Reads and validates the -bc_ options for a mesh of dimension dim (2 or 3; 0 only lists them for -help). Group names
/// are checked against the mesh later, when the conditions are applied. Collective.
[[nodiscard]] PetscErrorCode ReadBoundaryConditions(MPI_Comm comm, int dim, BoundaryConditions &bc);

/// Largest ratio of a load or prescribed displacement to the problem's scale (a strain-like number): beyond it the
/// displacements exceed the default gap tolerance (1e-9 x diagonal) by 1e15, so rounding decides the active set, and
/// far beyond it the system overflows.
constexpr double LOAD_SCALE_MAX = 1e6;

/// Refuses loads and prescribed displacements out of scale with the body (diagonal L) and the material (Young's
/// modulus E, thickness t): |traction|, |pressure| <= LOAD_SCALE_MAX E; |point force| <= LOAD_SCALE_MAX E t L;
/// |body force| <= LOAD_SCALE_MAX E / L; |prescribed displacement| <= LOAD_SCALE_MAX L. Collective.
[[nodiscard]] PetscErrorCode CheckLoadScale(MPI_Comm comm, const BoundaryConditions &bc, double L, double E, double t);

/// Parses one Dirichlet entry "GROUP:x=0:y=-0.1" (components x, y, z, or several letters such as xy sharing one
/// value; the value defaults to 0). Returns an empty string on success, else what is wrong.
std::string ParseDirichlet(const std::string &entry, int dim, std::vector<DirichletSpec> &out);

/// Parses one load entry "GROUP:v1[:v2...]" with exactly `count` finite numbers.
std::string ParseLoad(const std::string &entry, int count, const char *what, LoadSpec &out);

} // namespace signorini
