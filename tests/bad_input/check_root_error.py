#!/usr/bin/python3
"""An error raised by work that rank 0 does alone ends a run on several ranks cleanly (RunOnRoot).

The serial mesh's face table is built on rank 0 alone (Mesh::SerialFaces); a mesh whose physical curve is no cell
edge, or whose cells fold over each other, fails there. Each case runs twice:
  - as it is: exactly one "signorini: error:" line naming the mesh, no MPI_ABORT banner, no PETSc error message, a
    non-zero exit of mpiexec within the time limit, no process left behind;
  - each rank under a wrapper that records the exit status of its rank and exits 0 (so that mpiexec kills no rank
    early): every rank must have exited non-zero by itself, none killed by an abort of the job.

    check_root_error.py --exe build/signorini --mpiexec mpiexec --np 2

Exit status 0 when every check passed, 1 when one failed.
"""
import argparse
import os
import subprocess
import sys
import tempfile

from run_bad_input import ERROR_PREFIX, FORBIDDEN, CheckFailed, environment, run_failing

HERE = os.path.dirname(os.path.abspath(__file__))
MESHES = os.path.join(HERE, "meshes")

# name: (arguments, expected substrings of the error line).
CASES = {
    "curve_not_edge": (["-mesh_file", os.path.join(MESHES, "curve_not_edge.msh"), "-bc_traction", "diagonal:0:1"],
                       ["curve_not_edge.msh", "not an edge"]),
    "folded_cells": (["-mesh_file", os.path.join(MESHES, "folded_tet.msh")], ["folded_tet.msh", "overlap"]),
}


def expect(ok, message):
    """A check of the case: CheckFailed with the message when it does not hold (whatever python's -O says)."""
    if not ok:
        raise CheckFailed(message)


def check_case(args, name):
    arguments, expected = CASES[name]
    mpiexec = [args.mpiexec, "-n", str(args.np)]
    status, _, err, _ = run_failing(mpiexec + [args.exe] + arguments, environment())
    lines = [line for line in err.splitlines() if line.startswith(ERROR_PREFIX)]
    expect(status != 0, f"exit status 0, expected a failure; stderr:\n{err}")
    expect(len(lines) == 1, f"{len(lines)} error lines, expected 1; stderr:\n{err}")
    for text in expected:
        expect(text in lines[0], f"'{text}' not in the error line: {lines[0]}")
    for text in [*FORBIDDEN, "MPI_ABORT"]:
        expect(text not in err, f"'{text}' in stderr, expected none:\n{err}")
    with tempfile.TemporaryDirectory() as statuses:
        run_failing(mpiexec + [sys.executable, os.path.abspath(__file__), "--record", statuses, args.exe] + arguments,
                    environment())
        for rank in range(args.np):
            path = os.path.join(statuses, str(rank))
            expect(os.path.exists(path), f"rank {rank} did not finish by itself (killed?); expected its exit status")
            with open(path) as f:
                code = int(f.read())
            expect(code != 0, f"rank {rank} exited with status 0, expected non-zero")


def record(directory, cmd):
    """The wrapper around one rank: runs cmd, writes its exit status to directory/<rank>, exits 0."""
    code = subprocess.call(cmd)
    with open(os.path.join(directory, os.environ.get("OMPI_COMM_WORLD_RANK", "0")), "w") as f:
        f.write(str(code))
    return 0


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--record":
        return record(sys.argv[2], sys.argv[3:])
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--mpiexec", default="mpiexec")
    parser.add_argument("--np", type=int, default=2)
    args = parser.parse_args()
    failed = 0
    for name in CASES:
        try:
            check_case(args, name)
            print(f"{name}: ok")
        except CheckFailed as e:
            print(f"{name}: FAILED: {e}")
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
