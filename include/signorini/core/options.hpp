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
/// ("body diagonal", "E x thickness"; none for an absolute range); whole: whole numbers only (a count too large for
/// an integer option, such as -mesh_max_cells).
struct RealRange {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  double scale = 1;
  const char *unit = nullptr;
  bool whole = false;

  /// The whole numbers in [lo, hi].
  static RealRange Whole(double lo, double hi);
  bool Contains(double value) const;
  /// "[0, 0.001] x body diagonal", for -help and docs/options.md.
  std::string Relative() const;
  /// "[0, 0.0179] (1e-3 x body diagonal 17.9)": the bounds in absolute terms, for messages.
  std::string Absolute() const;
};

/// Reads the real option name into value (left as it is when the option is not set), strictly: decimal or scientific
/// notation only, finite, inside range. -help lists it with its range. Errors name the option, the value as written
/// and the range.
[[nodiscard]] PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                         const RealRange &range, double &value, PetscBool *set = nullptr);

/// Checks the text raw of the real option name (as given; empty when it is given without a value) as OptionsReal
/// does, with its messages, and returns it in value. For options that PETSc reads itself (the solver's). Raises on
/// comm: call on all its ranks together, with the same text.
[[nodiscard]] PetscErrorCode CheckRealValue(MPI_Comm comm, const std::string &name, const std::string &raw,
                                            const RealRange &range, double &value);

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

/// Whether the option name (without its '-', in lower case) is one of the saddle-point solver's, which PETSc reads
/// while the solve runs: -contact_ followed by the KSP's, the PC's, the factor matrix's (-contact_mat_mumps_*) or a
/// sub-solver's prefix (fieldsplit_, sub_, mg_, ...).
bool IsSolverOption(const std::string &name);

/// When CheckUnusedOptions runs: after the set-up (every component but the solve has read its options), or after the
/// solve (before the output is published).
enum class UnusedOptions { AFTER_SETUP, AFTER_SOLVE };

/// Refuses the options that were set (command line, options files, PETSC_OPTIONS) but never read, misspelt or not
/// meant for this run, with one error naming them, unless -options_left is false (the documented opt-out). After the
/// set-up it leaves those the solve may still read: the saddle-point solver's (-contact_ksp_*, -contact_pc_*,
/// -contact_mat_*, -contact_fieldsplit_*, the options of the sub-solvers it creates) and those of the vectors and
/// matrices it assembles (-vec_*, -mat_*, -is_*, -sf_*, -vecscatter_*, -viewer_*, -draw_*). PETSc's generic options
/// that it reads only in PetscFinalize (-options_view, ...) are never refused. After the solve it sets -options_left 0,
/// so that PetscFinalize does not list them again. Collective.
[[nodiscard]] PetscErrorCode CheckUnusedOptions(MPI_Comm comm, UnusedOptions when);

/// Checks the command line as PETSc reads it (-name value, -name, -options_file FILE, ...): an argument that is
/// neither an option nor an option's value (PETSc would skip it silently, e.g. a case file given without
/// -options_file), a misspelling of -options_file (PETSc would take it for an unused option and run the default
/// case), an option given twice (PETSc would keep the last value; -options_file may be given several times), or an
/// option that an -options_file after it sets again (PETSc would take the file's value; an option of the command
/// line overrides one of a file before it or of PETSC_OPTIONS) is an error that names it and says what was expected.
/// Collective (every rank has the same arguments).
[[nodiscard]] PetscErrorCode CheckCommandLine(int argc, char **argv);

/// The first options file that cannot be read, or a YAML one that sets an option twice (in one document or in two) or
/// names an options_file (PETSc would take either silently), as a message naming it and saying what was expected;
/// empty when there is none. The files are those of -options_file FILE and -options_file_yaml FILE on the command
/// line and in PETSC_OPTIONS, and those that a plain options file names in turn. files: the ones it saw, for
/// SetOptionsFiles.
/// Needs no PETSc (it runs before PetscInitialize).
std::string OptionsFileProblem(int argc, char **argv, std::string &files);

} // namespace signorini
