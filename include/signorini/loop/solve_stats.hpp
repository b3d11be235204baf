// The record of a run of the loop: its iterations, timings, counters and stopping reason.
#pragma once

#include "signorini/loop/reason.hpp"

#include <petscsys.h>

#include "signorini/linalg/solver_choice.hpp"

#include <string>
#include <vector>

namespace signorini {

/// One line of the monitor.
struct IterationRecord {
  PetscInt step, iteration, active, changed, krylov;
  double load_factor, min_lambda, max_penetration, residual;
  double solve_time; ///< seconds of the saddle-point solve that produced this iterate (factorisation included)
};

/// Timings (seconds, maximum over ranks) and counters of a run.
struct SolveStats {
  double time_assembly = 0, time_active_set = 0, time_solve = 0;
  PetscInt solves = 0, active_set_iterations = 0, krylov_iterations = 0, steps = 0, cuts = 0;
  PetscInt repairings = 0;        ///< svk: pair searches that changed the pairs (each rebuilds the pattern)
  PetscInt search_widenings = 0;  ///< load steps repeated with a wider search radius (WidenSearch)
  PetscInt pivoted_sets = 0;      ///< complementarity problems solved by Lemke's method (PivotedActiveSet)
  PetscInt krylov_fallbacks = 0;  ///< iterative solves that failed and were solved again by GMRES (RetryKrylov)
  double search_radius = 0;       ///< the search radius of the final pairs
  PetscInt stabilised_solves = 0; ///< solves with the stabilisation springs (the active set did not hold the body)
  std::vector<IterationRecord> history;
  Reason reason = Reason::NONE;
  std::string violation; ///< the certificate's failed condition, with reason DIVERGED_CERTIFICATE
  SolverChoice solver;   ///< the solver path and why (chosen at the first set-up of the system)
  bool solver_chosen = false;
};

} // namespace signorini
