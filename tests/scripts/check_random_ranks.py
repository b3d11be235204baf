#!/usr/bin/python3
"""random_outcomes.py with --np 1 and --np 2 on the same cases: the same line for every case (outcome, active-set
iterations, load steps, active pairs, max |u| to 6 digits) and the same counts."""
import argparse
import subprocess
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--cases", type=int, default=12)
    parser.add_argument("--seed", type=int, default=4242)
    parser.add_argument("--dim", type=int, default=2)
    opts = parser.parse_args()
    outputs = []
    for np_ in (1, 2):
        run = subprocess.run([sys.executable, opts.source_dir + "/scripts/random_outcomes.py", "--exe", opts.exe,
                              "--cases", str(opts.cases), "--seed", str(opts.seed), "--dim", str(opts.dim), "--np",
                              str(np_)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if run.returncode != 0:
            sys.exit("random_outcomes.py --np %d failed (%d):\n%s" % (np_, run.returncode, run.stdout))
        outputs.append(run.stdout.splitlines())
    one, two = outputs
    if len(one) != opts.cases + 1 or not one[-1].startswith("counts:") or "OK" not in one[-1]:
        sys.exit("expected one line per case, the counts and some converged cases:\n" + "\n".join(one))
    differ = [(a, b) for a, b in zip(one, two) if a != b]
    for a, b in differ:
        print("1 rank:  %s\n2 ranks: %s" % (a, b))
    if differ or len(one) != len(two):
        sys.exit("%d line(s) differ between 1 and 2 ranks" % len(differ))
    print("the same %d outcomes on 1 and 2 ranks: %s" % (opts.cases, one[-1]))


if __name__ == "__main__":
    main()
