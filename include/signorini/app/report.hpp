// The printed summary and summary.json of a run, and the Hertz comparison (-report_hertz R,P).
#pragma once

#include "signorini/contact/contact_results.hpp"
#include "signorini/fem/material.hpp"
#include "signorini/mesh/mesh.hpp"
#include "signorini/solver/contact_solver.hpp"

#include <map>
#include <string>

namespace signorini {

/// Hertz line contact of a cylinder (radius R, load P per unit thickness) on a rigid flat (Johnson 1985, 4.2).
struct HertzReport {
  bool enabled = false;
  double R = 0, P = 0;
  double a = 0, p0 = 0;                 ///< analytical half-width and peak pressure
  double a_h = 0, p0_h = 0;             ///< computed: contact length / 2 and peak nodal pressure
};

/// Reads -report_hertz R,P. Collective.
[[nodiscard]] PetscErrorCode ReadReportOptions(MPI_Comm comm, HertzReport &hertz);

/// Fills the analytical and computed Hertz values.
void ComputeHertz(const Material &m, const ContactSummary &s, HertzReport &hertz);

/// Everything the report needs besides the solver.
struct RunInfo {
  std::string mesh_file;
  int ranks = 1;
  std::map<std::string, double> timings; ///< phase -> seconds (max over ranks)
};

/// Prints the header of the run on rank 0 (model, mesh, unknowns), before the solve and its -contact_monitor
/// lines. Collective.
[[nodiscard]] PetscErrorCode PrintHeader(MPI_Comm comm, const RunInfo &info, const Material &m, ContactSolver &solver);

/// Prints the short deterministic summary of the result on rank 0. Collective.
[[nodiscard]] PetscErrorCode PrintSummary(MPI_Comm comm, ContactSolver &solver, const ContactSummary &s,
                                          const HertzReport &hertz);

/// The text of summary.json.
std::string SummaryJson(const RunInfo &info, const Material &m, ContactSolver &solver, const ContactSummary &s,
                        const HertzReport &hertz);

} // namespace signorini
