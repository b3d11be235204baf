// The options of the loop: load stepping and Newton-Raphson (-load_*, -newton_*).
#pragma once

#include "signorini/fem/material.hpp"

#include <petscsys.h>

namespace signorini {

struct SolverOptions {
  /// Upper bounds of the counts and tolerances (docs/options.md): no typo starts a run that never ends or accepts a
  /// wrong state.
  static constexpr PetscInt LOAD_STEPS_MAX = 10000, LOAD_MAX_CUTS_MAX = 30, NEWTON_MAX_IT_MAX = 1000;
  static constexpr double NEWTON_RTOL_MAX = 1e-4, NEWTON_ATOL_MAX = 1e-6;

  PetscInt load_steps = 1;    ///< -load_steps, in [1, LOAD_STEPS_MAX]
  PetscInt max_cuts = 5;      ///< -load_max_cuts: halvings of a failed load increment, in [0, LOAD_MAX_CUTS_MAX]
  PetscInt newton_max_it = 50; ///< -newton_max_it (svk): iterations per load step, in [1, NEWTON_MAX_IT_MAX]
  double newton_rtol = 1e-9;  ///< -newton_rtol: residual relative to the load scale, in (0, NEWTON_RTOL_MAX]
  double newton_atol = 1e-12; ///< -newton_atol: absolute residual (force units), in [0, NEWTON_ATOL_MAX]
  PetscBool line_search = PETSC_FALSE; ///< -newton_linesearch (Crisfield's line search; det F <= 0 always backtracks)
  PetscBool lagged_search = PETSC_TRUE;  ///< -newton_lagged_search (svk, kept factorisation): see ContactSolver
  PetscBool lagged_search_set = PETSC_FALSE;
  enum class MortarTangent { CONSISTENT, FROZEN };
  static constexpr const char *MORTAR_TANGENT_NAMES[2] = {"consistent", "frozen"};
  /// -newton_mortar_tangent (svk between bodies): the mortar rows' variation in the Newton tangent or not
  PetscInt mortar_tangent = (PetscInt)MortarTangent::CONSISTENT;
  PetscBool mortar_tangent_set = PETSC_FALSE;
  static constexpr double ACTIVE_SET_RTOL_MAX = 0.1;
  double active_set_rtol = 1e-3; ///< -contact_active_set_rtol: iterative solves while the set changes, [0, 0.1]
};

/// Reads the -load_ and -newton_ options. The ones that only the nonlinear material's Newton loop uses
/// (-load_max_cuts, -newton_max_it, -newton_linesearch, -newton_lagged_search, -newton_mortar_tangent) are an error when given with another
/// model, so that none is ignored silently (-newton_rtol and -newton_atol bound the equilibrium residual of every
/// model). Then checks the values of the saddle-point solver's PETSc options (CheckSolverOptionValues).
[[nodiscard]] PetscErrorCode ReadSolverOptions(MPI_Comm comm, MaterialModel model, SolverOptions &opts);

} // namespace signorini
