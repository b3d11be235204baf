// Entry point of the unit tests: PETSc is initialised once around all GoogleTest tests, with PETSc's memory tracing
// on so that tests can check that what they create is freed; a run that leaves a PETSc option unused fails (a test
// that sets an option must read it and clear it).
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdio>
#include <vector>

int main(int argc, char **argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
  // Trace PETSc allocations so that tests can compare PetscMallocGetCurrentUsage before and after. Later
  // command-line options take precedence.
  static char malloc_debug[] = "-malloc_debug";
  std::vector<char *> args = {argv[0], malloc_debug};
  args.insert(args.end(), argv + 1, argv + argc);
  args.push_back(nullptr);
  int nargs = (int)args.size() - 1;
  char **pargs = args.data();
  PetscCall(PetscInitialize(&nargs, &pargs, nullptr, "signorini unit tests\n"));
  int result = RUN_ALL_TESTS();
  PetscInt unused = 0;
  PetscCall(PetscOptionsAllUsed(nullptr, &unused));
  if (unused > 0) {
    std::fprintf(stderr, "unit_tests: %d PETSc option(s) left unused:\n", (int)unused);
    PetscCall(PetscOptionsLeft(nullptr));
    result = 1;
  }
  // The tests of error paths leave PETSc's own error-path allocations (PetscOptionsBegin, PetscOptionsEList) behind;
  // without -malloc_debug in the database PetscFinalize does not list them.
  PetscCall(PetscOptionsClearValue(nullptr, "-malloc_debug"));
  PetscCall(PetscFinalize());
  return result;
}
