"""Coulomb friction against rigid obstacles (-contact_friction, friction.hpp): mu = 0 is frictionless to the last
byte, a small mu converges to it, a block dragged over a floor in full slip carries mu times its normal force (2D and
3D), and one that sticks everywhere is the bonded block (also after several load steps)."""

import filecmp
import os
import re

import numpy as np

from harness import displacement, expect_balance, expect_same_state, log_event_count, test

SLIDING = ["-options_file", "options/sliding_block.yml"]
# The cube of options/cube_on_plane.yml dragged by its top (nu = 0: every slice y = const is the same plane problem,
# so the slip is along x alone).
CUBE_DRAG = ["-options_file", "options/cube_on_plane.yml", "-material_nu", "0", "-bc_dirichlet", "top:x=0.05",
             "-contact_friction", "0.3"]


def expect_friction_certificate(runner, r):
    """The friction conditions of the certificate within their tolerances (docs/theory.md section 9)."""
    c = r.get("certificate")
    for key, tol in (("friction_cone", "friction_force_tol"), ("stick_slip", "slip_tol"),
                     ("slip_rule", "friction_force_tol"), ("open_tangential_force", "friction_force_tol")):
        runner.expect_true("%s: certificate %s %.3g <= %.3g" % (r.label, key, c[key], c[tol]), c[key] <= c[tol])


# The cube with nu = 0.3 and a small drag: a stick zone, and slip directions that turn in the plane (the Poisson
# expansion under the pressure).
PARTIAL_3D = ["-options_file", "options/cube_on_plane.yml", "-bc_dirichlet", "top:x=3e-3", "-contact_friction", "0.3"]


@test("friction_zero_is_frictionless")
def friction_zero_is_frictionless(runner):
    """-contact_friction 0 on existing cases (2D, 3D, a body held by contact alone) writes the same node table as
    without it, byte for byte, and the same iterations; no friction entry appears in the summary."""
    for args in (["-options_file", "options/block_on_floor.yml"], ["-options_file", "options/cube_on_plane.yml"],
                 ["-options_file", "options/block_on_cylinder.yml"]):
        a = runner.run(args, "%s frictionless" % args[1])
        b = runner.run(args + ["-contact_friction", "0"], "%s -contact_friction 0" % args[1])
        runner.expect_true("%s: nodes.csv identical" % args[1],
                           filecmp.cmp(os.path.join(a.dir, "nodes.csv"), os.path.join(b.dir, "nodes.csv"),
                                       shallow=False))
        runner.expect_equal("%s: solves" % args[1], b.get("iterations.solves"), a.get("iterations.solves"))
        runner.expect_true("%s: no friction in the summary" % args[1], "friction" not in b.summary)


@test("friction_small_mu")
def friction_small_mu(runner):
    """A small mu converges to the frictionless state: the difference shrinks in proportion to mu (the friction force
    mu N changes the state linearly while the sets stay)."""
    ref = runner.run(SLIDING + ["-contact_friction", "0"], "sliding block, mu = 0")
    u0 = displacement(ref.nodes())
    diffs = []
    for mu in (1e-3, 1e-4, 1e-5):
        r = runner.run(SLIDING + ["-contact_friction", "%g" % mu], "sliding block, mu = %g" % mu)
        expect_friction_certificate(runner, r)
        diffs.append(np.abs(displacement(r.nodes()) - u0).max())
    runner.expect_true("difference at mu = 1e-5: %.3g <= 1e-5 of |u| %.3g" % (diffs[2], np.abs(u0).max()),
                       diffs[2] <= 1e-5 * np.abs(u0).max())
    for a, b in zip(diffs, diffs[1:]):
        runner.expect_close("difference ratio over a factor 10 in mu (%.3g / %.3g)" % (a, b), a / b, 10, 0.01)


@test("sliding_block")
def sliding_block(runner, dim):
    """A block pressed on a rigid floor and dragged by its top beyond what friction holds: every node in contact
    slips, the friction force on the body is -mu times its normal force to 1e-10 (2D: options/sliding_block.yml; 3D:
    the cube of cube_on_plane.yml), and at each node the friction traction is mu times the pressure, against the
    node's slip."""
    args = SLIDING if dim == "2d" else CUBE_DRAG
    r = runner.run(args, "sliding block %s" % dim)
    expect_friction_certificate(runner, r)
    expect_balance(runner, r, "sliding block %s" % dim)
    mu = r.get("friction.mu")
    normal = np.array(r.get("contact.contact_force")) - np.array(r.get("contact.friction_force"))
    want = np.zeros(len(normal))
    want[0] = -mu * np.linalg.norm(normal)
    runner.expect_close("friction force = -mu N", r.get("contact.friction_force"), want, 0, 1e-10 * abs(want[0]))
    runner.expect_equal("every active node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    nodes = r.nodes()
    axes = "xy" if dim == "2d" else "xyz"
    active = nodes["active"] == 1
    traction = np.stack([nodes["friction_traction_" + a] for a in axes], axis=1)[active]
    slip = np.stack([nodes["slip_" + a] for a in axes], axis=1)[active]
    pressure = nodes["pressure"][active]
    runner.expect_close("|friction traction| = mu p at every slip node", np.linalg.norm(traction, axis=1),
                        mu * pressure, 0, 1e-10 * pressure.max())
    direction = slip / np.linalg.norm(slip, axis=1)[:, None]
    runner.expect_close("friction traction against the slip", traction, -mu * pressure[:, None] * direction, 0,
                        1e-8 * pressure.max())
    runner.expect_true("friction_state 1 (slip) on the active nodes", np.all(nodes["friction_state"][active] == 1))


@test("sticking_block_is_bonded")
def sticking_block_is_bonded(runner):
    """With friction that holds every node (mu = 10, a small drag), the block is the bonded one: the same
    displacement as with its bottom clamped (1e-10), in one load step and in four."""
    args = SLIDING + ["-contact_friction", "10", "-bc_dirichlet", "top:x=5e-4"]
    bonded = runner.run(["-mesh_file", "meshes/block.msh", "-material_E", "1000", "-material_nu", "0.3",
                         "-bc_dirichlet", "top:x=5e-4,bottom:x:y", "-bc_pressure", "top:2"], "bonded block")
    u = displacement(bonded.nodes())
    for steps in ("1", "4"):
        r = runner.run(args + ["-load_steps", steps], "sticking block, %s load step(s)" % steps)
        expect_friction_certificate(runner, r)
        runner.expect_equal("every active node sticks", r.get("friction.stick_nodes"), r.get("contact.active_nodes"))
        runner.expect_equal("every bottom node active", r.get("contact.active_nodes"), 20)
        runner.expect_close("%s step(s): displacement of the bonded block" % steps, displacement(r.nodes()), u, 0,
                            1e-10 * np.abs(u).max())


@test("partial_slip")
def partial_slip(runner, dim):
    """A small drag: a stick zone and a slip zone, certified; the friction force is below mu N and balances the
    reaction; on 2 ranks the same state (case_friction_rank_independence)."""
    args = (SLIDING + ["-bc_dirichlet", "top:x=5e-4"]) if dim == "2d" else PARTIAL_3D
    r = runner.run(args, "partial slip %s" % dim)
    expect_friction_certificate(runner, r)
    expect_balance(runner, r, "partial slip %s" % dim)
    runner.expect_true("stick and slip nodes (%d, %d)" % (r.get("friction.stick_nodes"), r.get("friction.slip_nodes")),
                       r.get("friction.stick_nodes") > 0 and r.get("friction.slip_nodes") > 0)
    normal = np.array(r.get("contact.contact_force")) - np.array(r.get("contact.friction_force"))
    runner.expect_true("|friction force| < mu N",
                       np.linalg.norm(r.get("contact.friction_force")) < r.get("friction.mu") * np.linalg.norm(normal))


@test("friction_rank_independence")
def friction_rank_independence(runner, dim):
    """The frictional states of 1 and 2 ranks agree to 1e-10 (partial slip: stick and slip zones)."""
    args = (SLIDING + ["-bc_dirichlet", "top:x=5e-4"]) if dim == "2d" else PARTIAL_3D
    one = runner.run(args, "partial slip %s, 1 rank" % dim, np_=1)
    two = runner.run(args, "partial slip %s, 2 ranks" % dim, np_=2)
    expect_same_state(runner, one, two)
    for key in ("friction.stick_nodes", "friction.slip_nodes"):
        runner.expect_equal(key, two.get(key), one.get(key))
    f1, f2 = one.nodes(), two.nodes()
    for a in ("xy" if dim == "2d" else "xyz"):
        runner.expect_close("friction_" + a, f2["friction_" + a], f1["friction_" + a], 0,
                            1e-10 * np.abs(f1["friction_x"]).max())


@test("sliding_between_bodies")
def sliding_between_bodies(runner):
    """Friction between two bodies (-contact_pairs SLAVE:MASTER:MU): the upper block of the 2D patch test dragged by
    its top over the lower block beyond what friction holds: every slave node slips, the friction force on the upper
    block is -mu times its normal force to 1e-10, the master side carries the opposite force (the two sides' forces
    balance to round-off), and a pair's own MU overrides -contact_friction."""
    args = ["-options_file", "options/patch2d.yml", "-bc_dirichlet", "bottom:y,lower_left:x,upper_top:x=0.01"]
    r = runner.run(args + ["-contact_pairs", "upper_bottom:lower_top:0.3"], "patch blocks sliding, MU = 0.3")
    expect_friction_certificate(runner, r)
    runner.expect_true("force balance of both sides, reactions and load %.3g <= 1e-10" % r.get("contact.force_balance"),
                       r.get("contact.force_balance") <= 1e-10)
    normal = np.array(r.get("contact.contact_force")) - np.array(r.get("contact.friction_force"))
    want = [-0.3 * np.linalg.norm(normal), 0]
    runner.expect_close("friction force = -mu N", r.get("contact.friction_force"), want, 0, 1e-10 * abs(want[0]))
    runner.expect_close("master side = - slave side", r.get("contact.master_contact_force"),
                        -np.array(r.get("contact.contact_force")), 0, 1e-10 * np.linalg.norm(normal))
    runner.expect_equal("every active slave node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    o = runner.run(args + ["-contact_friction", "0.1", "-contact_pairs", "upper_bottom:lower_top:0.3"],
                   "patch blocks sliding, -contact_friction 0.1, MU = 0.3")
    runner.expect_close("the pair's MU overrides -contact_friction", o.get("contact.friction_force"),
                        r.get("contact.friction_force"), 1e-12)


# Cattaneo-Mindlin (Johnson, Contact Mechanics, 7.1): meshes/cattaneo2d.geo, two equal half-cylinders R = 8 (effective
# radius 4) of one material, the upper one's flat top moved rigidly: down by 0.2 over the first half of the load steps,
# then sideways by 0.05 over the second half (P about 11, Q/(mu P) about 0.48).
CATTANEO = ["-mesh_file", "meshes/cattaneo2d.geo", "-material_E", "200", "-material_nu", "0.3", "-contact_pairs",
            "upper_contact:lower_contact", "-contact_friction", "0.3"]
CATTANEO_PATH = "lower_bottom:x:y,upper_top:y=-0.2@0:0.5,upper_top:x=0.05@0.5:1"


def cattaneo_profile(r, mu=0.3, E=200.0, nu=0.3, R=4.0):
    """Johnson's values for the run's P and Q against the computed ones, in the reference configuration (the
    coordinates of Hertz's and Cattaneo's small-strain theory: the current ones add the surfaces' inward displacement
    under the pressure, about 2 % of a here): the contact and stick half-widths from the active and stick slave nodes
    (midway between the outermost one and the next on each side), Hertz's profile p^2 = p0^2 (1 - (x - x0)^2 / a^2)
    fitted to the nodal pressures within 0.8 of the contact half-width (a_fit and the centre x0), and the nodal
    tangential traction against q(x) = mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)], x from x0."""
    P = r.get("contact.contact_force.1") - r.get("contact.friction_force.1")
    Q = abs(r.get("contact.friction_force.0"))
    a = np.sqrt(4 * P * R / (np.pi * E / (2 * (1 - nu * nu))))
    p0 = 2 * P / (np.pi * a)
    c = a * np.sqrt(1 - Q / (mu * P))
    n = r.nodes()
    s = n[~np.isnan(n["gap"])]
    s = s[np.argsort(s["x"])]
    x = s["x"]

    def half_width(flags):
        i = np.where(flags)[0]
        lo, hi = (x[i[0]] + x[i[0] - 1]) / 2, (x[i[-1]] + x[i[-1] + 1]) / 2
        return (hi - lo) / 2, (hi + lo) / 2

    active = s["active"] == 1
    a_fe, x_mid = half_width(active)
    c_fe, _ = half_width(active & (s["friction_state"] == 2))
    # p^2 = k0 + k1 x + k2 x^2 by least squares over the inner nodes (the outer ones average the pressure over the
    # contact's edge): x0 = -k1 / (2 k2), p0^2 = k0 - k1^2 / (4 k2), a^2 = -p0^2 / k2.
    inner = active & (np.abs(x - x_mid) <= 0.8 * a_fe)
    k0, k1, k2 = np.linalg.lstsq(np.vstack([np.ones(inner.sum()), x[inner], x[inner] ** 2]).T,
                                 s["pressure"][inner] ** 2, rcond=None)[0]
    x0 = -k1 / (2 * k2)
    a_fit = np.sqrt(-(k0 - k1 * k1 / (4 * k2)) / k2)
    xi = x[active] - x0
    q_th = mu * p0 * (np.sqrt(np.clip(1 - xi ** 2 / a ** 2, 0, None)) -
                      (c / a) * np.sqrt(np.clip(1 - xi ** 2 / c ** 2, 0, None)))
    err = (np.abs(s["friction_traction_x"][active]) - q_th) / (mu * p0)
    return {"P": P, "Q": Q, "a": a, "c": c, "a_fe": a_fe, "c_fe": c_fe, "a_fit": a_fit, "x0": x0,
            "rms": np.sqrt(np.mean(err ** 2)), "max": np.abs(err).max(), "slip": r.get("friction.slip_nodes")}


@test("cattaneo_mindlin_2d")
def cattaneo_mindlin_2d(runner):
    """Partial slip of two equal cylinders pressed, then sheared (Q < mu P), on three meshes (size factors 2, 1.4, 1;
    20 load steps: 10 pressing, 10 shearing), against Johnson's half-space values for the run's P and Q in the
    reference configuration (cattaneo_profile): Hertz's half-width fitted to the pressures within 0.5 % of Johnson's
    a on every mesh; the stick zone's half-width c = a sqrt(1 - Q/(mu P)) within 2 % of a on the finest mesh, and
    c/a against Cattaneo's (both from the nodes) falling with the mesh; the tangential traction's profile within 2 %
    of mu p0 in the root mean square over the active nodes on the finest mesh, falling with the mesh. Each half-width
    is measured by whole nodes (midway between the outermost node and the next), so its error against Johnson's c
    moves by the mesh's steps and is not asserted to fall."""
    errors, ratios, rms = [], [], []
    for factor in ("2", "1.4", "1"):
        r = runner.run(CATTANEO + ["-mesh_size_factor", factor, "-bc_dirichlet", CATTANEO_PATH, "-load_steps", "20"],
                       "Cattaneo-Mindlin, size factor %s" % factor, heap_check=False)
        expect_friction_certificate(runner, r)
        k = cattaneo_profile(r)
        runner.expect_true("factor %s: Q/(mu P) = %.3f in the partial-slip range [0.3, 0.7]" % (factor, k["Q"] / (0.3 * k["P"])),
                           0.3 <= k["Q"] / (0.3 * k["P"]) <= 0.7)
        runner.expect_true("factor %s: Hertz's half-width fitted to the pressures %.4f within 0.5 %% of Johnson's %.4f "
                           "(%+.2f %%)" % (factor, k["a_fit"], k["a"], 100 * (k["a_fit"] / k["a"] - 1)),
                           abs(k["a_fit"] / k["a"] - 1) <= 0.005)
        errors.append(abs(k["c_fe"] - k["c"]) / k["a"])
        # c / a = sqrt(1 - Q/(mu P)) from the nodes alone, the contact half-width measured as the stick zone's.
        ratio = k["c_fe"] / k["a_fe"] / np.sqrt(1 - k["Q"] / (0.3 * k["P"])) - 1
        ratios.append(abs(ratio))
        rms.append(k["rms"])
        print("  factor %s: P %.4f Q %.4f a %.4f (nodes %.4f, fitted %.4f, centre %+.1e) c %.4f (nodes %.4f, %.2f %% "
              "of a; c/a %+.2f %% of Cattaneo's); q: rms %.2f %%, max %.2f %% of mu p0" % (
                  factor, k["P"], k["Q"], k["a"], k["a_fe"], k["a_fit"], k["x0"], k["c"], k["c_fe"], 100 * errors[-1],
                  100 * ratio, 100 * k["rms"], 100 * k["max"]))
    listed = lambda v: ", ".join("%.2f %%" % (100 * e) for e in v)  # noqa: E731
    runner.expect_true("c/a within 2 %% of Cattaneo's on the finest mesh, falling (%s)" % listed(ratios),
                       ratios[-1] <= 0.02 and ratios[0] > ratios[1] > ratios[2])
    runner.expect_true("stick half-width within 2 %% of Johnson's a on the finest mesh (%.2f %%; %s)" % (
        100 * errors[-1], listed(errors)), errors[-1] <= 0.02)
    # The largest nodal errors (about 10 % of mu p0 on the finest mesh) are at the contact's edges, whose nodes'
    # tributary lengths are only partly in contact, and next to the stick zone's edges (the theory's cusp).
    runner.expect_true("traction profile against Johnson's: rms within 2 %% of mu p0 on the finest mesh, falling "
                       "(%s)" % listed(rms), rms[-1] <= 0.02 and rms[0] > rms[1] > rms[2])


@test("cattaneo_load_path")
def cattaneo_load_path(runner):
    """The final displacements of Cattaneo-Mindlin reached in one step (P and Q together, proportionally) and in ten
    (pressed, then sheared): as Mindlin and Deresiewicz's theory says, a load whose tangential part grows no faster
    than mu times the normal one slips nowhere (every node sticks but at most the contact's outermost pair), while
    shearing after pressing opens a slip zone; the friction forces differ."""
    one = runner.run(CATTANEO + ["-mesh_size_factor", "2", "-bc_dirichlet",
                                 "lower_bottom:x:y,upper_top:y=-0.2,upper_top:x=0.05", "-load_steps", "1"],
                     "Cattaneo-Mindlin in one proportional step")
    ten = runner.run(CATTANEO + ["-mesh_size_factor", "2", "-bc_dirichlet", CATTANEO_PATH, "-load_steps", "10"],
                     "Cattaneo-Mindlin pressed, then sheared")
    for r in (one, ten):
        expect_friction_certificate(runner, r)
    runner.expect_true("one step: at most the 2 outermost nodes slip (%d)" % one.get("friction.slip_nodes"),
                       one.get("friction.slip_nodes") <= 2)
    runner.expect_true("ten steps: a slip zone (%d nodes)" % ten.get("friction.slip_nodes"),
                       ten.get("friction.slip_nodes") >= 10)
    q1, q10 = abs(one.get("contact.friction_force.0")), abs(ten.get("contact.friction_force.0"))
    runner.expect_true("the tangential forces differ (%.4f, %.4f)" % (q1, q10), abs(q1 - q10) > 0.02 * q10)


@test("svk_sliding_block")
def svk_sliding_block(runner):
    """St. Venant-Kirchhoff with friction against a rigid floor: the block of options/sliding_block.yml pressed over
    the first load step, then dragged by its top over 2.5 (more than its length, 2) in nine more along a floor long
    enough (x from -1 to 6): every step converges
    in full slip, and the friction force is -mu times the normal force to round-off (the floor is flat: the slip law's
    direction is the floor's)."""
    r = runner.run(SLIDING + ["-material_model", "svk", "-load_steps", "10", "-obstacle_segments", "-1,0,6,0",
                              "-bc_pressure", "top:2@0:0.1",
                              "-bc_dirichlet", "top:x=2.5@0.1:1"], "svk block dragged 2.5 over the floor")
    expect_friction_certificate(runner, r)
    runner.expect_equal("load steps", r.get("iterations.load_steps"), 10)
    normal = np.array(r.get("contact.contact_force")) - np.array(r.get("contact.friction_force"))
    want = [-0.3 * np.linalg.norm(normal), 0]
    runner.expect_close("friction force = -mu N", r.get("contact.friction_force"), want, 0, 1e-10 * abs(want[0]))
    runner.expect_equal("every active node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    runner.expect_true("the block moved by more than its length (%.4g)" % r.nodes()["u_x"].min(),
                       r.nodes()["u_x"].min() > 2.0)


def expect_svk_is_linear(runner, args, what):
    """At a small load svk with friction is the linear material with friction: both certified, stick and slip zones,
    the same stick and slip nodes, displacements within 1e-3 of the largest (the strains are about 1e-3)."""
    lin = runner.run(args, "linear, " + what)
    svk = runner.run(args + ["-material_model", "svk"], "svk, " + what)
    for r in (lin, svk):
        expect_friction_certificate(runner, r)
    runner.expect_true("stick and slip zones (%d, %d)" % (lin.get("friction.stick_nodes"), lin.get("friction.slip_nodes")),
                       lin.get("friction.stick_nodes") > 0 and lin.get("friction.slip_nodes") > 0)
    for key in ("friction.stick_nodes", "friction.slip_nodes"):
        runner.expect_equal(key, svk.get(key), lin.get(key))
    u = displacement(lin.nodes())
    runner.expect_close("svk displacement = linear", displacement(svk.nodes()), u, 0, 1e-3 * np.abs(u).max())


@test("svk_friction_small_load")
def svk_friction_small_load(runner):
    """At a small load (a drag of 5e-5: stick and slip zones), svk with friction is the linear material with friction:
    the same stick and slip nodes, displacements within 1e-3 of the largest (the strains are about 1e-3)."""
    expect_svk_is_linear(runner, SLIDING + ["-bc_pressure", "top:0.2", "-bc_dirichlet", "top:x=5e-5"], "small load")


@test("svk_friction_between_bodies")
def svk_friction_between_bodies(runner):
    """St. Venant-Kirchhoff with friction between bodies (the patch blocks of options/patch2d.yml): at a small load (a
    drag of 2e-5 under a pressure of 0.01: stick and slip zones) the linear material's stick and slip nodes and
    displacements within 1e-3 of the largest; dragged by 0.3 (pressed over the first 2 of 10 load steps, so that the
    slave side slides over the master side's elements in the current configuration), every slave node slips, the
    friction force is mu times the normal force (1e-8) and normal to it, against the drag, and the two sides' forces
    balance."""
    base = ["-options_file", "options/patch2d.yml", "-contact_pairs", "upper_bottom:lower_top:0.3"]
    expect_svk_is_linear(runner, base + ["-bc_dirichlet", "bottom:y,lower_left:x,upper_top:x=2e-5", "-bc_pressure",
                                          "upper_top:0.01"], "small drag")
    r = runner.run(base + ["-material_model", "svk", "-load_steps", "10", "-bc_dirichlet",
                           "bottom:y,lower_left:x,upper_top:y=-0.001@0:0.2,upper_top:x=0.3@0.2:1"],
                   "svk, dragged by 0.3")
    expect_friction_certificate(runner, r)
    runner.expect_equal("every active slave node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    t = np.array(r.get("contact.friction_force"))
    n = np.array(r.get("contact.contact_force")) - t
    runner.expect_close("|friction force| = mu |normal force|", np.linalg.norm(t), 0.3 * np.linalg.norm(n), 1e-8)
    runner.expect_true("friction force normal to the normal force (cosine %.2g)" % (t @ n / np.linalg.norm(t) /
                                                                                  np.linalg.norm(n)),
                       abs(t @ n) <= 1e-8 * np.linalg.norm(t) * np.linalg.norm(n))
    runner.expect_true("friction force against the drag (%.4g)" % t[0], t[0] < 0)
    runner.expect_true("force balance of both sides %.3g <= 1e-10" % r.get("contact.force_balance"),
                       r.get("contact.force_balance") <= 1e-10)
    runner.expect_close("master side = - slave side", r.get("contact.master_contact_force"),
                        -np.array(r.get("contact.contact_force")), 0, 1e-10 * np.linalg.norm(n))


@test("sliding_between_bodies_3d")
def sliding_between_bodies_3d(runner, mesh):
    """3D friction between bodies: the upper block of options/patch3d.yml (hexahedra, or tetrahedra on hexahedra)
    dragged by its top along (2, 1, 0) over the clamped lower one beyond what friction holds: every slave node in
    contact slips (the slip directions turn in the tangent plane), the friction force on the upper block is mu times
    its normal force in size (0.1 %) and against the drag (0.5 degrees), and the two sides' forces balance."""
    r = runner.run(["-options_file", "options/patch3d.yml", "-mesh_file", "meshes/patch3d_%s.msh" % mesh,
                    "-material_nu", "0", "-bc_dirichlet", "bottom:x:y:z,top:x=0.2:y=0.1",
                    "-contact_pairs", "upper_bottom:lower_top:0.3"], "3D blocks sliding (%s)" % mesh)
    expect_friction_certificate(runner, r)
    runner.expect_true("force balance %.3g <= 1e-10" % r.get("contact.force_balance"),
                       r.get("contact.force_balance") <= 1e-10)
    runner.expect_equal("every active slave node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    f = np.array(r.get("contact.friction_force"))
    normal = np.linalg.norm(np.array(r.get("contact.contact_force")) - f)
    runner.expect_close("|friction force| = mu N", np.linalg.norm(f), 0.3 * normal, 1e-3)
    drag = np.array([2.0, 1.0, 0.0]) / np.sqrt(5.0)
    angle = np.degrees(np.arccos(np.clip(-f.dot(drag) / np.linalg.norm(f), -1, 1)))
    runner.expect_true("friction force against the drag (%.3f degrees off)" % angle, angle <= 0.5)


@test("cattaneo_mindlin_3d")
def cattaneo_mindlin_3d(runner):
    """Partial slip of two equal balls (meshes/cattaneo3d.geo, R = 10, half model on the symmetry plane y = 0,
    tetrahedra, size factors 1.5 and 1: 13k and 38k dofs) pressed, then sheared with Q/(mu P) about 0.5: the stick
    zone's radius against Cattaneo's c = a (1 - Q/(mu P))^(1/3) within 5 % on both meshes and closer on the finer (the
    radii from the areas of the active and the stick slave nodes' tributary areas; a the computed contact radius,
    within 3.1 % of Johnson's for the run's P)."""
    errors = []
    for factor in ("1.5", "1"):
        r = runner.run(["-mesh_file", "meshes/cattaneo3d.geo", "-mesh_size_factor", factor, "-material_E", "200",
                        "-material_nu", "0.3", "-bc_dirichlet",
                        "symmetry_y:y,lower_bottom:x:y:z,upper_top:z=-0.5@0:0.5,upper_top:x=0.1@0.5:1",
                        "-contact_pairs", "upper_contact:lower_contact", "-contact_friction", "0.3", "-load_steps", "6"],
                       "Cattaneo-Mindlin 3D, size factor %s" % factor, heap_check=False)
        expect_friction_certificate(runner, r)
        n = r.nodes()
        s = n[~np.isnan(n["gap"])]
        active, stick = s["active"] == 1, s["friction_state"] == 2
        area = np.where(s["pressure"] > 0, s["lambda"] / np.where(s["pressure"] > 0, s["pressure"], 1), 0)
        a_fe = np.sqrt(2 * area[active].sum() / np.pi)  # half discs
        c_fe = np.sqrt(2 * area[active & stick].sum() / np.pi)
        P = 2 * (r.get("contact.contact_force.2") - r.get("contact.friction_force.2"))
        Q = 2 * abs(r.get("contact.friction_force.0"))
        a = (3 * P * 5.0 / (4 * 200.0 / (2 * (1 - 0.09)))) ** (1.0 / 3)
        ratio = (1 - Q / (0.3 * P)) ** (1.0 / 3)
        print("  factor %s: P %.4f Q %.4f (Q/(mu P) %.3f): a %.4f (Johnson %.4f, %+.2f %%), c %.4f (Cattaneo %.4f with "
              "the computed a, %+.2f %%; %+.2f %% of Johnson's a with his)" % (
                  factor, P, Q, Q / (0.3 * P), a_fe, a, 100 * (a_fe / a - 1), c_fe, ratio * a_fe,
                  100 * (c_fe / (ratio * a_fe) - 1), 100 * (c_fe - ratio * a) / a))
        runner.expect_true("factor %s: partial slip: Q/(mu P) = %.3f in [0.3, 0.7]" % (factor, Q / (0.3 * P)),
                           0.3 <= Q / (0.3 * P) <= 0.7)
        runner.expect_true("factor %s: contact radius within 5 %% of Johnson's (%.2f %%)" % (
            factor, 100 * (a_fe / a - 1)), abs(a_fe / a - 1) <= 0.05)
        errors.append(abs(c_fe / (ratio * a_fe) - 1))
        runner.expect_true("factor %s: stick radius within 5 %% of Cattaneo's (%.2f %%)" % (factor, 100 * errors[-1]),
                           errors[-1] <= 0.05)
    runner.expect_true("the stick radius closer to Cattaneo's on the finer mesh (%.2f %%, %.2f %%)" % (
        100 * errors[0], 100 * errors[1]), errors[1] < errors[0])


@test("friction_iterative")
def friction_iterative(runner):
    """The iterative path (Schur fieldsplit with GAMG, BiCGStab: -contact_solver iterative) solves friction's
    nonsymmetric system: against a rigid plane in 3D (stick and slip zones whose directions turn), between bodies in
    3D (tetrahedra on hexahedra, full slip) and in 2D (the sliding block), and svk dragged in 3D, the same sets, and
    displacements, multipliers and friction forces within 1e-8 of the direct path's (the run's ranks)."""
    cases = (("partial slip 3D", PARTIAL_3D),
             ("3D blocks sliding (tet_on_hex)",
              ["-options_file", "options/patch3d.yml", "-mesh_file", "meshes/patch3d_tet_on_hex.msh", "-material_nu",
               "0", "-bc_dirichlet", "bottom:x:y:z,top:x=0.2:y=0.1", "-contact_pairs", "upper_bottom:lower_top:0.3"]),
             ("sliding block 2D", SLIDING),
             ("svk cube dragged", ["-options_file", "options/cube_on_plane.yml", "-bc_dirichlet", "top:x=0.05",
                                   "-contact_friction", "0.3", "-material_model", "svk", "-load_steps", "2"]))
    for what, args in cases:
        direct = runner.run(args + ["-contact_solver", "direct"], what + ", direct")
        # Without the heap's validation at every allocation (-malloc_debug; the leak check stays): under it, the GAMG
        # set-ups took 10 s instead of 0.8 s on 2 ranks.
        it = runner.run(args + ["-contact_solver", "iterative"], what + ", iterative", heap_check=False)
        runner.expect_equal("%s: the iterative path ran" % what, it.get("solver.path"), "iterative")
        expect_friction_certificate(runner, it)
        expect_same_state(runner, direct, it, keys=("contact.active_nodes", "friction.stick_nodes",
                                                    "friction.slip_nodes"), tol=1e-8)
        f, g = direct.nodes(), it.nodes()
        axes = [a for a in "xyz" if "friction_" + a in f.dtype.names]
        scale = max(np.abs(f["friction_" + a]).max() for a in axes)
        runner.expect_true("%s: the same friction states" % what,
                           np.array_equal(np.nan_to_num(f["friction_state"]), np.nan_to_num(g["friction_state"])))
        for a in axes:
            runner.expect_close("%s: friction_%s" % (what, a), g["friction_" + a], f["friction_" + a], 0, 1e-8 * scale)
    # The multiplier block split into its normal and tangential rows (index sets lambda_n, lambda_t), each addressed by
    # its own options: the same state.
    split = runner.run(PARTIAL_3D + ["-contact_solver", "iterative", "-contact_fieldsplit_lambda_pc_type", "fieldsplit",
                                     "-contact_fieldsplit_lambda_fieldsplit_lambda_t_pc_type", "jacobi",
                                     "-contact_ksp_view"], "partial slip 3D, multiplier block split",
                       heap_check=False)
    runner.expect_true("-contact_ksp_view shows the split lambda_t",
                       "(contact_fieldsplit_lambda_fieldsplit_lambda_t_)" in split.output)
    direct = runner.run(PARTIAL_3D, "partial slip 3D, direct")
    expect_same_state(runner, direct, split, keys=("contact.active_nodes", "friction.stick_nodes"), tol=1e-8)


@test("friction_kept")
def friction_kept(runner):
    """With the linear material friction keeps its factorisation across the sets, as frictionless contact does: the
    turned rows and slip columns are mapped per pair onto fixed rows (KeptRows, docs/solver.md), and one factorisation
    serves the whole run (-info: one numerical factorisation), giving the same sets and states, within 1e-10, as MUMPS
    LU of the plain form refactored at every solve (-contact_reuse_factorization 0), for partial slip on a plane in 3D
    (slip directions that turn, the springs across them), full slip between bodies in 3D (tetrahedra on hexahedra),
    the sliding block in 2D and Cattaneo-Mindlin's partial slip between two cylinders pressed, then sheared (the run's
    ranks). -contact_ksp_view names the mapping. The 3D blocks are compared to 1e-8: there MUMPS LU of the plain form
    leaves an equilibrium residual of 3.4e-10 (the kept path 4.8e-13; the certificate's tolerance 1.5e-9)."""
    cases = (("partial slip 3D", PARTIAL_3D, 1e-10),
             ("3D blocks sliding (tet_on_hex)",
              ["-options_file", "options/patch3d.yml", "-mesh_file", "meshes/patch3d_tet_on_hex.msh", "-material_nu",
               "0", "-bc_dirichlet", "bottom:x:y:z,top:x=0.2:y=0.1", "-contact_pairs", "upper_bottom:lower_top:0.3"],
              1e-8),
             ("sliding block 2D", SLIDING + ["-bc_dirichlet", "top:x=5e-4"], 1e-10),
             ("Cattaneo-Mindlin 2D", CATTANEO + ["-mesh_size_factor", "2", "-bc_dirichlet", CATTANEO_PATH,
                                                 "-load_steps", "6"], 1e-10))
    for what, args, tol in cases:
        kept = runner.run(args + ["-log_view", "-contact_ksp_view"], what + ", kept factorisation")
        lu = runner.run(args + ["-contact_reuse_factorization", "0"], what + ", LU refactored")
        expect_friction_certificate(runner, kept)
        factored = log_event_count(kept.output, "SigMumpsFactor") + log_event_count(kept.output, "SigCholFactor")
        runner.expect_equal("%s: numerical factorisations of the kept path" % what, factored, 1)
        runner.expect_true("%s: -contact_ksp_view names the mapping of friction's rows" % what,
                           "friction's rows mapped per pair onto fixed rows" in kept.output)
        # Set changes after the first are low-rank updates of the dense Schur complement's factors (Woodbury).
        counts = re.findall(r"Schur complement: (\d+) dense LU\(s\), (\d+) low-rank update\(s\)", kept.output)
        lus, updates = (int(v) for v in counts[-1]) if counts else (0, 0)
        solves = kept.get("iterations.solves")
        runner.expect_true("%s: %d dense LU(s) and %d low-rank update(s) of the Schur complement for %d solves" % (
            what, lus, updates, solves), lus >= 1 and lus + updates <= solves)
        if what.startswith("Cattaneo"):  # 562 multipliers: the updates cost less than LUs
            runner.expect_true("%s: low-rank updates (%d)" % (what, updates), updates > 0)
        runner.expect_true("%s: more solves than factorisations (%d)" % (what, kept.get("iterations.solves")),
                           kept.get("iterations.solves") > 1)
        expect_same_state(runner, lu, kept, keys=("iterations.active_set", "contact.active_nodes",
                                                  "friction.stick_nodes", "friction.slip_nodes"), tol=tol)
        f, g = lu.nodes(), kept.nodes()
        runner.expect_true("%s: the same friction states" % what,
                           np.array_equal(np.nan_to_num(f["friction_state"]), np.nan_to_num(g["friction_state"])))
        axes = [a for a in "xyz" if "friction_" + a in f.dtype.names]
        scale = max(np.abs(f["friction_" + a]).max() for a in axes)
        for a in axes:
            runner.expect_close("%s: friction_%s" % (what, a), g["friction_" + a], f["friction_" + a], 0, tol * scale)


@test("obstacle_kind_friction")
def obstacle_kind_friction(runner):
    """A friction coefficient per kind of obstacle (-obstacle_friction KIND:MU): the block of sliding_block.yml dragged
    in full slip over a floor made of a segment (x < 1, -contact_friction 0.1) and a meshed line (x > 1,
    -obstacle_friction mesh:0.4): at every slip node the friction traction is its obstacle's mu times the pressure
    (1e-10), and the kind given alone is -contact_friction on that kind (the same state)."""
    floor = os.path.join(runner.workdir, "floor_right.geo")
    with open(floor, "w") as f:
        f.write('Point(1) = {1, 0, 0, 1}; Point(2) = {3, 0, 0, 1};\nLine(1) = {1, 2};\n'
                'Physical Curve("floor") = {1};\n')
    r = runner.run(SLIDING + ["-obstacle_segments", "-1,0,1,0", "-obstacle_mesh", floor, "-contact_friction", "0.1",
                              "-obstacle_friction", "mesh:0.4"], "block on a segment (mu 0.1) and a mesh (mu 0.4)")
    expect_friction_certificate(runner, r)
    runner.expect_equal("every active node slips", r.get("friction.slip_nodes"), r.get("contact.active_nodes"))
    n = r.nodes()
    s = n[(n["active"] == 1) & (np.abs(n["x"] - 1) > 1e-9)]  # the node at x = 1 may pair with either
    mu = np.where(s["x"] < 1, 0.1, 0.4)
    runner.expect_true("slip nodes on both kinds (%d, %d)" % ((s["x"] < 1).sum(), (s["x"] > 1).sum()),
                       (s["x"] < 1).sum() > 3 and (s["x"] > 1).sum() > 3)
    runner.expect_close("|friction traction| = mu of the node's obstacle x pressure",
                        np.abs(s["friction_traction_x"]), mu * s["pressure"], 0, 1e-10 * s["pressure"].max())
    a = runner.run(SLIDING + ["-contact_friction", "0", "-obstacle_friction", "segments:0.3"],
                   "sliding block, -obstacle_friction segments:0.3")
    b = runner.run(SLIDING, "sliding block, -contact_friction 0.3")
    expect_same_state(runner, b, a, keys=("contact.active_nodes", "friction.slip_nodes"))
