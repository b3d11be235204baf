#!/usr/bin/python3
"""scripts/plot.py on the outputs of the 3D default cases (hertz3d, cube_on_sphere in three load steps,
block_on_cylinder, cube_on_plane): it exits 0 and prints one line per picture; deformed.png and contact_pressure.png
(drawn by ParaView) are valid PNGs of 800 x 600 pixels, not blank (pixel values spread, many colours, a tenth of the
part left of the colour bar coloured: neither white nor grey), and the colour bar range printed for each is the range of
the field read here from solution.h5 with h5py (von_mises over the body's cells, contact_pressure over the contact
boundary's nodes, at the last load step); active_set.png and, with several load steps only, force_displacement.png are
valid PNGs, not blank."""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import matplotlib.image
import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PARAVIEW_SIZE = (800, 600)
CASES = (("hertz3d", []), ("cube_on_sphere", ["-load_steps", "3"]), ("block_on_cylinder", []), ("cube_on_plane", []))


def last_step_range(out, dataset):
    """min and max of a dataset of the last load step of out/solution.h5."""
    with h5py.File(os.path.join(out, "solution.h5"), "r") as f:
        last = sorted(k for k in f if k.startswith("step_"))[-1]
        values = f[last][dataset][()]
    return float(values.min()), float(values.max())


def picture_problems(path, paraview):
    """What is wrong with a picture: not a PNG, not the size expected, blank. Prints what it measured."""
    if not os.path.exists(path):
        return ["%s missing" % path]
    with open(path, "rb") as f:
        head = f.read(8)
    if head != PNG_SIGNATURE:
        return ["%s is not a PNG (signature %r)" % (path, head)]
    image = matplotlib.image.imread(path)[:, :, :3]
    height, width = image.shape[:2]
    colours = len(np.unique((image * 255).round().astype(np.uint8).reshape(-1, 3), axis=0))
    spread = float(image.std())
    # The scene: left of the colour bar, below the title; coloured pixels are neither white nor grey.
    scene = image[height // 10:, :int(0.8 * width)]
    coloured = float(np.mean(scene.max(axis=2) - scene.min(axis=2) > 0.15))
    problems = []
    if paraview and (width, height) != PARAVIEW_SIZE:
        problems.append("%s is %dx%d pixels, expected %dx%d" % ((path, width, height) + PARAVIEW_SIZE))
    if not paraview and min(width, height) < 200:
        problems.append("%s is %dx%d pixels, expected at least 200 each way" % (path, width, height))
    if spread < 0.05 or colours < 20:
        problems.append("%s looks blank: pixel standard deviation %.3f (expected >= 0.05), %d colours (expected >= "
                        "20)" % (path, spread, colours))
    if paraview and coloured < 0.1:
        problems.append("%s shows no field: %.1f%% of the scene coloured (expected >= 10%%)" % (path, 100 * coloured))
    print("%s %s: %d bytes, %dx%d pixels, std %.3f, %d colours%s" % (
        "FAIL" if problems else "ok  ", os.path.basename(path), os.path.getsize(path), width, height, spread, colours,
        ", %.0f%% of the scene coloured" % (100 * coloured) if paraview else ""))
    return problems


def check_case(args, work, name, options):
    out = os.path.join(work, name)
    pictures = os.path.join(work, name + "_pictures")
    cmd = [args.mpiexec, "-n", str(args.np), args.exe, "-options_file", "options/%s.yml" % name, "-output_dir",
           out] + options
    run = subprocess.run(cmd, cwd=args.source_dir, capture_output=True, text=True)
    if run.returncode != 0:
        return ["the run failed: %s\n%s%s" % (" ".join(cmd), run.stdout, run.stderr)]
    plot_cmd = [sys.executable, os.path.join(args.source_dir, "scripts", "plot.py"), out, "--out", pictures]
    plot = subprocess.run(plot_cmd, capture_output=True, text=True)
    print("%s: plot.py exit status %d" % (name, plot.returncode))
    if plot.returncode != 0:
        return ["%s: plot.py exit status %d:\n%s%s" % (name, plot.returncode, plot.stdout, plot.stderr)]
    lines = plot.stdout.splitlines()
    several_steps = "-load_steps" in options
    expected = ["deformed.png", "contact_pressure.png", "active_set.png"] + (
        ["force_displacement.png"] if several_steps else [])
    printed = [os.path.basename(line.split(" ")[0]) for line in lines]
    failures = []
    if printed != expected:
        failures.append("%s: plot.py printed the pictures %s, expected %s" % (name, printed, expected))
    if not several_steps and os.path.exists(os.path.join(pictures, "force_displacement.png")):
        failures.append("%s: force_displacement.png drawn for one load step" % name)
    for picture in expected:
        failures += ["%s: %s" % (name, p) for p in picture_problems(
            os.path.join(pictures, picture), picture in ("deformed.png", "contact_pressure.png"))]
    # The colour bars' ranges against the file's.
    for picture, field, dataset in (("deformed.png", "von_mises", "von_mises"),
                                    ("contact_pressure.png", "contact_pressure", "contact_boundary/contact_pressure")):
        line = next((l for l in lines if os.path.basename(l.split(" ")[0]) == picture), "")
        words = line.rsplit(" ", 3)
        lo, hi = last_step_range(out, dataset)
        try:
            ok = words[1] == field and np.allclose([float(words[2]), float(words[3])], [lo, hi], rtol=1e-9,
                                                   atol=1e-12 * max(abs(lo), abs(hi)))
        except (IndexError, ValueError):
            ok = False
        print("%s %s colour bar: printed %r, solution.h5 %s %.17g .. %.17g" % ("ok  " if ok else "FAIL", picture,
                                                                                " ".join(words[1:]), field, lo, hi))
        if not ok:
            failures.append("%s: %s's colour bar is %r, expected %s over [%.17g, %.17g] (solution.h5)" % (
                name, picture, " ".join(words[1:]), field, lo, hi))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--exe", required=True)
    parser.add_argument("--mpiexec", default="mpiexec")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--source-dir", required=True)
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="signorini_plot3d_")
    failures = []
    for name, options in CASES:
        failures += check_case(args, work, name, options)
    if failures:
        print("FAIL " + "\nFAIL ".join(failures) + "\nkept in " + work)
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
