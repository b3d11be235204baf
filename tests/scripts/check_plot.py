#!/usr/bin/python3
"""scripts/plot.py on the output of a small 2D run (the Hertz case, whose summary has a Hertz block, so that the
analytical curve is drawn, in two load steps): it exits 0 and writes deformed.png, contact_pressure.png and
active_set.png, each a valid PNG (signature, non-empty, an image matplotlib reads back, at least 200 pixels each way);
the pressure plot's analytical curve is Johnson's p0 sqrt(1 - x^2/a^2), with a and p0 computed here from R, P, E and
nu. It refuses, with one line naming the reason, no traceback, exit status 1 and no picture written: a directory that
does not exist, and one that is not an output. With friction (options/sliding_block.yml, every node slipping) it also
writes friction.png, whose slip markers are at mu times the pressure of the nodes in nodes.csv; a frictionless output has
no friction.png. 3D outputs: check_plot_3d.py."""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib.image
import numpy as np

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PICTURES = ("deformed.png", "contact_pressure.png", "active_set.png")


def johnson_2d(source_dir):
    """Johnson's (1985, 4.2) half-width a and peak pressure p0 of the Hertz case of options/hertz.yml, from its options:
    a cylinder R = 8 (meshes/hertz.geo) loaded by the traction on its flat top 2R wide, P = |t_y| 2R per unit
    thickness; E* = E / (1 - nu^2), a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a)."""
    options = {}
    with open(os.path.join(source_dir, "options", "hertz.yml")) as f:
        for line in f:
            key, _, value = line.split("#", 1)[0].partition(":")
            options[key.strip()] = value.strip()
    R = 8.0
    E, nu = float(options["material_E"]), float(options["material_nu"])
    P = abs(float(options["bc_traction"].split(":")[2])) * 2 * R
    a = np.sqrt(4 * P * R / (np.pi * E / (1 - nu * nu)))
    return a, 2 * P / (np.pi * a)


def analytic_curve(args, out):
    """The dashed analytical curve that plot.py's plot_pressure draws on the output out, against Johnson's values."""
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, os.path.join(args.source_dir, "scripts"))
    import plot

    figures = []
    plot.plt.close = lambda fig=None: figures.append(fig)  # keep the figure plot_pressure closes after saving it
    summary, data = plot.read_summary(out), plot.read(out)
    plot.plot_pressure(summary, data, os.path.join(out, "contact_pressure_check.png"))
    lines = [line for fig in figures if hasattr(fig, "axes") for ax in fig.axes for line in ax.get_lines()
             if line.get_label().startswith("Hertz")]
    if len(lines) != 1:
        return ["contact_pressure.png: %d analytical curve(s) labelled Hertz, expected 1" % len(lines)]
    a, p0 = johnson_2d(args.source_dir)
    x, p = np.asarray(lines[0].get_xdata()), np.asarray(lines[0].get_ydata())
    # plot.py draws the a and p0 of summary.json, which holds 10 significant digits: 1e-9 relative. Compared as
    # p^2 = p0^2 (1 - x^2/a^2), which the square root's slope at the ends does not amplify (1e-8 of p0^2: a few
    # times those digits on p0^2 and on x^2/a^2).
    ok = (np.isclose(x.min(), -a, rtol=1e-9, atol=0) and np.isclose(x.max(), a, rtol=1e-9, atol=0) and
          np.allclose(p ** 2, p0 ** 2 * (1 - x ** 2 / a ** 2), rtol=0, atol=1e-8 * p0 ** 2) and
          np.isclose(p.max(), p0, rtol=1e-9, atol=0))
    print("%s contact_pressure.png: the analytical curve over [%.6g, %.6g], peak %.6g (Johnson: a = %.6g, "
          "p0 = %.6g)" % ("ok  " if ok else "FAIL", x.min(), x.max(), p.max(), a, p0))
    return [] if ok else ["contact_pressure.png: the analytical curve is not Johnson's p0 sqrt(1 - x^2/a^2) with "
                          "a = %.6g, p0 = %.6g (drawn over [%.6g, %.6g], peak %.6g)" % (a, p0, x.min(), x.max(),
                                                                                        p.max())]


def friction_picture(args, work):
    """friction.png of a sliding block: a valid picture whose slip markers are the nodes' mu p (full slip)."""
    out = os.path.join(work, "friction")
    cmd = [args.mpiexec, "-n", str(args.np), args.exe, "-options_file", "options/sliding_block.yml", "-output_dir", out]
    run = subprocess.run(cmd, cwd=args.source_dir, capture_output=True, text=True)
    if run.returncode != 0:
        return ["the friction run failed: %s\n%s%s" % (" ".join(cmd), run.stdout, run.stderr)]
    sys.dont_write_bytecode = True
    sys.path.insert(0, os.path.join(args.source_dir, "scripts"))
    import plot

    figures = []
    close = plot.plt.close
    plot.plt.close = lambda fig=None: figures.append(fig)
    try:
        summary, data = plot.read_summary(out), plot.read(out)
        plot.plot_friction(summary, data, os.path.join(out, "friction.png"))
    finally:
        plot.plt.close = close
    image = matplotlib.image.imread(os.path.join(out, "friction.png"))
    slip = [line for fig in figures if hasattr(fig, "axes") for ax in fig.axes for line in ax.get_lines()
            if line.get_label().startswith("slip")]
    nodes = np.genfromtxt(os.path.join(out, "nodes.csv"), delimiter=",", names=True)
    want = np.sort(summary["friction"]["mu"] * nodes["pressure"][nodes["friction_state"] == 1])
    got = np.sort(np.asarray(slip[0].get_ydata())) if len(slip) == 1 else np.array([])
    ok = min(image.shape[:2]) >= 200 and got.shape == want.shape and np.allclose(got, want, rtol=1e-8, atol=0)
    print("%s friction.png: %dx%d pixels, %d slip markers at mu p" % ("ok  " if ok else "FAIL", image.shape[1],
                                                                     image.shape[0], got.size))
    return [] if ok else ["friction.png: %d slip marker(s) %s, expected mu p of the %d slip node(s) %s" % (
        got.size, got, want.size, want)]


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
        failures += analytic_curve(args, out)
        if os.path.exists(os.path.join(out, "friction.png")):
            failures.append("friction.png written for a frictionless output")
        failures += friction_picture(args, work)
    failures += refusals(args, work)
    if failures:
        print("FAIL " + "\nFAIL ".join(failures) + "\nkept in " + work)
        return 1
    shutil.rmtree(work, ignore_errors=True)
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
