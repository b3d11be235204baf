// Strict readers of option values: no value ignored, no hexadecimal or overflowing number, every range checked.
#include "signorini/options/readers.hpp"

#include "signorini/core/parse.hpp"

#include <cmath>

namespace signorini {

namespace {

constexpr const char *REAL_GRAMMAR = "a finite real number in decimal or scientific notation";

std::string Interval(double lo, double hi, bool lo_open, bool hi_open) {
  return std::string(lo_open ? "(" : "[") + FormatNumber(lo) + ", " + FormatNumber(hi) + (hi_open ? ")" : "]");
}

/// The raw text of option name ("" when it is given without a value); found = whether it is given at all. The PETSc
/// reader call before it has listed the option for -help and marked it used.
PetscErrorCode RawValue(PetscOptionItems *PetscOptionsObject, const char *name, std::string &raw, PetscBool &found) {
  const char *value = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(PetscOptionsObject->options, PetscOptionsObject->prefix, name, &value, &found));
  raw = found && value ? value : "";
  PetscFunctionReturn(0);
}

/// Lists option name in -help (with its default and help text), then returns its raw text.
PetscErrorCode ListAndRead(PetscOptionItems *PetscOptionsObject, const char *name, const std::string &help,
                           const std::string &default_text, std::string &raw, PetscBool &found) {
  char buffer[256];
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buffer, default_text.c_str(), sizeof(buffer)));
  PetscCall(PetscOptionsString(name, help.c_str(), "", buffer, buffer, sizeof(buffer), nullptr));
  PetscCall(RawValue(PetscOptionsObject, name, raw, found));
  PetscFunctionReturn(0);
}

} // namespace

RealRange RealRange::Whole(double lo, double hi) {
  RealRange range{lo, hi};
  range.whole = true;
  return range;
}

bool RealRange::Contains(double value) const {
  const double a = lo * scale, b = hi * scale;
  return (lo_open ? value > a : value >= a) && (hi_open ? value < b : value <= b) &&
         (!whole || value == std::floor(value));
}

std::string RealRange::Relative() const {
  return Interval(lo, hi, lo_open, hi_open) + (unit ? std::string(" x ") + unit : "");
}

std::string RealRange::Absolute() const {
  if (!unit) return Interval(lo, hi, lo_open, hi_open);
  return Interval(lo * scale, hi * scale, lo_open, hi_open) + " (" + Relative() + ", " + unit + " " +
         FormatNumber(scale) + ")";
}

PetscErrorCode OptionsReal(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                           const RealRange &range, double &value, PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  // A relative range lists its default in the range's unit ("0.1 x body diagonal"), not as a bare number.
  const std::string default_text =
      range.unit && range.scale != 0 ? FormatNumber(value / range.scale) + " x " + range.unit : FormatNumber(value);
  PetscCall(ListAndRead(PetscOptionsObject, name,
                        std::string(help) + "; range " + range.Relative() + (range.whole ? ", whole numbers" : ""),
                        default_text, raw, found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCall(CheckRealValue(comm, name, raw, range, value));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckRealValue(MPI_Comm comm, const std::string &name, const std::string &raw, const RealRange &range,
                              double &value) {
  const char *kind = range.whole ? "a whole number" : "a number";
  // " in [0, 1]"; nothing for a range without bounds (any finite number).
  const std::string in = std::isinf(range.lo) && std::isinf(range.hi) ? "" : " in " + range.Absolute();
  PetscFunctionBeginUser;
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT, "%s is given without a value; expected %s%s", name.c_str(),
             kind, in.c_str());
  const auto parsed = ParseFinite(raw);
  PetscCheck(parsed, comm, PETSC_ERR_USER_INPUT, "%s %s is invalid; expected %s%s", name.c_str(), raw.c_str(),
             range.whole ? "a whole number" : REAL_GRAMMAR, in.c_str());
  PetscCheck(range.Contains(*parsed), comm, PETSC_ERR_USER_INPUT, "%s %s is %s; expected %s%s", name.c_str(),
             raw.c_str(), range.whole && *parsed != std::floor(*parsed) ? "not a whole number" : "out of range", kind,
             in.c_str());
  value = *parsed;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsInt(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscInt lo,
                          PetscInt hi, PetscInt &value, PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, std::string(help) + "; range " + range, std::to_string(value), raw,
                        found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT, "%s is given without a value; expected an integer in %s", name,
             range.c_str());
  const auto parsed = ParseInteger(raw);
  PetscCheck(parsed && *parsed >= lo && *parsed <= hi, comm, PETSC_ERR_USER_INPUT,
             "%s %s is invalid; expected an integer in %s", name, raw.c_str(), range.c_str());
  value = (PetscInt)*parsed;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsString(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                             const char *expected, std::string &value, PetscBool *set) {
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, help, value, raw, found));
  if (set) *set = found;
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value; expected %s", name, expected);
  value = raw;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsStringList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                                 const char *empty_means, const char *expected, std::vector<std::string> &items,
                                 PetscBool *set) {
  MPI_Comm comm = PetscOptionsObject->comm;
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(ListAndRead(PetscOptionsObject, name, help, "", raw, found));
  if (set) *set = found;
  items.clear();
  if (!found) PetscFunctionReturn(0);
  PetscCheck(!raw.empty(), comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value, which would leave %s; expected %s", name, empty_means, expected);
  items = Split(raw, ',');
  for (std::size_t i = 0; i < items.size(); ++i) {
    // Blanks around an item are layout ("0,2, 0,0" in an options file), as PETSc's own list readers take them.
    const auto first = items[i].find_first_not_of(" \t"), last = items[i].find_last_not_of(" \t");
    items[i] = first == std::string::npos ? "" : items[i].substr(first, last - first + 1);
    PetscCheck(!items[i].empty(), comm, PETSC_ERR_USER_INPUT,
               "%s %s has an empty item %zu (an empty list would leave %s); expected %s", name, raw.c_str(), i + 1,
               empty_means, expected);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsRealList(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                               const char *empty_means, const char *expected, std::vector<double> &values,
                               PetscBool *set) {
  std::vector<std::string> items;
  PetscFunctionBeginUser;
  PetscCall(OptionsStringList(PetscOptionsObject, name, help, empty_means, expected, items, set));
  PetscCall(ParseRealList(PetscOptionsObject->comm, name, Join(items, ","), items, values));
  PetscFunctionReturn(0);
}

PetscErrorCode ParseRealList(MPI_Comm comm, const char *name, const std::string &text,
                             const std::vector<std::string> &items, std::vector<double> &values) {
  PetscFunctionBeginUser;
  values.clear();
  for (std::size_t i = 0; i < items.size(); ++i) {
    const auto v = ParseFinite(items[i]);
    PetscCheck(v, comm, PETSC_ERR_USER_INPUT, "%s %s: value %zu '%s' is invalid; expected %s", name, text.c_str(),
               i + 1, items[i].c_str(), REAL_GRAMMAR);
    values.push_back(*v);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsRequireValue(PetscOptionItems *PetscOptionsObject, const char *name, const char *expected) {
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(RawValue(PetscOptionsObject, name, raw, found));
  PetscCheck(!found || !raw.empty(), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT,
             "%s is given without a value; expected %s", name, expected);
  PetscFunctionReturn(0);
}

PetscErrorCode OptionsChoice(PetscOptionItems *PetscOptionsObject, const char *name, const char *help,
                             const char *expected, const char *const *list, PetscInt n, PetscInt &value,
                             PetscBool *set) {
  std::string raw;
  PetscBool found;
  PetscFunctionBeginUser;
  PetscCall(OptionsRequireValue(PetscOptionsObject, name, expected));
  PetscCall(RawValue(PetscOptionsObject, name, raw, found));
  if (found) {
    bool known = false;
    std::string names;
    for (PetscInt i = 0; i < n; ++i) {
      PetscBool same;
      PetscCall(PetscStrcasecmp(raw.c_str(), list[i], &same));
      known = known || same;
      names += std::string(i ? " " : "") + list[i];
    }
    PetscCheck(known, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "Unknown option %s for %s. Available options: %s",
               raw.c_str(), name, names.c_str());
  }
  PetscCall(PetscOptionsEList(name, help, "", list, n, list[value], &value, set));
  PetscFunctionReturn(0);
}

} // namespace signorini
