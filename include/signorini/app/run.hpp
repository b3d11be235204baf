// The whole run of the signorini executable: options, mesh, set-up, contact solve, results, output.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Runs one case described by the options database. Collective on PETSC_COMM_WORLD.
[[nodiscard]] PetscErrorCode Run();

} // namespace signorini
