// The report of options set but never read: misspelt, or not meant for this run.
#pragma once

#include <petscsys.h>

#include <string>

namespace signorini {

/// Whether the option name (without its '-', in lower case) is one of the saddle-point solver's, which PETSc reads
/// while the solve runs: -contact_ followed by the KSP's, the PC's, the factor matrix's (-contact_mat_mumps_*) or a
/// sub-solver's prefix (fieldsplit_, sub_, mg_, ...).
bool IsSolverOption(const std::string &name);

/// When CheckUnusedOptions runs: after the set-up (every component but the solve has read its options), or after the
/// solve (before the output is published).
enum class UnusedOptions { AFTER_SETUP, AFTER_SOLVE };

/// Refuses the options that were set (command line, options files, PETSC_OPTIONS) but never read, misspelt or not
/// meant for this run, with one error naming them, unless -options_left is false (the documented opt-out). After the
/// set-up it leaves those the solve may still read: the saddle-point solver's (-contact_ksp_*, -contact_pc_*,
/// -contact_mat_*, -contact_fieldsplit_*, the options of the sub-solvers it creates) and those of the vectors and
/// matrices it assembles (-vec_*, -mat_*, -is_*, -sf_*, -vecscatter_*, -viewer_*, -draw_*). PETSc's generic options
/// that it reads only in PetscFinalize (-options_view, ...) are never refused. After the solve it sets -options_left 0,
/// so that PetscFinalize does not list them again. Collective.
[[nodiscard]] PetscErrorCode CheckUnusedOptions(MPI_Comm comm, UnusedOptions when);

} // namespace signorini
