"""Bodies and contact between them: materials per physical group (a bar of two materials in series against its
exact end displacement, a mesh of two bodies with the body field), and -contact_pairs (mortar.hpp): the contact patch
test on non-matching meshes, Hertz between two bodies in 2D and 3D."""

import os

import numpy as np

from harness import displacement, expect_same_state, test, yaml_options

# The bars of meshes/bimaterial_bar.geo and bimaterial_bar3d.geo: soft on [0, L1], stiff on [L1, L1 + L2].
BAR_L1, BAR_L2, BAR_E, BAR_T = 1.2, 0.8, {"soft": 100.0, "stiff": 300.0}, 2.0


def uniaxial_strain(E, t, model):
    """The axial strain of a bar (nu = 0) under the dead traction t: t / E (linear); svk: the root of
    P = F S = (1 + e) E (e + e^2 / 2) = t (Green-Lagrange strain e + e^2 / 2, first Piola-Kirchhoff stress P)."""
    if model == "linear":
        return t / E
    roots = np.roots([0.5 * E, 1.5 * E, E, -t])
    return min(r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0)


@test("bimaterial_bar")
def bimaterial_bar(runner, dim):
    """A bar of two materials in series (nu = 0) pulled at one end: every node's axial displacement is the series
    springs' exact value, linear and svk (uniform strain in each material), to 1e-10 of the end displacement; also
    with the model per group (-material_model soft:svk,stiff:linear and the reverse: each part strains by its own
    law, Newton's method for the whole)."""
    geo, supports, traction = {"2d": ("meshes/bimaterial_bar.geo", "left:x,origin:y", "right:%g:0" % BAR_T),
                               "3d": ("meshes/bimaterial_bar3d.geo", "left:x,origin:yz,corner:z",
                                      "right:%g:0:0" % BAR_T)}[dim]
    E = ",".join("%s:%g" % kv for kv in BAR_E.items())
    # nu per group in 2D, one value in 3D: both forms of the option.
    nu = "soft:0,stiff:0" if dim == "2d" else "0"
    for model in ("linear", "svk", "soft:svk,stiff:linear", "soft:linear,stiff:svk"):
        r = runner.run(["-mesh_file", geo, "-material_model", model, "-material_E", E, "-material_nu", nu,
                        "-bc_dirichlet", supports, "-bc_traction", traction], "bimaterial bar %s %s" % (dim, model))
        runner.expect_equal("E per group in summary.json", r.get("material.E"), BAR_E)
        models = dict(item.split(":") for item in model.split(",")) if ":" in model else {"soft": model,
                                                                                          "stiff": model}
        if ":" in model:
            runner.expect_equal("the model per group in summary.json", r.get("material.model"), models)
            runner.expect_true("the header names each group's model",
                               "signorini: %s %s," % (dim.upper(), model.replace(",", ", ")) in r.output)
        e1, e2 = (uniaxial_strain(BAR_E[g], BAR_T, models[g]) for g in ("soft", "stiff"))
        nodes = r.nodes()
        x = nodes["x"]
        exact = np.where(x < BAR_L1, e1 * x, e1 * BAR_L1 + e2 * (x - BAR_L1))
        end = e1 * BAR_L1 + e2 * BAR_L2
        right = np.isclose(x, BAR_L1 + BAR_L2)
        runner.expect_close("%s: end displacement %.12g" % (model, end), nodes["u_x"][right],
                            np.full(right.sum(), end), 1e-10)
        runner.expect_close("%s: axial displacement" % model, nodes["u_x"], exact, 0, 1e-10 * end)
        for k in ("u_y", "u_z")[:2 if dim == "3d" else 1]:
            runner.expect_close("%s: %s" % (model, k), nodes[k], 0 * x, 0, 1e-10 * end)


@test("svk_between_bodies_newton")
def svk_between_bodies_newton(runner):
    """svk between bodies takes exact Newton steps by default (the lagged searches in the factored tangent's multiplier
    space cycled on the mortar rows, which move with the configuration: 59 iterations for the two cylinders of
    options/cylinders_2d.yml, 9 now), to the state of -newton_lagged_search false to 1e-10."""
    base = ["-options_file", "options/cylinders_2d.yml", "-material_model", "svk"]
    r = runner.run(base, "svk cylinders, default")
    ref = runner.run(base + ["-newton_lagged_search", "false"], "svk cylinders, exact Newton")
    runner.expect_true("Newton iterations %d <= 12" % r.get("iterations.active_set"),
                       r.get("iterations.active_set") <= 12)
    expect_same_state(runner, ref, r)


@test("two_bodies")
def two_bodies(runner):
    """Two blocks of one mesh that share no node: two bodies, numbered by their smallest file cell index (the lower
    block's cells come first), written as the cell field 'body'; each body's displacement scales with 1 / its E."""
    args = ["-mesh_file", "meshes/two_blocks.geo", "-bc_dirichlet", "lower_bottom:xy,upper_bottom:xy",
            "-bc_traction", "lower_top:0:-1,upper_top:0.5:0"]
    a = runner.run(args + ["-material_E", "lower:100,upper:50"], "two bodies, upper E 50")
    b = runner.run(args + ["-material_E", "lower:100,upper:100"], "two bodies, upper E 100")
    runner.expect_equal("bodies in summary.json", a.get("mesh.bodies"), 2)
    import h5py

    with h5py.File(os.path.join(a.dir, "solution.h5"), "r") as f:
        body = f["mesh/body"][()].ravel()
        xyz = f["mesh/coordinates"][()]
        topo = f["mesh/topology"][()]
    # Mixed topology (triangles and quadrilaterals): a type id before each cell's nodes.
    centroids_y, i = [], 0
    while i < len(topo):
        n = {4: 3, 5: 4}[int(topo[i])]
        centroids_y.append(xyz[topo[i + 1:i + 1 + n], 1].mean())
        i += n + 1
    expected = (np.array(centroids_y) > 1.25).astype(int)
    runner.expect_equal("body of each cell (%d and %d cells)" % tuple(np.bincount(expected)), body.tolist(),
                        expected.tolist())
    with open(os.path.join(a.dir, "solution.xdmf")) as f:
        runner.expect_true("the XDMF names the body attribute", 'Attribute Name="body"' in f.read())
    na, nb = a.nodes(), b.nodes()
    upper = na["y"] > 1.25
    for k in ("u_x", "u_y"):
        scale = np.abs(nb[k]).max()
        runner.expect_close("lower body unchanged (%s)" % k, na[k][~upper], nb[k][~upper], 0, 1e-12 * scale)
        runner.expect_close("upper body doubles (%s)" % k, na[k][upper], 2 * nb[k][upper], 0, 1e-12 * scale)


PATCH_MESHES = {"tri": "meshes/patch2d.msh", "quad": "meshes/patch2d_quad.msh", "hex": "meshes/patch3d_hex.msh",
                "tet": "meshes/patch3d_tet.msh", "tet_on_hex": "meshes/patch3d_tet_on_hex.msh"}


@test("patch")
def patch(runner, kind):
    """Two blocks stacked, non-matching meshes on their interface (meshes/patch2d.geo: tri, quad; meshes/patch3d.geo:
    hex, tet, tet_on_hex), a uniform pressure q on the top: every slave node active with the pressure q (to 1e-10),
    the exact linear field, the contact forces of the two sides equal and opposite. Run with the default solver and
    with the iterative path."""
    q = 2.0
    dim = 2 if kind in ("tri", "quad") else 3
    base = ["-options_file", "options/patch%dd.yml" % dim, "-mesh_file", PATCH_MESHES[kind]]
    up = "y" if dim == 2 else "z"
    area = 2.0 if dim == 2 else 1.0  # of the interface
    for solver, tol in (("auto", 1e-10), ("iterative", 1e-8)):
        r = runner.run(base + ["-contact_solver", solver], "patch %s %s" % (kind, solver))
        nodes = r.nodes()
        # The slave side: the upper block's bottom (pressure and gap reported); the master nodes carry none.
        on_interface = nodes[nodes[up] == 1.0]
        slave = on_interface[np.isfinite(on_interface["gap"])]
        n = len(slave)
        runner.expect_true("%s: slave nodes found (%d) beside the master's (%d)" % (solver, n, len(on_interface) - n),
                           n >= 5 and len(on_interface) - n >= 3)
        runner.expect_equal("%s: active pairs" % solver, r.get("contact.active_pairs"), n)
        runner.expect_equal("%s: active slave nodes" % solver, int(slave["active"].sum()), n)
        runner.expect_close("%s: contact pressure = q at every slave node" % solver, slave["pressure"],
                            np.full(n, q), tol)
        force = [0] * (dim - 1) + [q * area]
        runner.expect_close("%s: slave side force" % solver, r.get("contact.contact_force"), force, tol, tol * q * area)
        runner.expect_close("%s: master side force" % solver, r.get("contact.master_contact_force"), -np.array(force),
                            tol, tol * q * area)
        runner.expect_close("%s: force balance" % solver, r.get("contact.force_balance"), 0, 0, tol)
        runner.expect_true("%s: certificate: the two sides' forces balance (%.3g <= %.3g)" % (
            solver, r.get("certificate.pair_force_balance"), r.get("certificate.pair_force_tol")),
            r.get("certificate.pair_force_balance") <= r.get("certificate.pair_force_tol"))
        # sigma = -q along the vertical, zero across (plane strain in 2D), rollers on the faces through the origin:
        # one linear field through both bodies, the interface closed.
        E, nu = r.get("material.E"), r.get("material.nu")
        if dim == 2:
            exact = np.column_stack([nu * (1 + nu) * q / E * nodes["x"], -(1 - nu * nu) * q / E * nodes["y"]])
        else:
            exact = np.column_stack([nu * q / E * nodes["x"], nu * q / E * nodes["y"], -q / E * nodes["z"]])
        runner.expect_close("%s: displacement = exact linear field" % solver, displacement(nodes), exact, 0,
                            tol * np.abs(exact).max())


@test("thickness_per_group")
def thickness_per_group(runner):
    """-material_thickness per physical group (2D). A bar of two thicknesses in series (meshes/bimaterial_bar.geo, plane
    stress, nu = 0, the traction T on the end of the part of thickness t2): the force T h t2 strains each part by
    T t2 / (t E), exactly, to 1e-10 of the end displacement. Two blocks of thicknesses 0.5 (upper, the slave side) and
    2 (lower) in the contact patch test under the pressure q on the top: every slave node active with the pressure q
    (lambda over the tributary length times the slave's thickness) to 1e-10, the two sides' forces q w t_upper, equal
    and opposite, and each block's exact linear field (the lower one's stress q t_upper / t_lower)."""
    t = {"soft": 0.5, "stiff": 2.0}
    r = runner.run(["-mesh_file", "meshes/bimaterial_bar.geo", "-material_plane", "stress", "-material_E",
                    ",".join("%s:%g" % kv for kv in BAR_E.items()), "-material_nu", "0", "-material_thickness",
                    ",".join("%s:%g" % kv for kv in t.items()), "-bc_dirichlet", "left:x,origin:y", "-bc_traction",
                    "right:%g:0" % BAR_T], "bar of two thicknesses")
    runner.expect_equal("thickness per group in summary.json", r.get("material.thickness"), t)
    runner.expect_true("the header names each group's thickness", "thickness = soft:0.5, stiff:2" in r.output)
    e1, e2 = (BAR_T * t["stiff"] / (t[g] * BAR_E[g]) for g in ("soft", "stiff"))
    nodes = r.nodes()
    x = nodes["x"]
    end = e1 * BAR_L1 + e2 * BAR_L2
    exact = np.where(x < BAR_L1, e1 * x, e1 * BAR_L1 + e2 * (x - BAR_L1))
    runner.expect_close("axial displacement of the stepped bar (end %.12g)" % end, nodes["u_x"], exact, 0, 1e-10 * end)
    runner.expect_close("u_y", nodes["u_y"], 0 * x, 0, 1e-10 * end)
    runner.expect_close("reaction = T h t2", r.get("contact.reaction_force.0"), -BAR_T * 0.4 * t["stiff"], 1e-10)

    q, tu, tl = 2.0, 0.5, 2.0
    r = runner.run(["-options_file", "options/patch2d.yml", "-mesh_file", PATCH_MESHES["tri"],
                    "-material_thickness", "upper:%g,lower:%g" % (tu, tl)], "patch test, thicknesses 0.5 and 2")
    nodes = r.nodes()
    slave = nodes[(nodes["y"] == 1.0) & np.isfinite(nodes["gap"])]
    n = len(slave)
    runner.expect_equal("active slave nodes", int(slave["active"].sum()), n)
    runner.expect_close("contact pressure = q at every slave node", slave["pressure"], np.full(n, q), 1e-10)
    force = [0, q * 2.0 * tu]
    runner.expect_close("slave side force q w t_upper", r.get("contact.contact_force"), force, 1e-10, 1e-10 * q)
    runner.expect_close("master side force", r.get("contact.master_contact_force"), -np.array(force), 1e-10, 1e-10 * q)
    E, nu = r.get("material.E"), r.get("material.nu")
    upper = nodes["body"] == nodes["body"][nodes["y"] > 1.5][0]
    s = np.where(upper, q, q * tu / tl)  # each block's vertical compression
    uy_top_of_lower = -(1 - nu * nu) * q * tu / tl / E
    exact = np.column_stack([nu * (1 + nu) * s / E * nodes["x"],
                             np.where(upper, uy_top_of_lower - (1 - nu * nu) * q / E * (nodes["y"] - 1),
                                      -(1 - nu * nu) * s / E * nodes["y"])])
    runner.expect_close("each block's exact linear field", displacement(nodes), exact, 0, 1e-10 * np.abs(exact).max())


def combined_modulus(runner, case, first, second):
    """Johnson's E* of two bodies (physical groups first and second) of the case's materials per group:
    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2."""
    options = dict(yaml_options(runner.path(case)))
    per_group = {k: dict((g, float(v)) for g, v in (item.split(":") for item in options[k].split(",")))
                 for k in ("material_E", "material_nu")}
    E, nu = per_group["material_E"], per_group["material_nu"]
    return 1 / sum((1 - nu[g] ** 2) / E[g] for g in (first, second))


def print_hertz_errors(f, h, a, p0):
    """The errors of a Hertz run's contact half-width or radius (of the active nodes, of the profile's fit) and peak
    pressure against Johnson's a and p0."""
    print("factor %g: a %+.3f %% (fit %+.3f %%), p0 %+.3f %%" % (f, 100 * (h["a_computed"] / a - 1),
                                                                100 * (h["a_fit"] / a - 1),
                                                                100 * (h["p0_computed"] / p0 - 1)))


@test("cylinders_2d")
def cylinders_2d(runner):
    """Hertz contact of two cylinders of different materials (options/cylinders_2d.yml, Johnson 4.2): over three meshes
    the contact half-width of the active nodes converges to Johnson's (within twice the slave element size, which
    falls), and on the finest the fitted half-width and the peak pressure are within 1 %; the two sides' forces
    balance to round-off."""
    R1, R2, P = 8.0, 12.0, 10.0
    R = 1 / (1 / R1 + 1 / R2)
    Estar = combined_modulus(runner, "options/cylinders_2d.yml", "upper", "lower")
    a = np.sqrt(4 * P * R / (np.pi * Estar))
    p0 = 2 * P / (np.pi * a)
    for f, h_slave in ((2, 0.04), (1.4, 0.028), (1, 0.02)):
        r = runner.run(["-options_file", "options/cylinders_2d.yml", "-mesh_file", "meshes/cylinders2d.geo",
                        "-mesh_size_factor", f], "cylinders factor %g" % f)
        h = r.summary["hertz"]
        runner.expect_close("factor %g: summary's Johnson a (effective radius, combined modulus)" % f, h["a"], a, 1e-9)
        runner.expect_close("factor %g: summary's Johnson p0" % f, h["p0"], p0, 1e-9)
        runner.expect_close("factor %g: a of the active nodes within the slave element size" % f, h["a_computed"], a, 0,
                            2 * h_slave)
        slave, master = np.array(r.get("contact.contact_force")), np.array(r.get("contact.master_contact_force"))
        runner.expect_close("factor %g: slave side force = load" % f, slave, [0, P], 0, 1e-4 * P)
        runner.expect_close("factor %g: master side force = - slave side force" % f, master, -slave, 0, 1e-10 * P)
        print_hertz_errors(f, h, a, p0)
    # The half-width of the active nodes moves by whole elements (-1.2, +2.0, +1.6 %), within a bound that falls with
    # the element size (checked above); the profile's fit and the peak pressure stay within 0.3 %.
    runner.expect_close("finest: fitted a within 1 %", h["a_fit"], a, 0.01)
    runner.expect_close("finest: peak pressure within 1 %", h["p0_computed"], p0, 0.01)


@test("sphere_on_block")
def sphere_on_block(runner):
    """3D Hertz contact of two bodies (options/sphere_on_block.yml: an octant of a ball on a quarter block of another
    material): over three meshes the peak pressure converges to Johnson's, the contact radius of the active nodes
    stays within the contact element size of it, and on the finest the
    contact radius and the peak pressure are within 3 %; the two sides' forces balance to round-off."""
    R = 10.0
    Estar = combined_modulus(runner, "options/sphere_on_block.yml", "ball", "block")
    errors = []
    for f in (1.4, 1, 0.7):
        r = runner.run(["-options_file", "options/sphere_on_block.yml", "-mesh_file", "meshes/sphere_on_block.geo",
                        "-mesh_size_factor", f], "sphere on block factor %g" % f)
        h = r.summary["hertz"]
        # Johnson's values for the load the quarter model carries (its slave side's force, times 4).
        slave, master = np.array(r.get("contact.contact_force")), np.array(r.get("contact.master_contact_force"))
        P = 4 * np.linalg.norm(slave)
        a = np.cbrt(3 * P * R / (4 * Estar))
        p0 = 3 * P / (2 * np.pi * a * a)
        runner.expect_close("factor %g: summary's Johnson a (combined modulus)" % f, h["a"], a, 1e-8)
        runner.expect_close("factor %g: summary's Johnson p0" % f, h["p0"], p0, 1e-8)
        runner.expect_close("factor %g: master side force = - slave side force" % f, master, -slave, 0,
                            1e-10 * np.linalg.norm(slave))
        errors.append(abs(h["p0_computed"] / p0 - 1))
        runner.expect_close("factor %g: contact radius within the ball's contact element size" % f, h["a_computed"],
                            a, 0, 0.08 * f)
        print_hertz_errors(f, h, a, p0)
    # The contact radius of the active nodes moves by whole elements (-3.0, -2.1, -1.4 %); the peak pressure of the
    # profile's fit converges (+1.31, +0.90, +0.28 %).
    runner.expect_true("the error of p0 falls with the mesh size (%s)" % ", ".join("%.3g" % e for e in errors),
                       errors[0] > errors[1] > errors[2])
    runner.expect_close("finest: contact radius within 3 %", h["a_computed"], a, 0.03)
    runner.expect_close("finest: peak pressure within 3 %", h["p0_computed"], p0, 0.03)


@test("stiff_block_equals_rigid_plane")
def stiff_block_equals_rigid_plane(runner):
    """The ball of options/sphere_on_block.yml on a block 1e6 times stiffer than it gives the state of the same ball
    on a rigid plane at the block's top (options/hertz3d.yml's obstacle and candidates on the same mesh): the same
    active nodes, displacements and multipliers to 1e-4. The rows take the master's normal, so on a flat master they
    are the rigid plane's rows."""
    stiff = ["-mesh_file", "meshes/sphere_on_block.msh", "-material_E", "ball:200,block:2e8"]
    r = runner.run(["-options_file", "options/sphere_on_block.yml"] + stiff, "ball on a stiff block")
    ref = runner.run(["-options_file", "options/hertz3d.yml", "-bc_dirichlet",
                      "symmetry_x:x,symmetry_y:y,block_bottom:z", "-contact_groups", "contact"] + stiff,
                     "ball on a rigid plane")
    expect_same_state(runner, ref, r, tol=1e-4)


@test("body_held_by_contact")
def body_held_by_contact(runner):
    """Each body's rigid modes are checked on their own: the upper block of the patch test lifted 0.01 off the lower
    one (meshes/patch2d_gap.msh) is free until the interface closes, so the first solve is stabilised and the block
    comes down onto the lower one (the patch test's state shifted down by the gap); pulled up instead of pressed, no
    contact force can hold it: DIVERGED_NOT_HELD."""
    q, gap = 2.0, 0.01
    r = runner.run(["-options_file", "options/patch2d.yml", "-mesh_file", "meshes/patch2d_gap.msh"], "lifted block")
    nodes = r.nodes()
    slave = nodes[np.isfinite(nodes["gap"])]
    runner.expect_equal("every slave node active", int(slave["active"].sum()), len(slave))
    runner.expect_close("contact pressure = q", slave["pressure"], np.full(len(slave), q), 1e-9)
    E, nu = r.get("material.E"), r.get("material.nu")
    upper = nodes["y"] > 1 + gap / 2
    exact_y = -(1 - nu * nu) * q / E * (nodes["y"] - np.where(upper, gap, 0)) - np.where(upper, gap, 0)
    runner.expect_close("u_y = the patch test's field, the upper block lowered by the gap", nodes["u_y"], exact_y, 0,
                        1e-9 * gap)
    status, out, _ = runner.run_any(["-options_file", "options/patch2d.yml", "-bc_pressure", "upper_top:-2"],
                                    "block pulled off")
    runner.expect_true("the block pulled off ends as DIVERGED_NOT_HELD (exit %d)" % status,
                       status != 0 and "DIVERGED_NOT_HELD" in out)


@test("slide_svk")
def slide_svk(runner):
    """St. Venant-Kirchhoff between bodies (options/slide2d.yml): a block pushed 1.5 along a deformable floor, more
    than its length, over 10 load steps, the mortar rows computed again at every iterate. It converges with the
    block's whole bottom in contact carrying the pressure's load; on a floor 1e6 times stiffer it has the state of the
    same block on a rigid floor (a segment obstacle at the floor's top) to 1e-4."""
    r = runner.run(["-options_file", "options/slide2d.yml"], "block sliding on a floor")
    nodes = r.nodes()
    bottom = nodes[np.isfinite(nodes["gap"])]
    runner.expect_equal("the block's 11 bottom nodes active", int(bottom["active"].sum()), 11)
    runner.expect_close("the block's bottom moved 1.5 along the floor", bottom["u_x"], np.full(len(bottom), 1.5), 0,
                        0.05)
    runner.expect_close("the slave side carries the load 5 x 1", r.get("contact.contact_force")[1], 5.0, 1e-8)
    stiff = ["-material_E", "block:1000,floor:1e9"]
    r = runner.run(["-options_file", "options/slide2d.yml"] + stiff, "on a stiff floor")
    ref = runner.run(["-mesh_file", "meshes/slide2d.msh", "-material_model", "svk", "-material_nu", "0.3",
                      "-bc_dirichlet", "floor_bottom:x:y,block_left:x=1.5", "-bc_pressure", "block_top:5",
                      "-load_steps", "10", "-obstacle_segments", "-1,0,5,0", "-contact_groups", "block_bottom"] + stiff,
                     "on a rigid floor")
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-4)


def settled_residuals(result):
    """Per accepted load step, the Newton residuals from the first iteration whose active set stayed (changed 0) on,
    relative to the applied force."""
    scale = np.linalg.norm(result.get("contact.applied_force"))
    steps = {}
    for r in result.get("iterations.history"):
        if r["iteration"] == 1:
            steps[r["step"]] = []
        steps[r["step"]].append(r)
    out = []
    for records in steps.values():
        first = next((i for i, r in enumerate(records) if r["changed"] == 0), len(records))
        out.append([r["residual"] / scale for r in records[first:]])
    return out


def quadratic(residuals, constant=10.0, floor=1e-12):
    """(whether, checked): whether each Newton step, once the set stays, ends at most constant r_k^2 (residuals relative
    to the load), where that bound is above round-off (floor): a step from r_k = 4e-7 to 2e-13 is compared (bound
    1.6e-12), one from 1e-7 to 1e-12.5 is not; checked: how many steps were compared. The consistent tangent measures
    constants of 0.02-0.035 on the sliding block and 1.7 on the cylinders; the frozen rows, whose rate is linear, 3 to
    1e7 (the cylinders: 7.2, then 2.2e3 to 4.9e7)."""
    ok, checked = True, 0
    for r in residuals:
        for a, b in zip(r, r[1:]):
            if constant * a * a > floor:
                checked += 1
                ok = ok and b <= constant * a * a
    return ok, checked


@test("svk_mortar_tangent")
def svk_mortar_tangent(runner):
    """svk between bodies: the Newton tangent holds the mortar rows' variation (-newton_mortar_tangent consistent, the
    default): once the active set stays, each Newton step ends within 10 r^2 of its start r (quadratic; residuals
    relative to the load) on the two cylinders of options/cylinders_2d.yml (a curved interface) and on every step of
    the block sliding along a floor (options/slide2d.yml, 10 load steps), where the frozen rows' steps on the cylinders
    do not (linear); every slide step reaches the certificate's residual within 2 Newton steps of the set staying
    (the frozen rows take 4 to 5); both tangents end in the same state (1e-8). On one rank also in 3D (the ball on a
    block of options/sphere_on_block.yml), where the automatic choice takes the iterative path."""
    for args, what in ((["-options_file", "options/cylinders_2d.yml", "-material_model", "svk"], "cylinders"),
                       (["-options_file", "options/slide2d.yml"], "sliding block")):
        r = runner.run(args, "svk %s, consistent tangent" % what)
        f = runner.run(args + ["-newton_mortar_tangent", "frozen"], "svk %s, frozen tangent" % what)
        expect_same_state(runner, f, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
        runner.expect_true("%s: fewer Newton iterations with the consistent tangent (%d against %d)" % (
            what, r.get("iterations.active_set"), f.get("iterations.active_set")),
            r.get("iterations.active_set") < f.get("iterations.active_set"))
        settled = settled_residuals(r)
        ok, checked = quadratic(settled)
        runner.expect_true("%s: quadratic once the set stays (%d Newton steps compared): %s" % (what, checked, settled),
                           ok and checked >= 1)
        if what == "cylinders":
            frozen_ok, frozen_checked = quadratic(settled_residuals(f))
            runner.expect_true("%s: the frozen tangent's steps are not (%d compared): %s" % (
                what, frozen_checked, settled_residuals(f)), frozen_checked >= 1 and not frozen_ok)
        else:
            runner.expect_true("%s: every step within 2 Newton steps of the set staying: %s" % (what, settled),
                               all(len(s) <= 3 for s in settled))
    if runner.np != 1:
        return
    # 3D (one rank: the suite's time): the octant of a ball on a block, whose rows are clipped polygons. The automatic
    # choice counts the consistent tangent as an LU refactored at every solve and compares per solve: the iterative
    # path (BiCGStab) at this size.
    args = ["-options_file", "options/sphere_on_block.yml", "-material_model", "svk"]
    r = runner.run(args, "svk ball on a block, consistent tangent", heap_check=False)
    f = runner.run(args + ["-newton_mortar_tangent", "frozen", "-contact_solver", "direct"],
                   "svk ball on a block, frozen tangent", heap_check=False)
    expect_same_state(runner, f, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    ok, checked = quadratic(settled_residuals(r))
    runner.expect_true("3D: quadratic once the set stays (%d Newton steps compared): %s" % (
        checked, settled_residuals(r)), ok and checked >= 1)
    runner.expect_true("3D: the iterative path, compared per solve: %s" % r.get("solver.why"),
                       r.get("solver.path") == "iterative" and "refactored at every solve" in r.get("solver.why"))


@test("stack3")
def stack3(runner):
    """Three blocks stacked (options/stack3.yml): the middle one is held only through both interfaces, each body's
    rigid modes checked on their own. Touching at the start: every slave node of both interfaces active with the
    pressure q to 1e-10 and the exact linear field; with both interfaces open by 0.01 (meshes/stack3_gap.msh) the free
    blocks are stabilised until they close, and come to the same pressures."""
    q = 2.0
    for mesh, gap in (("meshes/stack3.msh", 0.0), ("meshes/stack3_gap.msh", 0.01)):
        r = runner.run(["-options_file", "options/stack3.yml", "-mesh_file", mesh], "stack, gap %g" % gap)
        nodes = r.nodes()
        slave = nodes[np.isfinite(nodes["gap"])]
        runner.expect_true("gap %g: slave nodes on both interfaces" % gap,
                           np.any(slave["y"] < 1.5) and np.any(slave["y"] > 1.5))
        runner.expect_equal("gap %g: every slave node active" % gap, int(slave["active"].sum()), len(slave))
        runner.expect_close("gap %g: contact pressure = q" % gap, slave["pressure"], np.full(len(slave), q), 1e-9)
        runner.expect_close("gap %g: the slave sides carry 2 q W" % gap, r.get("contact.contact_force"), [0, 8.0], 0,
                            1e-9)
        # nodes.csv: each node's body (numbered by the bodies' first cells in the file): one per block, three.
        level = nodes["y"] / (1 + gap)
        inside = np.abs(level - np.round(level)) > 1e-6  # off the blocks' bottoms and tops, which two blocks share
        per_block = [sorted(set(nodes["body"][inside & (np.floor(level) == k)])) for k in range(3)]
        runner.expect_true("gap %g: nodes.csv body column: one body per block, three in all (%s)" % (gap, per_block),
                           all(len(b) == 1 for b in per_block) and sorted(b[0] for b in per_block) == [0, 1, 2])
        if gap == 0:
            E, nu = r.get("material.E"), r.get("material.nu")
            exact = np.column_stack([nu * (1 + nu) * q / E * nodes["x"], -(1 - nu * nu) * q / E * nodes["y"]])
            runner.expect_close("the exact linear field", displacement(nodes), exact, 0, 1e-10 * np.abs(exact).max())
