// -help in the program's order: the program's option groups first (each component lists its own as it reads them),
// then the saddle-point solver's, then PETSc's generic options, which PETSc prints first on its own; the empty
// manual-page "()" PETSc puts after each option goes from ours.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Before PetscInitialize: PETSc's generic help text is held, to be printed last (PrintGenericHelp). Not collective.
void HoldGenericHelp();

/// From the program's option reading on: its groups are printed as they are read, and a generic -mat_* line that a
/// solver's set-up lists joins the held text. Not collective.
void ListProgramHelp();

/// While it lives, everything PETSc lists goes to the held generic text (a stand-in object's own options).
class GenericHelpHeld {
public:
  GenericHelpHeld();
  ~GenericHelpHeld();
  GenericHelpHeld(const GenericHelpHeld &) = delete;
  GenericHelpHeld &operator=(const GenericHelpHeld &) = delete;
};

/// Prints the held generic text under its heading, after the program's and the solver's groups. Collective.
[[nodiscard]] PetscErrorCode PrintGenericHelp(MPI_Comm comm);

} // namespace signorini
