"""Robustness of the active-set loop: bodies that nothing holds, cycling sets, units, the first update's damping, and
the property test over random small cases (whose generators scripts/random_outcomes.py also runs)."""

import re

import numpy as np

from harness import displacement, expect_balance, expect_same_state, test


def expect_svk_balance(runner, r):
    """Contact force + reactions + load of an svk state: each component is its equilibrium residual summed over the
    nodes, at most sqrt(number of nodes) times the residual's norm that the certificate reports (Cauchy-Schwarz)."""
    bound = np.sqrt(len(r.nodes())) * r.get("certificate")["equilibrium"]
    expect_balance(runner, r, r.label, max(bound, 1e-10 * np.linalg.norm(r.get("contact.applied_force"))))


@test("free_along_floor")
def free_along_floor(runner):
    """A body whose active set leaves a rigid motion free is moved along the free rigid part of its stabilised solve
    (RigidModes::FreeMotion), not along the whole displacement. Before, a pair that the elastic deformation of that
    solve brought a little nearer stretched the step by a huge factor, and the 2 x 1 block pushed right along a
    frictionless floor, away from its only wall, ended with DIVERGED_CYCLING (random case 23 of seed 777; 14 of the 15
    cycling cases of that survey are blocks pushed away from their only wall); no rigid motion holds it, and it now
    ends with DIVERGED_NOT_HELD. An svk block 0.01 into the floor, pushed right towards the foot of an inclined wall 0.145 away
    (random case 196), has no pair in its zone on that wall yet: its nodes' paths along the free motion enter the
    wall's zone, so the step moves it there. It converged only after two load-step cuts (noninvertible deformation
    after the stretched step); it now converges in one load step to the state of eight load steps."""
    pushed = ["-mesh_file", "meshes/block.msh", "-material_E", "130.924", "-material_nu", "0.093", "-contact_groups",
              "bottom,left,right", "-bc_traction", "top:0.167226:-0.89568", "-obstacle_segments",
              "-0.5,-0.026905,2.5,-0.026905,0,2,0,-0.5"]
    status, out, _ = runner.run_any(pushed, "block pushed away from its wall")
    errors = [line for line in out.splitlines() if line.startswith("signorini: error:")]
    runner.expect_true("one error line, DIVERGED_NOT_HELD (exit %d): %s" % (status, errors),
                       status != 0 and len(errors) == 1 and "DIVERGED_NOT_HELD" in errors[0] and
                       "DIVERGED_CYCLING" not in out)
    svk = ["-mesh_file", "meshes/block.msh", "-material_E", "3068.73", "-material_nu", "0.362", "-contact_groups",
           "bottom,left,right", "-material_model", "svk", "-bc_traction", "top:0.0360193:-0.391838",
           "-obstacle_segments", "-0.5,0.00985974,2.5,0.00985974,0,2,0,-0.5,2.14528,0.00985974,3.14528,0.47922"]
    r = runner.run(svk, "svk block towards an inclined wall")
    runner.expect_equal("one load step, no cut", r.get("iterations.load_steps"), 1)
    runner.expect_true("stabilised solves (%d)" % r.get("iterations.stabilised_solves"),
                       r.get("iterations.stabilised_solves") >= 1)
    depth = geometric_penetration(r.nodes(), svk)
    runner.expect_true("no candidate inside an obstacle (deepest %.3g)" % depth,
                       depth <= r.get("certificate")["gap_tol"])
    x = r.nodes()["x"] + r.nodes()["u_x"]
    runner.expect_true("active on the inclined wall", np.any((r.nodes()["active"] == 1) & (x > 2.1)))
    expect_svk_balance(runner, r)
    expect_same_state(runner, r, runner.run(svk + ["-load_steps", "8"], "svk, eight load steps"),
                      keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("unbalanced_iterative")
def unbalanced_iterative(runner):
    """The iterative path has no complementarity problem for a body that seems free (PivotedActiveSet needs the direct
    path's Schur complement); at the start of each load step it checks that some non-negative forces on the candidate
    pairs balance the load along the rigid motions that the supports leave free (RigidModes::Unbalanced). Three cases
    of the 3D survey (scripts/random_outcomes.py --dim 3 --seed 777, docs/survey.md) that the direct path ends
    DIVERGED_NOT_HELD ended on the iterative path out of iterations (case 12: a cube on a sphere pulled away from its
    wall, linear) or with a non-invertible deformation after five cuts (cases 35 and 111, svk): now DIVERGED_NOT_HELD
    on both paths, the iterative one saying which part of the load nothing balances (0.095, 0.19, 0.18; the direct
    path's complementarity problem leaves 0.096 of case 12's). Held bodies pass the check at every load step of the
    suite's iterative runs (the verdict is a necessary condition of equilibrium: a body that some state holds has a
    balance)."""
    cube = ["-mesh_file", "meshes/cube.msh", "-contact_groups", "bottom,front,left"]
    cases = {
        12: ["-material_E", "132.455", "-material_nu", "0.336", "-bc_traction", "top:-0.00607614:0.00404879:-0.0295612",
             "-obstacle_planes", "0,0,0,1,0,0,0,0,0,0,1,0", "-obstacle_spheres", "0.631854,0.597755,-1.03464,1"],
        35: ["-material_E", "360.487", "-material_nu", "0.166", "-material_model", "svk", "-bc_traction",
             "top:0.0176601:0.553755:-2.51641", "-obstacle_planes",
             "0,0,0,0,1,0,0.981005,0,-0.0469906,-0.780322,0,1", "-obstacle_spheres", "0.323881,0.518852,-1.04699,1"],
        111: ["-material_E", "458.356", "-material_nu", "0.236", "-material_model", "svk", "-bc_traction",
              "top:0.24869:-0.0376946:-1.01561", "-obstacle_planes", "0,0,0,1,0,0,0,0,0,0,1,0",
              "-obstacle_spheres", "0.646932,0.544932,-1.03581,1"],
    }
    for case, args in cases.items():
        for solver in ("direct", "iterative"):
            status, out, _ = runner.run_any(cube + args + ["-contact_solver", solver], "case %d, %s" % (case, solver))
            errors = [line for line in out.splitlines() if line.startswith("signorini: error:")]
            runner.expect_true("case %d, %s: one error line, DIVERGED_NOT_HELD (exit %d): %s" % (
                case, solver, status, errors), status != 0 and len(errors) == 1 and "DIVERGED_NOT_HELD" in errors[0])
            if solver == "iterative":
                runner.expect_true("case %d: the unbalanced part named: %s" % (case, errors),
                                   len(errors) == 1 and "no non-negative contact forces" in errors[0])


@test("cycling_set_pivoted")
def cycling_set_pivoted(runner):
    """The linear material's last resort when its active sets cycle or it finds the body free: the contact problem
    from the current iterate as a linear complementarity problem in the multipliers, solved by Lemke's method
    (ContactSolver::PivotedActiveSet), which is finite. A block on a floor between a vertical wall and an inclined one,
    held by contact alone and pushed down and towards the inclined wall (random case 151 of seed 777): with the radius
    1.19, its sets cycled in every repeated step and it ended with DIVERGED_CYCLING (so did the default radius, after
    repeats). With 1.19 the complementarity problem's solution puts a corner inside the inclined wall, whose zone did
    not hold it in the reference configuration: the certificate refuses it and the step is repeated with that pair.
    With the default radius the pairs lack that wall, the problem finds the body not held by them, and the step is
    repeated with wider pairs. Both reach the state of the radius 0.3, which needs no pivoting (1e-10), with no
    candidate inside an obstacle by the obstacles' geometry. Then 3D cases (below)."""
    block = ["-mesh_file", "meshes/notch_block.msh", "-material_E", "6239.61", "-material_nu", "0.260",
             "-contact_groups", "bottom,left,right", "-bc_traction", "top:0.598869:-19.9327", "-obstacle_segments",
             "-0.5,-0.0390607,1.5,-0.0390607,0,2,0,-0.5,1.1408,-0.0390607,2.1408,0.724722"]
    ref = runner.run(block + ["-contact_search_radius", "0.3"], "radius 0.3")
    runner.expect_equal("radius 0.3: no pivoting", ref.get("iterations.pivoted_sets"), 0)
    for radius in (None, "1.19033"):
        what = "radius " + (radius or "default")
        r = runner.run(block + (["-contact_search_radius", radius] if radius else []), what)
        runner.expect_true("%s: pivoted (%d)" % (what, r.get("iterations.pivoted_sets")),
                           r.get("iterations.pivoted_sets") >= 1)
        depth = geometric_penetration(r.nodes(), block)
        runner.expect_true("%s: no candidate inside an obstacle (deepest %.3g)" % (what, depth),
                           depth <= r.get("certificate")["gap_tol"])
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"))
    # 3D, the same code path: the unit cube held by contact alone on a sphere, against a vertical wall on each of two
    # sides and an inclined plane on the third, pushed down and against the front wall. It ran out of active-set
    # iterations (DIVERGED_MAX_IT: 50 per load step) with one load step or two, and converged in 48 iterations over four
    # load steps.
    cube = ["-mesh_file", "meshes/cube.msh", "-material_E", "5225.03", "-material_nu", "0.231", "-contact_groups",
            "bottom,front,left", "-bc_traction", "top:0.00995024:-0.1381:-0.501535", "-obstacle_planes",
            "-0.00749805,0,0,1,0,0,0,-0.0277454,0,0,1,0,1.09108,0,0,-0.797339,0,0.603531",
            "-obstacle_spheres", "0.5,0.5,-1.02047,1"]
    r = runner.run(cube, "3D cube on a sphere")
    runner.expect_true("3D: pivoted (%d)" % r.get("iterations.pivoted_sets"), r.get("iterations.pivoted_sets") >= 1)
    runner.expect_true("3D: at most 20 active-set iterations (%d)" % r.get("iterations.active_set"),
                       r.get("iterations.active_set") <= 20)
    expect_same_state(runner, runner.run(cube + ["-load_steps", "4"], "3D, four load steps"), r,
                      keys=("contact.active_pairs", "contact.active_nodes"))
    # A verdict: the cube on a sphere pushed away from its wall at y = 0, which it can slide or roll along (random
    # case 290 of random_outcomes.py --dim 3, seed 777). It ran out of active-set iterations; the complementarity
    # problem's solution leaves 8 % of the load along rigid motions to the regularisation's spring, so no contact
    # forces on the pairs hold it, also after the repeat with the pairs within the cube's diagonal.
    free = ["-mesh_file", "meshes/cube.msh", "-material_E", "1228.63", "-material_nu", "0.163", "-contact_groups",
            "bottom,front,left", "-bc_traction", "top:0.0197162:0.0408767:-0.149286", "-obstacle_planes",
            "0,0,0,1,0,0,0,0,0,0,1,0,1.05037,0,-0.0342131,-1.46851,0,1", "-obstacle_spheres",
            "0.666416,0.593367,-1.03421,1"]
    status, out, _ = runner.run_any(free, "3D cube sliding off its sphere")
    errors = [line for line in out.splitlines() if line.startswith("signorini: error:")]
    runner.expect_true("one error line, DIVERGED_NOT_HELD by the complementarity problem (exit %d): %s" %
                       (status, errors), status != 0 and len(errors) == 1 and "DIVERGED_NOT_HELD" in errors[0] and
                       "no contact forces on its" in errors[0])


def rigid_and_deformation(nodes):
    """A 2D displacement field split into its least-squares rigid motion (u_x, u_y of the origin and the small rotation
    w: u = c + w (-y, x)) and the rest, the deformation (one row per node)."""
    x, y = nodes["x"], nodes["y"]
    A = np.zeros((2 * len(x), 3))
    A[0::2, 0], A[1::2, 1], A[0::2, 2], A[1::2, 2] = 1, 1, -y, x
    u = displacement(nodes).ravel()
    move = np.linalg.lstsq(A, u, rcond=None)[0]
    return move, (u - A @ move).reshape(-1, 2)


@test("not_held_in_any_units")
def not_held_in_any_units(runner):
    """The complementarity problem's answers do not depend on the units. Random case 8 of seed 777 (the 2 x 1 block on a
    disc beside a wall, held by contact alone) with E and the load times 1e-6: Lemke's method, whose row scale and
    tolerances were absolute, found one or two active pairs where the problem has three, which left 0.42 and 0.32 of the
    load along rigid motions, and the run ended with DIVERGED_NOT_HELD. A block held between a floor and an inclined
    wall under a load 1e-4 of the survey's: the regularisation's spring carries eps r times the rigid travel, 0.0039 of
    that load (a fraction proportional to E / load), above the verdict's 1e-3, and it ended with DIVERGED_NOT_HELD. Both
    now converge to the state of -contact_reuse_factorization false (which has no complementarity problem). A free body
    in small units (free_along_floor's block pushed away from its wall, load times 1e-4) is still found not held, with
    the fraction of the load that nothing balances, its tangential part |t_x| / |t|."""
    disc = ["-mesh_file", "meshes/block.msh", "-material_E", "0.000941803", "-material_nu", "0.167", "-contact_groups",
            "bottom,left,right", "-bc_traction", "top:-9.99894e-08:-5.09574e-07", "-obstacle_segments", "0,2,0,-0.5",
            "-obstacle_discs", "1.36854,-0.995587,1"]
    wall = ["-mesh_file", "meshes/block.msh", "-material_E", "159.398", "-material_nu", "0.099", "-contact_groups",
            "bottom,left,right", "-bc_traction", "top:2.20444e-06:-1.10633e-05", "-obstacle_segments",
            "-0.5,-0.00417123,2.5,-0.00417123,0,2,0,-0.5,1.74823,-0.00417123,2.74823,1.09528"]
    # The same active set gives the same linear system, solved by two factorisations. The wedged block slides 0.27
    # rigidly into its wedge while its elastic deformation, which alone sets the multipliers, is of order load / E
    # = 7e-8: the displacement is compared as its rigid part (round-off of the travel) and its deformation, each
    # against its own size, so that the tolerance is not larger than the deformation it checks. The round-off of the
    # travel (1e-16 of 0.27) is about 1e-9 of the deformation, amplified by the condition of the stiffness: 1e-6 of
    # the deformation and of the multipliers for the wedged block (they differ by 2e-8 of the largest), 1e-8 on the
    # disc.
    for args, what, tol in ((disc, "block on a disc, E x 1e-6", 1e-8),
                            (wall, "block between floor and wall, load x 1e-4", 1e-6)):
        r = runner.run(args, what)
        runner.expect_true("%s: pivoted (%d)" % (what, r.get("iterations.pivoted_sets")),
                           r.get("iterations.pivoted_sets") >= 1)
        ref = runner.run(args + ["-contact_reuse_factorization", "false"], what + ", no kept factorisation")
        for key in ("contact.active_pairs", "contact.active_nodes"):
            runner.expect_equal("%s: %s" % (what, key), r.get(key), ref.get(key))
        a, b = ref.nodes(), r.nodes()
        runner.expect_true("%s: the same active nodes" % what, np.array_equal(a["active"], b["active"]))
        (move_a, strain_a), (move_b, strain_b) = rigid_and_deformation(a), rigid_and_deformation(b)
        runner.expect_close("%s: rigid motion (translation, rotation)" % what, move_b, move_a, 0,
                            1e-10 * np.abs(move_a).max())
        runner.expect_close("%s: deformation (displacement less its rigid part)" % what, strain_b, strain_a, 0,
                            tol * np.abs(strain_a).max())
        runner.expect_close("%s: lambda" % what, b["lambda"], a["lambda"], 0, tol * np.abs(a["lambda"]).max())
    free = ["-mesh_file", "meshes/block.msh", "-material_E", "130.924", "-material_nu", "0.093", "-contact_groups",
            "bottom,left,right", "-bc_traction", "top:1.67226e-05:-8.9568e-05", "-obstacle_segments",
            "-0.5,-0.026905,2.5,-0.026905,0,2,0,-0.5"]
    status, out, _ = runner.run_any(free, "block pushed away from its wall, load x 1e-4")
    errors = [line for line in out.splitlines() if line.startswith("signorini: error:")]
    # The frictionless floor balances the load's normal part; the tangential part |t_x| / |t| is left along the free
    # rigid motion (the sliding), whatever the units.
    tx, ty = (float(v) for v in free[free.index("-bc_traction") + 1].split(":")[1:])
    left = "leaves %.2g of it" % (abs(tx) / np.hypot(tx, ty))
    runner.expect_true("one error line, DIVERGED_NOT_HELD by the complementarity problem, '%s' (exit %d): %s"
                       % (left, status, errors), status != 0 and len(errors) == 1 and "DIVERGED_NOT_HELD" in errors[0]
                       and left in errors[0])


@test("activation_rules")
def activation_rules(runner):
    """The first update's damping rules take other paths to the same state: the default (-contact_activation_gap_factor
    2 in 2D, 1.77 in 3D) against the seed's rule (no damping) and the fraction rule (-contact_activation_fraction 0.9,
    the earlier default), on smooth contacts that start at a touching point (2D and 3D Hertz, Hertz in 3 load steps),
    on the plate pushed through an arc and the beam pushed onto a floor (no touching pair: the first solve has no
    contact at all). The default must also take fewer iterations than both on the Hertz cases (the gap factor
    activates about the final set at once) and on the beam (every candidate starts at the same gap: the default
    fraction 0.2 damps); the default (the dimension's factor) also takes fewer iterations than the other dimension's
    on 2D and 3D Hertz."""
    seed = ["-contact_activation_fraction", "0", "-contact_activation_gap_factor", "0"]
    fraction = ["-contact_activation_fraction", "0.9", "-contact_activation_gap_factor", "0"]
    defaults = {}
    for args, what, fewer in ((["-options_file", "options/hertz.yml"], "hertz", True),
                              (["-options_file", "options/hertz3d.yml"], "hertz3d", True),
                              (["-options_file", "options/hertz.yml", "-load_steps", "3"], "hertz, 3 load steps", True),
                              (["-options_file", "options/plate_on_arc.yml"], "plate on arc", False),
                              (["-options_file", "options/beam_on_floor.yml"], "beam on floor", True)):
        default = runner.run(args, what)
        defaults[what] = default
        for extra, rule in ((seed, "seed's rule"), (fraction, "fraction 0.9")):
            r = runner.run(args + extra, "%s, %s" % (what, rule))
            expect_same_state(runner, default, r, keys=("contact.active_pairs", "contact.active_nodes",
                                                        "iterations.load_steps"))
            if fewer:
                runner.expect_true("%s: fewer active-set iterations with the defaults (%d) than with the %s (%d)" % (
                    what, default.get("iterations.active_set"), rule, r.get("iterations.active_set")),
                    default.get("iterations.active_set") < r.get("iterations.active_set"))
    # The gap factor's default follows the dimension (ActivationGapFactor): 2 in 2D, (3 pi / 4)^(2/3) in 3D, where 2
    # activates a ring too many on the octant (16k dofs: 225 pairs for the 201 of the answer, 4 active-set iterations
    # against 3); each dimension's default takes fewer iterations than the other's factor.
    for case, other in (("hertz", "1.7707"), ("hertz3d", "2")):
        args = ["-options_file", "options/%s.yml" % case]
        default = defaults[case]
        r = runner.run(args + ["-contact_activation_gap_factor", other], "%s, factor %s" % (case, other))
        expect_same_state(runner, default, r, keys=("contact.active_pairs", "contact.active_nodes"))
        runner.expect_true("%s: fewer active-set iterations with the default (%d) than with the factor %s (%d)" % (
            case, default.get("iterations.active_set"), other, r.get("iterations.active_set")),
            default.get("iterations.active_set") < r.get("iterations.active_set"))


def random_body(rng, mesh, groups):
    """The body of a random case (random_case, random_case_3d): the mesh, E and nu, the candidate groups, linear or
    svk, supported normally on its side x = 0 or held only by contact; and the traction scale q."""
    E = 10 ** rng.uniform(2, 4)
    args = ["-mesh_file", mesh, "-material_E", "%.6g" % E, "-material_nu", "%.3f" % rng.uniform(0, 0.45),
            "-contact_groups", groups]
    if rng.random() < 0.3:
        args += ["-material_model", "svk"]
    if rng.random() < 0.4:
        args += ["-bc_dirichlet", "left:x"]
    return args, E * 10 ** rng.uniform(-4, -2)


def random_case(rng):
    """Options of a random small contact problem: a unit block (notch_block.msh) or the 2 x 1 mixed block
    (block.msh), linear or svk, supported on its left side or held only by contact, a random top traction, and a
    floor or a disc (which may start penetrating the block) with an optional left wall and inclined wall."""
    mesh, W = [("meshes/notch_block.msh", 1.0), ("meshes/block.msh", 2.0)][rng.integers(2)]
    args, q = random_body(rng, mesh, "bottom,left,right")
    args += ["-bc_traction", "top:%.6g:%.6g" % (q * rng.uniform(-0.3, 0.3), -q)]
    floor = rng.uniform(-0.01, 0.05)  # negative: the block starts penetrating the floor
    disc = rng.random() < 0.3  # a disc under the block instead of the flat floor
    segments = [] if disc else [-0.5, -floor, W + 0.5, -floor]
    if rng.random() < 0.6:
        segments += [0, 2, 0, -0.5]  # a wall that the left side touches
    if rng.random() < 0.4:
        x0 = W * rng.uniform(0.6, 1.2)
        segments += [x0, -floor, x0 + 1, -floor + rng.uniform(0.3, 1.5)]  # an inclined wall rising to the right
    if segments:
        args += ["-obstacle_segments", ",".join("%.6g" % v for v in segments)]
    if disc:
        args += ["-obstacle_discs", "%.6g,%.6g,%.6g" % (W * rng.uniform(0.3, 0.7), -floor - 1.0, 1.0)]
    return args


def random_case_3d(rng):
    """Options of a random small 3D contact problem, like random_case: the unit cube (cube.msh, 180 nodes; candidates
    on its faces x = 0, y = 0 and z = 0), linear or svk, supported normally on its face x = 0 or held only by contact,
    a random top traction, and a floor plane or a unit sphere under it (which may start penetrating the cube), with
    optional walls touching its faces x = 0 and y = 0 and an inclined plane rising in x."""
    args, q = random_body(rng, "meshes/cube.msh", "bottom,front,left")
    args += ["-bc_traction", "top:%.6g:%.6g:%.6g" % (q * rng.uniform(-0.3, 0.3), q * rng.uniform(-0.3, 0.3), -q)]
    floor = rng.uniform(-0.01, 0.05)  # negative: the cube starts penetrating the floor
    sphere = rng.random() < 0.3
    planes = [] if sphere else [0, 0, -floor, 0, 0, 1]
    if rng.random() < 0.8:
        planes += [0, 0, 0, 1, 0, 0]  # a wall that the face x = 0 touches
    if rng.random() < 0.8:
        planes += [0, 0, 0, 0, 1, 0]  # a wall that the face y = 0 touches
    if rng.random() < 0.4:
        slope = rng.uniform(0.3, 1.5)
        planes += [rng.uniform(0.6, 1.2), 0, -floor, -slope, 0, 1]  # rising in x; the normal points into the body
    if planes:
        args += ["-obstacle_planes", ",".join("%.6g" % v for v in planes)]
    if sphere:
        args += ["-obstacle_spheres", "%.6g,%.6g,%.6g,1" % (rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), -floor - 1.0)]
    return args


def geometric_penetration(nodes, args):
    """The deepest penetration of the obstacles of args (-obstacle_segments: the side to the right of each segment's
    direction, where a node projects onto it; -obstacle_discs: the inside) by the final positions of the boundary
    nodes of a random_case block (the candidates: x = 0, x = W, y = 0), computed from the node table and the options
    alone, independently of the solver's pairs. 3D (random_case_3d): -obstacle_planes (the side against the normal)
    and -obstacle_spheres (the inside), for the candidates on the faces x = 0, y = 0 and z = 0."""
    values = lambda name: [float(v) for v in args[args.index(name) + 1].split(",")] if name in args else []
    if "u_z" in nodes.dtype.names:
        p = np.stack([nodes[c] + nodes["u_" + c] for c in "xyz"], axis=1)
        p = p[(np.abs(nodes["x"]) < 1e-9) | (np.abs(nodes["y"]) < 1e-9) | (np.abs(nodes["z"]) < 1e-9)]
        deepest = 0.0
        planes = values("-obstacle_planes")
        for plane in (planes[i:i + 6] for i in range(0, len(planes), 6)):
            n = np.array(plane[3:]) / np.linalg.norm(plane[3:])
            deepest = max(deepest, (-(p - np.array(plane[:3])) @ n).max())
        spheres = values("-obstacle_spheres")
        for sphere in (spheres[i:i + 4] for i in range(0, len(spheres), 4)):
            deepest = max(deepest, (sphere[3] - np.linalg.norm(p - np.array(sphere[:3]), axis=1)).max())
        return deepest
    px, py = nodes["x"] + nodes["u_x"], nodes["y"] + nodes["u_y"]
    width = nodes["x"].max()
    boundary = (np.abs(nodes["x"]) < 1e-9) | (np.abs(nodes["x"] - width) < 1e-9) | (np.abs(nodes["y"]) < 1e-9)
    px, py = px[boundary], py[boundary]
    deepest = 0.0
    seg = values("-obstacle_segments")
    for ax, ay, bx, by in (seg[i:i + 4] for i in range(0, len(seg), 4)):
        length = np.hypot(bx - ax, by - ay)
        t = ((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / length ** 2
        behind = ((px - ax) * (by - ay) - (py - ay) * (bx - ax)) / length
        over = (t >= 0) & (t <= 1)
        if over.any():
            deepest = max(deepest, behind[over].max())
    disc = values("-obstacle_discs")
    for cx, cy, radius in (disc[i:i + 3] for i in range(0, len(disc), 3)):
        deepest = max(deepest, (radius - np.hypot(px - cx, py - cy)).max())
    return deepest


def held_by_construction(args):
    """Whether a random_case's block is held whatever the load's size, so that it must converge: supported on its left
    side (u_x = 0, which also stops its rotation) over a floor or a disc, or on a floor against the left wall and pushed
    towards it; in both without the inclined wall (which may start deep inside the block's corner)."""
    values = lambda name: [float(v) for v in args[args.index(name) + 1].split(",")] if name in args else []
    segments = values("-obstacle_segments")
    pieces = [segments[k:k + 4] for k in range(0, len(segments), 4)]
    floor = any(p[1] == p[3] for p in pieces)
    wall = [0, 2, 0, -0.5] in pieces
    inclined = any(p[1] != p[3] and p[0] != p[2] for p in pieces)
    tx = float(args[args.index("-bc_traction") + 1].split(":")[1])
    if inclined:
        return False
    if "-bc_dirichlet" in args:
        return floor or "-obstacle_discs" in args
    return floor and wall and tx <= 0


def outcome(status, out, result):
    """A run's outcome as pinned: ("converged", active-set iterations), or (the final DIVERGED_ reason,)."""
    if result is not None:
        return ("converged", result.get("iterations.active_set"))
    m = re.search(r"signorini: error: .*?(DIVERGED_\w+)", out)
    return (m.group(1) if m else "no reason (exit %d)" % status,)


# The outcome of each random case of random_cases (seed 20261123), the same on 1 and 2 ranks: the fixed seed makes
# them deterministic, so a change of outcome or of iteration count is a change of the solver's path to be looked at
# (and pinned again, with the reason in the commit message). Read case by case, every refusal is a block that nothing
# holds against its load (pushed along a frictionless floor away from any wall, or rolling off a disc), but case 47:
# an svk block whose corner starts deep inside an inclined wall (DIVERGED_NONINVERTIBLE_DEFORMATION).
RANDOM_CASES_SEED = 20261123
RANDOM_CASES_OUTCOMES = {
    0: ('DIVERGED_NOT_HELD',), 1: ('converged', 3), 2: ('converged', 11), 3: ('DIVERGED_NOT_HELD',),
    4: ('converged', 3), 5: ('converged', 15), 6: ('converged', 2), 7: ('DIVERGED_NOT_HELD',), 8: ('converged', 7),
    9: ('DIVERGED_NOT_HELD',), 10: ('converged', 23), 11: ('converged', 3), 12: ('DIVERGED_SINGULAR',),
    13: ('converged', 17), 14: ('converged', 2), 15: ('converged', 4), 16: ('converged', 7),
    17: ('DIVERGED_SINGULAR',), 18: ('converged', 12), 19: ('converged', 3), 20: ('DIVERGED_SINGULAR',),
    21: ('DIVERGED_NOT_HELD',), 22: ('converged', 10), 23: ('converged', 8), 24: ('converged', 1),
    25: ('DIVERGED_NOT_HELD',), 26: ('DIVERGED_SINGULAR',), 27: ('converged', 5), 28: ('converged', 6),
    29: ('DIVERGED_SINGULAR',), 30: ('DIVERGED_NOT_HELD',), 31: ('converged', 6), 32: ('DIVERGED_SINGULAR',),
    33: ('DIVERGED_SINGULAR',), 34: ('converged', 5), 35: ('DIVERGED_SINGULAR',), 36: ('converged', 4),
    37: ('converged', 3), 38: ('converged', 1), 39: ('converged', 12), 40: ('converged', 3), 41: ('converged', 8),
    42: ('converged', 6), 43: ('DIVERGED_NOT_HELD',), 44: ('converged', 6), 45: ('DIVERGED_NOT_HELD',),
    46: ('converged', 2), 47: ('DIVERGED_NONINVERTIBLE_DEFORMATION',), 48: ('converged', 30), 49: ('converged', 1)}


@test("random_cases")
def random_cases(runner):
    """Property test over 36 random small cases (the first 36 of the 50 pinned: fewer since the suite neared its 20
    minutes): each ends as pinned (RANDOM_CASES_OUTCOMES: converged in as many active-set iterations, or refused with
    the same reason); every exit 0 is a certified contact state, checked again
    from the node table; every failure is one clean error line and no output (Runner.run_any); a case held by
    construction (held_by_construction) converges."""
    rng = np.random.default_rng(RANDOM_CASES_SEED)
    outcomes = {}
    for seed in range(36):
        args = random_case(rng)
        status, out, r = runner.run_any(args, "random %d" % seed)
        label = "seed %d (%s)" % (seed, " ".join(args))
        outcomes[seed] = outcome(status, out, r)
        runner.expect_equal("%s: outcome" % label, outcomes[seed], RANDOM_CASES_OUTCOMES.get(seed))
        if held_by_construction(args):
            runner.expect_equal("%s: held by construction, converges" % label, outcomes[seed][0], "converged")
        if r is None:
            continue
        # Independently of the certificate: no node in a pair's zone behind the obstacle beyond the gap tolerance,
        # no tensile multiplier beyond its tolerance, balance of forces.
        c, nodes = r.get("certificate"), r.nodes()
        gaps = nodes["gap"][~np.isnan(nodes["gap"])]
        runner.expect_true("%s: node gaps >= -gap_tol" % label, gaps.size == 0 or gaps.min() >= -c["gap_tol"])
        # From the obstacles' geometry alone: the pairs' gaps above cover only the facets a node has a pair with (a
        # node paired with the floor went 0.07-0.17 into an inclined wall unseen, 14 of 300 random cases).
        depth = geometric_penetration(nodes, args)
        runner.expect_true("%s: no candidate inside an obstacle (deepest %.3g)" % (label, depth),
                           depth <= c["gap_tol"])
        runner.expect_true("%s: node multipliers >= -tol" % label, nodes["lambda"].min() >= -c["lambda_tol"])
        total = np.array(r.get("contact.contact_force")) + np.array(r.get("contact.reaction_force")) + \
            np.array(r.get("contact.applied_force"))
        runner.expect_true("%s: force balance %.2g" % (label, np.linalg.norm(total)),
                           np.linalg.norm(total) <= 1e-8 * np.linalg.norm(r.get("contact.applied_force")))
    print("  outcomes: {%s}" % ", ".join("%d: %r" % kv for kv in sorted(outcomes.items())))
