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

/// Parses the items of list option name (text: its value, for the message) as finite reals into values; an item that
/// is not one is an error naming the option, its value, the item and the grammar. Collective on comm.
[[nodiscard]] PetscErrorCode ParseRealList(MPI_Comm comm, const char *name, const std::string &text,
                                           const std::vector<std::string> &items, std::vector<double> &values);

/// Refuses the option name when it is given without a value (for choices read by PETSc, such as PetscOptionsEList).
[[nodiscard]] PetscErrorCode OptionsRequireValue(PetscOptionItems *PetscOptionsObject, const char *name,
                                                 const char *expected);

/// Reads the choice option name into value (the index of one of the n names of list, case-insensitive; left as it is
/// when the option is not set), as PetscOptionsEList lists and reads it, after refusing what it would refuse: a name
/// given without a value (expected says what it takes), and a value that is none of the names ("Unknown option V for
/// NAME. Available options: ..."), which PETSc 3.18's reader raises without freeing what it allocated.
[[nodiscard]] PetscErrorCode OptionsChoice(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                           const char *expected, const char *const *list, PetscInt n,
                                           PetscInt &value, PetscBool *set = nullptr);

} // namespace signorini
