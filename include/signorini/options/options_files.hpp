// The check of the options files before PETSc reads them.
#pragma once

#include <petscsys.h>

#include <string>

namespace signorini {

/// The first options file that cannot be read, or a YAML one that sets an option twice (in one document or in two) or
/// names an options_file (PETSc would take either silently), as a message naming it and saying what was expected;
/// empty when there is none. The files are those of -options_file FILE and -options_file_yaml FILE on the command
/// line and in PETSC_OPTIONS, and those that a plain options file names in turn. files: the ones it saw, for
/// SetOptionsFiles.
/// Needs no PETSc (it runs before PetscInitialize).
std::string OptionsFileProblem(int argc, char **argv, std::string &files);

} // namespace signorini
