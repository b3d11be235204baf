// Strict readers of option values, for use between PetscOptionsBegin and PetscOptionsEnd: an option given without a
// value is an error that names it, reals are decimal or scientific notation only, integers are read exactly, and
// every value is checked against its documented range.
#pragma once

#include <petscsys.h>

#include <limits>
#include <string>
#include <vector>

namespace signorini {

/// The valid values of a real option: lo..hi (either end open or closed), in units of scale, which unit names
/// ("body diagonal", "E x thickness"; none for an absolute range).
struct RealRange {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  double scale = 1;
  const char *unit = nullptr;

  bool Contains(double value) const;
  /// "[0, 0.001] x body diagonal", for -help and the README.
  std::string Relative() const;
  /// "[0, 0.0179] (1e-3 x body diagonal 17.9)": the bounds in absolute terms, for messages.
  std::string Absolute() const;
};

/// Reads the real option name into value (left as it is when the option is not set), strictly: decimal or scientific
/// notation only, finite, inside range. -help lists it with its range. Errors name the option, the value as written
/// and the range.
[[nodiscard]] PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                         const RealRange &range, double &value, PetscBool *set = nullptr);

/// Reads the integer option name into value: whole decimal integers only, exactly, in [lo, hi].
[[nodiscard]] PetscErrorCode OptionsInt(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                        PetscInt lo, PetscInt hi, PetscInt &value, PetscBool *set = nullptr);

/// Reads a string option; a name given without a value is an error that says what was expected.
[[nodiscard]] PetscErrorCode OptionsString(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                           const char *expected, std::string &value, PetscBool *set = nullptr);

/// Reads a comma-separated list; a name without a value or an empty item is an error that says what the empty list
/// would leave (empty_means, e.g. "no obstacle") and what was expected.
[[nodiscard]] PetscErrorCode OptionsStringList(PetscOptionItems *PetscOptionsObject, const char *name,
                                               const char *help, const char *empty_means, const char *expected,
                                               std::vector<std::string> &items, PetscBool *set = nullptr);

/// Reads a comma-separated list of finite reals (decimal or scientific notation) with OptionsStringList's checks.
[[nodiscard]] PetscErrorCode OptionsRealList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                             const char *empty_means, const char *expected,
                                             std::vector<double> &values, PetscBool *set = nullptr);

/// Refuses the option name when it is given without a value (for choices read by PETSc, such as PetscOptionsEList).
[[nodiscard]] PetscErrorCode OptionsRequireValue(PetscOptionItems *PetscOptionsObject, const char *name,
                                                 const char *expected);

/// Checks the command line as PETSc reads it (-name value, -name, -options_file FILE, ...): an argument that is
/// neither an option nor an option's value (PETSc would skip it silently, e.g. a case file given without
/// -options_file), or a misspelling of -options_file (PETSc would take it for an unused option and run the default
/// case), is an error that names it and says what was expected. Collective (every rank has the same arguments).
[[nodiscard]] PetscErrorCode CheckCommandLine(int argc, char **argv);

/// The first options file that cannot be read, or a YAML one that sets an option twice or names an options_file (PETSc
/// would take either silently), as a message naming it and saying what was expected; empty when there is none. The
/// files are those of -options_file FILE and -options_file_yaml FILE on the command line and in
/// PETSC_OPTIONS, and those that a plain options file names in turn. files: the ones it saw, for SetOptionsFiles.
/// Needs no PETSc (it runs before PetscInitialize).
std::string OptionsFileProblem(int argc, char **argv, std::string &files);

} // namespace signorini
