#!/usr/bin/python3
"""Pictures of a signorini output directory (matplotlib, no display needed).

    scripts/plot.py OUTPUT_DIR [--out DIR] [--scale S]

Writes into OUTPUT_DIR (or --out):
  deformed.png        the deformed mesh coloured by von Mises stress, with the obstacle (displacements times S,
                      default 1: a larger S would push the body through the rigid obstacle in the picture)
  contact_pressure.png  the contact pressure along the contact boundary against x, with Hertz's
                      p(x) = p0 sqrt(1 - x^2/a^2) when summary.json has a "hertz" block
  active_set.png      active pairs and maximum penetration per active-set iteration (summary.json iterations.history)
Reads solution.h5 (last load step: mesh, obstacle, contact boundary, fields) and summary.json. It draws 2D results
only: a 3D output is refused with a message (open it in ParaView: DIR/solution.xdmf or the per-block files
DIR/body.xdmf, obstacle.xdmf, contact_boundary.xdmf), and so is a directory that is not an output (exit status 1).
"""
import argparse
import json
import os
import sys

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
    """summary.json of an output directory of a 2D run; NotDrawable otherwise."""
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
    if dim != 2:
        raise NotDrawable("'%s' holds a %sD result, and plot.py draws 2D results only; open 3D results in ParaView: "
                          "%s, or the per-block files body.xdmf, obstacle.xdmf and contact_boundary.xdmf beside it" % (
                              directory, dim, os.path.join(directory, "solution.xdmf")))
    return summary


def read(directory):
    summary = read_summary(directory)
    try:
        return summary, read_solution(directory)
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


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output_dir")
    parser.add_argument("--out", help="where to write the PNGs (default: OUTPUT_DIR)")
    parser.add_argument("--scale", type=float, default=1.0, help="displacement scale of deformed.png (default 1)")
    args = parser.parse_args()
    out = args.out or args.output_dir
    try:
        summary, data = read(args.output_dir)
    except NotDrawable as e:
        print("plot.py: error: %s" % e, file=sys.stderr)
        return 1
    os.makedirs(out, exist_ok=True)
    plot_deformed(summary, data, os.path.join(out, "deformed.png"), args.scale)
    plot_pressure(summary, data, os.path.join(out, "contact_pressure.png"))
    plot_history(summary, os.path.join(out, "active_set.png"))
    for name in ("deformed.png", "contact_pressure.png", "active_set.png"):
        print(os.path.join(out, name))
    return 0


if __name__ == "__main__":
    sys.exit(main())
