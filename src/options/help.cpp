// -help in the program's order: its own option groups, then the saddle-point solver's, then PETSc's generic ones
// (help.hpp). PETSc prints its help through PetscHelpPrintf, and a type option through PetscVFPrintf to stdout.
#include "signorini/options/help.hpp"

#include <cstdarg>
#include <cstdio>
#include <string>

namespace signorini {

namespace {

std::string &HeldText() {
  static std::string text;
  return text;
}

/// PetscHelpPrintf while PetscInitialize runs: keeps the text for later.
PetscErrorCode HoldHelpPrintf(MPI_Comm, const char format[], ...) {
  char line[4096];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof(line), format, args);
  va_end(args);
  HeldText() += line;
  return 0;
}

/// PetscVFPrintf while the -help text of PETSc's generic objects is held: PETSc lists a type option
/// (-mat_seqaij_type) with PetscFPrintf to stdout, not through PetscHelpPrintf.
PetscErrorCode (*petsc_vfprintf)(FILE *, const char[], va_list) = nullptr;
PetscErrorCode HoldVFPrintf(FILE *fd, const char format[], va_list args) {
  if (fd != stdout && fd != PETSC_STDOUT) return petsc_vfprintf(fd, format, args);
  char line[4096];
  std::vsnprintf(line, sizeof(line), format, args);
  HeldText() += line;
  return 0;
}

/// PetscHelpPrintf while Run lists the program's and the solver's options. PETSc ends every option's line with its
/// manual page in parentheses, which our options do not have: the empty "()" goes. A generic -mat_* option (PETSc
/// lists -mat_seqaij_type again for the matrices the solver's set-up makes) joins the held generic text. PETSc prints
/// a line in pieces (a list option: its name, each choice, the manual page), so a line's start decides where it goes.
PetscErrorCode ProgramHelpPrintf(MPI_Comm comm, const char format[], ...) {
  static bool line_start = true, generic_line = false;
  char buffer[4096];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof(buffer), format, args);
  va_end(args);
  std::string piece = buffer;
  if (piece.empty()) return 0;
  if (line_start) generic_line = piece.rfind("  -mat_", 0) == 0;
  line_start = piece.back() == '\n';
  const std::string no_manual = " ()\n";
  if (piece.size() >= no_manual.size() &&
      piece.compare(piece.size() - no_manual.size(), no_manual.size(), no_manual) == 0)
    piece.replace(piece.size() - no_manual.size(), no_manual.size(), "\n");
  if (generic_line) {
    HeldText() += piece;
    return 0;
  }
  return PetscPrintf(comm, "%s", piece.c_str());
}

} // namespace

void HoldGenericHelp() { PetscHelpPrintf = HoldHelpPrintf; }

void ListProgramHelp() { PetscHelpPrintf = ProgramHelpPrintf; }

GenericHelpHeld::GenericHelpHeld() {
  PetscHelpPrintf = HoldHelpPrintf;
  petsc_vfprintf = PetscVFPrintf;
  PetscVFPrintf = HoldVFPrintf;
}

GenericHelpHeld::~GenericHelpHeld() {
  PetscHelpPrintf = ProgramHelpPrintf;
  PetscVFPrintf = petsc_vfprintf;
}

PetscErrorCode PrintGenericHelp(MPI_Comm comm) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(comm, "----------------------------------------\nPETSc's own options (every PETSc "
                        "program):\n%s", HeldText().c_str()));
  PetscFunctionReturn(0);
}

} // namespace signorini
