// The values of the saddle-point solver's PETSc options (-contact_ksp_*, -contact_pc_*, -contact_mat_mumps_*),
// checked before PETSc reads them: a value that PETSc or MUMPS would take without a word, or refuse only later
// without naming the option, is an error that names it and the values expected.
#pragma once

#include <petscsys.h>

namespace signorini {

/// Refuses a solver option whose value means nothing to PETSc or MUMPS, naming the option and what was expected:
/// a KSP or PC type that is not given or not registered (-contact_ksp_type, -contact_pc_type and a sub-solver's
/// ..._ksp_type, ..._pc_type), a Krylov tolerance outside PETSc's range (..._ksp_rtol in [0, 1), ..._ksp_atol >= 0),
/// an iteration limit ..._ksp_max_it below 1, a MUMPS control -contact_mat_mumps_icntl_<k> (k in 1..60) or
/// _cntl_<k> (k in 1..15) that PETSc's MUMPS interface does not pass on, or whose value MUMPS 5.5 does not define
/// (ICNTL(7), the ordering, is checked by ReadMumpsControls, which knows the orderings of this build).
/// It reads the options that no one has read yet, and marks none as read, so that an option that the solver then does
/// not read is still reported as unused: call it before the saddle-point KSP reads its options. Collective on comm
/// (every rank holds the same options).
[[nodiscard]] PetscErrorCode CheckSolverOptionValues(MPI_Comm comm);

} // namespace signorini
