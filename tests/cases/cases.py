"""Case tests: shipped and hand-built contact problems, most with an exact field or a force balance to round-off."""

import os

import numpy as np

from harness import (arc_segments, check_same_mesh, coordinates, displacement, expect_balance, expect_same_state,
                     options_args, rate, test, yaml_options)


def tributary(s):
    """Tributary lengths of nodes at the sorted positions s along a straight contact edge: half of each adjacent
    edge."""
    w = np.zeros_like(s)
    h = np.diff(s)
    w[:-1] += 0.5 * h
    w[1:] += 0.5 * h
    return w


@test("block_on_floor")
def block_on_floor(runner):
    """Block under uniform pressure on a rigid floor: every bottom node active, lambda_i = q w_i, the exact field."""
    q, W = 2.0, 2.0
    r = runner.run(["-options_file", "options/block_on_floor.yml"], "block_on_floor")
    nodes = r.nodes()
    bottom = nodes[nodes["y"] == 0.0]
    bottom = bottom[np.argsort(bottom["x"])]
    n = len(bottom)
    runner.expect_true("bottom nodes found (%d)" % n, n >= 3)
    # Uniform compression holds every bottom node on the floor; they all touch at the start, so the first active
    # set is the solution and one solve settles it.
    runner.expect_equal("candidate pairs", r.get("contact.pairs"), n)
    runner.expect_equal("active pairs", r.get("contact.active_pairs"), n)
    runner.expect_equal("active nodes", r.get("contact.active_nodes"), n)
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 1)
    runner.expect_equal("active flags of the bottom nodes", int(bottom["active"].sum()), n)
    runner.expect_equal("active nodes off the bottom", int(nodes["active"].sum()) - n, 0)
    # The exact solution (uniform stress sigma_yy = -q) is linear, so P1/Q1 reproduce it and the consistent nodal
    # forces of the pressure are q w_i: equal up to round-off (1e-10 leaves room for the conditioning of K).
    w = tributary(bottom["x"])
    runner.expect_close("lambda_i = q w_i", bottom["lambda"], q * w, 1e-10)
    runner.expect_close("contact pressure = q", bottom["pressure"], np.full(n, q), 1e-10)
    runner.expect_close("sum of lambda = q W", bottom["lambda"].sum(), q * W, 1e-10)
    runner.expect_close("contact force", r.get("contact.contact_force"), [0, q * W], 1e-10, 1e-10 * q * W)
    # Plane strain, sigma_xx = 0 (free right edge, frictionless floor), u_x = 0 on the left edge, u_y = 0 on the floor.
    E, nu = r.get("material.E"), r.get("material.nu")
    exact = np.column_stack([nu * (1 + nu) * q / E * nodes["x"], -(1 - nu * nu) * q / E * nodes["y"]])
    runner.expect_close("displacement = exact linear field", displacement(nodes), exact, 0,
                        1e-10 * np.abs(exact).max())


def bottom_tributary_areas(result, tags):
    """Tributary areas of the nodes on z = 0, by hand from solution.h5: a third of each bottom triangle of a
    tetrahedron, a quarter of each bottom rectangle of a hexahedron (the cube's bottom faces are axis-aligned)."""
    import h5py

    xyz, cells, _ = result.solution()
    with h5py.File(os.path.join(result.dir, "solution.h5"), "r") as f:
        file_tags = f["mesh/node_tags"][()]
    on_bottom = xyz[:, 2] == 0.0
    area = np.zeros(len(xyz))
    for cell in cells:
        face = [v for v in cell if on_bottom[v]]
        if len(face) == 3:
            p = xyz[face]
            a = 0.5 * np.linalg.norm(np.cross(p[1] - p[0], p[2] - p[0]))
        elif len(face) == 4:
            p = xyz[face]
            a = np.ptp(p[:, 0]) * np.ptp(p[:, 1])
        else:
            continue
        area[face] += a / len(face)
    by_tag = dict(zip(file_tags, area))
    return np.array([by_tag[t] for t in tags])


def expect_pressed_box(runner, r, nodes, bottom, q, area):
    """A box of base `area` on the rigid plane z = 0 under a uniform pressure q on its top (options/cube_on_plane.yml):
    every bottom node is a candidate and active after one solve, lambda_i = q w_i (w_i its tributary area), no
    penetration, the exact linear field u = (nu q x / E, nu q y / E, -q z / E) and the uniform stress sigma_zz = -q
    in every cell (VTK order: xx, yy, zz, xy, yz, xz), to round-off. Returns the tributary areas."""
    n = len(bottom)
    runner.expect_equal("candidate pairs", r.get("contact.pairs"), n)
    runner.expect_equal("active pairs: every bottom node", r.get("contact.active_pairs"), n)
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 1)
    runner.expect_equal("active nodes off the bottom", int(nodes["active"].sum()) - int(bottom["active"].sum()), 0)
    # The consistent nodal forces of the pressure are q w_i (1e-10 leaves room for the conditioning of K).
    w = bottom_tributary_areas(r, bottom["node_tag"])
    runner.expect_close("sum of tributary areas = %g" % area, w.sum(), area, 1e-14)
    runner.expect_close("lambda_i = q w_i", bottom["lambda"], q * w, 1e-10)
    runner.expect_close("contact pressure = q", bottom["pressure"], np.full(n, q), 1e-10)
    runner.expect_close("contact area", r.get("contact.contact_area"), area, 1e-12)
    runner.expect_true("no contact length in 3D", "contact_length" not in r.summary["contact"])
    runner.expect_close("contact force", r.get("contact.contact_force"), [0, 0, q * area], 0, 1e-10 * q)
    runner.expect_true("no penetration beyond round-off (%g)" % r.get("contact.max_penetration"),
                       r.get("contact.max_penetration") <= 1e-15)
    E, nu = r.get("material.E"), r.get("material.nu")
    exact = np.column_stack([nu * q / E * nodes["x"], nu * q / E * nodes["y"], -q / E * nodes["z"]])
    runner.expect_close("displacement = exact linear field", displacement(nodes), exact, 0,
                        1e-10 * np.abs(exact).max())
    stress = r.cell_field("stress")
    runner.expect_close("stress = (0, 0, -q, 0, 0, 0) in every cell", stress,
                        np.tile([0, 0, -q, 0, 0, 0], (len(stress), 1)), 0, 1e-10 * q)
    return w


@test("cube_on_plane")
def cube_on_plane(runner, mesh):
    """Unit cube (hexahedra or tetrahedra) under uniform pressure on a rigid plane: every bottom node active,
    lambda_i = q w_i with w_i its tributary area, no penetration, the exact linear field."""
    q = 2.0
    args = ["-options_file", "options/cube_on_plane.yml", "-mesh_file", "meshes/%s.msh" % mesh]
    r = runner.run(args, "cube_on_plane " + mesh)
    nodes = r.nodes()
    bottom = nodes[nodes["z"] == 0.0]
    n = len(bottom)
    runner.expect_true("bottom nodes found (%d)" % n, n >= 9)
    # Every bottom node touches the plane at the start and stays in compression: one solve settles it. The
    # supports u_x = 0, u_y = 0 fix one component only, so every bottom node is a candidate.
    runner.expect_equal("active flags of the bottom nodes", int(bottom["active"].sum()), n)
    w = expect_pressed_box(runner, r, nodes, bottom, q, 1.0)
    runner.expect_true("tributary areas differ (graded mesh)", w.max() > 1.5 * w.min())
    stress = r.cell_field("stress")
    runner.expect_close("von Mises = q", r.cell_field("von_mises"), np.full(len(stress), q), 1e-10)


@test("mixed_cells")
def mixed_cells(runner):
    """A mesh of hexahedra and tetrahedra (two cubes, meshes/cube_mixed.msh) under uniform pressure on a rigid plane:
    the exact field and lambda_i = q w_i on both, and the hexahedral cube's answer that of cube.msh alone."""
    q = 2.0
    r = runner.run(["-options_file", "options/cube_on_plane.yml", "-mesh_file", "meshes/cube_mixed.msh"],
                   "cube_on_plane cube_mixed")
    xyz, cells, _ = r.solution()
    kinds = sorted(set(len(c) for c in cells))
    runner.expect_equal("cell kinds (nodes per cell)", kinds, [4, 8])
    nodes = r.nodes()
    bottom = nodes[nodes["z"] == 0.0]
    n = len(bottom)
    runner.expect_equal("active pairs: every bottom node", r.get("contact.active_pairs"), n)
    w = bottom_tributary_areas(r, bottom["node_tag"])
    runner.expect_close("sum of tributary areas = 2", w.sum(), 2.0, 1e-14)
    runner.expect_close("lambda_i = q w_i", bottom["lambda"], q * w, 1e-10)
    runner.expect_close("contact force", r.get("contact.contact_force"), [0, 0, 2 * q], 0, 1e-10 * q)
    E, nu = r.get("material.E"), r.get("material.nu")
    x0 = np.where(nodes["x"] >= 2.0, 2.0, 0.0)  # each cube's symmetry face u_x = 0
    exact = np.column_stack([nu * q / E * (nodes["x"] - x0), nu * q / E * nodes["y"], -q / E * nodes["z"]])
    runner.expect_close("displacement = exact linear field in both cubes", displacement(nodes), exact, 0,
                        1e-10 * np.abs(exact).max())
    # The hexahedral cube is meshes/cube.geo itself: its nodes, displacements and multipliers are those of cube.msh
    # (the same equations, apart from the other cube's; round-off).
    pure = runner.run(["-options_file", "options/cube_on_plane.yml"], "cube_on_plane cube")
    ref = pure.nodes()
    hexes = nodes[nodes["x"] <= 1.0]
    key = lambda t: np.lexsort((t["z"], t["y"], t["x"]))
    hexes, ref = hexes[key(hexes)], ref[key(ref)]
    runner.expect_close("hexahedral cube: node coordinates", coordinates(hexes), coordinates(ref), 0, 1e-14)
    u = displacement(ref)
    runner.expect_close("hexahedral cube: displacement", displacement(hexes), u, 0, 1e-12 * np.abs(u).max())
    runner.expect_close("hexahedral cube: lambda", hexes["lambda"], ref["lambda"], 0, 1e-12 * ref["lambda"].max())


@test("mixed_conforming")
def mixed_conforming(runner):
    """The conforming mesh of hexahedra, pyramids and tetrahedra (meshes/cube_mixed_conforming.msh, a 2 x 1 x 1 box)
    under uniform pressure on a rigid plane: every bottom node active, lambda_i = q w_i, no penetration, the exact
    field and its uniform stress in every cell, pyramids included."""
    q = 2.0
    r = runner.run(["-options_file", "options/cube_on_plane.yml", "-mesh_file", "meshes/cube_mixed_conforming.msh"],
                   "cube_on_plane cube_mixed_conforming")
    xyz, cells, _ = r.solution()
    kinds = {n: sum(len(c) == n for c in cells) for n in sorted(set(len(c) for c in cells))}
    # gmsh put one pyramid on each of the 5 x 4 quadrilaterals of the face x = 1 between the 100 hexahedra and the
    # tetrahedra.
    runner.expect_equal("cell kinds (nodes per cell)", sorted(kinds), [4, 5, 8])
    runner.expect_equal("pyramids", kinds.get(5), 20)
    runner.expect_equal("hexahedra", kinds.get(8), 100)
    nodes = r.nodes()
    bottom = nodes[nodes["z"] == 0.0]
    # As cube_on_plane: the field is linear, reproduced exactly (round-off) by the conforming cells.
    expect_pressed_box(runner, r, nodes, bottom, q, 2.0)


@test("forces_3d")
def forces_3d(runner):
    """Point forces and a body force with three components on the mixed mesh: the applied load is their sum, and
    contact, supports and load balance to round-off."""
    q, body, point = 2.0, np.array([0.5, -0.3, -2.0]), np.array([0.01, 0.02, -0.05])
    r = runner.run(["-options_file", "options/cube_on_plane.yml", "-mesh_file", "meshes/cube_mixed.msh",
                    "-bc_body_force", ",".join(map(str, body)), "-bc_point_force", "top:%g:%g:%g" % tuple(point)],
                   "cube_mixed body and point forces")
    nodes = r.nodes()
    top = int(np.sum(nodes["z"] == 1.0))
    volume, area = 2.0, 2.0
    applied = volume * body + top * point + [0, 0, -q * area]
    runner.expect_close("applied load = body force x volume + point forces + pressure x area (%d top nodes)" % top,
                        r.get("contact.applied_force"), applied, 0, 1e-12 * np.abs(applied).max())
    total = (np.array(r.get("contact.contact_force")) + np.array(r.get("contact.applied_force")) +
             np.array(r.get("contact.reaction_force")))
    runner.expect_close("contact + applied + reactions = 0", total, [0, 0, 0], 0, 1e-10 * np.abs(applied).max())
    runner.expect_true("force balance %.3g <= 1e-10" % r.get("contact.force_balance"),
                       r.get("contact.force_balance") <= 1e-10)
    # The supports take the tangential load (frictionless contact cannot): reactions -F_x on the faces x = 0, 2 and
    # -F_y on y = 0; the plane takes the whole normal load.
    runner.expect_close("reactions take the tangential load", r.get("contact.reaction_force")[:2], -applied[:2], 0,
                        1e-10 * np.abs(applied).max())
    runner.expect_close("the plane takes the normal load", r.get("contact.contact_force"), [0, 0, -applied[2]], 0,
                        1e-10 * np.abs(applied).max())


@test("block_on_cylinder")
def block_on_cylinder(runner):
    """Block pressed onto a rigid cylinder: the cylinder carries the load, a strip around the line of first contact
    is active, and the contact pressure is symmetric about the plane through the cylinder's axis."""
    q, area = 1.0, 2.0
    r = runner.run(["-options_file", "options/block_on_cylinder.yml"], "block_on_cylinder")
    P = q * area
    # Force balance: the top is flat, so the applied load is exactly q x area; the cylinder's reaction balances it
    # (round-off of a direct solve), with no net x component (the symmetry) and no support reaction along z.
    runner.expect_close("applied load", r.get("contact.applied_force"), [0, 0, -P], 0, 1e-12 * P)
    runner.expect_close("contact force = applied load", r.get("contact.contact_force"), [0, 0, P], 0, 1e-10 * P)
    runner.expect_true("force balance %.3g <= 1e-10" % r.get("contact.force_balance"),
                       r.get("contact.force_balance") <= 1e-10)
    nodes = r.nodes()
    bottom = nodes[nodes["z"] == 0.0]
    active = bottom[bottom["active"] > 0]
    # Line contact spreading to a strip: the nodes over the axis are active, the block's ends are not.
    runner.expect_equal("active nodes over the axis (5 along y)", int(np.sum(active["x"] == 0.0)), 5)
    runner.expect_true("a strip: %d of %d bottom nodes active, none at |x| = 1" % (len(active), len(bottom)),
                       0 < len(active) < len(bottom) and np.abs(active["x"]).max() < 1)
    # Symmetry about x = 0: the mirror of every bottom node is a bottom node (the halves of the mesh are mirrored up
    # to gmsh's round-off in the coordinates), with the same active flag and pressure. The solve is symmetric up to
    # the conditioning of K: 1e-8 of the peak pressure.
    xy = np.column_stack([bottom["x"], bottom["y"]])
    mirror = np.array([np.argmin(np.sum((xy - [-x, y]) ** 2, axis=1)) for x, y in xy])
    runner.expect_close("bottom nodes mirrored about x = 0", xy[mirror], xy * [-1, 1], 0, 1e-10)
    runner.expect_equal("active set symmetric", list(bottom["active"][mirror]), list(bottom["active"]))
    p = bottom["pressure"]
    runner.expect_close("contact pressure symmetric", p[mirror], p, 0, 1e-8 * p.max())


@test("block_pulled_off")
def block_pulled_off(runner):
    """Block pulled off a floor it touches: no active pair, the same displacement as without any obstacle."""
    r = runner.run(["-options_file", "options/block_pulled_off.yml"], "block_pulled_off")
    no_obstacle = options_args(runner, "options/block_pulled_off.yml", drop=("obstacle_segments", "contact_groups"))
    free = runner.run(no_obstacle, "block_pulled_off without obstacle")
    nodes, ref = r.nodes(), free.nodes()
    n_bottom = int((nodes["y"] == 0.0).sum())
    # The clamped corner (0,0) has both components fixed and is no candidate; every other bottom node touches the
    # floor at the start. The first solve finds them all in tension and releases them, the second one confirms.
    runner.expect_equal("candidate pairs", r.get("contact.pairs"), n_bottom - 1)
    runner.expect_equal("pairs released after the first solve", r.get("iterations.history.0.changed"), n_bottom - 1)
    runner.expect_equal("active pairs", r.get("contact.active_pairs"), 0)
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 2)
    runner.expect_equal("multipliers without obstacle", free.get("problem.multipliers"), 0)
    runner.expect_close("lambda", nodes["lambda"], np.zeros(len(nodes)), 0, 0)
    runner.expect_close("contact force", r.get("contact.contact_force"), [0, 0], 0, 0)
    check_same_mesh(runner, "with and without obstacle", nodes, ref)
    # Inactive multipliers are decoupled rows (lambda = 0), so both runs solve K u = f; only the elimination order
    # differs: round-off of a stocky block (condition number of K ~ 1e3).
    u_ref = displacement(ref)
    runner.expect_close("displacement = displacement without obstacle", displacement(nodes), u_ref, 0,
                        1e-12 * np.abs(u_ref).max())
    # The tolerance on a tensile multiplier follows the forces, not E t times the gap tolerance: with a stiff material
    # (E = 1e9: c gap_tol = 2.2 against multipliers of 0.3) or a small suction (1e-5: multipliers of 1e-6), the
    # tensile pairs were kept and the block converged glued to the floor (contact force -3.2 and -1.6e-5).
    for label, extra in (("E = 1e9", ["-material_E", "1e9"]), ("suction 1e-5", ["-bc_pressure", "top:-1e-5"])):
        v = runner.run(["-options_file", "options/block_pulled_off.yml"] + extra, "block_pulled_off, " + label)
        runner.expect_equal("active pairs, " + label, v.get("contact.active_pairs"), 0)
        runner.expect_close("contact force, " + label, v.get("contact.contact_force"), [0, 0], 0, 0)
        runner.expect_close("lambda, " + label, v.nodes()["lambda"], np.zeros(len(nodes)), 0, 0)


@test("block_in_corner")
def block_in_corner(runner):
    """Block pressed into an L-shaped corner of two segments: the corner node is active on both."""
    q, W, H = 2.0, 2.0, 1.0
    r = runner.run(["-options_file", "options/block_in_corner.yml"], "block_in_corner")
    nodes = r.nodes()
    on_floor, on_wall = nodes["y"] == 0.0, nodes["x"] == 0.0
    corner = on_floor & on_wall
    n = int((on_floor | on_wall).sum())
    runner.expect_equal("corner nodes", int(corner.sum()), 1)
    # Biaxial compression keeps every bottom node on the floor and every left node on the wall; the corner node
    # (0,0) is on both, so there is one active pair more than active nodes. All touch at the start: one solve.
    runner.expect_equal("active nodes", r.get("contact.active_nodes"), n)
    runner.expect_equal("active pairs (corner node on both segments)", r.get("contact.active_pairs"), n + 1)
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 1)
    runner.expect_equal("active flags", int(nodes["active"].sum()), n)
    # The exact uniform stress field sigma_xx = sigma_yy = -q is linear: forces are q w up to round-off. The x force
    # is carried by the wall alone (q H) and the y force by the floor alone (q W); without the corner node's pair on
    # either segment its share q h/2 would be missing.
    runner.expect_close("contact force (q H, q W)", r.get("contact.contact_force"), [q * H, q * W], 1e-10)
    floor = nodes[on_floor][np.argsort(nodes[on_floor]["x"])]
    wall = nodes[on_wall][np.argsort(nodes[on_wall]["y"])]
    w_floor, w_wall = tributary(floor["x"]), tributary(wall["y"])
    runner.expect_close("corner lambda = q (w_floor + w_wall)", nodes[corner]["lambda"][0],
                        q * (w_floor[0] + w_wall[0]), 1e-10)
    runner.expect_close("floor lambda_i = q w_i (corner excluded)", floor["lambda"][1:], q * w_floor[1:], 1e-10)
    runner.expect_close("wall lambda_i = q w_i (corner excluded)", wall["lambda"][1:], q * w_wall[1:], 1e-10)
    runner.expect_close("contact pressure = q", nodes[on_floor | on_wall]["pressure"], np.full(n, q), 1e-10)
    E, nu = r.get("material.E"), r.get("material.nu")
    eps = -(1 + nu) * (1 - 2 * nu) * q / E  # plane strain, equal biaxial compression
    exact = np.column_stack([eps * nodes["x"], eps * nodes["y"]])
    runner.expect_close("displacement = exact linear field", displacement(nodes), exact, 0,
                        1e-10 * np.abs(exact).max())


MSH_VARIANTS = ["meshes/block.msh", "meshes/block_bin.msh", "meshes/block_v22.msh"]


@test("msh_formats")
def msh_formats(runner):
    """The block mesh as gmsh 4.1 ASCII, 4.1 binary and 2.2 ASCII gives the same result."""
    # A body force makes the field non-linear (the uniform-pressure solution alone would hide a misread cell).
    results = [runner.run(["-options_file", "options/block_on_floor.yml", "-mesh_file", m, "-bc_body_force", "1,-1"],
                          "block_on_floor %s" % os.path.basename(m)) for m in MSH_VARIANTS]
    ref, ref_nodes = results[0], results[0].nodes()
    for m, r in zip(MSH_VARIANTS[1:], results[1:]):
        what = os.path.basename(m)
        for key in ("mesh.nodes", "mesh.cells", "contact.pairs", "contact.active_pairs", "iterations.active_set"):
            runner.expect_equal("%s: %s" % (what, key), r.get(key), ref.get(key))
        nodes = r.nodes()
        check_same_mesh(runner, what, ref_nodes, nodes)
        # The same mesh up to the last digit of the ASCII coordinates: round-off.
        u = displacement(ref_nodes)
        runner.expect_close("%s: displacement" % what, displacement(nodes), u, 0, 1e-12 * np.abs(u).max())
        runner.expect_close("%s: lambda" % what, nodes["lambda"], ref_nodes["lambda"], 0,
                            1e-12 * np.abs(ref_nodes["lambda"]).max())


@test("thickness")
def thickness(runner):
    """Plane stress: thickness 2 instead of 1 under the same pressure, the same displacement and twice the force."""
    base = ["-options_file", "options/beam_on_floor.yml", "-material_plane", "stress"]
    one = runner.run(base + ["-material_thickness", 1], "beam_on_floor plane stress t=1")
    two = runner.run(base + ["-material_thickness", 2], "beam_on_floor plane stress t=2")
    runner.expect_equal("plane", two.get("material.plane"), "stress")
    runner.expect_true("contact happens (%d active pairs)" % one.get("contact.active_pairs"),
                       one.get("contact.active_pairs") > 0)
    for key in ("contact.active_pairs", "contact.active_nodes", "iterations.active_set"):
        runner.expect_equal(key, two.get(key), one.get(key))
    # Stiffness, load, multipliers and the complementarity weight all scale with t: the same problem up to round-off.
    a, b = one.nodes(), two.nodes()
    u = displacement(a)
    runner.expect_close("displacement", displacement(b), u, 0, 1e-10 * np.abs(u).max())
    runner.expect_close("lambda doubles", b["lambda"], 2 * a["lambda"], 0, 2e-10 * np.abs(a["lambda"]).max())
    runner.expect_close("contact pressure unchanged", b["pressure"], a["pressure"], 0,
                        1e-10 * np.abs(a["pressure"]).max())
    f1 = np.array(one.get("contact.contact_force"))
    runner.expect_close("contact force doubles", two.get("contact.contact_force"), 2 * f1, 1e-10,
                        2e-10 * np.abs(f1).max())
    f1 = np.array(one.get("contact.applied_force"))
    runner.expect_close("applied force doubles", two.get("contact.applied_force"), 2 * f1, 1e-10,
                        2e-10 * np.abs(f1).max())


@test("plate_on_arc")
def plate_on_arc(runner):
    """Clamped plate over a convex 30-segment arc: a first step far through the arc still ends on the arc."""
    arc = runner.run(["-options_file", "options/plate_on_arc.yml"], "plate on arc")
    # The first solve (no active pair) sends the free end tens of units through the arc; the activation must find
    # the facets the nodes went through.
    first = arc.get("iterations.history.0.max_penetration")
    runner.expect_true("first solve penetrates deeply (%.3g > 10)" % first, first > 10)
    runner.expect_true("at least 5 active nodes (%d)" % arc.get("contact.active_nodes"),
                       arc.get("contact.active_nodes") >= 5)
    expect_balance(runner, arc, "arcs")
    segments = runner.run(options_args(runner, "options/plate_on_arc.yml", drop=("obstacle_arcs",)) +
                          ["-obstacle_segments", arc_segments(4.5, -4.1, 4, 150, 30, 30)], "plate on 30 segments")
    runs = [segments] + [runner.run(["-options_file", "options/plate_on_arc.yml", "-contact_activation_fraction", f,
                                     "-contact_activation_gap_factor", "0"],
                                    "plate on arc, activation fraction %s" % f) for f in ("0", "0.9")]
    for r in runs:
        expect_balance(runner, r, r.label)
        # Other activation fractions may take other paths (iteration counts) to the same state.
        expect_same_state(runner, arc, r, keys=("contact.active_pairs",))


@test("block_in_notch")
def block_in_notch(runner):
    """Block held by contact alone in a three-wall notch: converges, and equals the same block held at one node."""
    free = runner.run(["-options_file", "options/block_in_notch.yml"], "block in notch")
    runner.expect_true("stabilised solves while the active set did not hold the block (%d)" %
                       free.get("iterations.stabilised_solves"), free.get("iterations.stabilised_solves") >= 1)
    expect_balance(runner, free, "unsupported block")
    runner.expect_close("no reactions", free.get("contact.reaction_force"), [0, 0], 0, 0)
    nodes = free.nodes()
    # Contact on all three walls: the left side (x = 0), the floor (y = -0.05) and the inclined wall through (1, -0.05).
    x, y = nodes["x"] + nodes["u_x"], nodes["y"] + nodes["u_y"]
    active = nodes["active"] == 1
    runner.expect_true("active on the left wall", np.any(active & (np.abs(x) < 1e-9)))
    runner.expect_true("active on the floor", np.any(active & (np.abs(y + 0.05) < 1e-9) & (x < 1 - 1e-6)))
    runner.expect_true("active on the inclined wall", np.any(active & (np.abs(y - x + 1.05) < 1e-9) & (x > 1 - 1e-9)))
    # The same block with its top-left corner held where the contact solution puts it: the anchor carries no load,
    # so the state is the same (1e-10 of the largest value), whatever the stabilisation did on the way.
    corner = nodes[(nodes["x"] == 0) & (nodes["y"] == 1)]
    ux, uy = float(corner["u_x"][0]), float(corner["u_y"][0])
    held = runner.run(["-options_file", "options/block_in_notch.yml", "-bc_dirichlet",
                       "anchor:x=%.17g:y=%.17g" % (ux, uy)], "block in notch, anchored")
    ref = held.nodes()
    runner.expect_equal("anchored: no stabilised solve", held.get("iterations.stabilised_solves"), 0)
    runner.expect_equal("active flags", list(nodes["active"]), list(ref["active"]))
    u = displacement(ref)
    runner.expect_close("displacement = anchored", displacement(nodes), u, 0, 1e-10 * np.abs(u).max())
    runner.expect_close("lambda = anchored", nodes["lambda"], ref["lambda"], 0, 1e-10 * np.abs(ref["lambda"]).max())
    runner.expect_close("anchor reaction", held.get("contact.reaction_force"), [0, 0], 0,
                        1e-10 * np.linalg.norm(held.get("contact.applied_force")))
    # A load a million times smaller: the stabilised solve barely moves the block, which is then moved along that
    # free motion until the floor is reached, and the state is again certified (Runner.run) and balanced.
    small = runner.run(["-options_file", "options/block_in_notch.yml", "-bc_traction", "top:0:-1e-6"],
                       "block in notch, small load")
    # The forces are K u with u dominated by the rigid drop onto the floor (0.05), so their round-off is of order
    # 1e-16 E |u| per entry, not relative to the tiny load: 1e-12 E max|u| bounds it (5e-5 of the load here).
    expect_balance(runner, small, "small load", 1e-12 * small.get("material.E") * small.get("solution.max_displacement"))
    runner.expect_true("small load: the block rests on the floor",
                       np.any((small.nodes()["active"] == 1) & (small.nodes()["y"] == 0)))


@test("rigid_translation_steps")
def rigid_translation_steps(runner):
    """Prescribed displacements that only translate the body leave F_int of round-off size and no load: the equilibrium
    tolerance relative to the forces was about 1e-21 against a residual of 1e-15, and such a step ended
    DIVERGED_EQUILIBRIUM_STALLED (linear) or ran out of Newton iterations (svk), whatever -newton_rtol. The tolerance now
    includes the residual's round-off (ContactSolver::ROUNDOFF_FACTOR): a translated ring (2D, linear and svk) and a
    translated 3D body converge to the exact translation, and the punch approached in 5 displacement steps (its
    first step only closes the gap) reaches the state of one step (1e-8)."""
    for extra, what, dim in (([], "linear", 2), (["-material_model", "svk", "-load_steps", "3"], "svk", 2)):
        r = runner.run(["-mesh_file", "meshes/lame.msh", "-bc_dirichlet", "symmetry_x:x=0.01,symmetry_y:y=-0.02"] + extra,
                       "ring translated, " + what)
        nodes = r.nodes()
        runner.expect_close("%s: u_x" % what, nodes["u_x"], np.full(len(nodes), 0.01), 0, 1e-12)
        runner.expect_close("%s: u_y" % what, nodes["u_y"], np.full(len(nodes), -0.02), 0, 1e-12)
    r = runner.run(["-mesh_file", "meshes/hertz3d.msh", "-bc_dirichlet", "symmetry_x:x=1,symmetry_y:y=1,top:z=0.5",
                    "-load_steps", "2"], "3D body translated in 2 steps")
    nodes = r.nodes()
    for k, v in (("u_x", 1), ("u_y", 1), ("u_z", 0.5)):
        runner.expect_close("3D: " + k, nodes[k], np.full(len(nodes), float(v)), 0, 1e-12)
    one = runner.run(["-options_file", "options/punch_on_plate.yml"], "punch, one step")
    five = runner.run(["-options_file", "options/punch_on_plate.yml", "-load_steps", "5"], "punch, five steps")
    runner.expect_equal("punch: five load steps", five.get("iterations.load_steps"), 5)
    expect_same_state(runner, one, five, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("nearly_incompressible")
def nearly_incompressible(runner):
    """nu = 0.499999 in plane strain: the run used to end DIVERGED_EQUILIBRIUM_STALLED, its residual at round-off
    (about 0.2 eps ||u|| sum_j |K_ij|) above a tolerance relative to the forces alone; at 0.49999 it converged without
    a word to a contact 65 % too narrow. Now it converges, its residual within the round-off part of the tolerance, and
    says that the displacement elements lock; plane stress, which does not lock, says nothing."""
    r = runner.run(["-material_nu", "0.499999"], "Hertz, nu = 0.499999")
    runner.expect_true("the locking note", "Note: -material_nu 0.499999 is nearly incompressible" in r.output)
    # Independently of the certificate: the load P = |t_y| 2R of options/hertz.yml, applied exactly (a straight edge),
    # and balanced by the flat. The round-off of K u grows with the stiffness's largest entries, (lambda + 2 mu)
    # against mu = 2 (1 - nu) / (1 - 2 nu), 5e5 here: 1e-12 of the load per unit of that ratio (nu = 0.3: 3.5).
    options = dict(yaml_options(runner.path("options/hertz.yml")))
    P = -float(options["bc_traction"].split(":")[2]) * 2 * float(options["report_hertz"].split(",")[0])
    runner.expect_close("applied load", r.get("contact.applied_force"), [0, -P], 0, 1e-12 * P)
    nu = 0.499999
    expect_balance(runner, r, r.label, 1e-12 * P * 2 * (1 - nu) / (1 - 2 * nu))
    runner.expect_close("the flat carries the load", r.get("contact.contact_force"), [0, P], 0,
                        1e-12 * P * 2 * (1 - nu) / (1 - 2 * nu))
    for extra, what in ((["-material_nu", "0.49"], "nu = 0.49"),
                        (["-material_nu", "0.499999", "-material_plane", "stress"], "plane stress")):
        q = runner.run(extra, "Hertz, " + what)
        runner.expect_true("%s: no locking note" % what, "nearly incompressible" not in q.output)


def expect_outside_facets(runner, r, corners):
    """Independently of the pairs and the certificate: no node of the plate's top has gone into the convex punch, whose
    solid near its tip is where a point lies behind the plane of every triangle (corners: 3 per triangle, in the
    order that orients it); a node near an edge or a vertex of the triangles is held like one over a triangle."""
    nodes = r.nodes()
    top = nodes[nodes["z"] == 0.25]
    x = coordinates(top) + displacement(top)
    p0, p1, p2 = corners[0::3], corners[1::3], corners[2::3]
    n = np.cross(p1 - p0, p2 - p0)
    n /= np.linalg.norm(n, axis=1)[:, None]
    # Signed distance of each node to each triangle's plane (n into the plate); the largest is the distance outside.
    outside = np.max(x @ n.T - np.sum(n * p0, axis=1)[None, :], axis=1)
    penetration = max(0.0, -outside.min())
    runner.expect_true("%s: no top node inside the faceted punch (max penetration %.3g <= gap tolerance %.3g)" % (
        r.label, penetration, r.get("certificate.gap_tol")), penetration <= r.get("certificate.gap_tol"))


@test("punch_on_plate")
def punch_on_plate(runner):
    """The shipped case: a plate pushed against a rigid punch with a spherical end given as 878 triangles. Converges
    with a valid certificate (Runner.run), balanced, linear and svk; the punch is written as a triangle grid; under
    refinement of the punch's triangles the contact force converges to that of the exact sphere
    (-obstacle_spheres) at the rate of the facets' sagitta, h^2 / (8 R)."""
    r = runner.run(["-options_file", "options/punch_on_plate.yml"], "punch on plate")
    runner.expect_true("at least 10 active nodes (%d)" % r.get("contact.active_nodes"),
                       r.get("contact.active_nodes") >= 10)
    total = np.array(r.get("contact.contact_force")) + np.array(r.get("contact.reaction_force"))
    runner.expect_close("contact force + reactions = 0", total, [0, 0, 0], 0,
                        1e-10 * np.linalg.norm(r.get("contact.contact_force")))
    # The punch is written as a triangle grid next to the body (solution.h5 /obstacle, the XDMF grid "obstacle"):
    # the 878 triangles of meshes/punch.msh, their corners on the sphere (to the digits of the .msh file).
    import h5py

    with h5py.File(os.path.join(r.dir, "solution.h5"), "r") as f:
        xyz, topology = f["obstacle/coordinates"][()], f["obstacle/topology"][()]
    runner.expect_equal("obstacle grid: triangles", list(topology.shape), [878, 3])
    runner.expect_close("obstacle grid corners on the sphere", np.linalg.norm(xyz - [0, 0, 1.252], axis=1),
                        np.ones(len(xyz)), 0, 1e-12)
    expect_outside_facets(runner, r, xyz)
    case = options_args(runner, "options/punch_on_plate.yml", drop=("obstacle_mesh",))
    fz_sphere = runner.run(case + ["-obstacle_spheres", "0,0,1.252,1"], "punch as a sphere").get(
        "contact.contact_force.2")
    # The punch's .geo meshed with triangles of size h = 0.03, 0.015, 0.0075 (meshed by the run, -obstacle_mesh
    # FILE.geo).
    with open(runner.path("meshes/punch.geo")) as f:
        geo = f.read()
    runner.expect_true("meshes/punch.geo sets Mesh.MeshSizeMax = 0.03", "Mesh.MeshSizeMax = 0.03;" in geo)
    sizes, errors = [0.03, 0.015, 0.0075], []
    for h in sizes:
        path = os.path.join(runner.workdir, "punch_%g.geo" % h)
        with open(path, "w") as f:
            f.write(geo.replace("Mesh.MeshSizeMax = 0.03;", "Mesh.MeshSizeMax = %g;" % h))
        fz = runner.run(case + ["-obstacle_mesh", path + ":tip"], "punch of size %g" % h).get("contact.contact_force.2")
        errors.append(abs(fz - fz_sphere) / abs(fz_sphere))
    print("  h        force error vs sphere")
    for h, e in zip(sizes, errors):
        print("  %-8g %.3e" % (h, e))
    # The triangles lie inside the sphere by up to their sagitta h^2 / (8 R) (1.1e-4 at h = 0.03), which shortens
    # the indentation (about 0.008) by up to 1.4%; the force grows like the indentation to the power 3/2: about 2%
    # at h = 0.03, 5% leaves room for the facets' normals. Halving h divides the sagitta by 4: rates near 2.
    runner.expect_close("h = 0.03: contact force vs exact sphere", errors[0], 0, 0, 0.05)
    rates = rate(np.array(sizes), np.array(errors))
    runner.expect_true("force error rates %s >= 1.5 (sagitta: 2)" % np.round(rates, 2), np.all(rates >= 1.5))
    # St. Venant-Kirchhoff: contact in the current configuration, pairs activated by the path crossing a triangle.
    svk = runner.run(["-options_file", "options/punch_on_plate.yml", "-material_model", "svk"], "svk punch on plate")
    expect_outside_facets(runner, svk, xyz)
    runner.expect_true("svk: at least 10 active nodes (%d)" % svk.get("contact.active_nodes"),
                       svk.get("contact.active_nodes") >= 10)
