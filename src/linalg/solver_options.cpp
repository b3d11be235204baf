// The values of the saddle-point solver's PETSc options, checked before PETSc reads them, and the refusal of those
// that the chosen solver will never read.
#include "signorini/linalg/solver_options.hpp"
#include "signorini/linalg/pc_nullspace.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/options/readers.hpp"
#include "signorini/options/unused_options.hpp"
#include "signorini/core/parse.hpp"

#include <petscksp.h>

#include <algorithm>
#include <cctype>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace signorini {

namespace {

constexpr long long ANY_LO = std::numeric_limits<long long>::min(), ANY_HI = std::numeric_limits<long long>::max();

/// The integers an option takes: [lo, hi], or the values of only when it is not empty.
struct IntValues {
  long long lo = ANY_LO, hi = ANY_HI;
  std::vector<long long> only;

  IntValues() = default;
  IntValues(long long lo_, long long hi_) : lo(lo_), hi(hi_) {}
  static IntValues Of(std::vector<long long> values) {
    IntValues v;
    v.only = std::move(values);
    return v;
  }

  bool Contains(long long v) const {
    return only.empty() ? v >= lo && v <= hi : std::find(only.begin(), only.end(), v) != only.end();
  }
  /// "an integer >= 0", "an integer in [0, 3]", "one of -2, 0, 1, 77", for messages.
  std::string Expected() const {
    if (!only.empty()) {
      std::vector<std::string> items;
      for (long long v : only) items.push_back(std::to_string(v));
      return "one of " + Join(items, ", ");
    }
    if (hi == ANY_HI) return lo == ANY_LO ? "an integer" : "an integer >= " + std::to_string(lo);
    if (lo == ANY_LO) return "an integer <= " + std::to_string(hi);
    return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  }
};

/// An ICNTL that PETSc's MUMPS interface (PETSc 3.18) passes on, with the values that MUMPS 5.5's users' guide
/// defines for it (MUMPS treats others as its default, or fails later with an INFOG code that names no option).
struct Icntl {
  int k;
  const char *meaning;
  IntValues values;
};

const std::vector<Icntl> &Icntls() {
  static const std::vector<Icntl> table = {
      {1, "output stream for errors", {}},
      {2, "output stream for diagnostics", {}},
      {3, "output stream for global information", {}},
      {4, "level of printing", {}},
      {6, "permutation to a zero-free diagonal", {0, 7}},
      // The ordering: ReadMumpsControls checks it against the orderings this MUMPS is built with.
      {7, "ordering", {}},
      // -1 is a scaling given by the caller, which neither PETSc's interface nor the kept factorisation gives.
      {8, "scaling strategy", IntValues::Of({-2, 0, 1, 3, 4, 7, 8, 77})},
      {10, "iterative refinement steps", {}},
      {11, "error analysis", {0, 2}},
      {12, "ordering strategy for symmetric matrices", {0, 3}},
      {13, "parallelism of the root node", {-1, ANY_HI}},
      {14, "workspace increase, in percent", {0, ANY_HI}},
      {15, "compression of a block format", {ANY_LO, 1}},
      {19, "Schur complement", {0, 3}},
      {20, "right-hand side format", IntValues::Of({0, 1, 2, 3, 10, 11})},
      {22, "out-of-core factorisation", {0, 1}},
      {23, "working memory per process, in MB", {0, ANY_HI}},
      {24, "null pivot detection", {0, 1}},
      {25, "solution of a deficient matrix", {-1, ANY_HI}},
      {26, "solution phase with a Schur complement", {0, 2}},
      {27, "blocking size for multiple right-hand sides", {}},
      {28, "sequential or parallel analysis", {0, 2}},
      {29, "parallel ordering", {0, 2}},
      {31, "factors discarded during the factorisation", {0, 2}},
      {33, "determinant", {0, 1}},
      {35, "block low-rank factorisation", {0, 3}},
      {36, "block low-rank variant", {0, 1}},
      {38, "estimated compression rate of block low-rank factors, per mille", {0, 1000}},
  };
  return table;
}

/// A CNTL that PETSc's MUMPS interface passes on, with the values MUMPS 5.5 defines for it.
struct Cntl {
  int k;
  RealRange values;
};

const std::vector<Cntl> &Cntls() {
  static const std::vector<Cntl> table = {
      {1, {0, 1}},                                       // relative pivoting threshold
      {2, {}},                                           // refinement stop (< 0: sqrt(eps))
      {3, {}},                                           // null pivot threshold (< 0: absolute)
      {4, {}},                                           // static pivoting (< 0: off)
      {5, {}},                                           // fixation of null pivots (<= 0: the default)
      {7, {0, std::numeric_limits<double>::infinity()}}, // block low-rank dropping parameter
  };
  return table;
}

/// name ends with the option suffix (the whole name after the prefix, or after a '_').
bool HasSuffix(const std::string &name, const std::string &suffix) {
  return name == suffix || EndsWith(name, "_" + suffix);
}

/// k of a name "..._mat_mumps_<array>_<k>" ("icntl" or "cntl"), or 0.
int MumpsIndex(const std::string &name, const std::string &array) {
  const std::string key = "mat_mumps_" + array + "_";
  const auto pos = name.rfind(key);
  if (pos == std::string::npos || (pos > 0 && name[pos - 1] != '_')) return 0;
  const auto k = ParseInteger(name.substr(pos + key.size()));
  return k && *k > 0 && *k <= 60 ? (int)*k : 0;
}

/// Refuses the type option name with value (nullptr when given without one) unless list registers it.
PetscErrorCode CheckType(MPI_Comm comm, const std::string &name, const char *value, PetscFunctionList list,
                         const char *kind) {
  const char **names = nullptr;
  int n = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListGet(list, &names, &n));
  std::vector<std::string> types; // n counts the array's closing nullptr
  for (int i = 0; i < n && names[i]; ++i) types.emplace_back(names[i]);
  PetscCall(PetscFree(names));
  const std::string given = value ? value : "";
  if (std::find(types.begin(), types.end(), given) != types.end()) PetscFunctionReturn(0);
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s %s; expected a %s type, one of %s", name.c_str(),
          given.empty() ? "is given without a value" : (given + " is not a " + kind + " type").c_str(), kind,
          Join(types, ", ").c_str());
}

/// Refuses the integer option name with value unless it is one of values.
PetscErrorCode CheckInt(MPI_Comm comm, const std::string &name, const char *value, const IntValues &values,
                        const std::string &about) {
  PetscFunctionBeginUser;
  const std::string given = value ? value : "";
  PetscCheck(!given.empty(), comm, PETSC_ERR_USER_INPUT, "%s is given without a value; expected %s", name.c_str(),
             values.Expected().c_str());
  const auto v = ParseInteger(given);
  PetscCheck(v, comm, PETSC_ERR_USER_INPUT, "%s %s is invalid; expected %s", name.c_str(), given.c_str(),
             values.Expected().c_str());
  PetscCheck(values.Contains(*v), comm, PETSC_ERR_USER_INPUT, "%s %s is out of range%s; expected %s", name.c_str(),
             given.c_str(), about.c_str(), values.Expected().c_str());
  PetscFunctionReturn(0);
}

/// Checks one MUMPS control (array "icntl" or "cntl", index k) against the controls passed on and what MUMPS defines.
PetscErrorCode CheckMumpsControl(MPI_Comm comm, const std::string &name, const char *value, const std::string &array,
                                 int k) {
  const bool icntl = array == "icntl";
  const char *upper = icntl ? "ICNTL" : "CNTL";
  double ignored;
  PetscFunctionBeginUser;
  std::vector<std::string> passed;
  for (const Icntl &c : Icntls())
    if (icntl && c.k == k) {
      PetscCall(CheckInt(comm, name, value, c.values, " for MUMPS's ICNTL(" + std::to_string(k) + ") (" + c.meaning +
                                                        ")"));
      PetscFunctionReturn(0);
    } else if (icntl) passed.push_back(std::to_string(c.k));
  for (const Cntl &c : Cntls())
    if (!icntl && c.k == k) {
      PetscCall(CheckRealValue(comm, name, value ? value : "", c.values, ignored));
      PetscFunctionReturn(0);
    } else if (!icntl) passed.push_back(std::to_string(c.k));
  SETERRQ(comm, PETSC_ERR_USER_INPUT,
          "%s: %s(%d) is not among the MUMPS controls that this solver passes on (PETSc's MUMPS interface would "
          "ignore it); expected one of %s %s", name.c_str(), upper, k, upper, Join(passed, ", ").c_str());
}

/// Checks the solver option name (without its '-', in lower case) given with value (nullptr: without one).
PetscErrorCode CheckSolverOption(MPI_Comm comm, const std::string &lower, const char *value) {
  const std::string name = "-" + lower;
  double ignored;
  PetscFunctionBeginUser;
  if (HasSuffix(lower, "ksp_type")) PetscCall(CheckType(comm, name, value, KSPList, "KSP"));
  else if (HasSuffix(lower, "pc_type")) PetscCall(CheckType(comm, name, value, PCList, "PC"));
  else if (HasSuffix(lower, "ksp_rtol"))
    PetscCall(CheckRealValue(comm, name, value ? value : "", {0, 1, false, true}, ignored));
  else if (HasSuffix(lower, "ksp_atol"))
    PetscCall(CheckRealValue(comm, name, value ? value : "", {0, std::numeric_limits<double>::infinity()}, ignored));
  else if (HasSuffix(lower, "ksp_max_it")) PetscCall(CheckInt(comm, name, value, {1, ANY_HI}, ""));
  else if (const int k = MumpsIndex(lower, "icntl")) PetscCall(CheckMumpsControl(comm, name, value, "icntl", k));
  else if (const int k = MumpsIndex(lower, "cntl"); k && k <= 15)
    PetscCall(CheckMumpsControl(comm, name, value, "cntl", k));
  PetscFunctionReturn(0);
}

/// An option that no one has read yet: its name as given (without the dash) and in lower case, and its value.
struct UnreadOption {
  std::string name, lower, value;
  bool valued;
};

/// The options not read yet, in the same order on every rank; copies, so that the database's arrays go back before
/// an error is raised.
PetscErrorCode UnreadOptions(std::vector<UnreadOption> &unread) {
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  unread.clear();
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  for (PetscInt i = 0; i < n; ++i)
    unread.push_back({names[i], LowerCase(names[i]), values[i] ? values[i] : "", values[i] != nullptr});
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckSolverOptionValues(MPI_Comm comm) {
  std::vector<UnreadOption> unread;
  PetscFunctionBeginUser;
  PetscCall(KSPInitializePackage()); // registers the KSP and PC types
  PetscCall(PCInitializePackage());
  PetscCall(PCNullSpaceRegister()); // signorini's own type, a value of -contact_pc_type
  // The options not read yet: the solver's, before its KSP reads them.
  PetscCall(UnreadOptions(unread));
  for (const UnreadOption &o : unread)
    if (IsSolverOption(o.lower)) PetscCall(CheckSolverOption(comm, o.lower, o.valued ? o.value.c_str() : nullptr));
  PetscFunctionReturn(0);
}

namespace {

/// The Krylov tolerances of the saddle-point KSP: KSPSetFromOptions reads them for a KSP type other than preonly only,
/// and nothing reads them later.
constexpr const char *KRYLOV_TOLERANCES[] = {"contact_ksp_rtol", "contact_ksp_atol", "contact_ksp_divtol",
                                             "contact_ksp_max_it"};
/// The options of the saddle-point PC, and of the sub-solvers that only PC types other than LU and Cholesky create:
/// an LU or Cholesky PC reads all of its own options in PCSetFromOptions (its factor's, -contact_mat_*, come later).
constexpr const char *OTHER_PC_PREFIXES[] = {"contact_pc_",  "contact_fieldsplit_",   "contact_sub_",
                                             "contact_mg_",  "contact_redundant_",    "contact_telescope_",
                                             "contact_lsc_", "contact_redistribute_", "contact_galerkin_",
                                             "contact_hmg_", "contact_patch_"};

/// "-a 1 does" or "-a 1, -b 2 do", for messages.
std::string NamedOptions(const std::vector<std::string> &options) {
  return Join(options, ", ") + (options.size() == 1 ? " does" : " do");
}

/// What the solver is, for messages: "the kept MUMPS factorisation (a direct solve, -contact_pc_type cholesky)", ...
std::string DescribeSolver(bool kept, bool preonly, bool factor, const std::string &pc_type) {
  const std::string pc = "-contact_pc_type " + pc_type;
  if (kept) return "the kept MUMPS factorisation (a direct solve, " + pc + ")";
  if (preonly && factor) return "a direct solve (-contact_ksp_type preonly, " + pc + ")";
  if (preonly) return "-contact_ksp_type preonly (one application of " + pc + ")";
  return pc;
}

} // namespace

PetscErrorCode RefuseSolverOptionsNotRead(KSP ksp, bool kept) {
  MPI_Comm comm = PetscObjectComm((PetscObject)ksp);
  PetscBool refuse = PETSC_TRUE, preonly, factor;
  PC pc;
  PCType pc_type;
  std::vector<UnreadOption> unread;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-options_left", &refuse, nullptr));
  if (!refuse) PetscFunctionReturn(0);
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  PetscCall(PCGetType(pc, &pc_type));
  std::vector<std::string> tolerances, other_pc; // "-name value" as given, in the database's order
  PetscCall(UnreadOptions(unread));
  for (const UnreadOption &o : unread) {
    const std::string given = "-" + o.name + (o.valued ? " " + o.value : "");
    const auto is = [&](const char *name) { return o.lower == name; };
    const auto under = [&](const char *prefix) { return o.lower.rfind(prefix, 0) == 0; };
    if (preonly && std::any_of(std::begin(KRYLOV_TOLERANCES), std::end(KRYLOV_TOLERANCES), is))
      tolerances.push_back(given);
    else if (factor && std::any_of(std::begin(OTHER_PC_PREFIXES), std::end(OTHER_PC_PREFIXES), under))
      other_pc.push_back(given);
  }
  const std::string solver = DescribeSolver(kept, preonly, factor, pc_type);
  std::string message;
  if (!tolerances.empty())
    message = NamedOptions(tolerances) + " not apply to " + solver + ", which makes no Krylov iterations; " +
              (tolerances.size() == 1 ? "it applies" : "they apply") +
              " with an iterative solver (-contact_ksp_type other than preonly, or a fieldsplit preset such as "
              "-options_file options/solver/fieldsplit_gamg.yml)";
  else if (!other_pc.empty()) {
    const bool one = other_pc.size() == 1;
    message = NamedOptions(other_pc) + " not apply to " + solver + ": " + (one ? "it is an option" : "they are options") +
              " of another preconditioner, or of a sub-solver that only another one creates (" + pc_type +
              " has read its own); expected the -contact_pc_type or solver preset that reads " + (one ? "it" : "them") +
              " (-help lists the options of the solver chosen)";
  }
  // Every rank holds the same options and the same solver: rank 0's verdict, so that all raise it or none.
  PetscCall(Broadcast(comm, 0, message));
  PetscCheck(message.empty(), comm, PETSC_ERR_USER_INPUT, "%s", message.c_str());
  PetscFunctionReturn(0);
}
} // namespace signorini
