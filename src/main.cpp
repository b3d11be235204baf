// signorini: frictionless contact of elastic bodies against rigid obstacles. Initialise, run, finalise.
#include "signorini/app/run.hpp"
#include "signorini/core/errors.hpp"
#include "signorini/core/memory.hpp"
#include "signorini/options/command_line.hpp"
#include "signorini/options/help.hpp"
#include "signorini/options/options_files.hpp"

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

/// Open MPI's shared file pointers without its shared-memory component. Open MPI 4.1 (OMPIO) opens every MPI-IO file
/// with a shared file pointer whose component "sm" takes a POSIX semaphore named after the file's base name alone
/// (/dev/shm/sem.OMPIO_solution.h5 for every run's output, whatever its directory). A run killed while it held it
/// left it taken, and every later run that opened a file of that name (one rank or several) waited for it in
/// MPI_File_open forever. signorini never moves a shared file pointer (HDF5 writes at explicit offsets), so the
/// other components (a lock file beside the file, released when a process dies) serve; a value the user set stays.
/// Read by MPI_Init, so set before it; other MPI libraries ignore it.
void NoSharedMemoryFilePointer() {
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
}

} // namespace

int main(int argc, char **argv) {
  // The handler goes first so that a bad -options_file, read by PetscInitialize, is reported like any other input.
  PetscCall(signorini::InstallErrorHandler());
  signorini::HoldGenericHelp();
  // No help text here: PETSc would print it with a stray separator line; Run() prints it above the option groups.
  // MPI first, so that an options file that cannot be read is reported once, by rank 0, before PETSc reads it
  // (PETSc's own check of a directory or an unreadable file is made by rank 0 alone, while the others wait).
  NoSharedMemoryFilePointer();
  MPI_Init(&argc, &argv);
  std::string files;
  const std::string problem = signorini::OptionsFileProblem(argc, argv, files);
  signorini::SetOptionsFiles(files);
  if (!problem.empty()) {
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) std::fprintf(stderr, "signorini: error: %s\n", problem.c_str());
    MPI_Finalize();
    return 1;
  }
  if (PetscInitialize(&argc, &argv, nullptr, nullptr)) {
    // The handler has reported it (a bad -options_file, read by every rank alike); PetscCall here would abort MPI.
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
    return 1;
  }
  // A closed pipe on stdout (`signorini ... | head -1` in a batch script) is no reason to lose the results: PETSc's
  // handler would abort on SIGPIPE and leave no output; ignored, the writes to the pipe fail and the run goes on.
  std::signal(SIGPIPE, SIG_IGN);
  PetscErrorCode ierr = signorini::UseHugePages();
  if (!ierr) ierr = signorini::CheckCommandLine(argc, argv);
  if (!ierr) ierr = signorini::Run();
  if (ierr) {
    // No half-written output: the staging directory of a run that failed goes (an earlier good output stays).
    signorini::RemoveFailedOutput();
    (void)PetscOptionsSetValue(nullptr, "-options_left", "0");
  }
  PetscCall(PetscFinalize());
  MPI_Finalize(); // PETSc leaves MPI to whoever initialised it
  return ierr ? 1 : 0;
}
