#!/usr/bin/python3
"""random_outcomes.py with --np 1 and --np 2 on the same cases: the same line for every case (outcome, active-set
iterations, load steps, active pairs, max |u| to 6 digits) and the same counts.

--solvers: instead, the direct path against -contact_solver iterative on one rank: a case that converges on one
converges on the other, with the same active pairs and max |u|; a case that fails (a body that nothing holds) fails
on both for the same reason: DIVERGED_SINGULAR where the supports and every candidate pair leave a rigid-body motion
free (the direct path finds null pivots, the iterative one checks the rigid modes before it solves; it used to end in
a Krylov breakdown or DIVERGED_MAX_IT), DIVERGED_NOT_HELD where the pairs could hold the body but the load pulls it
off. The iteration counts are each path's own."""
import argparse
import subprocess
import sys


def same_outcomes(direct, iterative):
    """Lines "k OK its steps active max|u|" or "k FAIL reason ...": the same outcome, for a converged case the same
    active pairs and max |u|, for a failed one the same reason."""
    bad, converged = [], 0
    for a, b in zip((line.split() for line in direct), (line.split() for line in iterative)):
        same = a[1] == b[1] and ((a[4], a[5]) == (b[4], b[5]) if a[1] == "OK" else a[2] == b[2])
        converged += a[1] == "OK"
        print("%s case %s: direct %s, iterative %s" % ("ok  " if same else "FAIL", a[0], " ".join(a[1:]),
                                                        " ".join(b[1:])))
        if not same:
            bad.append(a[0])
    if bad:
        sys.exit("case(s) %s: the direct and iterative paths disagree" % ", ".join(bad))
    print("the same outcomes on both paths: %d converged, %d failed" % (converged, len(direct) - converged))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--cases", type=int, default=12)
    parser.add_argument("--seed", type=int, default=4242)
    parser.add_argument("--dim", type=int, default=2)
    parser.add_argument("--solvers", action="store_true", help="direct against iterative instead of 1 against 2 ranks")
    opts = parser.parse_args()
    outputs = []
    variants = (["--np", "1"], ["--options", "-contact_solver iterative"]) if opts.solvers else (["--np", "1"],
                                                                                                 ["--np", "2"])
    for variant in variants:
        run = subprocess.run([sys.executable, opts.source_dir + "/scripts/random_outcomes.py", "--exe", opts.exe,
                              "--cases", str(opts.cases), "--seed", str(opts.seed), "--dim", str(opts.dim)] + variant,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if run.returncode != 0:
            sys.exit("random_outcomes.py %s failed (%d):\n%s" % (" ".join(variant), run.returncode, run.stdout))
        outputs.append(run.stdout.splitlines())
    one, two = outputs
    if len(one) != opts.cases + 1 or not one[-1].startswith("counts:") or "OK" not in one[-1]:
        sys.exit("expected one line per case, the counts and some converged cases:\n" + "\n".join(one))
    if opts.solvers:
        same_outcomes(one[:-1], two[:-1])
        return
    differ = [(a, b) for a, b in zip(one, two) if a != b]
    for a, b in differ:
        print("1 rank:  %s\n2 ranks: %s" % (a, b))
    if differ or len(one) != len(two):
        sys.exit("%d line(s) differ between 1 and 2 ranks" % len(differ))
    print("the same %d outcomes on 1 and 2 ranks: %s" % (opts.cases, one[-1]))


if __name__ == "__main__":
    main()
