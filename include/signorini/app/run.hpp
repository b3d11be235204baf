// The whole run of the signorini executable: options, mesh, set-up, contact solve, results, output.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Holds back the help text that PetscInitialize prints for -help (PETSc's generic options), so that the program's
/// own option groups come first; Run prints it after them. Call before PetscInitialize.
void HoldGenericHelp();

/// Runs one case described by the options database. Collective on PETSC_COMM_WORLD.
[[nodiscard]] PetscErrorCode Run();

} // namespace signorini
