// The check of the command line as PETSc reads it.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Checks the command line as PETSc reads it (-name value, -name, -options_file FILE, ...): an argument that is
/// neither an option nor an option's value (PETSc would skip it silently, e.g. a case file given without
/// -options_file), a misspelling of -options_file (PETSc would take it for an unused option and run the default
/// case), an option given twice (PETSc would keep the last value; -options_file may be given several times), or an
/// option that an -options_file after it sets again (PETSc would take the file's value; an option of the command
/// line overrides one of a file before it or of PETSC_OPTIONS) is an error that names it and says what was expected.
/// Collective (every rank has the same arguments).
[[nodiscard]] PetscErrorCode CheckCommandLine(int argc, char **argv);

} // namespace signorini
