// signorini: frictionless contact of elastic bodies against rigid obstacles. Initialise, run, finalise.
#include "signorini/app/run.hpp"
#include "signorini/core/errors.hpp"

static const char help[] = "signorini: frictionless (Signorini) contact of elastic bodies against rigid obstacles.\n"
                           "Every input is a PETSc option; without -mesh_file the built-in 2D Hertz case runs.\n\n";

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, help));
  PetscCall(signorini::InstallErrorHandler());
  const PetscErrorCode ierr = signorini::Run();
  if (ierr) (void)PetscOptionsSetValue(nullptr, "-options_left", "0");
  // The handler's stack entry is PETSc memory: pop it so that -malloc_dump reports no leak.
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFinalize());
  return ierr ? 1 : 0;
}
