// One line per phase of a long run on stderr (-progress): what the run is doing and how long it has taken.
#include "signorini/core/progress.hpp"
#include "signorini/core/handle.hpp"

#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

namespace {

struct State {
  bool enabled = false;
  double start = 0;
  std::vector<std::pair<std::string, double>> open; ///< phases begun and not ended, with their start times
};

State &Progress() {
  static State state;
  return state;
}

void Print(const std::string &text) {
  State &s = Progress();
  std::fprintf(stderr, "signorini: [%8.2f s] %s\n", MPI_Wtime() - s.start, text.c_str());
  std::fflush(stderr);
}

} // namespace

PetscErrorCode ReadProgressOptions(MPI_Comm comm) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int tty = rank == 0 ? isatty(2) : 0;
  PetscCallMPI(MPI_Bcast(&tty, 1, MPI_INT, 0, comm));
  PetscBool progress = tty ? PETSC_TRUE : PETSC_FALSE;
  PetscOptionsBegin(comm, nullptr, "Progress", "signorini");
  const OptionsBlockGuard options_block(PetscOptionsObject); // ends the block on an error
  PetscCall(PetscOptionsBool("-progress", "One line per phase on stderr (default: on when stderr is a terminal)", "",
                             progress, &progress, nullptr));
  PetscOptionsEnd();
  State &s = Progress();
  s.enabled = progress && rank == 0;
  s.start = MPI_Wtime();
  s.open.clear();
  PetscFunctionReturn(0);
}

void ProgressBegin(const char *phase) {
  State &s = Progress();
  if (!s.enabled) return;
  s.open.emplace_back(phase, MPI_Wtime());
  Print(std::string(phase) + " ...");
}

void ProgressEnd() {
  State &s = Progress();
  if (!s.enabled || s.open.empty()) return;
  const auto [phase, t0] = s.open.back();
  s.open.pop_back();
  char took[64];
  std::snprintf(took, sizeof(took), " done (%.2f s)", MPI_Wtime() - t0);
  Print(phase + took);
}

void ProgressNote(const char *format, ...) {
  if (!Progress().enabled) return;
  char line[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof(line), format, args);
  va_end(args);
  Print(line);
}

} // namespace signorini
