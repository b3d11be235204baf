// Boundary conditions and loads (prefix -bc_): Dirichlet per component on any physical group, tractions and
// pressure on physical curves (2D) or surfaces (3D), point forces on node sets, a body force.
#pragma once

#include <petscsys.h>

#include <algorithm>
#include <string>
#include <vector>

namespace signorini {

/// The share of an item's value applied at the load steps' pseudo-time t in [0, 1] (docs/theory.md §6): an item
/// suffixed @T0:T1 (0 <= T0 < T1 <= 1) is applied with ramp(t) = clamp((t - T0) / (T1 - T0), 0, 1), nothing before T0
/// and all of it from T1 on; without a suffix the ramp is [0, 1], ramp(t) = t exactly (the proportional load path).
struct Ramp {
  double t0 = 0, t1 = 1;
  [[nodiscard]] double At(double t) const { return std::clamp((t - t0) / (t1 - t0), 0.0, 1.0); }
  [[nodiscard]] bool Proportional() const { return t0 == 0 && t1 == 1; }
  bool operator==(const Ramp &other) const { return t0 == other.t0 && t1 == other.t1; }
  bool operator!=(const Ramp &other) const { return !(*this == other); }
  /// The suffix as an item writes it ("@0.5:1"), "" for the proportional ramp.
  [[nodiscard]] std::string Suffix() const;
};

struct DirichletSpec {
  std::string group;
  int component = 0;
  double value = 0;
  std::string item; ///< the -bc_dirichlet item as written, for messages
  Ramp ramp;        ///< the item's ramp, shared by all its components
};

/// A load on a physical group: a vector (traction, point force) or a scalar (pressure).
struct LoadSpec {
  std::string group;
  std::vector<double> value;
  std::string item; ///< the item as written, for messages
  Ramp ramp;
};

/// Every item below may end with a ramp @T0:T1 (Ramp).
struct BoundaryConditions {
  std::vector<DirichletSpec> dirichlet; ///< -bc_dirichlet GROUP:x[=v][:y[=v]][:z[=v]],...
  std::vector<LoadSpec> traction;       ///< -bc_traction GROUP:tx:ty[:tz],... (force per unit area, reference config.)
  std::vector<LoadSpec> pressure;       ///< -bc_pressure GROUP:p,...          (along the inward normal)
  std::vector<LoadSpec> point_force;    ///< -bc_point_force GROUP:fx:fy[:fz],... (force on every node of the group)
  std::vector<double> body_force;       ///< -bc_body_force bx,by[,bz]         (force per unit volume)
  Ramp body_force_ramp;                 ///< -bc_body_force's ramp, after its last number
};

/// Whether some item with a nonzero value (load or prescribed displacement) applies a different share at the load
/// steps' pseudo-time t1 than at t0: false when every ramp is at rest over [t0, t1] (not started yet, or over).
[[nodiscard]] bool AnyRampMoves(const BoundaryConditions &bc, double t0, double t1);

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

/// Splits entry "TEXT[@T0:T1]" into TEXT (rest) and its ramp (the proportional one without a suffix). Returns an empty
/// string on success, else what is wrong with the ramp, quoting entry ("'top:5@1:0' has ramp '@1:0' ...").
std::string ParseRamp(const std::string &entry, std::string &rest, Ramp &ramp);

/// Parses one Dirichlet entry "GROUP:x=0:y=-0.1[@T0:T1]" (components x, y, z, or several letters such as xy sharing
/// one value; the value defaults to 0; the ramp applies to every component). Returns an empty string on success, else
/// what is wrong.
std::string ParseDirichlet(const std::string &entry, int dim, std::vector<DirichletSpec> &out);

/// Parses one load entry "GROUP:v1[:v2...][@T0:T1]" with exactly `count` finite numbers.
std::string ParseLoad(const std::string &entry, int count, const char *what, LoadSpec &out);

} // namespace signorini
