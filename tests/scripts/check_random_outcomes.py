#!/usr/bin/python3
"""random_outcomes.py on the first cases of a fixed seed: every case ends as pinned here (OK with the same active-set
iterations, load steps and active pairs, or FAIL with the same DIVERGED_ reason), none inside an obstacle, none an
OTHER failure (a crash, or an error line without a reason), and the script exits 0.

    check_random_outcomes.py --exe build/signorini --source-dir . --dim 2 --seed 777 --cases 12

The fixed seed makes the cases and their outcomes deterministic (check_random_ranks.py relies on it too): a changed
line is a change of the solver's path, to be looked at and pinned again with the reason in the commit message.
Exit status 0 when every case ends as pinned, 1 otherwise.
"""
import argparse
import subprocess
import sys

# (dim, seed) -> case number -> ("OK", active-set iterations, load steps, active pairs) or ("FAIL", reason). Read case
# by case: every failure is a body that nothing holds against its load (pushed along a frictionless floor or plane away
# from any wall, or rolling off a disc or sphere); every case held by construction (supported or against walls it is
# pushed towards, without an inclined wall inside its corner) is OK.
PINNED = {
    (2, 777): {
        0: ('OK', 9, 1, 1), 1: ('OK', 96, 4, 3), 2: ('OK', 17, 1, 9), 3: ('OK', 2, 1, 11),
        4: ('FAIL', 'DIVERGED_SINGULAR'), 5: ('OK', 6, 1, 1), 6: ('OK', 3, 1, 26), 7: ('FAIL', 'DIVERGED_SINGULAR'),
        8: ('OK', 13, 1, 3), 9: ('FAIL', 'DIVERGED_SINGULAR'), 10: ('OK', 2, 1, 11), 11: ('OK', 1, 1, 20)},
    (3, 777): {
        0: ('FAIL', 'DIVERGED_NOT_HELD'), 1: ('FAIL', 'DIVERGED_SINGULAR'), 2: ('OK', 5, 1, 21),
        3: ('FAIL', 'DIVERGED_SINGULAR'), 4: ('FAIL', 'DIVERGED_SINGULAR'), 5: ('FAIL', 'DIVERGED_NOT_HELD'),
        6: ('OK', 5, 1, 61), 7: ('OK', 15, 1, 8), 8: ('FAIL', 'DIVERGED_NOT_HELD'), 9: ('FAIL', 'DIVERGED_NOT_HELD'),
        10: ('FAIL', 'DIVERGED_NOT_HELD'), 11: ('FAIL', 'DIVERGED_NOT_HELD'), 12: ('FAIL', 'DIVERGED_NOT_HELD'),
        13: ('FAIL', 'DIVERGED_NOT_HELD'), 14: ('FAIL', 'DIVERGED_SINGULAR'), 15: ('FAIL', 'DIVERGED_NOT_HELD'),
        16: ('FAIL', 'DIVERGED_NOT_HELD'), 17: ('FAIL', 'DIVERGED_NOT_HELD'), 18: ('FAIL', 'DIVERGED_MAX_IT'),
        19: ('FAIL', 'DIVERGED_SINGULAR')},
}


def parse(line):
    """A case line of random_outcomes.py as (case number, pinned form)."""
    words = line.split()
    k = int(words[0])
    if words[1] == "OK":
        return k, ("OK", int(words[2]), int(words[3]), int(words[4]))
    if words[1] == "FAIL":
        return k, ("FAIL", " ".join(words[2:]))
    return k, tuple(words[1:])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--cases", type=int, required=True)
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--dim", type=int, default=2)
    opts = parser.parse_args()
    run = subprocess.run([sys.executable, opts.source_dir + "/scripts/random_outcomes.py", "--exe", opts.exe,
                          "--cases", str(opts.cases), "--seed", str(opts.seed), "--dim", str(opts.dim)],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(run.stdout)
    lines = run.stdout.splitlines()
    failures = []
    if run.returncode != 0:
        failures.append("random_outcomes.py exit status %d, expected 0" % run.returncode)
    if len(lines) != opts.cases + 1 or not lines[-1].startswith("counts:"):
        failures.append("expected one line per case (%d) and the counts" % opts.cases)
    pinned = PINNED.get((opts.dim, opts.seed), {})
    got = dict(parse(line) for line in lines[:-1] if line[:1].isdigit())
    for k in range(opts.cases):
        if got.get(k) != pinned.get(k):
            failures.append("case %d: %s, expected %s" % (k, got.get(k), pinned.get(k)))
    print("observed: {%s}" % ", ".join("%d: %r" % kv for kv in sorted(got.items())))
    if failures:
        print("FAIL " + "\nFAIL ".join(failures))
        return 1
    print("PASS: the %d cases of seed %d (%dD) end as pinned: %s" % (opts.cases, opts.seed, opts.dim, lines[-1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
