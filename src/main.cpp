// signorini: frictionless contact of elastic bodies against rigid obstacles. Initialise, run, finalise.
#include "signorini/app/run.hpp"
#include "signorini/core/errors.hpp"

int main(int argc, char **argv) {
  // The handler goes first so that a bad -options_file, read by PetscInitialize, is reported like any other input.
  PetscCall(signorini::InstallErrorHandler());
  signorini::HoldGenericHelp();
  // No help text here: PETSc would print it with a stray separator line; Run() prints it above the option groups.
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  const PetscErrorCode ierr = signorini::Run();
  if (ierr) (void)PetscOptionsSetValue(nullptr, "-options_left", "0");
  PetscCall(PetscFinalize());
  return ierr ? 1 : 0;
}
