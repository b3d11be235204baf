// The options of the loop: load stepping and Newton-Raphson, read and checked in one place.
#include "signorini/loop/loop_options.hpp"
#include "signorini/core/handle.hpp"

#include "signorini/linalg/solver_options.hpp"
#include "signorini/loop/material_policy.hpp"
#include "signorini/options/readers.hpp"

namespace signorini {

PetscErrorCode ReadSolverOptions(MPI_Comm comm, MaterialModel model, SolverOptions &opts) {
  // Ranges (docs/options.md): a relative residual above 1e-4 or an absolute one above 1e-6 (force units) would accept a
  // visibly unconverged state; the counts are bounded so that a typo cannot start a run that never ends.
  const RealRange rtol{0, SolverOptions::NEWTON_RTOL_MAX, true, false}, atol{0, SolverOptions::NEWTON_ATOL_MAX};
  PetscBool max_cuts_set = PETSC_FALSE, max_it_set = PETSC_FALSE, line_search_set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "Load stepping and Newton-Raphson", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(OptionsInt(PetscOptionsObject, "-load_steps", "Number of load increments (step k at pseudo-time "
                       "k/N, along which each -bc_ item's ramp runs)", 1, SolverOptions::LOAD_STEPS_MAX,
                       opts.load_steps));
  PetscCall(OptionsInt(PetscOptionsObject, "-load_max_cuts", "Halvings allowed for a failed load increment (svk)", 0,
                       SolverOptions::LOAD_MAX_CUTS_MAX, opts.max_cuts, &max_cuts_set));
  PetscCall(OptionsInt(PetscOptionsObject, "-newton_max_it", "Newton iterations per load step (svk; at most "
                       "-contact_max_it of them change the active set)", 1,
                       SolverOptions::NEWTON_MAX_IT_MAX, opts.newton_max_it, &max_it_set));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_rtol", "Residual tolerance relative to the force scale", rtol,
                        opts.newton_rtol));
  PetscCall(OptionsReal(PetscOptionsObject, "-newton_atol", "Absolute residual tolerance (force units)", atol,
                        opts.newton_atol));
  PetscCall(PetscOptionsBool("-newton_linesearch",
                             "svk: line search on du.R(u + s du) (det F <= 1e-10 always halves the step)", "",
                             opts.line_search, &opts.line_search, &line_search_set));
  PetscCall(PetscOptionsBool("-newton_lagged_search",
                             "svk with the kept factorisation (-contact_reuse_factorization): while the active set "
                             "changes and the residual halves per step, a Newton step searches the active set in the "
                             "multiplier space with the factored tangent (modified Newton: one forward and one "
                             "backward pass); once it settles, inexact Newton steps with the current tangent (FGMRES "
                             "to a residual of min(0.1, ||R||/scale) ||R||); the run's first load step that fails "
                             "after lagged searches (not singular) is repeated with exact Newton steps before a cut; "
                             "false: exact Newton at every iteration (the default with -contact_pairs)",
                             "", opts.lagged_search, &opts.lagged_search, &opts.lagged_search_set));
  PetscCall(OptionsChoice(PetscOptionsObject, "-newton_mortar_tangent",
                          "svk between bodies (-contact_pairs): consistent: the Newton tangent holds the variation of "
                          "the mortar rows (their normals and weights) with the displacement, so that Newton converges "
                          "superlinearly (a nonsymmetric matrix: MUMPS LU, or BiCGStab on the iterative path); frozen: "
                          "the rows of the current iterate only (linear convergence, a symmetric matrix); with "
                          "friction always frozen", "consistent or frozen", SolverOptions::MORTAR_TANGENT_NAMES, 2,
                          opts.mortar_tangent, &opts.mortar_tangent_set));
  PetscCall(OptionsReal(PetscOptionsObject, "-contact_active_set_rtol",
                        "Iterative solvers, linear material: the saddle-point solves of the active-set iterations "
                        "stop when their residual fell by this times the load step's first right-hand side over "
                        "their own; the solve after which the set stays is corrected to the certificate's "
                        "tolerance. 0: every solve to -contact_ksp_rtol",
                        {0, SolverOptions::ACTIVE_SET_RTOL_MAX}, opts.active_set_rtol));
  PetscOptionsEnd();
  // A linear material solves a load step by the active-set loop alone (-contact_max_it) and never cuts one: these
  // would be ignored.
  if (!MakeMaterialPolicy(model)->Nonlinear()) {
    PetscCheck(!max_cuts_set, comm, PETSC_ERR_USER_INPUT,
               "-load_max_cuts %" PetscInt_FMT " applies to -material_model svk only (the linear material never cuts a "
               "load step)", opts.max_cuts);
    PetscCheck(!max_it_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_max_it %" PetscInt_FMT " applies to -material_model svk only (the linear material's "
               "iterations are bounded by -contact_max_it)", opts.newton_max_it);
    PetscCheck(!line_search_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_linesearch %s applies to -material_model svk only", opts.line_search ? "true" : "false");
    PetscCheck(!opts.mortar_tangent_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_mortar_tangent %s applies to -material_model svk only (the linear material's mortar rows are "
               "those of the reference configuration)", SolverOptions::MORTAR_TANGENT_NAMES[opts.mortar_tangent]);
    PetscCheck(!opts.lagged_search_set, comm, PETSC_ERR_USER_INPUT,
               "-newton_lagged_search %s applies to -material_model svk only, with the kept factorisation "
               "(-contact_reuse_factorization with a MUMPS LU or Cholesky solver)",
               opts.lagged_search ? "true" : "false");
  }
  // The saddle-point solver's PETSc options, before its KSP reads them (and before the mesh is read).
  PetscCall(CheckSolverOptionValues(comm));
  PetscFunctionReturn(0);
}

} // namespace signorini
