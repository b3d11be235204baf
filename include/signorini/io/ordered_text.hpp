// A text file written by every rank together through MPI-IO: the ranks' pieces of text, concatenated in rank order.
#pragma once

#include <petscsys.h>

#include <string>

namespace signorini {

/// Writes the file at path (replacing it) as the concatenation of every rank's text in rank order; each rank writes
/// its own piece at its offset, so that no rank holds the whole file. Collective; when the file cannot be written,
/// every rank raises one error naming it.
[[nodiscard]] PetscErrorCode WriteInRankOrder(MPI_Comm comm, const std::string &path, const std::string &text);

} // namespace signorini
