// The report of options set but never read (misspelt, or not meant for this run).
#include "signorini/options/unused_options.hpp"

#include "signorini/core/errors.hpp"
#include "signorini/core/parse.hpp"
#include "signorini/options/option_paths.hpp"

#include <algorithm>
#include <cstring>
#include <set>

namespace signorini {

namespace {

/// PETSc's generic options (-help lists them) that PETSc reads only in PetscFinalize or when the feature they tune
/// starts (a debugger, a shared temporary directory): given, they are not misspelt, whether or not they were read.
constexpr const char *GENERIC_READ_LATE[] = {"options_view",   "citations", "get_total_flops", "debugger_ranks",
                                             "debugger_pause", "tmp",       "shared_tmp",      "not_shared_tmp"};

/// The kinds of PETSc object whose options the saddle-point KSP (prefix contact_) and what it creates read while
/// the solve runs: the KSP and PC themselves, the factor matrix (-contact_mat_mumps_*), fieldsplit's blocks, and the
/// sub-solvers of block Jacobi/ASM, multigrid levels, redundant, telescope, LSC, redistribute, Galerkin, HMG, patch,
/// deflation and FETI-DP.
constexpr const char *SOLVER_PREFIX = "contact_";
constexpr const char *SOLVER_OBJECTS[] = {"ksp_",      "pc_",        "mat_",       "fieldsplit_", "sub_",
                                          "mg_",       "redundant_", "telescope_", "lsc_",        "redistribute_",
                                          "galerkin_", "hmg_",       "patch_",     "deflation_",  "fetidp_"};
/// The kinds of PETSc object that the solve makes or assembles without a prefix, whose generic options
/// (-vec_view, -mat_view, ...) it reads then.
constexpr const char *UNPREFIXED_OBJECTS[] = {"vec_", "mat_", "is_", "sf_", "vecscatter_", "viewer_", "draw_"};

/// Whether name (without its '-') is prefix followed by one of the object kinds.
template <std::size_t N>
bool NamesObject(const std::string &name, const std::string &prefix, const char *const (&objects)[N]) {
  return name.rfind(prefix, 0) == 0 && std::any_of(std::begin(objects), std::end(objects), [&](const char *k) {
           return name.compare(prefix.size(), std::strlen(k), k) == 0;
         });
}

} // namespace

bool IsSolverOption(const std::string &name) { return NamesObject(name, SOLVER_PREFIX, SOLVER_OBJECTS); }

PetscErrorCode CheckUnusedOptions(MPI_Comm comm, UnusedOptions when) {
  PetscBool refuse = PETSC_TRUE;
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-options_left", &refuse, nullptr));
  std::set<std::string> mine; // "-name value" of the options this rank has not read
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  for (PetscInt i = 0; i < n; ++i) {
    const std::string name = names[i];
    if (std::find(std::begin(GENERIC_READ_LATE), std::end(GENERIC_READ_LATE), name) != std::end(GENERIC_READ_LATE))
      continue;
    if (when == UnusedOptions::AFTER_SETUP &&
        (IsSolverOption(name) || NamesObject(name, "", UNPREFIXED_OBJECTS)))
      continue;
    mine.insert("-" + name + (values[i] ? std::string(" ") + values[i] : ""));
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  // Every rank holds the same options; an option counts as unused when no rank has read it (rank 0's list, agreed).
  std::string list = Join(std::vector<std::string>(mine.begin(), mine.end()), "\n");
  PetscCall(Broadcast(comm, 0, list));
  const std::vector<std::string> candidates = list.empty() ? std::vector<std::string>() : Split(list, '\n');
  std::vector<int> unused(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    unused[i] = mine.count(candidates[i]) ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, unused.data(), (int)unused.size(), MPI_INT, MPI_LAND, comm));
  std::vector<std::string> refused;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!unused[i]) continue;
    std::string origin;
    if (refuse) PetscCall(OptionOrigin(candidates[i].substr(0, candidates[i].find(' ')), origin));
    refused.push_back(candidates[i] + (origin.empty() ? "" : " (" + origin + ")"));
  }
  PetscCheck(!refuse || refused.empty(), comm, PETSC_ERR_USER_INPUT,
             "%s %s set but never read (misspelt, or not an option of this run); expected only options that this run "
             "reads (-help lists them; -options_left 0 lets unread options pass)",
             refused.size() == 1 ? "option" : "options",
             (Join(refused, ", ") + (refused.size() == 1 ? " is" : " are")).c_str());
  // PETSc's own report in PetscFinalize would list them again.
  if (when == UnusedOptions::AFTER_SOLVE) PetscCall(PetscOptionsSetValue(nullptr, "-options_left", "0"));
  PetscFunctionReturn(0);
}

} // namespace signorini
