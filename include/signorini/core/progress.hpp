// One line per phase of a long run on stderr (-progress): what the run is doing and how long it has taken.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Reads -progress (default: on when rank 0's stderr is a terminal, so batch runs stay quiet); the same choice on
/// every rank. Collective on comm.
[[nodiscard]] PetscErrorCode ReadProgressOptions(MPI_Comm comm);

/// Phase phase starts / ends: rank 0 prints "signorini: [elapsed] phase ..." and, at the end, the phase's duration.
/// Phases nest (a stack); End closes the innermost. Any rank may call these, only rank 0 prints; no communication.
void ProgressBegin(const char *phase);
void ProgressEnd();

/// One line of its own (an iteration), printf-style, with the elapsed time.
void ProgressNote(const char *format, ...) __attribute__((format(printf, 1, 2)));

} // namespace signorini
