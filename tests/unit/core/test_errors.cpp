// RunOnRoot: work of rank 0 alone runs there only, and an error it raises reaches every rank, reported once. Runs on
// one rank in unit_tests and on two in unit_tests_run_on_root_np2.
#include "signorini/core/errors.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

namespace signorini {
namespace {

/// Replaces PETSc's error handler for its lifetime and counts the errors raised (not their tracebacks), keeping the
/// first one's code, message and communicator.
class ErrorCount {
public:
  ErrorCount() { (void)PetscPushErrorHandler(Handler, this); }
  ErrorCount(const ErrorCount &) = delete;
  ErrorCount &operator=(const ErrorCount &) = delete;
  ~ErrorCount() { (void)PetscPopErrorHandler(); }
  int count = 0;
  PetscErrorCode code = 0;
  std::string message;
  MPI_Comm comm = MPI_COMM_NULL;

private:
  static PetscErrorCode Handler(MPI_Comm comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p,
                                const char *mess, void *ctx) {
    auto &self = *static_cast<ErrorCount *>(ctx);
    if (p != PETSC_ERROR_INITIAL) return n;
    if (self.count++ == 0) self.code = n, self.message = mess ? mess : "", self.comm = comm;
    return n;
  }
};

int Rank() {
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

/// The work of the tests that fail: an error two calls deep, raised on this rank alone.
PetscErrorCode OutOfRange(int value) {
  PetscFunctionBeginUser;
  PetscCheck(value < 10, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "value %d out of range; expected below 10", value);
  PetscFunctionReturn(0);
}

PetscErrorCode Work(int value, int &calls) {
  PetscFunctionBeginUser;
  ++calls;
  PetscCall(OutOfRange(value));
  PetscFunctionReturn(0);
}

TEST(RunOnRoot, RunsWorkOnRootOnly) {
  ErrorCount errors;
  int calls = 0;
  EXPECT_EQ(RunOnRoot(PETSC_COMM_WORLD, [&] { return Work(3, calls); }), 0);
  EXPECT_EQ(calls, Rank() == 0 ? 1 : 0);
  EXPECT_EQ(errors.count, 0);
}

TEST(RunOnRoot, RaisesTheErrorOfRootOnEveryRankOnce) {
  ErrorCount errors;
  int calls = 0;
  EXPECT_EQ(RunOnRoot(PETSC_COMM_WORLD, [&] { return Work(42, calls); }), PETSC_ERR_ARG_OUTOFRANGE);
  EXPECT_EQ(calls, Rank() == 0 ? 1 : 0);
  // Once per rank: the raise of rank 0 alone is recorded, not reported; the collective one is.
  EXPECT_EQ(errors.count, 1);
  EXPECT_EQ(errors.code, PETSC_ERR_ARG_OUTOFRANGE);
  EXPECT_EQ(errors.message, "value 42 out of range; expected below 10");
  int same = MPI_UNEQUAL;
  if (errors.comm != MPI_COMM_NULL) MPI_Comm_compare(errors.comm, PETSC_COMM_WORLD, &same);
  EXPECT_TRUE(same == MPI_IDENT || same == MPI_CONGRUENT) << "the error is not raised on the given communicator";
  // The handler of the run is back: the next error on rank 0 alone reaches it directly.
  if (Rank() == 0) {
    EXPECT_EQ(OutOfRange(11), PETSC_ERR_ARG_OUTOFRANGE);
    EXPECT_EQ(errors.count, 2);
  }
}

TEST(RunOnRoot, RaisesAnExceptionAndABareCodeOnEveryRank) {
  ErrorCount errors;
  EXPECT_EQ(RunOnRoot(PETSC_COMM_WORLD, []() -> PetscErrorCode { throw std::runtime_error("no memory for it"); }),
            PETSC_ERR_LIB);
  EXPECT_EQ(errors.message, "no memory for it");
  ErrorCount bare;
  EXPECT_EQ(RunOnRoot(PETSC_COMM_WORLD, [] { return (PetscErrorCode)PETSC_ERR_SUP; }), PETSC_ERR_SUP);
  EXPECT_EQ(bare.count, 1);
  EXPECT_FALSE(bare.message.empty());
}

TEST(RaiseFromRoot, RaisesTheMessageOfRootOnEveryRank) {
  ErrorCount errors;
  EXPECT_EQ(RaiseFromRoot(PETSC_COMM_WORLD, Rank() == 0 ? "mesh 'a.msh' is empty" : "ignored"), PETSC_ERR_USER_INPUT);
  EXPECT_EQ(errors.count, 1);
  EXPECT_EQ(errors.message, "mesh 'a.msh' is empty");
  EXPECT_EQ(RaiseFromRoot(PETSC_COMM_WORLD, Rank() == 0 ? "" : "ignored"), 0);
  EXPECT_EQ(errors.count, 1);
}

TEST(RunOnRoot, TheRunsHandlerPrintsOneErrorLineAndAbortsNothing) {
  // signorini's handler aborts the job for an error of one rank out of several, and prints every error it reports:
  // reaching the end of this test on every rank, with one line on rank 0 and none elsewhere, is the check.
  ASSERT_EQ(InstallErrorHandler(), 0);
  testing::internal::CaptureStderr();
  int calls = 0;
  const PetscErrorCode code = RunOnRoot(PETSC_COMM_WORLD, [&] { return Work(42, calls); });
  const std::string err = testing::internal::GetCapturedStderr();
  (void)PetscPopErrorHandler();
  EXPECT_EQ(code, PETSC_ERR_ARG_OUTOFRANGE);
  std::istringstream lines(err);
  int count = 0;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("signorini: error:", 0) == 0) {
      ++count;
      EXPECT_EQ(line, "signorini: error: value 42 out of range; expected below 10");
    }
  EXPECT_EQ(count, Rank() == 0 ? 1 : 0) << err;
}

} // namespace
} // namespace signorini
