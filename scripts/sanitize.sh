#!/usr/bin/env bash
# Build signorini with AddressSanitizer and UndefinedBehaviorSanitizer (-DSIGNORINI_SANITIZE=ON) in a build
# directory of its own and run the test suite there. It takes several times as long as the Release suite, so it is
# run by hand (before a release, after touching memory handling), not by CI.
#   scripts/sanitize.sh                 configure, build, run every test
#   scripts/sanitize.sh -L bad_input    configure, build, run the tests CTest selects with these arguments
# The build directory is build-sanitize/ unless SIGNORINI_SANITIZE_BUILD_DIR names another.
# A sanitizer report makes the run exit non-zero, so the test that hit it fails; ctest --output-on-failure shows it.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${SIGNORINI_SANITIZE_BUILD_DIR:-$here/build-sanitize}
jobs=$(nproc)

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSIGNORINI_SANITIZE=ON
cmake --build "$build_dir" -j "$jobs"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
# mpiexec otherwise waits 2 s after a rank exits non-zero (docs/running.md, MPI).
export OMPI_MCA_odls_base_sigkill_timeout=0
# Leak checking is off: Open MPI, hwloc, PETSc and gmsh keep allocations until exit or never free them, so
# LeakSanitizer would report those libraries on every run. Our own PETSc objects are checked for leaks by the case
# tests (-malloc_debug -malloc_dump) and by the unit tests' PETSc memory tracing instead.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:check_initialization_order=1:strict_init_order=1}
# Undefined behaviour stops the run at the first report, with a stack trace, instead of only printing it.
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

cd "$build_dir"
start=$(date +%s)
status=0
ctest --output-on-failure -j "$jobs" "$@" || status=$?
echo "sanitize: ctest finished in $(($(date +%s) - start)) s with status $status"
exit "$status"
