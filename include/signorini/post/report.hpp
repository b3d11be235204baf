// The printed summary and summary.json of a run, and the Hertz comparison (-report_hertz R,P).
#pragma once

#include "signorini/post/contact_results.hpp"
#include "signorini/fem/material.hpp"
#include "signorini/mesh/mesh.hpp"
#include "signorini/loop/solved_state.hpp"

#include <map>
#include <string>

namespace signorini {

/// Hertz contact on a rigid flat (Johnson 1985, 4.2), by the mesh's dimension: in 2D line contact of a cylinder
/// (radius R, load P per unit thickness), in 3D a sphere (radius R, total load P).
struct HertzReport {
  bool enabled = false;
  int dim = 2;
  double R = 0, P = 0;
  double fraction = 1, P_model = 0;     ///< the fraction of the body modelled (symmetry planes), the load it stands for
  double a = 0, p0 = 0;                 ///< analytical half-width (2D) or contact radius (3D) and peak pressure
  double a_h = 0, p0_h = 0;             ///< computed (see ComputeHertz)
  PetscInt fit_nodes = 0;               ///< nodal pressures in the fit of p0_h
  double a_fit = 0;                     ///< a of the same fit (0: none), free of a_h's steps of whole elements
  bool out_of_range = false;            ///< the default case's comparison, not made: a is not small against R
  int contact_materials = 1;            ///< materials of the cells at the contact boundary: no comparison unless 1
  bool check_load = true;               ///< P must be the load the model carries (not when the default case filled
                                        ///< it in: its P follows the run's load)
};

/// Reads -report_hertz R,P. Collective.
[[nodiscard]] PetscErrorCode ReadReportOptions(MPI_Comm comm, HertzReport &hertz);

/// Fills the analytical and computed Hertz values. The model is the fraction 1, 1/2 or 1/4 of the body (symmetry
/// planes) nearest to |contact force| / P, and Johnson's values are those of the load it carries, P_model =
/// |contact force| / fraction. 2D: a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a), computed a = contact length /
/// (2 fraction). 3D: a = (3 P R / (4 E*))^(1/3), p0 = 3 P / (2 pi a^2), computed a = radius of the circle of area
/// contact area / fraction. Computed p0: the intercept of Hertz's profile p^2 = p0^2 (1 - r^2 / a^2) fitted to the
/// nodal pressures around the contact centre (the candidate node of the first contact). Collective.
[[nodiscard]] PetscErrorCode ComputeHertz(const SolvedState &state, const Material &m, const NodeContact &nodes,
                                          const ContactSummary &s, HertzReport &hertz);

/// Everything the report needs besides the solver.
struct RunInfo {
  std::string mesh_file;
  int ranks = 1;
  std::map<std::string, double> timings; ///< phase -> seconds (max over ranks)
};

/// Prints the header of the run on rank 0 (model, mesh, unknowns), before the solve and its -contact_monitor
/// lines. Collective.
[[nodiscard]] PetscErrorCode PrintHeader(MPI_Comm comm, const RunInfo &info, const Material &m, const SolvedState &state);

/// Prints the short deterministic summary of the result on rank 0. Collective.
[[nodiscard]] PetscErrorCode PrintSummary(MPI_Comm comm, const SolvedState &state, const ContactSummary &s,
                                          const HertzReport &hertz);

/// The text of summary.json.
std::string SummaryJson(const RunInfo &info, const Material &m, const SolvedState &state, const ContactSummary &s,
                        const HertzReport &hertz);

} // namespace signorini
