"""St. Venant-Kirchhoff (svk) tests: large deflection against theory, Newton's quadratic convergence, agreement with
the linear material at small loads, and svk contact paths (sliding, lagged searches, the kept factorisation)."""

import numpy as np

from harness import accepted_step_iterations, displacement, expect_balance, expect_same_state, log_event_count, test
from parallel import RANK_CASES
from robustness import geometric_penetration
from solvers import kept_factorisations


SVK_CASES = {"hertz": ["-options_file", "options/hertz.yml", "-material_model", "svk", "-load_steps", "3"],
             "punch_on_plate": RANK_CASES["punch_on_plate_svk"],
             "cube_on_sphere": RANK_CASES["cube_on_sphere_svk"],
             "cube_mixed_conforming": RANK_CASES["cube_mixed_conforming_svk"],
             "beam_on_floor": ["-options_file", "options/beam_on_floor.yml", "-material_model", "svk", "-load_steps",
                               "2"],
             # Pairs searched again while sliding (new pairs: a new pattern and a new factorisation).
             "sliding_repair": ["-mesh_file", "meshes/block.msh", "-material_model", "svk", "-material_E", "1000",
                                "-bc_dirichlet", "top:x=1.5:y=-0.01", "-contact_groups", "bottom", "-load_steps", "5",
                                "-obstacle_segments", ",".join("%g,0,%g,0" % (-1 + 0.25 * k, -0.75 + 0.25 * k)
                                                               for k in range(24))],
             # Stabilised solves (the body held by contact only in y).
             "onto_disc": ["-mesh_file", "meshes/block.msh", "-material_model", "svk", "-material_E", "1000",
                           "-bc_dirichlet", "left:x", "-bc_pressure", "top:2", "-obstacle_discs", "1,-1.05,1",
                           "-contact_groups", "bottom"]}


@test("svk_reuse_factorization")
def svk_reuse_factorization(runner, case):
    """svk with the kept MUMPS factorisation (the default: FGMRES on the current tangent preconditioned by the
    factorisation of an earlier one, inexact Newton steps, and while the active set changes its search in the
    multiplier space with the factored tangent) against a refactorisation at every Newton iteration
    (-contact_reuse_factorization false, PETSc's MUMPS on the plain saddle-point form): the same converged state.
    Also the kept factorisation without the lagged search (exact Newton throughout: the same iterations as
    refactorising) and refactored at every solve (-contact_reuse_max_it 0: the Schur path's numerical
    refactorisation)."""
    args = SVK_CASES[case] + ["-log_view"]
    fresh = runner.run(args + ["-contact_reuse_factorization", "false"], case + " refactorise")
    kept = runner.run(args, case + " keep factorisation")
    exact = runner.run(args + ["-newton_lagged_search", "false"], case + " keep factorisation, exact Newton")
    every = runner.run(args + ["-contact_reuse_max_it", "0", "-newton_lagged_search", "false"],
                       case + " refactor the Schur path at every solve")
    solves = fresh.get("iterations.solves")
    runner.expect_equal("refactorising: numeric factorisations", log_event_count(fresh.output, "MatCholFctrNum"),
                        solves)
    runner.expect_equal("refactorising: no kept factorisation", kept_factorisations(fresh.output), 0)
    # The default's active-set search runs in the multiplier space (reduced solves on the dense Schur complement)
    # unless its solves carry the stabilisation springs (onto_disc); exact Newton never condenses.
    if not kept.get("iterations.stabilised_solves"):
        reduced = log_event_count(kept.output, "SigReducedSolve")
        runner.expect_true("kept: condensed searches (%d reduced solves)" % reduced, reduced > 0)
    runner.expect_equal("exact Newton: no reduced solves", log_event_count(exact.output, "SigReducedSolve"), 0)
    for r, what in ((kept, "kept"), (exact, "exact Newton"), (every, "every solve")):
        runner.expect_equal(what + ": no PETSc factorisations", log_event_count(r.output, "MatCholFctrNum"), 0)
        factors = kept_factorisations(r.output)
        if r is every:
            runner.expect_equal(what + ": a MUMPS factorisation per solve", factors, r.get("iterations.solves"))
        else:
            runner.expect_true("%s: fewer MUMPS factorisations (%d) than solves (%d)" % (
                what, factors, r.get("iterations.solves")), 1 <= factors < r.get("iterations.solves"))
    # Exact Newton with the kept factorisation as preconditioner solves the same systems (to the KSP tolerance, 1e-10):
    # the same iterations as refactorising. An attempt that failed and was cut (the punch's first step cycles) amplifies
    # round-off (rank_independence): there the cuts and the accepted steps' iterations must agree.
    for r, what in ((exact, "exact Newton"), (every, "every solve")):
        if fresh.get("iterations.step_cuts"):
            runner.expect_equal(what + ": step cuts", r.get("iterations.step_cuts"), fresh.get("iterations.step_cuts"))
            runner.expect_equal(what + ": iterations of the accepted steps", accepted_step_iterations(r),
                                accepted_step_iterations(fresh))
        else:
            runner.expect_equal(what + ": active-set iterations", r.get("iterations.active_set"),
                                fresh.get("iterations.active_set"))
    a = fresh.nodes()
    for r, what in ((kept, "kept"), (exact, "exact Newton"), (every, "every solve")):
        for key in ("contact.active_pairs", "contact.active_nodes", "iterations.load_steps"):
            runner.expect_equal("%s: %s" % (what, key), r.get(key), fresh.get(key))
        b = r.nodes()
        runner.expect_true(what + ": same active nodes", np.array_equal(a["active"], b["active"]))
        # Converged states of the same discrete problem, each to the Newton tolerance (1e-9 of the force scale): 1e-8
        # of the largest value is above that and far below any physical difference.
        runner.expect_close(what + ": displacement", displacement(b), displacement(a), 0,
                            1e-8 * np.abs(displacement(a)).max())
        runner.expect_close(what + ": lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
        runner.expect_close(what + ": contact force", r.get("contact.contact_force"),
                            fresh.get("contact.contact_force"), 1e-8,
                            1e-8 * np.abs(fresh.get("contact.contact_force")).max())


# Nonlinear (St. Venant-Kirchhoff) cases, on the same harness (leaks, PETSc errors, unused options, certificate).
def node_at(nodes, x, y):
    """Displacement (u_x, u_y) of the node nearest to (x, y)."""
    i = int(np.argmin((nodes["x"] - x) ** 2 + (nodes["y"] - y) ** 2))
    return float(nodes["u_x"][i]), float(nodes["u_y"][i])


@test("nonlinear_cantilever")
def nonlinear_cantilever(runner):
    """Large-deflection cantilever (svk) against Bisshopp & Drucker (1945)."""
    # Bisshopp & Drucker (1945), Quart. Appl. Math. 3(3): cantilever with an end load, P L^2/(E I) = 1: vertical tip
    # deflection 0.30172 L, horizontal 0.05643 L. Q1 elements are slightly stiff in bending (shear locking, about
    # 0.5 % on this mesh of 160 x 8): 1.5 % bounds the discretisation error, not the theory.
    r = runner.run(["-options_file", "options/cantilever_large.yml"], "cantilever")
    ux, uy = node_at(r.nodes(), 10.0, 0.25)
    runner.expect_close("tip deflection / L", -uy / 10, 0.30172, 0.015)
    runner.expect_close("tip shortening / L", -ux / 10, 0.05643, 0.03)
    runner.expect_equal("load steps", r.get("iterations.load_steps"), 4)


@test("nonlinear_quadratic")
def nonlinear_quadratic(runner):
    """Newton with the consistent tangent converges quadratically in every load step."""
    # Order p = log(r_n/r_n-1) / log(r_n-1/r_n-2) on the last three residuals above the round-off floor (1e-10 of
    # the step's first residual): linear convergence gives p close to 1, Newton about 2.
    r = runner.run(["-options_file", "options/cantilever_large.yml", "-load_steps", "8"], "cantilever 8 steps")
    history = r.get("iterations.history")
    for step in sorted({h["step"] for h in history}):
        res = [h["residual"] for h in history if h["step"] == step]
        res = [x for x in res if x > 1e-10 * res[0]]
        if not runner.expect_true("step %d: %d iterations above round-off (>= 3)" % (step, len(res)), len(res) >= 3):
            continue
        p = np.log(res[-1] / res[-2]) / np.log(res[-2] / res[-3])
        runner.expect_true("step %d: observed order %.2f >= 1.5" % (step, p), p >= 1.5)


@test("nonlinear_small_load")
def nonlinear_small_load(runner):
    """As the load tends to zero, svk and linear elasticity agree."""
    args = ["-options_file", "options/cantilever_large.yml", "-bc_traction", "right:0:-2.0833333333333e-6",
            "-load_steps", "1"]
    a = np.array(node_at(runner.run(args, "svk small load").nodes(), 10, 0.25))
    b = np.array(node_at(runner.run(args + ["-material_model", "linear"], "linear small load").nodes(), 10, 0.25))
    # The geometric nonlinearity is of the order of the load relative to E: below 1e-6 at this load.
    runner.expect_close("svk vs linear tip displacement", a, b, 0, 1e-6 * np.linalg.norm(b))


@test("nonlinear_hertz_small")
def nonlinear_hertz_small(runner):
    """Hertz at a 100 times smaller load: svk and linear half-width and peak pressure agree within 1 %."""
    args = ["-bc_traction", "top:0:-0.00625", "-report_hertz", "8,0.1"]
    svk = runner.run(args + ["-material_model", "svk"], "hertz svk")
    lin = runner.run(args, "hertz linear")
    for key in ("a_computed", "p0_computed"):
        runner.expect_close("hertz %s svk vs linear" % key, svk.get("hertz." + key), lin.get("hertz." + key), 0.01)
    runner.expect_true("svk run has contact", svk.get("contact.active_pairs") > 0)


@test("nonlinear_sliding")
def nonlinear_sliding(runner):
    """svk block dragged across the joint of two collinear floor segments: the same as a one-segment floor."""
    # Pressed 0.01 into the floor and dragged 1.5 along it by its top edge in 5 steps; the search radius covers the
    # sliding distance.
    args = ["-mesh_file", "meshes/block.msh", "-material_model", "svk", "-material_E", "1000", "-bc_dirichlet",
            "top:x=1.5:y=-0.01", "-contact_groups", "bottom", "-load_steps", "5", "-contact_search_radius", "2"]
    two = runner.run(args + ["-obstacle_segments", "-5,0,1,0,1,0,7,0"], "two-segment floor")
    one = runner.run(args + ["-obstacle_segments", "-5,0,7,0"], "one-segment floor")
    runner.expect_equal("active nodes, two segments", two.get("contact.active_nodes"), 20)
    runner.expect_equal("active nodes, one segment", one.get("contact.active_nodes"), 20)
    n2, n1 = two.nodes(), one.nodes()
    crossed = int(np.sum((n2["y"] == 0) & (n2["x"] < 1) & (n2["x"] + n2["u_x"] > 1)))
    runner.expect_true("%d bottom nodes slid across the joint (>= 3)" % crossed, crossed >= 3)
    # Both floors are the same line: the converged states agree to the Newton tolerance.
    runner.expect_close("two-segment floor = one-segment floor", displacement(n2), displacement(n1), 0, 1e-8)
    runner.expect_close("contact force", two.get("contact.contact_force.1"), one.get("contact.contact_force.1"), 1e-8)


@test("svk_free_after_lagged_search")
def svk_free_after_lagged_search(runner):
    """svk steps that fail at the end of the lagged searches' path are repeated with exact Newton steps. An svk block on a disc, tipping towards a wall (seed 4242 case 270), held by contact alone: the lagged searches
    and the stabilised moves along the free rigid motion carried it off the wall and past its balance on the disc,
    from where the load rolls it off, and the run ended "the body is not held" (also with the pairs within the
    diagonal). Such a step is now repeated with exact Newton steps, and converges: the top-left corner on the wall and
    two nodes on the disc, outside the obstacles, and the same state (1e-8) with that corner held at its height,
    where the support carries no load."""
    args = ["-mesh_file", "meshes/notch_block.msh", "-material_E", "276.736", "-material_nu", "0.411",
            "-contact_groups", "bottom,left,right", "-material_model", "svk", "-bc_traction",
            "top:0.00286477:-0.0419029", "-obstacle_segments", "0,2,0,-0.5", "-obstacle_discs", "0.639252,-0.998728,1"]
    r = runner.run(args, "svk block tipping on a disc")
    runner.expect_true("repeated with exact Newton steps after the lagged searches found it free",
                       "failed (DIVERGED_NOT_HELD) after lagged Newton searches: repeating it with exact Newton steps"
                       in r.output)
    runner.expect_equal("active pairs", r.get("contact.active_pairs"), 3)
    nodes = r.nodes()
    x = nodes["x"] + nodes["u_x"]
    corner = (nodes["x"] == 0) & (nodes["y"] == 1)
    runner.expect_true("the top-left corner on the wall", bool(nodes["active"][corner][0] == 1) and
                       abs(float(x[corner][0])) <= r.get("certificate.gap_tol"))
    depth = geometric_penetration(nodes, args)
    runner.expect_true("outside the obstacles (%g)" % depth, depth <= r.get("certificate.gap_tol"))
    held = runner.run(args + ["-bc_dirichlet", "anchor:y=%.17g" % float(nodes["u_y"][corner][0])],
                      "svk block tipping on a disc, corner held at its height")
    runner.expect_close("the support carries no load", held.get("contact.reaction_force"), [0, 0], 0,
                        1e-8 * np.linalg.norm(held.get("contact.applied_force")))
    expect_same_state(runner, r, held, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # Other failures at the end of the lagged searches' path (seed 31337): a block dropping 0.04 onto a floor beside
    # an inclined wall (case 110) was found free, searched again within the diagonal, and then deformed
    # non-invertibly, down to the smallest cut; a block supported on its left side over a disc (case 69) deformed
    # non-invertibly at every cut. Their first step is now repeated with exact Newton steps and converges to the state
    # of -contact_reuse_factorization false (1e-8), which never lags.
    for args, what, reason in (
            (["-mesh_file", "meshes/notch_block.msh", "-material_E", "2862.82", "-material_nu", "0.390",
              "-contact_groups", "bottom,left,right", "-material_model", "svk", "-bc_traction", "top:-0.529165:-13.1703",
              "-obstacle_segments", "-0.5,-0.042087,1.5,-0.042087,0,2,0,-0.5,0.894895,-0.042087,1.8949,0.502567"],
             "svk block dropping onto a floor", "DIVERGED_NONINVERTIBLE_DEFORMATION"),
            (["-mesh_file", "meshes/notch_block.msh", "-material_E", "1081.38", "-material_nu", "0.280",
              "-contact_groups", "bottom,left,right", "-material_model", "svk", "-bc_dirichlet", "left:x",
              "-bc_traction", "top:-0.225872:-1.07768", "-obstacle_segments", "0,2,0,-0.5,0.608827,0.00590966,1.60883,"
              "1.36017", "-obstacle_discs", "0.406251,-0.99409,1"], "svk block over a disc",
             "DIVERGED_NONINVERTIBLE_DEFORMATION")):
        r = runner.run(args, what)
        runner.expect_true("%s: repeated with exact Newton steps after the lagged searches failed (%s)" % (what, reason),
                           "Load step at factor 1 failed (%s) after lagged Newton searches: repeating it with exact "
                           "Newton steps" % reason in r.output and r.get("iterations.step_cuts") == 0)
        ref = runner.run(args + ["-contact_reuse_factorization", "false"], what + ", refactorised at every solve")
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("svk_notch_cycle")
def svk_notch_cycle(runner):
    """svk block in the notch: with the lagged searches (the default) its active set went round a loop of 11 sets
    and every load-step cut failed (DIVERGED_CYCLING). A set that comes back now ends the lagged searches of the load
    step, then switches one pair per update: the default converges in one load step to the state of exact Newton
    (-newton_lagged_search false) and of refactoring (-contact_reuse_factorization false), which reach it directly."""
    args = ["-options_file", "options/block_in_notch.yml", "-material_model", "svk"]
    default = runner.run(args, "svk block in notch")
    runner.expect_equal("one load step, no cut", default.get("iterations.load_steps"), 1)
    expect_balance(runner, default, default.label)
    for extra, what in ((["-newton_lagged_search", "false"], "exact Newton"),
                        (["-contact_reuse_factorization", "false"], "refactoring")):
        r = runner.run(args + extra, "svk block in notch, " + what)
        runner.expect_equal("%s: one load step" % what, r.get("iterations.load_steps"), 1)
        nodes, ref = r.nodes(), default.nodes()
        runner.expect_true("%s: the same active nodes" % what, np.array_equal(nodes["active"], ref["active"]))
        runner.expect_equal("%s: active pairs" % what, r.get("contact.active_pairs"), default.get("contact.active_pairs"))
        u = displacement(ref)
        runner.expect_close("%s: displacement" % what, displacement(nodes), u, 0, 1e-8 * np.abs(u).max())
        runner.expect_close("%s: lambda" % what, nodes["lambda"], ref["lambda"], 0, 1e-8 * np.abs(ref["lambda"]).max())


@test("svk_pairs_kept")
def svk_pairs_kept(runner):
    """svk Hertz in 3 load steps with the default search radius: the pair search at a load step's start finds new
    pairs, all farther than half the radius from their nodes, so the pairs, the system and its factorisation stay (no
    repairing, one MUMPS factorisation in the run; before, each such search rebuilt the system). The state is that of
    a radius of the whole body diagonal, with which the first search pairs every candidate."""
    args = ["-options_file", "options/hertz.yml", "-material_model", "svk", "-load_steps", "3", "-log_view"]
    kept = runner.run(args + ["-info", ":sys"], "default radius")
    wide = runner.run(args + ["-contact_search_radius", "1"], "radius of the body diagonal")
    runner.expect_true("new pairs left for a later search", "farther than half the search radius" in kept.output)
    runner.expect_equal("no repairing", kept.get("iterations.repairings"), 0)
    runner.expect_equal("one factorisation", kept_factorisations(kept.output), 1)
    a, b = kept.nodes(), wide.nodes()
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    runner.expect_close("displacement", displacement(a), displacement(b), 0, 1e-8 * np.abs(displacement(b)).max())
    runner.expect_close("lambda", a["lambda"], b["lambda"], 0, 1e-8 * np.nanmax(np.abs(b["lambda"])))


@test("nonlinear_sliding_repair")
def nonlinear_sliding_repair(runner):
    """svk block dragged 1.5 along a floor of 24 short collinear segments with the default search radius (0.22,
    less than the 0.3 it slides per load step): the pairs follow the current configuration, and the state equals
    that of a one-segment floor with a radius covering the path."""
    args = ["-mesh_file", "meshes/block.msh", "-material_model", "svk", "-material_E", "1000", "-bc_dirichlet",
            "top:x=1.5:y=-0.01", "-contact_groups", "bottom", "-load_steps", "5"]
    floor = ",".join("%g,0,%g,0" % (-1 + 0.25 * k, -0.75 + 0.25 * k) for k in range(24))
    short = runner.run(args + ["-obstacle_segments", floor], "24-segment floor, default radius")
    one = runner.run(args + ["-obstacle_segments", "-5,0,7,0", "-contact_search_radius", "2"],
                     "one-segment floor, radius 2")
    runner.expect_true("the pairs were searched again (%d)" % short.get("iterations.repairings"),
                       short.get("iterations.repairings") >= 1)
    runner.expect_equal("active nodes", short.get("contact.active_nodes"), one.get("contact.active_nodes"))
    runner.expect_equal("every bottom node in contact", one.get("contact.active_nodes"), 20)
    a, b = short.nodes(), one.nodes()
    # Both floors are the same line: the converged states agree to the Newton tolerance.
    runner.expect_close("24-segment floor = one-segment floor", displacement(a), displacement(b), 0, 1e-8)
    runner.expect_close("contact force", short.get("contact.contact_force.1"), one.get("contact.contact_force.1"),
                        1e-8)


@test("nonlinear_onto_disc")
def nonlinear_onto_disc(runner):
    """svk block held only in x (left side), pressed down onto a rigid disc 0.05 below it: the stabilised step moves
    it into contact (cut to the search radius so that the pairs searched again still see the disc), then Newton
    converges on the disc."""
    r = runner.run(["-mesh_file", "meshes/block.msh", "-material_model", "svk", "-material_E", "1000",
                    "-bc_dirichlet", "left:x", "-bc_pressure", "top:2", "-obstacle_discs", "1,-1.05,1",
                    "-contact_groups", "bottom"], "svk block onto a disc")
    runner.expect_true("stabilised solves (%d)" % r.get("iterations.stabilised_solves"),
                       r.get("iterations.stabilised_solves") >= 1)
    runner.expect_true("in contact (%d active pairs)" % r.get("contact.active_pairs"), r.get("contact.active_pairs") >= 1)
    # The disc carries the whole load q W = 4 (round-off of Newton's converged residual, 1e-9 relative).
    runner.expect_close("contact force", r.get("contact.contact_force.1"), 4.0, 1e-8)


@test("svk_iterative_first_update")
def svk_iterative_first_update(runner):
    """svk on the iterative path, held at a touching point first (the octant of options/hertz3d.yml): the step length
    cuts the touching solve's increment (det F <= 0 near the one node that holds the body), so the first update reads
    the linearised gaps of the whole increment instead of the cut iterate's, which is not applied: the next solve
    starts from the step's start, as the linear material's restarts there. The first update then changes about the
    linear material's pairs (198 and 194, within 5 %: the linear material's null-space preconditioner weights its
    inactive rows less, so its touching solve, stopped at 0.03, is not svk's; from the cut iterate 26, then 507 and a
    release over 10 Newton iterations), and the state is the direct path's (1e-8)."""
    base = ["-options_file", "options/hertz3d.yml", "-contact_solver", "iterative"]
    linear = runner.run(base, "linear, iterative", heap_check=False)
    svk = runner.run(base + ["-material_model", "svk", "-info", ":sys"], "svk, iterative", heap_check=False)
    direct = runner.run(["-options_file", "options/hertz3d.yml", "-material_model", "svk", "-contact_solver", "direct"],
                        "svk, direct")
    first = [r.get("iterations.history")[0]["changed"] for r in (linear, svk)]
    runner.expect_true("the first update changes about the linear material's pairs (%d, svk %d)" % tuple(first),
                       abs(first[0] - first[1]) <= 0.05 * first[0] and first[0] > 100)
    # The increment is not applied: the first iteration's record is the step's start (the body touching at a point,
    # no multiplier); a build that applied the cut increment recorded a penetration of 1.49 there.
    start = svk.get("iterations.history")[0]
    runner.expect_true("the touching solve's increment not applied (first record: penetration %g, min lambda %g)" % (
        start["max_penetration"], start["min_lambda"]), start["max_penetration"] == 0 and start["min_lambda"] == 0)
    runner.expect_true("the first update reads the whole increment's gaps, the next solve starts from the step's start",
                       "first update: from the gaps of the touching solve's whole increment (svk); the next solve "
                       "starts from the step's start" in svk.output)
    expect_same_state(runner, direct, svk, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
