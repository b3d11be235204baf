// Where a file-valued option was set, so that a relative path in an options file is read relative to that file.
#pragma once

#include <petscsys.h>

#include <string>
#include <vector>

namespace signorini {

/// The places a relative path given to an option is looked for, in order: the directory of the options file that
/// last set the option (when an options file did), then the current directory. An absolute path is its own only place.
struct PathCandidates {
  std::vector<std::string> paths;   ///< where to look, first match wins
  std::vector<std::string> origins; ///< for each path, what it is relative to ("options file X", "the current directory")
};

/// PETSc's sources of options in its order of insertion (PETSC_OPTIONS, then the command line, each -options_file
/// read where it stands), reduced to the options files that set option name: returns the last such file, or "" when
/// the command line or PETSC_OPTIONS set the option last (or nothing did). Reads each options file with PETSc's own
/// reader (plain and YAML). Call after PetscInitialize on any rank; reads no option of the global database.
[[nodiscard]] PetscErrorCode LastOptionsFileSetting(const std::vector<std::string> &args, const char *petsc_options,
                                                    const std::string &name, std::string &file);

/// The command line PetscInitialize received (without the program name).
std::vector<std::string> CommandLineArgs();

/// Where to look for the value of option name (as given, possibly relative): see PathCandidates. Not collective.
[[nodiscard]] PetscErrorCode PathCandidatesFor(const std::string &name, const std::string &value, PathCandidates &out);

/// Where option name ("-name") was set last, for a message: "set in options file 'F'", "on the command line", "in
/// PETSC_OPTIONS", or "" when none of them names it (PETSc's own defaults). Not collective; the same on every rank.
[[nodiscard]] PetscErrorCode OptionOrigin(const std::string &name, std::string &origin);

/// The first candidate that exists; else "" and looked names every place looked ("'a' (relative to ...) nor at 'b'
/// (...)").
std::string FirstExisting(const PathCandidates &candidates, std::string &looked);

} // namespace signorini
