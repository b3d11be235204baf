// Helpers for unit tests that call PETSc: scoped options, error capture, PETSc memory in use.
#pragma once

#include <petscsys.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace signorini::test {

/// Sets PETSc options for the lifetime of the object and clears them afterwards, so that no test leaks options.
class ScopedOptions {
public:
  ScopedOptions(std::initializer_list<std::pair<std::string, std::string>> options) : options_(options) {
    for (const auto &[name, value] : options_)
      (void)PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str());
  }
  ScopedOptions(const ScopedOptions &) = delete;
  ScopedOptions &operator=(const ScopedOptions &) = delete;
  ~ScopedOptions() {
    for (const auto &option : options_)
      (void)PetscOptionsClearValue(nullptr, option.first.c_str());
  }

private:
  std::vector<std::pair<std::string, std::string>> options_;
};

/// Replaces PETSc's error handler for its lifetime: errors are not printed, the first error message is kept.
class ErrorCapture {
public:
  ErrorCapture() { (void)PetscPushErrorHandler(Handler, &message_); }
  ErrorCapture(const ErrorCapture &) = delete;
  ErrorCapture &operator=(const ErrorCapture &) = delete;
  ~ErrorCapture() { (void)PetscPopErrorHandler(); }
  const std::string &Message() const { return message_; }

private:
  static PetscErrorCode Handler(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p,
                                const char *mess, void *ctx) {
    auto *message = static_cast<std::string *>(ctx);
    if (p == PETSC_ERROR_INITIAL && message->empty() && mess) *message = mess;
    return n;
  }
  std::string message_;
};

/// Bytes currently allocated through PETSc (main.cpp turns on -malloc_debug, without which this is 0).
inline double PetscMemoryInUse() {
  PetscLogDouble bytes = 0;
  (void)PetscMallocGetCurrentUsage(&bytes);
  return bytes;
}

} // namespace signorini::test
