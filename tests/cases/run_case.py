#!/usr/bin/python3
"""Runs one case or verification test of tests/cases: the signorini executable under mpiexec, then checks.

    run_case.py --exe build/signorini --np 2 --source-dir . block_on_floor
    run_case.py --list

The harness (Runner, Result, the checks every run gets) is harness.py; the tests are in the modules of TEST_MODULES,
one per theme; a name may carry a parameter after a colon (solver_preset:mumps_lu).
By hand, set the environment that ctest sets (SIGNORINI_TEST_ENV in tests/CMakeLists.txt: Open MPI as root, one
thread per rank); `ctest -L cases` runs them all.
Exit status 0 when every check passed, 1 when one failed, 2 on a usage error, 77 when a tool the test needs is
missing and nothing was checked (a skip after a failed check is a failure).
"""
import argparse
import importlib
import inspect
import os
import re
import shutil
import sys
import tempfile
import time

# The test modules, by theme; each registers its tests with @test when imported.
TEST_MODULES = ("cases", "verification", "obstacles", "robustness", "parallel", "solvers", "svk", "output",
                "mesh_h5", "bodies", "friction", "load_paths")


def main():
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    # Imported here, after the two lines above: no bytecode written into the source tree.
    from harness import TESTS, CheckFailed, Runner, Skipped

    for module in TEST_MODULES:
        importlib.import_module(module)  # registers its tests in TESTS

    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("test", nargs="?", help="test name, NAME or NAME:PARAMETER")
    parser.add_argument("--exe", default="build/signorini", help="the signorini executable")
    parser.add_argument("--mpiexec", default=shutil.which("mpiexec") or "mpiexec")
    parser.add_argument("--np", type=int, default=1, help="MPI ranks")
    parser.add_argument("--source-dir", default=os.getcwd(), help="where relative mesh and options paths start")
    parser.add_argument("--keep", action="store_true", help="keep the output directories even when the test passes")
    parser.add_argument("--verbose", action="store_true", help="print the executable's output")
    parser.add_argument("--list", action="store_true", help="list the tests and exit")
    args = parser.parse_args()
    if args.list:
        for name, test in sorted(TESTS.items()):
            print("%-28s %s" % (name, (test.__doc__ or "").strip().splitlines()[0]))
        return 0
    if not args.test:
        parser.error("a test name is required (--list shows them)")
    name, _, param = args.test.partition(":")
    if name not in TESTS:
        parser.error("unknown test '%s' (--list shows them)" % name)
    wants_param = len(inspect.signature(TESTS[name]).parameters) > 1
    if wants_param != bool(param):
        parser.error("test '%s' %s" % (name, "needs a parameter (NAME:PARAMETER)" if wants_param else
                                       "takes no parameter"))
    workdir = tempfile.mkdtemp(prefix="signorini_case_%s_np%d_" % (re.sub(r"\W+", "_", args.test), args.np))
    runner = Runner(os.path.abspath(args.exe), args.mpiexec, args.np, os.path.abspath(args.source_dir), workdir,
                    args.verbose)
    start = time.time()
    try:
        TESTS[name](runner, *([param] if param else []))
    except Skipped as e:
        if not runner.failures and not runner.checks:
            print("SKIP %s: %s" % (args.test, e))
            shutil.rmtree(workdir, ignore_errors=True)
            return 77
        # A skip after checks were made would hide them (or hide that the rest went unchecked): a failure.
        runner.failures.append("skipped after %d check(s) (%d failed): %s" % (runner.checks, len(runner.failures), e))
        print("FAIL %s" % runner.failures[-1])
    except CheckFailed as e:
        runner.failures.append(str(e))
        print("FAIL %s" % e)
    elapsed = time.time() - start
    if runner.failures:
        print("%s (np %d): %d check(s) failed in %.1f s; outputs kept in %s" % (
            args.test, args.np, len(runner.failures), elapsed, workdir))
        return 1
    print("%s (np %d): all checks passed in %.1f s" % (args.test, args.np, elapsed))
    if args.keep:
        print("outputs kept in %s" % workdir)
    else:
        shutil.rmtree(workdir, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
