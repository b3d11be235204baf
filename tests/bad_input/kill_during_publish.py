#!/usr/bin/python3
"""Kills a run at every rename and symlink call of its output (strace injects SIGKILL at the Nth call), through the
switch of the output directory, and checks after each kill that DIR holds the files of one run, whole.

    kill_during_publish.py --exe build/signorini --mpiexec mpiexec --np 2

A first good run (beam_on_floor, one load step) fills DIR. Each later run (two load steps, another pressure) is
killed at call N of rename (then symlink, then unlinkat: the removal of the earlier run after the switch), N = 1, 2,
... until a run gets through. After every kill, the files that DIR names must agree: summary.json's load steps
= the step groups of solution.h5 = the steps of solution.xdmf and of each per-block XDMF file, and nodes.csv's
displacement = solution.h5's last step. Some kill must leave DIR byte for byte as it was and some must leave the new
run, so the kills did reach the switch from both sides.
Exit status 0 when every check passed, 1 when one failed, 77 when strace is missing or not permitted.
"""
import argparse
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
XDMF = ("solution.xdmf", "body.xdmf", "obstacle.xdmf", "contact_boundary.xdmf")  # the beam has all three blocks
FILES = ("solution.h5",) + XDMF + ("nodes.csv", "summary.json")
BEAM = ["-options_file", os.path.join(ROOT, "options", "beam_on_floor.yml")]


def run(cmd):
    proc = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)
    out, _ = proc.communicate()  # a hang is left to CTest's TIMEOUT
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # whatever the kill left of the job
    except ProcessLookupError:
        pass
    return proc.returncode, out


def contents(out_dir):
    """sha256 of each file that DIR names (None where missing)."""
    digest = {}
    for name in FILES:
        path = os.path.join(out_dir, name)
        digest[name] = hashlib.sha256(open(path, "rb").read()).hexdigest() if os.path.exists(path) else None
    return digest


def consistency(out_dir):
    """The problems that show files of different runs side by side (empty when DIR is one whole run)."""
    import h5py

    missing = [n for n in FILES if not os.path.exists(os.path.join(out_dir, n))]
    if missing:
        return ["missing: " + ", ".join(missing)]
    with open(os.path.join(out_dir, "summary.json")) as f:
        steps = json.load(f)["iterations"]["load_steps"]
    with h5py.File(os.path.join(out_dir, "solution.h5"), "r") as f:
        groups = sorted(k for k in f if k.startswith("step_"))
        u = f[groups[-1]]["displacement"][:, :2]
        tags = f["mesh/node_tags"][()]
    xdmf_steps = []
    for name in XDMF:
        with open(os.path.join(out_dir, name)) as f:
            xdmf_steps.append(len(re.findall(r'<Grid Name="step_\d+"', f.read())))
    table = np.genfromtxt(os.path.join(out_dir, "nodes.csv"), delimiter=",", names=True)
    order = np.argsort(table["node_tag"])
    csv_u = np.column_stack([table["u_x"], table["u_y"]])[order]
    h5_u = u[np.argsort(tags)]
    problems = []
    if not steps == len(groups) == min(xdmf_steps) == max(xdmf_steps):
        problems.append("load steps: summary.json %d, solution.h5 %d, %s" % (
            steps, len(groups), ", ".join("%s %d" % (n, k) for n, k in zip(XDMF, xdmf_steps))))
    if csv_u.shape != h5_u.shape or not np.allclose(csv_u, h5_u, rtol=0, atol=1e-14):
        problems.append("nodes.csv displacement differs from solution.h5's last step")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", default=os.path.join(ROOT, "build", "signorini"))
    parser.add_argument("--mpiexec", default=shutil.which("mpiexec") or "mpiexec")
    parser.add_argument("--np", type=int, default=1)
    args = parser.parse_args()
    strace = shutil.which("strace")
    if not strace or subprocess.run([strace, "-qq", "-o", os.devnull, "true"]).returncode != 0:
        print("SKIP: strace is missing or may not trace here")
        return 77
    work = tempfile.mkdtemp(prefix="signorini_kill_publish_np%d_" % args.np)
    out_dir = os.path.join(work, "out")
    launch = [args.mpiexec, "-n", str(args.np)]
    status, out = run(launch + [args.exe] + BEAM + ["-output_dir", out_dir])
    failures = []
    if status != 0 or consistency(out_dir):
        failures.append("the first good run failed (status %d):\n%s" % (status, out))
    kept = switched = 0
    for call in ("rename", "symlink", "unlinkat"):
        for n in range(1, 100):
            if failures:
                break
            before = contents(out_dir)
            trace = [strace, "-f", "-qq", "-o", os.devnull, "-e", "trace=" + call,
                     "-e", "inject=%s:signal=KILL:when=%d" % (call, n)]
            status, out = run(launch + trace + [args.exe] + BEAM + ["-load_steps", "2", "-bc_pressure", "top:0.3",
                                                                     "-output_dir", out_dir])
            after = contents(out_dir)
            if status == 0:
                print("%s call %d: none left, the run completed" % (call, n))
                problems = consistency(out_dir)
                if problems:
                    failures.append("after the complete run: " + "; ".join(problems))
                break
            problems = consistency(out_dir)
            state = "unchanged" if after == before else "switched"
            kept += state == "unchanged"
            switched += state == "switched"
            print("killed at %s call %d (status %d): DIR %s%s" % (call, n, status, state,
                                                                 ": " + "; ".join(problems) if problems else ""))
            if problems:
                failures.append("killed at %s call %d: %s\n%s" % (call, n, "; ".join(problems), out[-2000:]))
    if not failures and (kept == 0 or switched == 0):
        failures.append("no kill fell %s the switch (%d unchanged, %d switched)" % (
            "before" if kept == 0 else "after", kept, switched))
    if failures:
        print("FAIL " + "\nFAIL ".join(failures) + "\noutputs kept in " + work)
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("PASS: %d kills left the earlier run, %d the new one, each whole" % (kept, switched))
    return 0


if __name__ == "__main__":
    sys.exit(main())
