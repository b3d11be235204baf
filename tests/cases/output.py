"""Output tests: the written strain and stress fields, what ParaView shows of the XDMF files through each reader, and
the order of the console lines."""

import json
import os
import shutil
import subprocess

import numpy as np

from harness import Skipped, test


def p1_displacement_gradients(result):
    """H = grad u of each cell of a triangle mesh (P1: one constant gradient per cell), from solution.h5."""
    xyz, cells, u = result.solution()
    H = []
    for cell in cells:
        X, U = xyz[cell], u[cell]
        H.append(np.linalg.solve(X[1:] - X[0], U[1:] - U[0]).T)  # rows: d u_i / d X
    return np.array(H)


@test("plane_stress_strain_zz")
def plane_stress_strain_zz(runner):
    """The cell strain's zz component (solution.h5, VTK order xx, yy, zz, xy, yz, xz): in plane stress, where
    sigma_zz = 0, eps_zz = -lambda / (lambda + 2 mu) (eps_xx + eps_yy) with the 3D lambda (linear) and likewise the
    Green-Lagrange E_zz (St. Venant-Kirchhoff, S_zz = lambda tr E + 2 mu E_zz = 0); it was written as 0. In plane
    strain it stays 0, with sigma_zz = nu (sigma_xx + sigma_yy) (linear). The in-plane strain is the one of the P1
    displacement, the in-plane stress the plane-stress law of it (lambda* = 2 lambda mu / (lambda + 2 mu))."""
    plate = ["-options_file", "options/plate_on_arc.yml"]
    for model, args in (("linear", plate), ("svk", plate + ["-material_model", "svk", "-bc_traction", "top:0:-5"])):
        r = runner.run(args, "plate on arc, %s plane stress" % model)
        E, nu = r.get("material.E"), r.get("material.nu")
        lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
        strain, stress = r.cell_field("strain"), r.cell_field("stress")
        H = p1_displacement_gradients(r)
        exact = 0.5 * (H + H.transpose(0, 2, 1))
        if model == "svk":
            exact += 0.5 * np.einsum("cki,ckj->cij", H, H)  # Green-Lagrange E = (H + H^T + H^T H) / 2
        # The same gradient in another order of operations: round-off of the largest strain.
        scale = np.abs(exact).max()
        runner.expect_close("%s: in-plane strain xx, yy, xy = the P1 displacement's" % model, strain[:, [0, 1, 3]],
                            np.column_stack([exact[:, 0, 0], exact[:, 1, 1], exact[:, 0, 1]]), 0, 1e-12 * scale)
        trace = strain[:, 0] + strain[:, 1]
        # The formula on the written in-plane values: round-off (and of the largest strain where the trace cancels).
        runner.expect_close("%s: eps_zz = -lambda / (lambda + 2 mu) (eps_xx + eps_yy)" % model, strain[:, 2],
                            -lam / (lam + 2 * mu) * trace, 1e-12, 1e-15 * scale)
        runner.expect_true("%s: eps_zz nonzero (max |eps_zz| %.3g)" % (model, np.abs(strain[:, 2]).max()),
                           np.abs(strain[:, 2]).max() > 1e-3 * scale)
        runner.expect_equal("%s: strain yz, xz = 0" % model, bool(np.all(strain[:, 4:] == 0)), True)
        runner.expect_equal("%s: sigma_zz, yz, xz = 0" % model, bool(np.all(stress[:, [2, 4, 5]] == 0)), True)
        if model == "linear":
            lam_star = 2 * lam * mu / (lam + 2 * mu)
            runner.expect_close("linear: sigma = lambda* tr eps I + 2 mu eps in plane",
                                stress[:, [0, 1, 3]], np.column_stack([lam_star * trace + 2 * mu * strain[:, 0],
                                                                       lam_star * trace + 2 * mu * strain[:, 1],
                                                                       2 * mu * strain[:, 3]]),
                                0, 1e-12 * np.abs(stress).max())
    r = runner.run([], "hertz, linear plane strain")
    nu = r.get("material.nu")
    strain, stress = r.cell_field("strain"), r.cell_field("stress")
    runner.expect_equal("plane strain: eps_zz = 0", bool(np.all(strain[:, 2] == 0)), True)
    runner.expect_close("plane strain: sigma_zz = nu (sigma_xx + sigma_yy)", stress[:, 2],
                        nu * (stress[:, 0] + stress[:, 1]), 0, 1e-12 * np.abs(stress).max())


PARAVIEW_READERS = ("Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader")


def require_pvpython():
    """pvpython's path; skips the test when it is not installed. Called before the test's first run, so that a skip
    never hides a check made before it."""
    pvpython = shutil.which("pvpython")
    if not pvpython:
        raise Skipped("pvpython not found (Debian package python3-paraview; scripts/bootstrap.sh installs it)")
    return pvpython


def paraview_dump(runner, results):
    """What each ParaView XDMF reader shows of each result's solution.xdmf and of its per-block files
    (paraview_dump.py under pvpython, one call for all): per result, a dict reader -> {class, times, blocks at the last
    time step} with "files": block name -> the same per reader, or None when pvpython failed (a recorded check)."""
    pvpython = require_pvpython()
    args = []
    for r in results:
        args += [os.path.join(r.dir, "solution.xdmf"), os.path.join(r.dir, "paraview.json")]
    proc = subprocess.run([pvpython, os.path.join(os.path.dirname(os.path.abspath(__file__)), "paraview_dump.py")] +
                          args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    runner.expect_equal("pvpython exit status (output: %s)" % proc.stdout[-2000:], proc.returncode, 0)
    if proc.returncode != 0:
        return [None] * len(results)
    dumps = []
    for r in results:
        with open(os.path.join(r.dir, "paraview.json")) as f:
            dumps.append(json.load(f))
    return dumps


def check_contact_displacement(runner, r):
    """solution.h5: the contact boundary's displacement at every step is the body's at the same nodes (node tags)."""
    import h5py

    with h5py.File(os.path.join(r.dir, "solution.h5"), "r") as f:
        row = {int(t): k for k, t in enumerate(f["mesh/node_tags"][()])}
        rows = [row[int(t)] for t in f["contact_boundary/node_tags"][()]]
        steps = sorted(k for k in f if k.startswith("step_"))
        runner.expect_equal("solution.h5: load steps", len(steps), r.get("iterations.load_steps"))
        for step in steps:
            got = f[step + "/contact_boundary/displacement"][()] if "displacement" in f[step + "/contact_boundary"] \
                else np.full((len(rows), 3), np.nan)
            runner.expect_close("solution.h5 %s: contact boundary displacement = the body's at its nodes" % step,
                                got, f[step + "/displacement"][()][rows], 0, 0)


def check_block_files(runner, dump, names):
    """What every reader shows of body.xdmf, obstacle.xdmf and contact_boundary.xdmf (names: the blocks of
    solution.xdmf in order): a plain vtkUnstructuredGrid with the time steps of solution.xdmf, whose points, cells and
    arrays at the last step are those of the block of solution.xdmf, value for value; and on the contact boundary of
    solution.xdmf the displacement of the body at the same nodes (node_tags), so that Warp By Vector moves both."""
    runner.expect_equal("per-block XDMF files", sorted(dump["files"]), sorted(names))
    for reader in PARAVIEW_READERS:
        whole = dump[reader]
        runner.expect_equal("%s: solution.xdmf blocks" % reader, len(whole["blocks"]), len(names))
        if len(whole["blocks"]) != len(names):
            continue
        for k, name in enumerate(names):
            view = dump["files"].get(name, {}).get(reader)
            if view is None:
                continue
            what = "%s: %s.xdmf" % (reader, name)
            runner.expect_equal("%s: dataset class" % what, view["class"], "vtkUnstructuredGrid")
            runner.expect_equal("%s: time steps (solution.xdmf's)" % what, view["times"], whole["times"])
            runner.expect_equal("%s: datasets" % what, len(view["blocks"]), 1)
            got, want = view["blocks"][0], whole["blocks"][k]
            runner.expect_equal("%s: points at the last step" % what, got["points"], want["points"])
            runner.expect_equal("%s: cells" % what, got["cells"], want["cells"])
            for kind in ("point_data", "cell_data"):
                runner.expect_equal("%s: %s arrays" % (what, kind), sorted(got[kind]), sorted(want[kind]))
                for array in sorted(set(got[kind]) & set(want[kind])):
                    a, b = got[kind][array], want[kind][array]
                    runner.expect_equal("%s: %s component names" % (what, array), a["components"], b["components"])
                    runner.expect_true("%s: %s at the last step = solution.xdmf's %s block's" % (what, array, name),
                                       np.array_equal(np.array(a["values"]), np.array(b["values"]), equal_nan=True))
        body, contact = whole["blocks"][0], whole["blocks"][names.index("contact_boundary")]
        u = {int(t[0]): v for t, v in zip(body["point_data"]["node_tags"]["values"],
                                         body["point_data"]["displacement"]["values"])}
        tags = [int(t[0]) for t in contact["point_data"]["node_tags"]["values"]]
        shown = contact["point_data"].get("displacement", {"values": [[np.nan] * 3] * len(tags)})["values"]
        runner.expect_close("%s: contact_boundary displacement = the body's at its node_tags" % reader, shown,
                            [u[t] for t in tags], 0, 0)


@test("paraview_view")
def paraview_view(runner):
    """What ParaView shows of block_on_floor in two load steps, through each of its XDMF readers, at the last step:
    stress and strain under the right component names, the floor as its own grid, the contact fields and the
    displacement on a grid of the contact boundary (finite gap everywhere), node and cell tags that match nodes.csv;
    and each block in a file of its own (check_block_files)."""
    require_pvpython()
    q = 2.0
    r = runner.run(["-options_file", "options/block_on_floor.yml", "-load_steps", "2"], "block_on_floor")
    check_contact_displacement(runner, r)
    dump = paraview_dump(runner, [r])[0]
    if dump is None:
        return
    check_block_files(runner, dump, ["body", "obstacle", "contact_boundary"])
    readers = {reader: dump[reader]["blocks"] for reader in PARAVIEW_READERS}
    nodes = r.nodes()
    by_tag = {int(t): (x, y) for t, x, y in zip(nodes["node_tag"], nodes["x"], nodes["y"])}
    bottom = nodes[nodes["y"] == 0.0]
    E, nu = r.get("material.E"), r.get("material.nu")
    # The exact field is uniform (block_on_floor): sigma_yy = -q, sigma_zz = nu sigma_yy (plane strain), no shear;
    # eps_xx = nu (1 + nu) q / E, eps_yy = -(1 - nu^2) q / E. P1/Q1 reproduce it up to round-off (1e-10 as there).
    exact = {"stress": {"XX": 0, "YY": -q, "ZZ": -nu * q, "XY": 0, "YZ": 0, "XZ": 0},
             "strain": {"XX": nu * (1 + nu) * q / E, "YY": -(1 - nu * nu) * q / E, "ZZ": 0, "XY": 0, "YZ": 0,
                        "XZ": 0}}
    for reader, blocks in readers.items():
        runner.expect_equal("%s: blocks (body, obstacle, contact boundary)" % reader, len(blocks), 3)
        if len(blocks) != 3:
            continue
        body, floor, contact = blocks
        for field, want in exact.items():
            array = body["cell_data"][field]
            runner.expect_equal("%s: %s component names" % (reader, field), sorted(array["components"]),
                                sorted(want))
            got = {name: [cell[k] for cell in array["values"]] for k, name in enumerate(array["components"])}
            for name, value in want.items():
                runner.expect_close("%s: %s_%s of every cell" % (reader, field, name), got.get(name, [np.nan]),
                                    np.full(len(got.get(name, [0])), value), 0, 1e-10 * q)
        # node_tags on the body: the tag a selection shows is the nodes.csv row at the same coordinates.
        tags = [int(t[0]) for t in body["point_data"]["node_tags"]["values"]]
        runner.expect_close("%s: nodes.csv coordinates of the body's node_tags" % reader,
                            [by_tag[t] for t in tags], [p[:2] for p in body["points"]], 0, 1e-12)
        runner.expect_equal("%s: cell_tags on every cell" % reader, len(body["cell_data"]["cell_tags"]["values"]),
                            len(body["cells"]))
        # The floor, -obstacle_segments -1,0,3,0 of the case: one segment.
        runner.expect_close("%s: obstacle points" % reader, floor["points"], [[-1, 0, 0], [3, 0, 0]], 0, 1e-12)
        runner.expect_equal("%s: obstacle cells" % reader, floor["cells"], [[0, 1]])
        # The contact boundary: the bottom nodes (the group 'bottom') and the edges between them.
        cx = sorted(p[0] for p in contact["points"])
        runner.expect_close("%s: contact boundary nodes are the bottom nodes" % reader, cx, np.sort(bottom["x"]), 0,
                            1e-12)
        runner.expect_equal("%s: contact boundary edges" % reader, len(contact["cells"]), len(bottom) - 1)
        gap = np.array(contact["point_data"]["contact_gap"]["values"]).ravel()
        runner.expect_true("%s: contact_gap finite on every contact-boundary node" % reader, np.all(np.isfinite(gap)))
        runner.expect_close("%s: contact_pressure on the contact boundary = q" % reader,
                            np.array(contact["point_data"]["contact_pressure"]["values"]).ravel(),
                            np.full(len(gap), q), 1e-10)
        ctags = [int(t[0]) for t in contact["point_data"]["node_tags"]["values"]]
        runner.expect_close("%s: nodes.csv coordinates of the contact boundary's node_tags" % reader,
                            [by_tag[t] for t in ctags], [p[:2] for p in contact["points"]], 0, 1e-12)


@test("paraview_view_3d")
def paraview_view_3d(runner):
    """What ParaView shows of a 3D output, through each of its XDMF readers: the conforming mesh of tetrahedra,
    pyramids and hexahedra (a Mixed topology) cell by cell, and the analytic obstacles drawn as triangles in the
    obstacle grid, each with the bounds its options give: the plane z = 0 as the rectangle under the body, a cylinder
    over the body's extent along its axis, a whole sphere (placed apart, below the body, so that they do not touch
    it); in two load steps, at the last one; and each block in a file of its own (check_block_files)."""
    require_pvpython()
    plane, cylinder, sphere = [0, 0, 0, 0, 0, 1], [0, 0.5, -4, 1, 0, 0, 0.5], [1, 0.5, -10, 2]
    r = runner.run(["-options_file", "options/cube_on_plane.yml", "-mesh_file", "meshes/cube_mixed_conforming.msh",
                    "-obstacle_planes", ",".join(map(str, plane)), "-obstacle_cylinders",
                    ",".join(map(str, cylinder)), "-obstacle_spheres", ",".join(map(str, sphere)), "-load_steps", "2"],
                   "cube_mixed_conforming with a plane, a cylinder and a sphere")
    check_contact_displacement(runner, r)
    dump = paraview_dump(runner, [r])[0]
    if dump is None:
        return
    check_block_files(runner, dump, ["body", "obstacle", "contact_boundary"])
    readers = {reader: dump[reader]["blocks"] for reader in PARAVIEW_READERS}
    xyz, cells, _ = r.solution()
    kinds = {n: sum(len(c) == n for c in cells) for n in (4, 5, 8)}
    # The body's box [0, 2] x [0, 1] x [0, 1] bounds the unbounded shapes: the plane's rectangle is the box's
    # projection, the cylinder (axis x, centre line y = 0.5, z = -4, radius 0.5) spans x in [0, 2]. Triangles: 2 for
    # the plane, 2 x 64 for the cylinder (64 sides), 2 x 64 x 31 for the sphere (64 meridians, 32 bands).
    shapes = {"plane": (lambda z: z > -1, 2, [[0, 0, 0], [2, 1, 0]]),
              "cylinder": (lambda z: -5 < z < -3, 2 * 64, [[0, 0, -4.5], [2, 1, -3.5]]),
              "sphere": (lambda z: z < -7, 2 * 64 * 31, [[-1, -1.5, -12], [3, 2.5, -8]])}
    # The contact surface: the bottom faces (z = 0), quadrilaterals of the hexahedra and triangles of the tetrahedra
    # (and of a pyramid whose apex lies on the bottom), a Mixed topology; its multipliers carry the load q * area.
    bottom = {3: 0, 4: 0}
    for c in cells:
        on = sum(abs(xyz[v][2]) < 1e-12 for v in c)
        if (len(c), on) in ((4, 3), (5, 3), (8, 4)):
            bottom[on] += 1
    for reader, blocks in readers.items():
        runner.expect_equal("%s: blocks (body, obstacle, contact_boundary)" % reader, len(blocks), 3)
        if len(blocks) != 3:
            continue
        body, obstacle, contact = blocks
        runner.expect_equal("%s: contact faces by vertices (triangles, quadrilaterals)" % reader,
                            {n: sum(len(c) == n for c in contact["cells"]) for n in (3, 4)}, bottom)
        runner.expect_close("%s: contact surface at z = 0" % reader,
                            [p[2] for p in contact["points"]], [0.0] * len(contact["points"]), 0, 1e-14)
        lam = contact["point_data"].get("contact_lambda", {"values": [[0.0]]})["values"]
        runner.expect_close("%s: contact multipliers sum to q * area" % reader, sum(v[0] for v in lam), 2.0 * 2.0,
                            1e-10, 0)
        runner.expect_equal("%s: body points" % reader, len(body["points"]), len(xyz))
        shown = {n: sum(len(c) == n for c in body["cells"]) for n in (4, 5, 8)}
        runner.expect_equal("%s: body cells by vertices (tetrahedra, pyramids, hexahedra)" % reader, shown, kinds)
        runner.expect_equal("%s: cell_tags on every cell" % reader, len(body["cell_data"]["cell_tags"]["values"]),
                            len(cells))
        # The cells' vertices as ParaView shows them are the file's (pyramids: the base, then the apex).
        runner.expect_close("%s: cell vertices" % reader,
                            [body["points"][v] for c in body["cells"] for v in c],
                            [list(xyz[v]) for c in cells for v in c], 0, 1e-14)
        points = np.array(obstacle["points"])
        runner.expect_true("%s: obstacle cells are triangles" % reader, all(len(c) == 3 for c in obstacle["cells"]))
        runner.expect_equal("%s: obstacle cells" % reader, len(obstacle["cells"]),
                            sum(n for _, n, _ in shapes.values()))
        for name, (where, count, bounds) in shapes.items():
            tri = [c for c in obstacle["cells"] if where(points[c].mean(axis=0)[2])]
            runner.expect_equal("%s: %s triangles" % (reader, name), len(tri), count)
            if not tri:
                continue
            p = points[np.array(tri).ravel()]
            runner.expect_close("%s: %s bounds" % (reader, name), [p.min(axis=0), p.max(axis=0)], bounds, 0, 1e-12)


@test("monitor_after_header")
def monitor_after_header(runner):
    """-contact_monitor lines come after the run's header (model, mesh, unknowns) and before the result lines."""
    r = runner.run(["-options_file", "options/beam_on_floor.yml", "-contact_monitor"], "beam_on_floor monitor")
    lines = r.output.splitlines()

    def first(prefix):
        return next((i for i, line in enumerate(lines) if line.strip().startswith(prefix)), -1)

    header, unknowns, monitor = first("signorini: 2D"), first("unknowns:"), first("step 1 (load 1) it 1:")
    result = first("CONVERGED")
    runner.expect_true("header line %d, unknowns line %d, first monitor line %d, result line %d in that order" % (
        header, unknowns, monitor, result), 0 <= header < unknowns < monitor < result)


@test("paraview_view_bodies")
def paraview_view_bodies(runner):
    """What ParaView shows of a case of two bodies (the 3D contact patch test, tetrahedra on hexahedra), through each
    of its XDMF readers: the body grid with every cell and the cell field body (one value per block), no obstacle grid, and the contact boundary on the slave side (the upper block's bottom, z = 1) whose
    multipliers carry the load q * area; each block in a file of its own (check_block_files)."""
    require_pvpython()
    r = runner.run(["-options_file", "options/patch3d.yml", "-mesh_file", "meshes/patch3d_tet_on_hex.msh"],
                   "patch test, tetrahedra on hexahedra")
    check_contact_displacement(runner, r)
    dump = paraview_dump(runner, [r])[0]
    if dump is None:
        return
    check_block_files(runner, dump, ["body", "contact_boundary"])
    xyz, cells, _ = r.solution()
    for reader in PARAVIEW_READERS:
        blocks = dump[reader]["blocks"]
        runner.expect_equal("%s: blocks (body, contact_boundary)" % reader, len(blocks), 2)
        if len(blocks) != 2:
            continue
        body, contact = blocks
        runner.expect_equal("%s: body cells" % reader, len(body["cells"]), len(cells))
        shown = np.array([v[0] for v in body["cell_data"]["body"]["values"]])
        above = np.array([np.mean([body["points"][v][2] for v in c]) > 1 for c in body["cells"]])
        # Bodies are numbered by their first cell in the file: the tetrahedra (above) come first in this mesh.
        runner.expect_equal("%s: body field on the cells above the interface (values)" % reader,
                            sorted(set(shown[above])), [0.0])
        runner.expect_equal("%s: body field on the cells below it (values)" % reader, sorted(set(shown[~above])),
                            [1.0])
        runner.expect_close("%s: contact boundary at z = 1 (the slave side)" % reader,
                            [p[2] for p in contact["points"]], [1.0] * len(contact["points"]), 0, 1e-14)
        lam = contact["point_data"].get("contact_lambda", {"values": [[0.0]]})["values"]
        runner.expect_close("%s: contact multipliers sum to q * area" % reader, sum(v[0] for v in lam), 2.0, 1e-10, 0)
