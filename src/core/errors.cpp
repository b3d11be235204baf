// Error handler and collective error checks.
#include "signorini/core/errors.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <vector>

namespace signorini {

namespace {

std::string &OptionsFiles() {
  static std::string files;
  return files;
}

std::string &FailedOutput() {
  static std::string dir;
  return dir;
}

int &MadeParents() {
  static int made = 0;
  return made;
}

/// Rewrites PETSc's "Input string abc has no numeric value" (and its integer and logical variants) to name the option
/// holding the bad value, found by that value in the options database, and to say what was expected.
std::string DescribeBadOptionValue(const std::string &mess) {
  const std::string input = "Input string ", logical = "Unknown logical value: ";
  std::string token, expected;
  if (mess.rfind(input, 0) == 0 && mess.find(" has no ") != std::string::npos) {
    token = mess.substr(input.size(), mess.find(" has no ") - input.size());
    expected = mess.find("integer") != std::string::npos ? "an integer" : "a real number";
  } else if (mess.rfind(logical, 0) == 0) {
    token = mess.substr(logical.size());
    expected = "true or false";
  } else {
    return mess;
  }
  std::string option;
  char *all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) == 0 && all) {
    // "-name value -name -name value ...": a word starting with '-' and a letter is a name, anything else a value.
    std::istringstream words(all);
    std::string word, name;
    while (option.empty() && words >> word) {
      if (word.size() > 1 && word[0] == '-' && std::isalpha((unsigned char)word[1])) {
        name = word;
        continue;
      }
      std::istringstream items(word);
      std::string item;
      while (option.empty() && std::getline(items, item, ','))
        if (item == token) option = name + " " + word + ": ";
    }
    (void)PetscFree(all);
  }
  return option + "'" + token + "' is invalid; expected " + expected;
}

PetscErrorCode Handler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p,
                       const char *mess, void *) {
  if (p != PETSC_ERROR_INITIAL) return n;
  int mpi_up = 0, world_size = 1, comm_size = 1, rank = 0;
  MPI_Initialized(&mpi_up);
  const MPI_Comm world = PETSC_COMM_WORLD != MPI_COMM_NULL ? PETSC_COMM_WORLD : MPI_COMM_WORLD;
  if (mpi_up) MPI_Comm_size(world, &world_size);
  if (mpi_up && comm != MPI_COMM_NULL) MPI_Comm_size(comm, &comm_size), MPI_Comm_rank(comm, &rank);
  // PETSc's options code: while PetscInitialize reads -options_file (the handler is installed before it), or, once
  // it is done, a bad option value. The latter is raised on PETSC_COMM_SELF but on every rank alike, since every
  // rank holds the same options and reads them together: report it once, from rank 0, and let every rank unwind.
  const bool options_code = file && std::strstr(file, "sys/objects/options") != nullptr;
  // The same holds while PetscInitialize reads the command line (a missing file name) and a YAML file (rank 0 reads
  // it, every rank parses it), but not for a plain options file: rank 0 parses it while the others wait (a syntax
  // error), yet a file it names is opened by every rank. Its errors are reported by rank 0 alone, and every rank that
  // raises one aborts the others. (main checks beforehand that every options file it can find is readable.)
  const bool option_value = options_code && PetscInitializeCalled;
  const bool plain_file = options_code && func && std::strcmp(func, "PetscOptionsInsertFilePetsc") == 0;
  if (options_code && mpi_up) MPI_Comm_rank(world, &rank), comm_size = plain_file ? 1 : world_size;
  const bool collective = comm_size == world_size;
  std::string message = mess ? mess : "";
  while (!message.empty() && std::isspace((unsigned char)message.back()))
    message.pop_back();
  if (option_value)
    message = DescribeBadOptionValue(message);
  else if (options_code)
    message = "-options_file" + (OptionsFiles().empty() ? "" : " " + OptionsFiles()) + ": " + message +
              "; expected a readable YAML or PETSc options file";
  if (n == PETSC_ERR_ARG_UNKNOWN_TYPE) message += "; expected one of the types that -help lists";
  const char *text = message.c_str();
  const bool user = options_code || n == PETSC_ERR_USER_INPUT || n == PETSC_ERR_ARG_UNKNOWN_TYPE ||
                    n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_READ || n == PETSC_ERR_FILE_WRITE ||
                    n == PETSC_ERR_FILE_UNEXPECTED || n == PETSC_ERR_ARG_OUTOFRANGE || n == PETSC_ERR_NOT_CONVERGED ||
                    n == PETSC_ERR_CONV_FAILED || n == PETSC_ERR_ARG_WRONG;
  if (plain_file ? rank == 0 : !collective || rank == 0) {
    if (n == PETSC_ERR_MEM)
      std::fprintf(stderr, "signorini: error: out of memory (%s)\n", text);
    else if (user)
      std::fprintf(stderr, "signorini: error: %s\n", text);
    else
      std::fprintf(stderr, "signorini: error: %s [PETSc error %d in %s() at %s:%d]\n", text, (int)n, func, file, line);
    std::fflush(stderr);
  }
  if (!collective && world_size > 1) {
    // A signal leaves the staging directory as it is: the interrupted run's files are there to be looked at.
    if (n != PETSC_ERR_SIG) RemoveFailedOutput();
    MPI_Abort(world, 1);
  }
  return n;
}

/// The first error raised while Record is the error handler (RunOnRoot).
struct RecordedError {
  int code = 0, line = 0;
  std::string func, file, message;
};

/// Keeps the first error in ctx (a RecordedError) instead of printing it or aborting the job.
PetscErrorCode Record(MPI_Comm, int line, const char *func, const char *file, PetscErrorCode n, PetscErrorType p,
                      const char *mess, void *ctx) {
  auto &error = *static_cast<RecordedError *>(ctx);
  if (p == PETSC_ERROR_INITIAL && error.code == 0)
    error = {(int)n, line, func ? func : "", file ? file : "", mess ? mess : ""};
  return n;
}

/// Calls work, a C++ exception it throws turned into a PETSc error.
PetscErrorCode CallWork(const std::function<PetscErrorCode()> &work) {
  PetscErrorCode code = 0;
  PetscFunctionBeginUser;
  PetscCallCXX(code = work());
  PetscCall(code);
  PetscFunctionReturn(0);
}

/// Runs work with Record as the error handler; an error code returned without an error raised gets PETSc's text for
/// it. Local (no communication).
PetscErrorCode RecordWork(const std::function<PetscErrorCode()> &work, RecordedError &error) {
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(Record, &error));
  const PetscErrorCode code = CallWork(work); // recorded, not raised: Record has to go first
  PetscCall(PetscPopErrorHandler());
  if (code != 0 && error.code == 0) {
    const char *text = nullptr;
    PetscCall(PetscErrorMessage(code, &text, nullptr));
    error = {(int)code, __LINE__, PETSC_FUNCTION_NAME, __FILE__, text ? text : "unknown error"};
  }
  PetscFunctionReturn(0);
}

} // namespace

void SetOptionsFiles(const std::string &files) { OptionsFiles() = files; }

void RemoveOnFailure(const std::string &dir, int made) {
  FailedOutput() = dir;
  MadeParents() = made;
}

void RemoveFailedOutput() {
  std::error_code ignored;
  if (!FailedOutput().empty()) std::filesystem::remove_all(FailedOutput(), ignored);
  // Then the parents the run made, from the innermost, while they are empty (remove refuses any other).
  std::filesystem::path p = std::filesystem::absolute(FailedOutput(), ignored).lexically_normal().parent_path();
  for (int i = 0; i < MadeParents() && std::filesystem::remove(p, ignored); ++i) p = p.parent_path();
  FailedOutput().clear();
  MadeParents() = 0;
}

PetscErrorCode InstallErrorHandler() {
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(Handler, nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckCollective(MPI_Comm comm, bool ok, const std::string &message) {
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscMPIInt mine = ok ? size : rank, first;
  PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm));
  if (first == size) PetscFunctionReturn(0);
  std::string text = message;
  PetscCall(Broadcast(comm, first, text));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", text.c_str());
}

PetscErrorCode RaiseFromRoot(MPI_Comm comm, const std::string &message_on_root) {
  PetscFunctionBeginUser;
  PetscCall(RunOnRoot(comm, [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCheck(message_on_root.empty(), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "%s", message_on_root.c_str());
    PetscFunctionReturn(0);
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode RunOnRoot(MPI_Comm comm, const std::function<PetscErrorCode()> &work) {
  PetscMPIInt rank;
  RecordedError error;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(RecordWork(work, error));
  int head[2] = {error.code, error.line};
  PetscCallMPI(MPI_Bcast(head, 2, MPI_INT, 0, comm));
  if (head[0] == 0) PetscFunctionReturn(0);
  for (std::string *text : {&error.func, &error.file, &error.message}) PetscCall(Broadcast(comm, 0, *text));
  // The error as work raised it, now on every rank of comm (the handler prints it once).
  return PetscError(comm, head[1], error.func.c_str(), error.file.c_str(), (PetscErrorCode)head[0],
                    PETSC_ERROR_INITIAL, "%s", error.message.c_str());
}

PetscErrorCode Broadcast(MPI_Comm comm, PetscMPIInt root, std::string &text) {
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int len = rank == root ? (int)text.size() : 0;
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, root, comm));
  std::vector<char> buf(len + 1, '\0');
  if (rank == root) std::memcpy(buf.data(), text.data(), len);
  PetscCallMPI(MPI_Bcast(buf.data(), len, MPI_CHAR, root, comm));
  text.assign(buf.data(), len);
  PetscFunctionReturn(0);
}

} // namespace signorini
