// A temporary file path that every rank of PETSC_COMM_WORLD names alike, for the tests of collective writers.
#pragma once

#include <gtest/gtest.h>
#include <petscsys.h>
#include <unistd.h>

#include <string>

namespace signorini::test {

/// TempDir()/signorini_NAME_PID with rank 0's process id, the same on every rank. Collective.
inline std::string SharedTempPath(const std::string &name) {
  int pid = (int)getpid();
  (void)MPI_Bcast(&pid, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  return ::testing::TempDir() + "signorini_" + name + "_" + std::to_string(pid);
}

} // namespace signorini::test
