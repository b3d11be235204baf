// The values of the saddle-point solver's PETSc options (-contact_ksp_*, -contact_pc_*, -contact_mat_mumps_*),
// checked before PETSc reads them: a value that PETSc or MUMPS would take without a word, or refuse only later
// without naming the option, is an error that names it and the values expected.
#pragma once

#include <petscksp.h>

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

/// Refuses, before any solve, the saddle-point solver's options that the solver set up on ksp (KSPSetFromOptions
/// done; kept: the kept MUMPS factorisation will solve) will certainly never read, naming them and why:
///  - with -contact_ksp_type preonly (a direct solve, the default), the Krylov tolerances -contact_ksp_rtol,
///    -contact_ksp_atol, -contact_ksp_divtol and -contact_ksp_max_it, which PETSc reads only for another KSP type and
///    nothing reads later (the kept factorisation, and PETSc's MUMPS when it declines, make no Krylov iterations);
///  - with an LU or Cholesky PC, the -contact_pc_* options that it has not read (PCSetFromOptions reads all of a
///    factorisation's; the others belong to another PC type) and those of the sub-solvers that only other PCs create
///    (-contact_fieldsplit_*, -contact_sub_*, -contact_mg_*, ...).
/// Options read lazily (-contact_mat_mumps_* at the factorisation, -contact_ksp_view and the like at the solve, a
/// fieldsplit's blocks at its set-up) are left to the check after the solve (CheckUnusedOptions). -options_left false
/// lets these pass too. Collective on ksp's communicator (rank 0's verdict, given to every rank).
[[nodiscard]] PetscErrorCode RefuseSolverOptionsNotRead(KSP ksp, bool kept);

} // namespace signorini
