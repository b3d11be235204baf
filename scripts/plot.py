#!/usr/bin/python3
"""Pictures of a signorini output directory, without a display (2D: matplotlib; 3D: ParaView's pvpython under Xvfb).

    scripts/plot.py OUTPUT_DIR [--out DIR] [--scale S]

Writes into OUTPUT_DIR (or --out), for a 2D result:
  deformed.png        the deformed mesh coloured by von Mises stress, with the obstacle (displacements times S,
                      default 1: a larger S would push the body through the rigid obstacle in the picture)
  contact_pressure.png  the contact pressure along the contact boundary against x, with Hertz's
                      p(x) = p0 sqrt(1 - x^2/a^2) when summary.json has a "hertz" block
  active_set.png      active pairs and maximum penetration per active-set iteration (summary.json iterations.history)
  friction.png        with friction only (-contact_friction): the tangential traction along the contact boundary
                      against x, each node marked by its state (stick, slip, open), with mu times the pressure (the
                      bound that slip nodes reach) and the stick zones shaded
and for a 3D result (summary.json's mesh.dim), drawn by ParaView (scripts/plot3d_pvpython.py run by pvpython):
  deformed.png        the body warped by its displacement times S (default: the round number that makes the largest
                      displacement about a tenth of the body's size; the title states it), coloured by the von Mises
                      stress, the obstacles translucent, seen from above the contact
  contact_pressure.png  the contact boundary coloured by the contact pressure, seen from the obstacle's side (looking
                      at the contact face), framed on the contact patch
  active_set.png      as in 2D
  force_displacement.png  with several load steps only: the total normal contact force (the sum of the nodal
                      multipliers) and the applied load against the largest displacement, per load step
Debian's ParaView renders through X: plot.py starts a private Xvfb (Debian package xvfb) for it, or uses DISPLAY.
Reads solution.h5 (last load step: mesh, obstacle, contact boundary, fields; every step for the force curve) and
summary.json. A directory that is not an output is refused with one line (exit status 1), and so is a 3D result when
pvpython, or both Xvfb and DISPLAY, are missing.
"""
import argparse
import contextlib
import json
import math
import os
import re
import select
import shutil
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402


def cells_of(topology):
    """Cells as node-index arrays (uniform 2D topology, or XDMF mixed: 4 triangle, 5 quadrilateral before each)."""
    if topology.ndim == 2:
        return list(topology)
    cells, i = [], 0
    while i < len(topology):
        n = {4: 3, 5: 4}[int(topology[i])]
        cells.append(topology[i + 1:i + 1 + n])
        i += n + 1
    return cells


class NotDrawable(Exception):
    """An output plot.py does not draw, or no output at all: its message is all the user needs (no traceback)."""


def read_summary(directory):
    """summary.json of an output directory of a 2D or 3D run; NotDrawable otherwise."""
    if not os.path.isdir(directory):
        raise NotDrawable("'%s' %s; expected the -output_dir of a signorini run" % (
            directory, "is not a directory" if os.path.exists(directory) else "does not exist"))
    missing = [n for n in ("summary.json", "solution.h5") if not os.path.exists(os.path.join(directory, n))]
    if missing:
        raise NotDrawable("'%s' is not a signorini output directory (no %s there); expected the -output_dir of a "
                          "successful run" % (directory, " and no ".join(missing)))
    try:
        with open(os.path.join(directory, "summary.json")) as f:
            summary = json.load(f)
        dim = summary["mesh"]["dim"]
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise NotDrawable("'%s' is not a signorini output directory (its summary.json cannot be read: %s)" % (
            os.path.join(directory, "summary.json"), e))
    if dim not in (2, 3):
        raise NotDrawable("'%s' holds a result of dimension %r; expected 2 or 3" % (directory, dim))
    return summary


def read(directory):
    """The last load step of a 2D output's solution.h5; NotDrawable when it cannot be read."""
    try:
        return read_solution(directory)
    except (OSError, KeyError, IndexError) as e:
        raise NotDrawable("'%s' is not a signorini output (cannot read its last load step: %s)" % (
            os.path.join(directory, "solution.h5"), e))


def read_solution(directory):
    with h5py.File(os.path.join(directory, "solution.h5"), "r") as f:
        last = sorted(k for k in f if k.startswith("step_"))[-1]
        step = f[last]
        data = {"xy": f["mesh/coordinates"][:, :2], "cells": cells_of(f["mesh/topology"][()]),
                "u": step["displacement"][:, :2], "von_mises": step["von_mises"][()]}
        if "obstacle" in f:
            data["obstacle"] = f["obstacle/coordinates"][:, :2].reshape(-1, 2, 2)
        if "contact_boundary" in f and "contact_boundary" in step:
            data["contact_xy"] = f["contact_boundary/coordinates"][:, :2]
            data["contact_pressure"] = step["contact_boundary/contact_pressure"][()]
            if "contact_friction_traction" in step["contact_boundary"]:
                data["friction_traction"] = step["contact_boundary/contact_friction_traction"][:, :2]
                data["friction_state"] = step["contact_boundary/contact_friction_state"][()]
    return data


def plot_deformed(summary, d, path, scale):
    x = d["xy"] + scale * d["u"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    polys = PolyCollection([x[c] for c in d["cells"]], array=d["von_mises"], cmap="viridis", edgecolors="face",
                           linewidths=0.2)
    ax.add_collection(polys)
    fig.colorbar(polys, ax=ax, label="von Mises stress")
    if "obstacle" in d:
        ax.add_collection(LineCollection(d["obstacle"], colors="black", linewidths=2.5, label="obstacle"))
        ax.legend(loc="upper right")
    # Frame the body and the obstacle near it (a long floor would otherwise shrink the body to a line).
    lo, hi = x.min(axis=0), x.max(axis=0)
    margin = 0.15 * (hi - lo).max()
    ax.set_xlim(lo[0] - margin, hi[0] + margin)
    ax.set_ylim(lo[1] - margin, hi[1] + margin)
    ax.set_aspect("equal")
    ax.set_title("deformed mesh (displacements x %.3g), %s" % (scale, summary["mesh"]["file"].split("/")[-1]))
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def plot_pressure(summary, d, path):
    fig, ax = plt.subplots(figsize=(7, 4))
    if "contact_xy" in d:
        order = np.argsort(d["contact_xy"][:, 0])
        ax.plot(d["contact_xy"][order, 0], d["contact_pressure"][order], "o-", ms=3, label="computed (nodal)")
    hertz = summary.get("hertz")
    if hertz:
        a, p0 = hertz["a"], hertz["p0"]
        xs = np.linspace(-a, a, 201)
        ax.plot(xs, p0 * np.sqrt(np.clip(1 - xs ** 2 / a ** 2, 0, None)), "k--",
                label="Hertz p0 sqrt(1 - x²/a²), a = %.4g, p0 = %.4g" % (a, p0))
        ax.set_xlim(-2 * a, 2 * a)
    ax.set_xlabel("x")
    ax.set_ylabel("contact pressure")
    ax.set_title("contact pressure along the contact boundary")
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def plot_friction(summary, d, path):
    """The tangential traction |t| against x per contact boundary node, marked by state, with mu p and the stick zones."""
    mu = summary["friction"]["mu"]
    order = np.argsort(d["contact_xy"][:, 0])
    x = d["contact_xy"][order, 0]
    t = np.linalg.norm(d["friction_traction"][order], axis=1)
    state = d["friction_state"][order]
    p = d["contact_pressure"][order]
    fig, ax = plt.subplots(figsize=(7, 4))
    active = state > 0
    ax.plot(x[active], mu * p[active], "k--", lw=1, label="mu x pressure (mu = %g)" % mu)
    ax.plot(x[active], t[active], "-", color="0.6", lw=1)
    for value, name, colour in ((2, "stick", "tab:green"), (1, "slip", "tab:red"), (0, "open", "0.7")):
        sel = state == value
        if sel.any():
            ax.plot(x[sel], t[sel], "o", ms=3, color=colour, label="%s (%d)" % (name, sel.sum()))
    # The stick zones: runs of consecutive stick nodes.
    stick = np.where(state == 2)[0]
    for run in np.split(stick, np.where(np.diff(stick) > 1)[0] + 1) if stick.size else []:
        ax.axvspan(x[run[0]], x[run[-1]], color="tab:green", alpha=0.08)
    if active.any():
        span = x[active].max() - x[active].min()
        ax.set_xlim(x[active].min() - 0.25 * span, x[active].max() + 0.25 * span)
    ax.set_xlabel("x")
    ax.set_ylabel("tangential traction |t|")
    ax.set_title("friction along the contact boundary: %d stick, %d slip node(s)" % (
        summary["friction"]["stick_nodes"], summary["friction"]["slip_nodes"]))
    ax.legend()
    ax.grid(True, alpha=0.3)
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def plot_history(summary, path):
    history = summary["iterations"]["history"]
    it = np.arange(1, len(history) + 1)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(it, [h["active"] for h in history], "o-", color="C0")
    ax.set_xlabel("active-set iteration (all load steps)")
    ax.set_ylabel("active pairs", color="C0")
    ax2 = ax.twinx()
    pen = np.array([max(h["max_penetration"], 0.0) for h in history])
    floor = summary["certificate"]["gap_tol"] * 1e-3
    ax2.semilogy(it, np.maximum(pen, floor), "s--", color="C3")
    ax2.set_ylabel("max penetration (floored at gap_tol/1000)", color="C3")
    ax.set_title("active-set history (%d iterations, %d load step(s))" % (len(history),
                                                                        summary["iterations"]["load_steps"]))
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


PICTURE_SIZE = [800, 600]
PVPYTHON_SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "plot3d_pvpython.py")


def step_times(directory):
    """The time (load factor) of each load step, from solution.xdmf: {"step_000001": 0.25, ...}."""
    with open(os.path.join(directory, "solution.xdmf")) as f:
        text = f.read()
    return {name: float(t) for name, t in re.findall(r'<Grid Name="(step_\d+)"[^>]*>\s*<Time Value="([^"]+)"', text)}


def read_3d(directory):
    """What the 3D pictures need from solution.h5: per load step its time, the total normal contact force (the sum of
    the nodal multipliers on the contact boundary) and the largest displacement; at the last step the contact
    boundary's nodes with their pressure, the body's size and its largest displacement."""
    times = step_times(directory)
    with h5py.File(os.path.join(directory, "solution.h5"), "r") as f:
        names = sorted(k for k in f if k.startswith("step_"))
        xyz = f["mesh/coordinates"][()]
        steps = []
        for name in names:
            group = f[name]
            force = float(np.sum(group["contact_boundary/contact_lambda"][()])) if "contact_boundary" in group else 0.0
            steps.append({"time": times.get(name, float(len(steps) + 1)), "force": force,
                          "max_u": float(np.linalg.norm(group["displacement"][()], axis=1).max())})
        last = f[names[-1]]
        data = {"steps": steps, "size": float(np.linalg.norm(xyz.max(axis=0) - xyz.min(axis=0))),
                "lo": xyz.min(axis=0), "hi": xyz.max(axis=0), "has_obstacle": "obstacle" in f}
        if "contact_boundary" in f and "contact_boundary" in last:
            data["contact_xyz"] = f["contact_boundary/coordinates"][()]
            data["contact_pressure"] = last["contact_boundary/contact_pressure"][()]
    return data


def nice_scale(size, max_u):
    """The displacement scale of the 3D deformed picture: the round number (1, 2 or 5 times a power of ten, at least 1)
    that makes the largest displacement about a tenth of the body's size."""
    if max_u <= 0 or max_u >= 0.1 * size:
        return 1.0
    target = 0.1 * size / max_u
    power = 10.0 ** math.floor(math.log10(target))
    return max(m * power for m in (1, 2, 5) if m * power <= target * (1 + 1e-12))


def contact_patch(d):
    """The box the pressure picture frames: the contact boundary's nodes under pressure, widened by a third of their
    extent (at least a hundredth of the body's size) each way but not past the contact boundary (a symmetry plane
    through the patch stays at the picture's edge); the whole contact boundary when none is pressed."""
    xyz = d["contact_xyz"]
    pressed = xyz[d["contact_pressure"] > 0] if "contact_pressure" in d else xyz[:0]
    if len(pressed) == 0:
        pressed = xyz
    lo, hi = pressed.min(axis=0), pressed.max(axis=0)
    margin = max(float((hi - lo).max()) / 3, 0.01 * d["size"])
    return list(np.maximum(lo - margin, xyz.min(axis=0))), list(np.minimum(hi + margin, xyz.max(axis=0)))


def plot_force_displacement(summary, d, path):
    steps = d["steps"]
    u = [0.0] + [s["max_u"] for s in steps]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(u, [0.0] + [s["force"] for s in steps], "o-", label="total normal contact force (sum of the multipliers)")
    applied = np.linalg.norm(summary["contact"]["applied_force"])
    ax.plot(u, [0.0] + [s["time"] * applied for s in steps], "k--",
            label="applied load (load factor x %.4g)" % applied)
    for s in steps:
        ax.annotate("%.3g" % s["time"], (s["max_u"], s["force"]), textcoords="offset points", xytext=(6, -12),
                    fontsize=8)
    ax.set_xlabel("largest displacement |u| in the body")
    ax.set_ylabel("force")
    ax.set_title("force against displacement, %d load steps (labels: load factor)" % len(steps))
    ax.legend(loc="upper left")
    ax.grid(True, alpha=0.3)
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def pvpython():
    pvpython = shutil.which("pvpython")
    if not pvpython:
        raise NotDrawable("3D pictures are drawn by ParaView's pvpython, which is not installed (Debian package "
                          "python3-paraview; scripts/bootstrap.sh installs it)")
    return pvpython


def start_xvfb(xvfb, log):
    """A private Xvfb and its display number, or (None, None): a display number of its own (from the process id, so
    that plot.py's run side by side do not meet; Xvfb exits when another server holds it, and the next is tried),
    written by Xvfb to a pipe once it accepts connections; its messages in the file log."""
    for attempt in range(10):
        number = 100 + (os.getpid() * 10 + attempt) % 30000
        read_end, write_end = os.pipe()
        with open(log, "a") as messages:
            # -noreset: by default the server resets when its last client leaves, and pvpython, which connects,
            # leaves and connects again, then meets a server that refuses it ("bad X server connection").
            server = subprocess.Popen([xvfb, ":%d" % number, "-displayfd", str(write_end), "-screen", "0",
                                       "1280x1024x24", "-nolisten", "tcp", "-noreset"], pass_fds=(write_end,),
                                      stdout=messages, stderr=messages)
        os.close(write_end)
        with os.fdopen(read_end) as pipe:
            ready, _, _ = select.select([pipe], [], [], 60)
            written = pipe.readline().strip() if ready else ""
        if written == str(number) and server.poll() is None:
            return server, number
        if server.poll() is None:
            server.kill()
        server.wait()
    return None, None


@contextlib.contextmanager
def x_display(log):
    """The DISPLAY for pvpython: a private Xvfb's (Debian's ParaView renders through X only), its messages in the file
    log; the DISPLAY there is without Xvfb; NotDrawable with neither."""
    xvfb = shutil.which("Xvfb")
    if not xvfb:
        if os.environ.get("DISPLAY"):
            yield os.environ["DISPLAY"]
            return
        raise NotDrawable("Debian's ParaView draws through an X server, and there is no DISPLAY and no Xvfb (Debian "
                          "package xvfb; scripts/bootstrap.sh installs it)")
    server, number = start_xvfb(xvfb, log)
    if server is None:
        raise NotDrawable("Xvfb did not start:\n%s" % open(log).read())
    try:
        yield ":%d" % number
    finally:
        server.terminate()
        server.wait()


def plot_3d(summary, directory, out, scale):
    """deformed.png and contact_pressure.png by ParaView, active_set.png and (several load steps) force_displacement.png
    by matplotlib. Returns the lines to print: a picture per line, the ParaView ones with their colour bar's field and
    range."""
    try:
        d = read_3d(directory)
    except (OSError, KeyError, IndexError, ValueError) as e:
        raise NotDrawable("'%s' is not a signorini output (cannot read its load steps: %s)" % (
            os.path.join(directory, "solution.h5"), e))
    command = [pvpython(), "--force-offscreen-rendering", PVPYTHON_SCRIPT]
    if "contact_xyz" not in d:
        raise NotDrawable("'%s' has no contact boundary to draw the contact pressure on" % directory)
    if scale is None:
        scale = nice_scale(d["size"], d["steps"][-1]["max_u"])
    force = np.array(summary["contact"]["contact_force"], dtype=float)
    up = list(force / np.linalg.norm(force)) if np.linalg.norm(force) > 0 else [0.0, 0.0, 1.0]
    patch_lo, patch_hi = contact_patch(d)
    # The box that clips the contact boundary: the patch's, deep along the axis nearest the line of sight.
    # (a little wider than the patch, whose sides may lie on the contact boundary's edges).
    clip_lo, clip_hi = [c - 1e-3 * d["size"] for c in patch_lo], [c + 1e-3 * d["size"] for c in patch_hi]
    axis = int(np.argmax(np.abs(up)))
    clip_lo[axis] -= d["size"]
    clip_hi[axis] += d["size"]
    mesh = summary["mesh"]["file"].split("/")[-1]
    steps = summary["iterations"]["load_steps"]
    pressure_title = ("contact pressure seen from the obstacle, %s: max %.4g, contact area %.4g\n"
                      "red: the edge of the active set" % (mesh, summary["contact"]["max_pressure"],
                                                           summary["contact"]["contact_area"]))
    if summary.get("hertz"):
        pressure_title += "; Hertz: contact radius a = %.4g, peak pressure p0 = %.4g" % (
            summary["hertz"]["a"], summary["hertz"]["p0"])
    spec = {"body": os.path.join(directory, "body.xdmf"), "contact_boundary": os.path.join(directory,
                                                                                            "contact_boundary.xdmf"),
            "obstacle": os.path.join(directory, "obstacle.xdmf") if d["has_obstacle"] else None,
            "scale": scale, "up": up, "patch_lo": patch_lo, "patch_hi": patch_hi, "clip_lo": clip_lo,
            "clip_hi": clip_hi, "body_size": d["size"], "size": PICTURE_SIZE,
            "deformed_title": "deformed body (displacements x %.3g), %s%s" % (
                scale, mesh, ", load step %d of %d" % (steps, steps) if steps > 1 else ""),
            "pressure_title": pressure_title,
            "deformed_png": os.path.join(out, "deformed.png"),
            "pressure_png": os.path.join(out, "contact_pressure.png")}
    with tempfile.TemporaryDirectory(prefix="signorini_plot3d_") as work:
        spec_path = os.path.join(work, "spec.json")
        with open(spec_path, "w") as f:
            json.dump(spec, f)
        xvfb_log = os.path.join(work, "xvfb.log")
        with x_display(xvfb_log) as display:
            run = subprocess.run(command + [spec_path], capture_output=True, text=True,
                                 env=dict(os.environ, DISPLAY=display))
        x_messages = open(xvfb_log).read() if os.path.exists(xvfb_log) else ""
    # The helper prints "PICTURE FIELD MIN MAX" per picture: the colour bar's field and range.
    lines = [line for line in run.stdout.splitlines()
             if line.rsplit(" ", 3)[0] in (spec["deformed_png"], spec["pressure_png"])]
    if run.returncode != 0 or len(lines) != 2:
        raise NotDrawable("ParaView failed to draw '%s' (%s on DISPLAY %s, exit status %d):\n%s%s%s" % (
            directory, " ".join(command), display, run.returncode, run.stdout, run.stderr,
            "Xvfb said:\n" + x_messages if x_messages else ""))
    plot_history(summary, os.path.join(out, "active_set.png"))
    lines.append(os.path.join(out, "active_set.png"))
    if len(d["steps"]) > 1:
        plot_force_displacement(summary, d, os.path.join(out, "force_displacement.png"))
        lines.append(os.path.join(out, "force_displacement.png"))
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output_dir")
    parser.add_argument("--out", help="where to write the PNGs (default: OUTPUT_DIR)")
    parser.add_argument("--scale", type=float, help="displacement scale of deformed.png (default 1 in 2D, automatic "
                        "in 3D)")
    args = parser.parse_args()
    out = args.out or args.output_dir
    try:
        summary = read_summary(args.output_dir)
        if summary["mesh"]["dim"] == 3:
            os.makedirs(out, exist_ok=True)
            lines = plot_3d(summary, args.output_dir, out, args.scale)
        else:
            data = read(args.output_dir)
            os.makedirs(out, exist_ok=True)
            scale = 1.0 if args.scale is None else args.scale
            plot_deformed(summary, data, os.path.join(out, "deformed.png"), scale)
            plot_pressure(summary, data, os.path.join(out, "contact_pressure.png"))
            plot_history(summary, os.path.join(out, "active_set.png"))
            names = ["deformed.png", "contact_pressure.png", "active_set.png"]
            if "friction" in summary and "friction_traction" in data:
                plot_friction(summary, data, os.path.join(out, "friction.png"))
                names.append("friction.png")
            lines = [os.path.join(out, n) for n in names]
    except NotDrawable as e:
        print("plot.py: error: %s" % e, file=sys.stderr)
        return 1
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
