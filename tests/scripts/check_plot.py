#!/usr/bin/python3
"""scripts/plot.py on the output of a small 2D run (the Hertz case, whose summary has a Hertz block, so that the
analytical curve is drawn, in two load steps): it exits 0 and writes deformed.png, contact_pressure.png and
active_set.png, each a valid PNG (signature, non-empty, an image matplotlib reads back, at least 200 pixels each way).
It refuses, with one line naming the reason, no traceback, exit status 1 and no picture written: a directory that does
not exist, and one that is not an output. 3D outputs: check_plot_3d.py."""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib.image

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PICTURES = ("deformed.png", "contact_pressure.png", "active_set.png")


def refusals(args, work):
    """plot.py on what it does not draw: the failures."""
    empty = os.path.join(work, "not_an_output")
    os.makedirs(empty)
    failures = []
    for what, directory, words in (("a missing directory", os.path.join(work, "missing"), ["does not exist"]),
                                   ("a directory that is not an output", empty, ["not a signorini output"])):
        plot = subprocess.run([sys.executable, os.path.join(args.source_dir, "scripts", "plot.py"), directory],
                              capture_output=True, text=True)
        lines = (plot.stdout + plot.stderr).splitlines()
        written = [n for n in PICTURES if os.path.exists(os.path.join(directory, n))]
        ok = (plot.returncode == 1 and len(lines) == 1 and lines[0].startswith("plot.py: error: ") and
              all(w in lines[0] for w in words) and not written)
        print("%s refuses %s: exit status %d, %s" % ("ok  " if ok else "FAIL", what, plot.returncode, lines))
        if not ok:
            failures.append("plot.py on %s: exit status %d (expected 1), output %r (expected one 'plot.py: error:' "
                            "line with %s), pictures written: %s" % (what, plot.returncode, plot.stdout + plot.stderr,
                                                                      words, written))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--mpiexec", default="mpiexec")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--source-dir", required=True)
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="signorini_plot_np%d_" % args.np)
    out = os.path.join(work, "out")
    cmd = [args.mpiexec, "-n", str(args.np), args.exe, "-options_file", "options/hertz.yml", "-load_steps", "2",
           "-output_dir", out]
    failures = []
    run = subprocess.run(cmd, cwd=args.source_dir, capture_output=True, text=True)
    if run.returncode != 0:
        failures.append("the run failed: %s\n%s%s" % (" ".join(cmd), run.stdout, run.stderr))
    else:
        plot = subprocess.run([sys.executable, os.path.join(args.source_dir, "scripts", "plot.py"), out],
                              capture_output=True, text=True)
        if plot.returncode != 0:
            failures.append("plot.py exit status %d:\n%s%s" % (plot.returncode, plot.stdout, plot.stderr))
        for name in PICTURES:
            path = os.path.join(out, name)
            if not os.path.exists(path):
                failures.append("%s missing" % name)
                continue
            with open(path, "rb") as f:
                head = f.read(8)
            size = os.path.getsize(path)
            image = matplotlib.image.imread(path)
            ok = head == PNG_SIGNATURE and size > 0 and image.ndim == 3 and min(image.shape[:2]) >= 200
            print("%s %s: %d bytes, %dx%d pixels" % ("ok  " if ok else "FAIL", name, size, image.shape[1],
                                                   image.shape[0]))
            if not ok:
                failures.append("%s is not a valid picture (signature %r, %d bytes, shape %s)" % (
                    name, head, size, image.shape))
    failures += refusals(args, work)
    if failures:
        print("FAIL " + "\nFAIL ".join(failures) + "\nkept in " + work)
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
