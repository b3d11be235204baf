#!/usr/bin/python3
"""Outcomes of signorini on random small contact problems: a robustness survey, for comparing two builds.

    scripts/random_outcomes.py [--exe build/signorini] [--cases 300] [--seed 777] [--dim 2] [--np 1] [--options O]

The problems are those of the property test random_cases (tests/cases/robustness.py, random_case): a unit block or
the 2 x 1 block, linear or svk, on a floor or a disc with optional walls, supported on its left side or held by
contact alone, under a random top traction; many of them rightly fail (a body that nothing holds). --dim 3: the unit
cube on a floor plane or a sphere with optional walls and an inclined plane (random_case_3d). Each case prints
one line: its number, OK with its active-set iterations, load steps, active pairs and max |u|, or FAIL with the reason
(DIVERGED_..., SINGULAR for an older build's singular-system message without a reason, OTHER). A converged state is also
checked against the obstacles' geometry from its node table (robustness.geometric_penetration, independent of the
solver's pairs): one with a candidate inside an obstacle beyond the gap tolerance is counted INSIDE, with its depth.
Then the counts.
Two builds run with the same --seed see the same cases, so `diff` of their outputs shows what changed (docs/survey.md,
Running the survey); so do two rank counts (--np 2: every case under mpiexec -n 2), whose outputs must be the same,
and two solvers (--options "-contact_solver iterative": options added to every run), whose outcomes, active pairs and
displacements must be the same (their iteration counts are their own).
"""
import argparse
import collections
import json
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "cases"))
from robustness import geometric_penetration, random_case, random_case_3d  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "signorini"))
    parser.add_argument("--cases", type=int, default=300)
    parser.add_argument("--seed", type=int, default=777)
    parser.add_argument("--dim", type=int, choices=(2, 3), default=2)
    parser.add_argument("--np", type=int, default=1, help="MPI ranks of each run (mpiexec -n NP when above 1)")
    parser.add_argument("--options", default="", help="options added to every run (split at blanks)")
    opts = parser.parse_args()
    if opts.np < 1:
        parser.error("--np %d: expected a number of ranks of at least 1" % opts.np)
    launch = [] if opts.np == 1 else ["mpiexec", "-n", str(opts.np)] + (
        ["--oversubscribe"] if opts.np > (os.cpu_count() or 1) else [])
    rng = np.random.default_rng(opts.seed)
    counts = collections.Counter()
    for k in range(opts.cases):
        args = random_case(rng) if opts.dim == 2 else random_case_3d(rng)
        args = args + opts.options.split()
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out")
            run = subprocess.run(launch + [opts.exe] + args + ["-output_dir", out], cwd=ROOT, stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True, timeout=300)
            if run.returncode == 0:
                nodes = np.genfromtxt(os.path.join(out, "nodes.csv"), delimiter=",", names=True)
                with open(os.path.join(out, "summary.json")) as f:
                    gap_tol = json.load(f)["certificate"]["gap_tol"]
                depth = geometric_penetration(nodes, args)
        if run.returncode == 0:
            m = re.search(r"CONVERGED_\w+ after (\d+) active-set iteration\(s\) in (\d+) load step\(s\): (\d+) active",
                          run.stdout)
            u = re.search(r"max \|u\| (\S+)", run.stdout)
            if not m or not u:
                sys.exit("case %d exited 0 without a summary:\n%s" % (k, run.stdout))
            inside = depth > gap_tol
            print(k, "INSIDE %.3g" % depth if inside else "OK", m.group(1), m.group(2), m.group(3), u.group(1))
            counts["INSIDE" if inside else "OK"] += 1
        else:
            m = re.search(r"signorini: error: .*?(DIVERGED_\w+)", run.stdout)  # the final reason, not a repeated step's
            reason = m.group(1) if m else ("SINGULAR" if "is singular" in run.stdout else "OTHER")
            last = run.stdout.strip().splitlines()[-1:]
            print(k, "FAIL", reason if reason != "OTHER" else "OTHER (exit %d): %s" % (run.returncode, last))
            counts[reason] += 1
    print("counts:", " ".join("%s %d" % kv for kv in sorted(counts.items())))


if __name__ == "__main__":
    main()
