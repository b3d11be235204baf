#!/usr/bin/python3
"""random_outcomes.py on the same 3D cases with the direct path and with -contact_solver iterative: a case that
converges on one converges on the other, with the same active pairs and max |u| (to the 6 digits printed); a case that
fails (a body that nothing holds) fails on both. The iteration counts are each path's own, and so are the reasons of
the failures (the direct path's null pivots say DIVERGED_SINGULAR where the Krylov method breaks down or runs out of
iterations: docs/solver.md)."""
import argparse
import subprocess
import sys


def outcomes(opts, extra):
    cmd = [sys.executable, opts.source_dir + "/scripts/random_outcomes.py", "--exe", opts.exe, "--cases",
           str(opts.cases), "--seed", str(opts.seed), "--dim", "3"]
    if extra:
        cmd += ["--options", extra]
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if run.returncode != 0:
        sys.exit("random_outcomes.py %s failed (%d):\n%s" % (extra, run.returncode, run.stdout))
    lines = run.stdout.splitlines()
    if len(lines) != opts.cases + 1 or not lines[-1].startswith("counts:"):
        sys.exit("expected one line per case and the counts:\n" + run.stdout)
    return [line.split() for line in lines[:-1]]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--cases", type=int, default=20)
    parser.add_argument("--seed", type=int, default=777)
    opts = parser.parse_args()
    direct, iterative = outcomes(opts, ""), outcomes(opts, "-contact_solver iterative")
    bad, converged = [], 0
    for a, b in zip(direct, iterative):
        # "k OK its steps active max|u|" or "k FAIL reason ..."
        same = a[1] == b[1] and (a[1] != "OK" or (a[4], a[5]) == (b[4], b[5]))
        converged += a[1] == "OK"
        print("%s case %s: direct %s, iterative %s" % ("ok  " if same else "FAIL", a[0], " ".join(a[1:]),
                                                        " ".join(b[1:])))
        if not same:
            bad.append(a[0])
    if converged == 0:
        sys.exit("no converged case among the %d: nothing compared" % opts.cases)
    if bad:
        sys.exit("case(s) %s: the direct and iterative paths disagree" % ", ".join(bad))
    print("the same outcomes on both paths: %d converged, %d failed" % (converged, opts.cases - converged))


if __name__ == "__main__":
    main()
