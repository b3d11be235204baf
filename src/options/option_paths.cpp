// Where a file-valued option was set, so that a relative path in an options file is read relative to that file.
#include "signorini/options/option_paths.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace signorini {

namespace {

std::string Directory(const std::string &file) {
  const auto slash = file.find_last_of('/');
  return slash == std::string::npos ? "." : slash == 0 ? "/" : file.substr(0, slash);
}

std::string Join(const std::string &dir, const std::string &path) { return dir == "." ? path : dir + "/" + path; }

/// Whether the options file sets name, read with PETSc's reader into a database of its own.
PetscErrorCode FileSets(const std::string &file, bool yaml, const std::string &name, bool &sets) {
  PetscOptions options;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsCreate(&options));
  if (yaml) PetscCall(PetscOptionsInsertFileYAML(PETSC_COMM_SELF, options, file.c_str(), PETSC_FALSE));
  else PetscCall(PetscOptionsInsertFile(PETSC_COMM_SELF, options, file.c_str(), PETSC_FALSE));
  PetscCall(PetscOptionsHasName(options, nullptr, name.c_str(), &found));
  PetscCall(PetscOptionsDestroy(&options));
  sets = found;
  PetscFunctionReturn(0);
}

/// Walks one source of options (PETSC_OPTIONS or the command line): each -options_file may set name, and name
/// itself given here resets the setter to "" (relative to the current directory).
PetscErrorCode Scan(const std::vector<std::string> &words, const std::string &name, std::string &file) {
  PetscFunctionBeginUser;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const bool plain = words[i] == "-options_file", yaml = words[i] == "-options_file_yaml";
    if ((plain || yaml) && i + 1 < words.size()) {
      bool sets = false;
      PetscCall(FileSets(words[i + 1], yaml, name, sets));
      if (sets) file = words[i + 1];
      ++i;
    } else if (words[i] == name) {
      file.clear();
    }
  }
  PetscFunctionReturn(0);
}

/// The words of PETSC_OPTIONS (null: none), as PETSc splits them.
std::vector<std::string> Words(const char *text) {
  std::vector<std::string> words;
  std::istringstream in(text ? text : "");
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

} // namespace

PetscErrorCode LastOptionsFileSetting(const std::vector<std::string> &args, const char *petsc_options,
                                      const std::string &name, std::string &file) {
  PetscFunctionBeginUser;
  file.clear();
  PetscCall(Scan(Words(petsc_options), name, file));
  PetscCall(Scan(args, name, file));
  PetscFunctionReturn(0);
}

std::vector<std::string> CommandLineArgs() {
  int argc = 0;
  char **argv = nullptr;
  std::vector<std::string> args;
  if (PetscGetArgs(&argc, &argv) != 0 || !argv) return args;
  for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
  return args;
}

PetscErrorCode PathCandidatesFor(const std::string &name, const std::string &value, PathCandidates &out) {
  PetscFunctionBeginUser;
  out = PathCandidates{};
  if (!value.empty() && value[0] == '/') {
    out.paths = {value};
    out.origins = {"an absolute path"};
    PetscFunctionReturn(0);
  }
  std::string file;
  PetscCall(LastOptionsFileSetting(CommandLineArgs(), std::getenv("PETSC_OPTIONS"), name, file));
  if (!file.empty()) {
    out.paths.push_back(Join(Directory(file), value));
    out.origins.push_back("relative to options file '" + file + "'");
  }
  out.paths.push_back(value);
  out.origins.push_back("relative to the current directory");
  PetscFunctionReturn(0);
}

PetscErrorCode OptionOrigin(const std::string &name, std::string &origin) {
  PetscFunctionBeginUser;
  const std::vector<std::string> args = CommandLineArgs();
  const char *petsc_options = std::getenv("PETSC_OPTIONS");
  std::string file;
  PetscCall(LastOptionsFileSetting(args, petsc_options, name, file));
  const auto in = [&name](const std::vector<std::string> &words) {
    return std::find(words.begin(), words.end(), name) != words.end();
  };
  if (!file.empty()) origin = "set in options file '" + file + "'";
  else if (in(args)) origin = "on the command line";
  else if (in(Words(petsc_options))) origin = "in PETSC_OPTIONS";
  else origin.clear();
  PetscFunctionReturn(0);
}

std::string FirstExisting(const PathCandidates &candidates, std::string &looked) {
  looked.clear();
  for (const auto &path : candidates.paths)
    if (access(path.c_str(), F_OK) == 0) return path;
  for (std::size_t i = 0; i < candidates.paths.size(); ++i)
    looked += (i ? " nor at '" : "'") + candidates.paths[i] + "' (" + candidates.origins[i] + ")";
  return "";
}

} // namespace signorini
