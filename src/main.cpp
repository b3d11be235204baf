// signorini: frictionless contact of elastic bodies against rigid obstacles. Initialise, run, finalise.
#include "signorini/app/run.hpp"
#include "signorini/core/errors.hpp"

static const char help[] = "signorini: frictionless (Signorini) contact of elastic bodies against rigid obstacles.\n"
                           "Every input is a PETSc option; without -mesh_file the built-in 2D Hertz case runs.\n\n";

int main(int argc, char **argv) {
  // The handler goes first so that a bad -options_file, read by PetscInitialize, is reported like any other input.
  PetscCall(signorini::InstallErrorHandler());
  signorini::HoldGenericHelp();
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  const PetscErrorCode ierr = signorini::Run();
  if (ierr) (void)PetscOptionsSetValue(nullptr, "-options_left", "0");
  PetscCall(PetscFinalize());
  return ierr ? 1 : 0;
}
