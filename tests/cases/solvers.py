"""Solvers: the kept factorisation against refactorising, its Cholesky and MUMPS, the solver presets, iterative
solvers on contact, and the pivot orders; each against another path to the same state."""

import re

import numpy as np

from harness import displacement, expect_same_state, log_event_count, test


def kept_factorisations(output):
    """Numerical factorisations of the kept factorisation, by MUMPS or by the supernodal Cholesky
    (-contact_kept_solver)."""
    return log_event_count(output, "SigMumpsFactor") + log_event_count(output, "SigCholFactor")


def kept_solve_phases(output):
    """Forward (condensation) and backward (expansion) passes of the kept factorisation, MUMPS's or the Cholesky's."""
    return log_event_count(output, "SigMumpsSolve") + log_event_count(output, "SigCholSolve")


@test("reuse_factorization")
def reuse_factorization(runner, preset):
    """Hertz (49k dofs, two load steps) with the factorisation kept across active sets and load steps (MUMPS Schur
    complement on the multipliers, the default for a linear material) against a refactorisation at every solve: the
    same iterations and active set, equal solutions, and exactly one sparse factorisation instead of one per solve."""
    base = ["-options_file", "options/hertz.yml", "-mesh_file", "meshes/hertz.geo", "-mesh_size_factor", "0.5",
            "-load_steps", "2", "-options_file", "options/solver/%s.yml" % preset, "-log_view",
            "-contact_mat_mumps_icntl_7", "4"]  # PORD ordering: the MUMPS options reach both solvers (none unused)
    kept = runner.run(base, "hertz keep factorisation")
    fresh = runner.run(base + ["-contact_reuse_factorization", "false"], "hertz refactorise")
    for key in ("contact.active_pairs", "contact.active_nodes", "iterations.active_set"):
        runner.expect_equal(key, kept.get(key), fresh.get(key))
    solves = fresh.get("iterations.solves")
    runner.expect_equal("refactorising run: one solve per active-set iteration", solves,
                        fresh.get("iterations.active_set"))
    runner.expect_true("several solves (%d)" % solves, solves > 2)
    numeric = "MatCholFctrNum" if preset == "mumps_cholesky" else "MatLUFactorNum"
    runner.expect_equal("refactorising run: numeric factorisations", log_event_count(fresh.output, numeric), solves)
    runner.expect_equal("kept: MUMPS factorisations", kept_factorisations(kept.output), 1)
    runner.expect_equal("kept: PETSc factorisations", log_event_count(kept.output, numeric), 0)
    # Kept: per load step one condensation of the right-hand side (MUMPS's forward pass), every active-set iteration
    # in the multiplier space (condensed solves), and one expansion (the backward pass) for the displacement of the
    # last active set.
    steps = kept.get("iterations.load_steps")
    runner.expect_equal("kept: MUMPS solve phases", kept_solve_phases(kept.output), 2 * steps)
    runner.expect_equal("kept: condensed solves", log_event_count(kept.output, "SigReducedSolve"), solves)
    runner.expect_equal("kept: solves", kept.get("iterations.solves"), solves + steps)
    a, b = fresh.nodes(), kept.nodes()
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    # Two direct solves of the same system, one through the augmented form and a Schur complement: round-off
    # amplified by the conditioning; 1e-8 of the largest value is far above it and far below any physical difference.
    runner.expect_close("displacement", displacement(b), displacement(a), 0, 1e-8 * np.abs(displacement(a)).max())
    runner.expect_close("lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
    runner.expect_close("peak pressure", kept.get("hertz.p0_computed"), fresh.get("hertz.p0_computed"), 1e-8)
    # A load step that starts by applying a prescribed displacement (the punch's bottom moves up): its first solve is a
    # full one, the condensation starts from the second; the same state as refactorising.
    punch = ["-options_file", "options/punch_on_plate.yml", "-options_file", "options/solver/%s.yml" % preset,
             "-log_view"]
    kept = runner.run(punch, "punch keep factorisation")
    fresh = runner.run(punch + ["-contact_reuse_factorization", "false"], "punch refactorise")
    for key in ("contact.active_pairs", "contact.active_nodes", "iterations.active_set"):
        runner.expect_equal("punch: " + key, kept.get(key), fresh.get(key))
    runner.expect_equal("punch kept: condensed solves", log_event_count(kept.output, "SigReducedSolve"),
                        fresh.get("iterations.solves") - 1)
    a, b = fresh.nodes(), kept.nodes()
    runner.expect_true("punch: same active nodes", np.array_equal(a["active"], b["active"]))
    runner.expect_close("punch: displacement", displacement(b), displacement(a), 0,
                        1e-8 * np.abs(displacement(a)).max())
    runner.expect_close("punch: lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
    # Many candidates on a body that factors cheaply (meshes/strip.geo: one layer of 400 cells, all 401 bottom nodes
    # candidates, on a V-shaped floor, held vertically by contact alone): the dense Schur complement would cost more
    # than the sparse factors (MumpsSchur::DenseCostsMore), so it is declined and MUMPS refactorises the augmented
    # matrix at every active-set change; -contact_reuse_factorization keeps it. The same state either way.
    strip = ["-mesh_file", "meshes/strip.geo", "-material_E", "1000", "-material_nu", "0.3", "-bc_dirichlet",
             "left:x", "-bc_pressure", "top:0.001", "-obstacle_segments",
             "-1,0.0002,11,-0.0001,11,-0.0001,22,0.0002", "-contact_groups", "bottom",
             "-options_file", "options/solver/%s.yml" % preset, "-log_view"]
    auto = runner.run(strip + ["-info", ":sys"], "strip declined")
    kept = runner.run(strip + ["-contact_reuse_factorization", "true"], "strip kept")
    declined = re.search(r"Factor\(\): dense Schur complement of (\d+) candidates: .*: declined$", auto.output, re.M)
    runner.expect_true("strip: the Schur complement declined (-info)", declined is not None)
    runner.expect_equal("strip declined: Schur-complement factorisations", kept_factorisations(auto.output), 0)
    runner.expect_equal("strip declined: a numeric factorisation per solve", log_event_count(auto.output, numeric),
                        auto.get("iterations.solves"))
    runner.expect_true("strip: several active-set iterations (%d)" % auto.get("iterations.active_set"),
                       auto.get("iterations.active_set") > 2)
    runner.expect_equal("strip kept: Schur-complement factorisations", kept_factorisations(kept.output), 1)
    for key in ("contact.active_pairs", "iterations.active_set"):
        runner.expect_equal("strip: " + key, auto.get(key), kept.get(key))
    a, b = kept.nodes(), auto.nodes()
    runner.expect_true("strip: same active nodes", np.array_equal(a["active"], b["active"]))
    runner.expect_close("strip: displacement", displacement(b), displacement(a), 0,
                        1e-8 * np.abs(displacement(a)).max())
    runner.expect_close("strip: lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())


@test("kept_solver")
def kept_solver(runner):
    """The kept factorisation by the supernodal Cholesky (-contact_kept_solver cholesky, auto's choice on one rank)
    against MUMPS's (-contact_kept_solver mumps): the same state on the 2D Hertz case in two load steps, the 3D cube on
    a plane and svk Hertz in three load steps, the last also numerically refactored at every solve
    (-contact_reuse_max_it 0). Two direct factorisations of the same positive definite block: 1e-10 of the largest
    values for the linear material, svk's Newton tolerance (1e-8) for the two Newton paths. On two ranks rank 0
    factors the gathered matrix (auto's choice up to 50k rows). A block that the candidates do not hold (a floor only, free sideways) stops the Cholesky at a pivot that is
    not positive; MUMPS then judges the block, and the run ends as with MUMPS alone: DIVERGED_SINGULAR, one null
    pivot."""
    cases = ((["-options_file", "options/hertz.yml", "-load_steps", "2"], "hertz", 1e-10),
             (["-options_file", "options/cube_on_plane.yml"], "cube", 1e-10),
             (["-options_file", "options/hertz.yml", "-material_model", "svk", "-load_steps", "3"], "svk hertz", 1e-8),
             (["-options_file", "options/hertz.yml", "-material_model", "svk", "-load_steps", "3",
               "-contact_reuse_max_it", "0"], "svk hertz refactored", 1e-8))
    for args, what, tol in cases:
        mumps = runner.run(args + ["-contact_kept_solver", "mumps", "-log_view"], what + ", MUMPS")
        auto = runner.run(args + ["-log_view"], what + ", auto")
        runner.expect_equal("%s, MUMPS: no Cholesky factorisation" % what, log_event_count(mumps.output, "SigCholFactor"),
                            0)
        cholesky, by_mumps = log_event_count(auto.output, "SigCholFactor"), log_event_count(auto.output, "SigMumpsFactor")
        runner.expect_true("%s, auto: Cholesky factorisations only (%d, MUMPS %d)" % (what, cholesky, by_mumps),
                           cholesky >= 1 and by_mumps == 0)
        runner.expect_equal("%s: the same factorisation count" % what, cholesky + by_mumps,
                            kept_factorisations(mumps.output))
        expect_same_state(runner, mumps, auto, tol=tol)
        if what == "hertz":
            hertz = mumps
    explicit = runner.run(cases[0][0] + ["-contact_kept_solver", "cholesky", "-log_view"], "hertz, cholesky")
    runner.expect_equal("hertz, cholesky: Cholesky factorisations", log_event_count(explicit.output, "SigCholFactor"),
                        1)
    expect_same_state(runner, hertz, explicit)
    free = ["-mesh_file", "meshes/block.msh", "-material_E", "1000", "-contact_groups", "bottom", "-bc_pressure",
            "top:1", "-obstacle_segments", "-1,-0.01,3,-0.01"]
    for solver in ("mumps", "auto"):
        status, out, _ = runner.run_any(free + ["-contact_kept_solver", solver], "free block, " + solver)
        errors = [line for line in out.splitlines() if line.startswith("signorini: error:")]
        runner.expect_true("free block, %s: one error, DIVERGED_SINGULAR with MUMPS's null pivot (exit %d): %s" % (
            solver, status, errors), status != 0 and len(errors) == 1 and "DIVERGED_SINGULAR" in errors[0] and
            "MUMPS found 1 null pivot" in errors[0])
    # The same run with -info (its lines from both ranks may interleave with the error line: a run of its own).
    status, out, _ = runner.run_any(free + ["-info", ":sys"], "free block, auto, -info")
    runner.expect_true("free block, auto: the Cholesky stops and MUMPS factorises (exit %d)" % status,
                       status != 0 and "MUMPS factorises instead" in out)
    # Declined (the strip of the reuse_factorization test: many candidates on a body that factors cheaply): PETSc's
    # MUMPS refactorises, and the run says that the choice given does not apply.
    strip = ["-mesh_file", "meshes/strip.geo", "-material_E", "1000", "-material_nu", "0.3", "-bc_dirichlet",
             "left:x", "-bc_pressure", "top:0.001", "-obstacle_segments",
             "-1,0.0002,11,-0.0001,11,-0.0001,22,0.0002", "-contact_groups", "bottom", "-contact_kept_solver", "mumps"]
    r = runner.run(strip, "strip, declined")
    runner.expect_true("strip: the note that -contact_kept_solver mumps does not apply",
                       "Note: -contact_kept_solver mumps does not apply: the kept factorisation declined" in r.output)


@test("solver_preset")
def solver_preset(runner, preset):
    """beam_on_floor with a solver preset gives the state of another solver: mumps_cholesky's, or for mumps_cholesky
    itself mumps_lu's (a second factorisation, not the same run twice): the same active set, contact force,
    displacements and multipliers."""
    base = ["-options_file", "options/beam_on_floor.yml"]
    other = "mumps_lu" if preset == "mumps_cholesky" else "mumps_cholesky"
    ref = runner.run(base + ["-options_file", "options/solver/%s.yml" % other], "beam_on_floor %s" % other)
    # On two ranks the preset runs without the heap validation at every allocation (the leak check stays): it makes
    # GAMG set-up about 50 times slower there (4 s -> 240 s); one rank keeps the full check.
    r = runner.run(base + ["-options_file", "options/solver/%s.yml" % preset], "beam_on_floor %s" % preset,
                   heap_check=runner.np == 1)
    runner.expect_equal("active pairs", r.get("contact.active_pairs"), ref.get("contact.active_pairs"))
    runner.expect_equal("active nodes", r.get("contact.active_nodes"), ref.get("contact.active_nodes"))
    a, b = ref.nodes(), r.nodes()
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    # The iterative presets solve to ksp_rtol 1e-10; the state then agrees to about that times the conditioning of
    # the saddle-point matrix, within 1e-8 of the largest value (two direct factorisations agree far closer).
    f_ref = np.array(ref.get("contact.contact_force"))
    runner.expect_close("contact force", r.get("contact.contact_force"), f_ref, 1e-8, 1e-8 * np.abs(f_ref).max())
    u = displacement(a)
    runner.expect_close("displacement", displacement(b), u, 0, 1e-8 * np.abs(u).max())
    runner.expect_close("lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
    print("  iterations: active set %d, Krylov %d (%s: %d, %d)" % (
        r.get("iterations.active_set"), r.get("iterations.krylov"), other, ref.get("iterations.active_set"),
        ref.get("iterations.krylov")))


@test("iterative_on_contact")
def iterative_on_contact(runner, preset, case="hertz"):
    """The Hertz case, whose stiffness K alone is singular (the cylinder is held vertically only by contact), with a
    Schur fieldsplit preset: built on the augmented block K + r B_C^T B_C it gives the active set, multipliers and
    displacements of the default MUMPS solver to 1e-8."""
    base = ["-options_file", "options/%s.yml" % case]
    ref = runner.run(base, "hertz mumps")
    # In 3D the later active-set changes are small: -info tells whether the displacement block's preconditioner was
    # kept for them (KeepDisplacementPreconditioner), which the comparison below then covers.
    # -info also says each loose solve's tolerance (checked below; printed to 6 digits).
    info = ["-info", ":sys"]
    r = runner.run(base + ["-options_file", "options/solver/%s.yml" % preset, "-contact_ksp_view"] + info,
                   "hertz %s" % preset, heap_check=runner.np == 1)
    # The fieldsplit works on the blocks of a nested matrix, not on a copy of the displacement block.
    runner.expect_true("the saddle-point matrix is nested",
                       re.search(r"Mat Object: saddle_point .*\n\s+type: nest$", r.output, re.M) is not None)
    if case == "hertz3d":
        kept = len(re.findall(r"^\[0\] <sys> KeepDisplacementPreconditioner\(\).*: kept$", r.output, re.M))
        runner.expect_true("the displacement block's preconditioner kept for %d solve(s)" % kept, kept >= 1)
    a, b = ref.nodes(), r.nodes()
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    lam = np.abs(a["lambda"]).max()
    runner.expect_close("multipliers", b["lambda"], a["lambda"], 0, 1e-8 * lam)
    runner.expect_close("displacement", displacement(b), displacement(a), 0, 1e-8 * np.abs(displacement(a)).max())
    runner.expect_equal("status", r.get("status"), "converged")
    its, krylov = r.get("iterations.active_set"), r.get("iterations.krylov")
    history = [h["krylov"] for h in r.get("iterations.history")]
    print("  %s: %d active-set iterations, %d Krylov iterations (%.0f per solve): %s" % (
        preset, its, krylov, krylov / max(its, 1), history))
    # Every solve to the KSP's tolerance (-contact_active_set_rtol 0): the same state, more Krylov iterations than the
    # inexact active set (solves to 1e-3 of the load step's first residual while the set changes, then one
    # correction).
    exact = runner.run(base + ["-options_file", "options/solver/%s.yml" % preset, "-contact_active_set_rtol", "0"],
                       "hertz %s, every solve exact" % preset)
    expect_same_state(runner, exact, r, keys=("contact.active_pairs",), tol=1e-8)
    runner.expect_true("inexact active set: %d Krylov iterations < %d solving every set exactly" % (
        krylov, exact.get("iterations.krylov")), krylov < exact.get("iterations.krylov"))
    # Loose solves decide the sets on states as accurate as the first solve's (their tolerance is relative to the load
    # step's first residual, and each iterate's residual is evaluated in full): the exact solves' path, and at most
    # the correction solve more (relative to each solve's own start, the octant at 290k dofs took 9 active-set
    # iterations against 5).
    runner.expect_true("inexact active set: %d active-set iterations <= %d + 1 solving every set exactly" % (
        its, exact.get("iterations.active_set")), its <= exact.get("iterations.active_set") + 1)
    # Each loose solve stops at -contact_active_set_rtol (1e-3) of the norm of the load step's first right-hand side,
    # whatever its own (-info, SolveKsp): the second solve's right-hand side holds the penetrations of the pairs the
    # first update activates (4.5 times the first's in 2D, 23 in 3D), and 1e-3 of it would stop there instead. The
    # first solve, held at the touching point alone (1 to 3 pairs: ContactSolver::TOUCHING_PAIRS), stops at 0.03
    # (TOUCHING_RTOL): its displacement only picks the first update's pairs.
    loose = [(float(m.group(1)), float(m.group(2)), float(m.group(3))) for m in re.finditer(
        r"^\[0\] <sys> SolveKsp\(\): loose solve: rtol (\S+) of \|\|b\|\| = (\S+) \(the load step's first \|\|b\|\|: "
        r"(\S+)\)", r.output, re.M)]
    runner.expect_true("%d loose solves logged, at least 2" % len(loose), len(loose) >= 2)
    if loose:
        ref = loose[0][1]
        ends = [rt * b / ref for rt, b, first in loose]
        runner.expect_true("loose solves stop at %s of the first right-hand side's norm (the touching solve's 0.03, "
                           "then <= 1e-3), the reference the same in each" % ", ".join("%.3g" % e for e in ends),
                           abs(ends[0] - 0.03) <= 1e-6 and max(ends[1:] + [0]) <= 1e-3 * (1 + 1e-5) and
                           all(first == ref for rt, b, first in loose))
        runner.expect_true("a right-hand side larger than the first's gets a tighter tolerance (%s)" % ", ".join(
            "%.3g of ||b|| %.3g" % (rt, b / ref) for rt, b, first in loose),
            all(rt < 1e-3 for rt, b, first in loose if b > ref))
    # The octant is held by contact alone: its first solve, held at the touching node, turns the body about it, and
    # the next solve restarts from the step's start, where its right-hand side is smaller (RestartFromStepStart).
    restart = re.search(r"^\[0\] <sys> RestartFromStepStart\(\): first update: the next solve's \|\|b\|\| (\S+) from "
                        r"the step's start, (\S+) from the touching pairs' solve: (.*)$", r.output, re.M)
    runner.expect_true("the first update compares the next solve's right-hand sides%s" % (
        ": %s from the start, %s from the first solve, %s" % restart.groups() if restart else ""), restart is not None)
    if restart and case == "hertz3d":
        there, here = float(restart.group(1)), float(restart.group(2))
        runner.expect_true("the octant restarts from the step's start (%.3g < %.3g)" % (there, here),
                           there < here and restart.group(3) == "restarts from the start")
    # A solve after an unchanged active set only corrects the equilibrium residual (to a tenth of the certificate's
    # tolerance, not -contact_ksp_rtol relative to its start): far fewer iterations than the solve before it.
    h = exact.get("iterations.history")
    if len(h) >= 2 and h[-2]["changed"] == 0:
        runner.expect_true("correction solve: %d Krylov iterations < half of the %d before" % (
            h[-1]["krylov"], h[-2]["krylov"]), 2 * h[-1]["krylov"] < h[-2]["krylov"])
    its, krylov = exact.get("iterations.active_set"), exact.get("iterations.krylov")
    max_mean_krylov = {("hertz", "fieldsplit_gamg"): 35}.get((case, preset))
    if max_mean_krylov:
        # The inactive rows' small augmentation weight keeps the Schur complement well conditioned: BiCGStab took
        # 15-16 iterations per solve (30-32 V-cycles) on 1 and 2 ranks, against 33-34 with the weight r on every row;
        # GMRES (one V-cycle per iteration) takes 30-31.
        runner.expect_true("Krylov iterations per solve %.1f <= %d" % (krylov / its, max_mean_krylov),
                           krylov <= max_mean_krylov * its)


@test("iterative_on_contact_3d")
def iterative_on_contact_3d(runner, preset):
    """The same in 3D: the octant of a ball of options/hertz3d.yml (16k dofs), held vertically only by the plane."""
    iterative_on_contact(runner, preset, "hertz3d")


@test("solver_choice")
def solver_choice(runner):
    """The automatic solver choice (-contact_solver auto, the default) on the 3D octant: its factorisation fits the
    machine, so the direct path runs; under a memory budget it does not fit, the iterative path runs and gives the
    direct path's state to 1e-8. The header and summary.json name the path, who chose it and why;
    -contact_solver and a preset file override the choice."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "auto, machine's memory")
    runner.expect_equal("auto picks direct", (ref.get("solver.path"), ref.get("solver.chosen_by")), ("direct", "auto"))
    # Its time is within a factor 4 of the iterative path's: the header says the analysis decides, summary.json what
    # it decided.
    runner.expect_true("the header says why", "solver: direct (auto: the measured model puts a factorisation near "
                       "the limits" in ref.output and "the analysis of the matrix decides" in ref.output)
    runner.expect_true("summary.json says why", ref.get("solver.why").startswith("the factorisation fits (about"))
    runner.expect_equal("the analysis confirmed the direct path",
                        (ref.get("solver.factor_estimate"), ref.get("solver.left_direct")), ("analysis", False))
    runner.expect_true("the output says so once", ref.output.count("solver: direct, confirmed: the factorisation "
                                                                   "fits (about") == 1)
    runner.expect_true("the budget is the machine's", ref.get("solver.budget_bytes") > 1e8)
    # 20M: the measured model (178 MB) is 4 times the budget or more and decides alone. 100M: within a factor 4 of
    # it the model does not decide: the direct path starts, and the analysis of the matrix (the Cholesky's symbolic
    # factorisation, 132 MB) sends the run to the iterative path before any numerical factorisation; the header says
    # both, summary.json the final path.
    for budget, estimate, said in (("20M", "model", "solver: iterative (auto: a factorisation would need about"),
                                   ("100M", "analysis", "Solver: the direct path stopped (the analysis of the matrix "
                                                        "puts a factorisation at about")):
        r = runner.run(base + ["-contact_memory_budget", budget], "auto, budget %s" % budget)
        runner.expect_equal("budget %s: iterative" % budget, r.get("solver.path"), "iterative")
        runner.expect_true("budget %s: the output says why" % budget,
                           said in r.output and "of -contact_memory_budget" in r.output)
        runner.expect_equal("budget %s: the estimate by the %s" % (budget, estimate), r.get("solver.factor_estimate"),
                            estimate)
        runner.expect_equal("budget %s: the direct path left at run time" % budget, r.get("solver.left_direct"),
                            estimate == "analysis")
        runner.expect_true("budget %s: the estimate exceeds it" % budget,
                           r.get("solver.direct_bytes") > r.get("solver.budget_bytes"))
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    forced = runner.run(base + ["-contact_solver", "iterative"], "-contact_solver iterative")
    runner.expect_equal("-contact_solver iterative", (forced.get("solver.path"), forced.get("solver.chosen_by")),
                        ("iterative", "-contact_solver"))
    expect_same_state(runner, ref, forced, keys=("contact.active_pairs",), tol=1e-8)
    direct = runner.run(base + ["-contact_solver", "direct", "-contact_memory_budget", "1M"], "-contact_solver direct")
    runner.expect_equal("-contact_solver direct over the budget", direct.get("solver.path"), "direct")
    preset = runner.run(base + ["-options_file", "options/solver/mumps_lu.yml", "-contact_memory_budget", "1M"],
                        "a preset decides")
    runner.expect_equal("a preset decides", (preset.get("solver.path"), preset.get("solver.chosen_by")),
                        ("direct", "solver options"))


@test("solver_choice_mumps_analysis")
def solver_choice_mumps_analysis(runner):
    """The automatic choice near its limits on 2 ranks, where MUMPS factors (52.7k displacement rows, above the
    gathered Cholesky's 50k): the hexahedral cube under a sphere (25^3 cells) with a budget of 450 MB per rank, above
    the measured model's 393 MB but below MUMPS's own estimate after its analysis (INFOG(16), 524 MB): the direct path
    starts, the analysis sends the run to the iterative path before the numerical factorisation, and the state is
    the direct path's (to 1e-8). Without the budget the analysis confirms the direct path."""
    base = ["-options_file", "options/cube_under_sphere.yml", "-mesh_size_factor", "0.64"]
    ref = runner.run(base, "auto, machine's memory")
    runner.expect_equal("the analysis confirms the direct path",
                        (ref.get("solver.path"), ref.get("solver.factor_estimate"), ref.get("solver.left_direct")),
                        ("direct", "analysis", False))
    r = runner.run(base + ["-contact_memory_budget", "450M"], "auto, budget 450M")
    runner.expect_true("the model puts the direct path within the budget",
                       "near the limits (about 393 MB per rank)" in r.output)
    runner.expect_equal("MUMPS's analysis sends the run to the iterative path",
                        (r.get("solver.path"), r.get("solver.factor_estimate"), r.get("solver.left_direct")),
                        ("iterative", "analysis", True))
    runner.expect_true("the output says why", "Solver: the direct path stopped (the analysis of the matrix puts a "
                       "factorisation at about 524 MB per rank, more than the 450 MB of -contact_memory_budget)"
                       in r.output)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("iterative_hierarchy_reuse")
def iterative_hierarchy_reuse(runner):
    """The iterative path sets the displacement block's GAMG hierarchy up at most once per load step: across active
    sets (kept while at most 30 % of the candidate rows changed weight) and, for svk, across Newton iterations (the
    tangent of an earlier iteration preconditions while a solve takes at most 1.5 times the iterations of the first
    after its set-up): the set-ups counted from -log_view (PCSetUp_GAMG), the state the direct path's to 1e-8. The
    octant of options/hertz3d.yml with svk in 3 load steps (22 Newton iterations, 2 set-ups on one rank) and the
    hexahedral cube under a sphere, linear, in 2."""
    cases = [("svk octant", ["-options_file", "options/hertz3d.yml", "-material_model", "svk", "-load_steps", "3"]),
             ("linear cube", ["-options_file", "options/cube_under_sphere.yml", "-mesh_size_factor", "1",
                              "-load_steps", "2"])]
    for label, base in cases:
        ref = runner.run(base, "%s, direct" % label)
        r = runner.run(base + ["-contact_solver", "iterative", "-log_view"], "%s, iterative" % label,
                       heap_check=False)
        setups, steps = log_event_count(r.output, "PCSetUp_GAMG+"), r.get("iterations.load_steps")
        runner.expect_true("%s: %d GAMG set-up(s) for %d load steps and %d solves" % (
            label, setups, steps, r.get("iterations.solves")), 1 <= setups <= steps)
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


def hierarchy_checks(output):
    """The relative differences that -contact_hierarchy_check printed (-info :sys), one per hierarchy update."""
    return [float(x) for x in re.findall(r"hierarchy check: the first coarse operator differs from a new Galerkin "
                                         r"product by (\S+) of its norm", output)]


@test("iterative_hierarchy_update")
def iterative_hierarchy_update(runner):
    """The linear material's GAMG hierarchy follows the active set without a new set-up (-contact_hierarchy_update,
    the default): each coarse operator gets the Galerkin image of the rows that changed weight. On the octant of
    options/hertz3d.yml (5 active-set iterations, the first update changing 224 of 597 rows, more than the 30 % after
    which the hierarchy was set up again): one GAMG set-up (PCSetUp_GAMG in -log_view), every update exact (the first
    coarse operator against a new Galerkin product, -contact_hierarchy_check: 1e-12 of its norm at most), the direct
    path's state to 1e-8; with -contact_hierarchy_update false two set-ups and the same state."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    it = base + ["-contact_solver", "iterative", "-log_view"]
    r = runner.run(it + ["-contact_hierarchy_check", "-info", ":sys"], "iterative, updates checked", heap_check=False)
    runner.expect_equal("one GAMG set-up", log_event_count(r.output, "PCSetUp_GAMG+"), 1)
    checks = hierarchy_checks(r.output)
    updates = r.output.count("updated (the changed rows' Galerkin images added to the coarse operators)")
    runner.expect_true("%d updates, each checked (%s)" % (updates, checks), updates >= 2 and len(checks) == updates)
    runner.expect_true("every update exact (largest difference %.3g)" % max(checks or [1]), max(checks or [1]) <= 1e-12)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    off = runner.run(it + ["-contact_hierarchy_update", "false"], "iterative, set up again", heap_check=False)
    runner.expect_equal("without updates: two set-ups", log_event_count(off.output, "PCSetUp_GAMG+"), 2)
    expect_same_state(runner, ref, off, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # The update is collective, also where a rank has no pairs: on 2 ranks the slave side of the 3D patch test (a
    # tetrahedral block on a hexahedral one) lies on one rank; with the upper block's top lifted by 0.001 every pair
    # opens after the first solve, and the update changes all 45 rows (the other rank waited in its solve for ever
    # before).
    patch = ["-options_file", "options/patch3d.yml", "-mesh_file", "meshes/patch3d_tet_on_hex.msh", "-contact_solver",
             "iterative", "-info", ":sys"]
    lifted = runner.run(patch + ["-bc_dirichlet", "bottom:z,x0:x,y0:y,top:z=0.001", "-bc_pressure", "top:0"],
                        "patch test, top lifted", heap_check=False)
    if runner.np > 1:
        updates = lifted.output.count("updated (the changed rows' Galerkin images added to the coarse operators)")
        runner.expect_true("patch test, top lifted: %d hierarchy updates (on one rank: none)" % updates, updates >= 1)
    runner.expect_equal("patch test, top lifted: every pair open", lifted.get("contact.active_pairs"), 0)
    # Loose solves to 0.1 keep every pressed pair: after a loose solve the rule reads an active pair's multiplier
    # alone (ActiveSet::Next), where lambda - c g released pairs whose gap had opened by the solve's error, and 2
    # ranks then took more active-set iterations (updates that released and activated a few rows again).
    loose = runner.run(patch + ["-contact_active_set_rtol", "0.1"], "patch test, loose solves", heap_check=False)
    runner.expect_equal("patch test, loose solves: every slave node active", loose.get("contact.active_pairs"), 45)
    runner.expect_equal("patch test, loose solves: no switch (one loose solve, one correction)",
                        loose.get("iterations.active_set"), 2)


@test("gamg_lean_product")
def gamg_lean_product(runner):
    """GAMG's first Galerkin product on several ranks (-contact_gamg_product, LeanPtAP): PETSc 3.18's product of
    parallel matrices keeps A P of each rank's rows (3.3 GB per rank on a 4.1M-dof cube on 2 ranks); lean, the
    default, multiplies each rank's rows by sequential products in chunks and adds the parts. On the octant of
    options/hertz3d.yml: lean and petsc each give the direct path's state to 1e-8; lean's product is the one the
    hierarchy updates are checked against (-contact_hierarchy_check, 1e-12); the same on the 2D beam of
    options/beam_on_floor.yml. One rank: PETSc's sequential product whatever the option."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    it = base + ["-contact_solver", "iterative", "-info", ":mat,sys"]
    lean_line = "P^T A P by the ranks' sequential products (LeanPtAP)"
    lean = runner.run(it + ["-contact_hierarchy_check"], "lean (the default)", heap_check=False)
    runner.expect_equal("lean: the ranks' products (on one rank PETSc's)", lean_line in lean.output, runner.np > 1)
    # The coarsener (lean_coarsen.cpp): PETSc's aggregation with its matrix of the aggregates' members on other ranks
    # compacted, on every level; petsc keeps PETSc's coarsener.
    coarsen = re.findall(r"members on other ranks: (\d+) entries kept of (\d+) allocated \(LeanCoarsen\)", lean.output)
    runner.expect_true("lean: the compacting coarsener ran (%d levels)" % len(coarsen), len(coarsen) >= 2)
    checks = hierarchy_checks(lean.output)
    runner.expect_true("lean: every hierarchy update equal to a new product (%s)" % checks,
                       len(checks) >= 1 and max(checks) <= 1e-12)
    expect_same_state(runner, ref, lean, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    petsc = runner.run(it + ["-contact_gamg_product", "petsc", "-contact_hierarchy_check"], "petsc",
                       heap_check=False)
    runner.expect_true("petsc: PETSc's product", lean_line not in petsc.output)
    runner.expect_true("petsc: PETSc's coarsener", "(LeanCoarsen)" not in petsc.output)
    checks = hierarchy_checks(petsc.output)
    runner.expect_true("petsc: every hierarchy update equal to a new product (%s)" % checks,
                       len(checks) >= 1 and max(checks) <= 1e-12)
    expect_same_state(runner, ref, petsc, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # 2D: the coarse operator's blocks are P's column blocks (3 rigid modes per node), not the fine level's 2 (the
    # first version took them from P's rows: "Local size 27 not compatible with block size 2" on 2 ranks).
    beam = ["-options_file", "options/beam_on_floor.yml"]
    ref2 = runner.run(beam, "2D beam, direct")
    for product in ("lean", "petsc"):
        r = runner.run(beam + ["-contact_solver", "iterative", "-contact_gamg_product", product], "2D beam, " + product,
                       heap_check=False)
        expect_same_state(runner, ref2, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # Without contact candidates (a plain elastic solve: the sphere out of reach) the fieldsplit's one block is its own
    # copy of the matrix, which gets the lean product too (before: PETSc's, 7.3 GB per rank on the 4.1M-dof cube on
    # 2 ranks where one rank takes 8.4 GB).
    plain = ["-options_file", "options/cube_under_sphere.yml", "-bc_pressure", "top:1", "-obstacle_spheres",
             "0.5,0.5,3,0.5"]
    ref3 = runner.run(plain, "no candidates, direct")
    r = runner.run(plain + ["-contact_solver", "iterative", "-info", ":mat"], "no candidates, lean", heap_check=False)
    runner.expect_equal("no candidates: the ranks' products (on one rank PETSc's)", lean_line in r.output,
                        runner.np > 1)
    expect_same_state(runner, ref3, r, tol=1e-8)


@test("nullspace_pc")
def nullspace_pc(runner):
    """The iterative path's preconditioner in 3D (rigid obstacles, no friction) is the null-space method on the
    active rows (-contact_pc_type nullspace, src/linalg/pc_nullspace.cpp) with CG; -contact_ksp_view shows it and its
    displacement block's GAMG. On the octant of options/hertz3d.yml: CG (the default), GMRES and the Schur fieldsplit
    each give the direct path's state to 1e-8. The cube pushed into three planes (nodes on two and three planes: Gram
    blocks of 2 and 3 rows): the direct path's state and its 96 active pairs on 80 nodes."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    it = base + ["-contact_solver", "iterative"]
    cg = runner.run(it + ["-contact_ksp_view"], "the default: CG on the null-space preconditioner")
    runner.expect_true("the view names the null-space PC", "type: nullspace" in cg.output and
                       "null-space method on the active rows" in cg.output)
    runner.expect_true("the view names CG on the true residual", "type: cg" in cg.output and
                       "using UNPRECONDITIONED norm type" in cg.output)
    runner.expect_true("its displacement block by GAMG", "PC Object: (contact_fieldsplit_u_)" in cg.output)
    # After the hierarchy's update (UpdateGalerkin) the coarse levels' Chebyshev smoothers estimate their bounds
    # themselves (EstimateCoarseBounds); the finest keeps GAMG's. The first solve's view: GAMG's bounds everywhere.
    views = cg.output.split("KSP Object: (contact_) ")[1:]
    bounds = [dict(re.findall(r"mg_levels_(\d+)_\) .*\n.*\n.*\n\s*eigenvalues (provided|estimated)", v))
              for v in views]
    runner.expect_true("every solve's smoothers on levels 1 and 2 (%s)" % bounds,
                       len(bounds) >= 2 and all(set(b) == {"1", "2"} for b in bounds))
    runner.expect_true("the first solve's smoothers have GAMG's bounds",
                       bounds and set(bounds[0].values()) == {"provided"})
    runner.expect_true("after the update: level 1 estimates its bounds, the finest (2) keeps GAMG's",
                       bounds and bounds[-1] == {"1": "estimated", "2": "provided"})
    expect_same_state(runner, ref, cg, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # The inactive rows weigh 2e-4 of the element scale in its V-cycle (NULLSPACE_INACTIVE_WEIGHT): the touching
    # solve, where the body sinks about one node, takes 6 CG iterations on 1 and 2 ranks (7 and 8 with the
    # fieldsplit's 1e-2, whose springs held the candidate surface in the V-cycle alone).
    touching = cg.get("iterations.history")[0].get("krylov")
    runner.expect_true("the touching solve in at most 6 CG iterations (%s)" % touching,
                       touching is not None and touching <= 6)
    gm = runner.run(it + ["-contact_ksp_type", "gmres"], "GMRES on the null-space preconditioner")
    expect_same_state(runner, ref, gm, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    # The defaults follow what the run gives: the PC named keeps CG; a right side asks for GMRES; CG never gets the
    # right side (which it refuses), and no default is left unread.
    for extra, method in ((["-contact_pc_type", "nullspace"], "cg"), (["-contact_ksp_pc_side", "right"], "gmres"),
                          (["-contact_ksp_type", "cg"], "cg")):
        r = runner.run(it + extra + ["-contact_ksp_view"], " ".join(extra))
        runner.expect_true("%s: %s on the null-space PC" % (" ".join(extra), method),
                           "type: %s" % method in r.output and "type: nullspace" in r.output)
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    fs = runner.run(it + ["-contact_pc_type", "fieldsplit", "-contact_ksp_view"], "the Schur fieldsplit")
    runner.expect_true("the fieldsplit when asked for", "type: fieldsplit" in fs.output and
                       "type: nullspace" not in fs.output)
    expect_same_state(runner, ref, fs, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    corner = ["-mesh_file", "meshes/cube.msh", "-material_E", "1000", "-material_nu", "0.3", "-bc_body_force",
              "-1,-1.5,-2", "-contact_groups", "bottom,left,front", "-obstacle_planes",
              "0,0,0,0,0,1,0,0,0,1,0,0,0,0,0,0,1,0"]
    cref = runner.run(corner, "cube in three planes, direct")
    c = runner.run(corner + ["-contact_solver", "iterative", "-contact_ksp_view"], "cube in three planes, iterative")
    runner.expect_true("96 rows on 80 nodes in the view", "(96 rows on 80 nodes)" in c.output)
    runner.expect_equal("active pairs", c.get("contact.active_pairs"), 96)
    expect_same_state(runner, cref, c, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("nullspace_fine_level")
def nullspace_fine_level(runner):
    """The null-space preconditioner's multigrid smooths its finest level on the operator with the active rows
    eliminated, the one the method solves (-contact_nullspace_fine_level eliminated, the default), instead of the
    augmented block, whose springs on the active rows only approximate the elimination. The octant of
    options/hertz3d.yml: the direct path's state to 1e-8 either way, fewer CG iterations eliminated; the view says
    which, and an elastic solve (no active row) is not changed. The touching solve stops at 0.1 with CG, 0.03 with
    GMRES."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    it = base + ["-contact_solver", "iterative", "-contact_ksp_view"]
    line = "finest level smoothed on the operator with the active rows eliminated"
    new = runner.run(it, "iterative, finest level eliminated")
    old = runner.run(it + ["-contact_nullspace_fine_level", "augmented"], "iterative, finest level augmented")
    runner.expect_true("the view says the finest level is eliminated", line in new.output)
    runner.expect_true("and not when asked for the augmented block", line not in old.output)
    expect_same_state(runner, ref, new, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    expect_same_state(runner, ref, old, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    kn, ko = new.get("iterations.krylov"), old.get("iterations.krylov")
    runner.expect_true("CG iterations: %d eliminated < %d augmented" % (kn, ko), kn < ko)
    # No active row (the plane out of reach, the top clamped): the block itself, the same iterations either way.
    free = base + ["-contact_solver", "iterative", "-bc_dirichlet", "symmetry_x:x,symmetry_y:y,top:x:y:z",
                   "-bc_body_force", "0,0,0.00716", "-obstacle_planes", "0,0,-10.0001,0,0,1"]
    fn = runner.run(free, "elastic, eliminated")
    fo = runner.run(free + ["-contact_nullspace_fine_level", "augmented"], "elastic, augmented")
    runner.expect_equal("elastic: the same CG iterations", fn.get("iterations.krylov"), fo.get("iterations.krylov"))
    expect_same_state(runner, fo, fn, keys=("contact.active_pairs",), tol=1e-12)
    # The touching solve (held at one node) stops at 0.1 with CG (ContactSolver::TOUCHING_RTOL_CG), 0.03 with GMRES.
    for extra, label, want in (([], "CG", 0.1), (["-contact_ksp_type", "gmres"], "GMRES", 0.03)):
        r = runner.run(base + ["-contact_solver", "iterative", "-info", ":sys"] + extra, "touching solve, " + label)
        tols = [float(x) for x in re.findall(r"^\[0\] <sys> SolveKsp\(\): loose solve: rtol (\S+) of", r.output, re.M)]
        runner.expect_true("%s: the touching solve to %g (%s)" % (label, want, tols[:1]), tols[:1] == [want])
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("stiffness_product")
def stiffness_product(runner):
    """On the iterative path the linear material's loose solves get their iterate's internal forces as the last
    iterate's plus K du, a product with the assembled displacement block less its augmentation
    (SaddlePointSystem::StiffnessTimes), instead of a pass over the cells; the certificate's residual is the cells'.
    Where both are at the same displacement (-info) they agree to round-off. The octant of options/hertz3d.yml (the
    null-space preconditioner), the beam of options/beam_on_floor.yml (2D, the fieldsplit) and the two cylinders of
    options/cylinders_2d.yml (mortar rows: on 2 ranks some span ranks, and the cells serve): the direct path's state
    to 1e-8."""
    pattern = re.compile(r"F_int from the stiffness product: \|\|difference\|\| (\S+) against the cells' \|\|F_int\|\| "
                         r"(\S+) on the free rows")
    for case in ("hertz3d", "beam_on_floor", "cylinders_2d"):
        base = ["-options_file", "options/%s.yml" % case]
        ref = runner.run(base, case + ", direct")
        r = runner.run(base + ["-contact_solver", "iterative", "-info", ":sys", "-log_view"], case + ", iterative",
                       heap_check=False)
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
        pairs = [(float(a), float(b)) for a, b in pattern.findall(r.output)]
        products = log_event_count(r.output, "SigStiffnessProduct")
        if case == "cylinders_2d" and runner.np > 1:
            runner.expect_true("%s: no product where rows span ranks (%d)" % (case, products),
                               not pairs and products == 0)
            continue
        runner.expect_true("%s: the product against the cells at the same displacement (%s)" % (case, pairs),
                           len(pairs) >= 1 and all(d <= 1e-10 * f for d, f in pairs))
        runner.expect_true("%s: %d products" % (case, products), products >= 1)


@test("iterative_prescribed_displacement")
def iterative_prescribed_displacement(runner):
    """A punch pressed by a prescribed displacement into a plate (options/punch_on_plate.yml) on the iterative path:
    the prescribed rows make the step's first right-hand side 200 times the later ones, against which the loose
    solves' tolerance is scaled; capped at 0.01 (SaddlePointSystem::LOOSE_RTOL_MAX) they still decide the sets, where
    at 0.1 each took one Krylov iteration and the sets cycled (DIVERGED_CYCLING). The direct path's state to 1e-8, 1
    and 2 ranks."""
    base = ["-options_file", "options/punch_on_plate.yml"]
    ref = runner.run(base, "direct")
    r = runner.run(base + ["-contact_solver", "iterative", "-info", ":sys"], "iterative")
    # The first solve holds no pair (the punch is placed on the plate, nothing penetrates yet): not a solve held at a
    # touching point (ContactSolver::TOUCHING_RTOL), so every loose solve at 0.01 of its start at most.
    tols = [float(x) for x in re.findall(r"loose solve: rtol (\S+) of", r.output)]
    runner.expect_true("loose solves at most 0.01 relative to their start (%s)" % ", ".join("%.3g" % t for t in tols),
                       len(tols) >= 2 and max(tols) <= 0.01)
    # The first update does not restart from the step's start here (the punch's prescribed displacement is in place
    # and the plate not yet moved: a larger right-hand side there), so the touching solve's state is put back whole
    # (RestartFromStepStart), which the comparison with the direct path below covers.
    goes_on = re.search(r"RestartFromStepStart\(\): first update: the next solve's \|\|b\|\| (\S+) from the step's "
                        r"start, (\S+) from the touching pairs' solve: goes on$", r.output, re.M)
    runner.expect_true("the first update goes on from the touching solve%s" % (
        " (||b|| %s from the start, %s from it)" % goes_on.groups() if goes_on else ""), goes_on is not None)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("iterative_augmentation_weight")
def iterative_augmentation_weight(runner):
    """The iterative path's augmentation weight r in 3D without friction is half of K's mean diagonal entry on the
    candidate rows (-contact_augmentation_weight 0.5, IterativeWeight), about 6 times the element stiffness scale on
    the octant's tetrahedral surface, where r was that scale before: selfp's diagonal 1/(k + r) then misjudged the
    active rows' Schur complement (between 1/(k + r) and 1/r) by up to k/r. The octant of options/hertz3d.yml: the
    direct path's state to 1e-8 with either weight, fewer Krylov iterations with the default; in 2D r stays the
    element scale (a third of an assembled entry there already)."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    it = base + ["-contact_solver", "iterative", "-info", ":sys"]
    new = runner.run(it, "iterative, default weight", heap_check=False)
    m = re.search(r"iterative augmentation weight r = (\S+) \((\S+) of the candidates' mean diagonal entry (\S+), at "
                  r"least the element scale (\S+)\)", new.output)
    runner.expect_true("-info gives the weight", m is not None)
    if m:
        r, rel, mean, scale = (float(m.group(i)) for i in range(1, 5))
        runner.expect_true("r = %g = 0.5 of the mean diagonal entry %g, which is %.1f times the element scale %g" % (
            r, mean, mean / scale, scale), rel == 0.5 and abs(r - 0.5 * mean) <= 1e-5 * r and mean > 5 * scale)
    old = runner.run(it + ["-contact_augmentation_weight", "0"], "iterative, the element scale", heap_check=False)
    runner.expect_true("weight 0: r is the element scale",
                       "iterative augmentation weight" not in old.output)
    expect_same_state(runner, ref, new, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    expect_same_state(runner, ref, old, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    kn, ko = new.get("iterations.krylov"), old.get("iterations.krylov")
    runner.expect_true("Krylov iterations: %d with the default weight < %d with the element scale" % (kn, ko), kn < ko)
    flat = runner.run(["-options_file", "options/hertz.yml", "-contact_solver", "iterative", "-info", ":sys"],
                      "2D iterative", heap_check=False)
    runner.expect_true("2D: r stays the element scale", "iterative augmentation weight" not in flat.output)
    runner.expect_equal("2D: converged", flat.get("status"), "converged")


@test("iterative_first_overlap")
def iterative_first_overlap(runner):
    """A rigid sphere placed 0.01 into the top of a clamped cube (options/cube_under_sphere.yml) on the iterative path:
    a smooth indenter pressed to a depth d touches over half the area it overlaps (Hertz: r^2 = R d against 2 R d), so
    the first solve holds only the pairs that start at least half the deepest overlap in (ActiveSet::First), which
    here is the answer's set: 2 active-set iterations (that solve and its correction), where the whole overlap took
    one more. The direct path's state to 1e-8, 1 and 2 ranks."""
    base = ["-options_file", "options/cube_under_sphere.yml", "-mesh_size_factor", "0.64"]
    ref = runner.run(base + ["-contact_solver", "direct"], "direct")
    r = runner.run(base + ["-contact_solver", "iterative", "-info", ":sys"], "iterative")
    first = re.search(r"first set: (\d+) of the (\d+) pairs that start touching or overlapping", r.output)
    runner.expect_true("the first set is part of the overlap (-info: %s)" % (first.group(0) if first else "no line"),
                       first is not None and int(first.group(1)) < int(first.group(2)))
    if first:
        runner.expect_equal("the first set is the answer's", int(first.group(1)), ref.get("contact.active_pairs"))
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 2)
    # A first set of more than a few pairs is solved as any other set: to -contact_active_set_rtol (1e-3), not to the
    # touching solve's 0.03 (ContactSolver::TOUCHING_PAIRS), whose errors would read as changes here.
    tols = [float(x) for x in re.findall(r"^\[0\] <sys> SolveKsp\(\): loose solve: rtol (\S+) of", r.output, re.M)]
    runner.expect_true("the first solve to 1e-3 (%s)" % ", ".join("%.3g" % t for t in tols),
                       len(tols) >= 1 and tols[0] == 1e-3)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("iterative_first_overlap_update")
def iterative_first_overlap_update(runner):
    """After a first set of half an overlap (ActiveSet::First) the first update is not damped: that solve did not
    overshoot, and the pairs it leaves penetrating are the ring just outside its set. The cube of
    options/cube_under_sphere.yml at its coarsest mesh with the sphere 0.03 into it: 9 of the 21 overlapping pairs
    first, then all 21 of the answer at once (3 active-set iterations: two solves and the correction), where the gap
    factor, whose start gaps are negative here, held 8 of them back for one iteration more (13, 21, 21, 21). The
    direct path's state to 1e-8, 1 and 2 ranks."""
    base = ["-options_file", "options/cube_under_sphere.yml", "-obstacle_spheres", "0.5,0.5,1.47,0.5"]
    ref = runner.run(base + ["-contact_solver", "direct"], "direct")
    r = runner.run(base + ["-contact_solver", "iterative", "-info", ":sys"], "iterative")
    first = re.search(r"first set: (\d+) of the (\d+) pairs that start touching or overlapping", r.output)
    runner.expect_true("the first set is part of the overlap (-info: %s)" % (first.group(0) if first else "no line"),
                       first is not None and int(first.group(1)) < int(first.group(2)) and
                       int(first.group(1)) < ref.get("contact.active_pairs"))
    runner.expect_true("-info: the first update not damped", "every penetrating pair activated (not damped)" in r.output
                       and "penetrating pair(s) held back" not in r.output)
    sets = [h["active"] for h in r.get("iterations.history")]
    runner.expect_equal("the first update's set is the answer's (sets %s)" % sets, sets[0],
                        ref.get("contact.active_pairs"))
    runner.expect_equal("active-set iterations", r.get("iterations.active_set"), 3)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)


@test("gamg_square_graph_3d")
def gamg_square_graph_3d(runner):
    """In 3D the iterative path's GAMG squares the graph on its first two levels (PETSc's default: one), unless the
    run gives -contact_fieldsplit_u_pc_gamg_square_graph; in 2D PETSc's default stays (-contact_ksp_view shows the
    number of levels). The 3D state is the direct path's to 1e-8."""
    levels = r"Number of levels to square graph (\d+)"
    ref = runner.run(["-options_file", "options/hertz3d.yml"], "3D direct")
    r = runner.run(["-options_file", "options/hertz3d.yml", "-contact_solver", "iterative", "-contact_ksp_view"],
                   "3D iterative")
    runner.expect_equal("3D: squared on two levels", sorted(set(re.findall(levels, r.output))), ["2"])
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"), tol=1e-8)
    given = runner.run(["-options_file", "options/hertz3d.yml", "-contact_solver", "iterative", "-contact_ksp_view",
                        "-contact_fieldsplit_u_pc_gamg_square_graph", "1"], "3D iterative, one level given")
    runner.expect_equal("the option given decides", sorted(set(re.findall(levels, given.output))), ["1"])
    two = runner.run(["-contact_solver", "iterative", "-contact_ksp_view"], "2D iterative")
    runner.expect_equal("2D: PETSc's default", sorted(set(re.findall(levels, two.output))), ["1"])


@test("krylov_fallback")
def krylov_fallback(runner):
    """A Krylov method that fails on the saddle-point system (CG on the indefinite system stops with
    DIVERGED_INDEFINITE_PC) is not the end of the run: the preconditioner is set up again and GMRES solves from the
    same start, for the rest of the run; the state is the direct solver's and summary.json counts the fallbacks."""
    base = ["-options_file", "options/hertz3d.yml"]
    ref = runner.run(base, "direct")
    # CG breaks down on the Schur fieldsplit (an indefinite preconditioner); on the null-space preconditioner of the
    # default iterative path it converges (a constraint preconditioner: CG works in the constraints' null space).
    r = runner.run(base + ["-contact_solver", "iterative", "-contact_pc_type", "fieldsplit", "-contact_ksp_type", "cg",
                           "-contact_ksp_pc_side", "left", "-info", ":sys"], "CG, then GMRES")
    runner.expect_true("CG stopped and GMRES took over",
                       re.search(r"RetryKrylov\(\): cg stopped with DIVERGED_\w+ after \d+ iterations", r.output)
                       is not None)
    runner.expect_equal("one fallback (GMRES stays)", r.get("iterations.krylov_fallbacks"), 1)
    runner.expect_equal("no fallback on the direct path", ref.get("iterations.krylov_fallbacks"), 0)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs",), tol=1e-8)
    c = runner.run(base + ["-contact_solver", "iterative", "-contact_ksp_type", "cg", "-contact_ksp_pc_side", "left"],
                   "CG on the null-space preconditioner")
    runner.expect_equal("CG on the null-space preconditioner: no fallback", c.get("iterations.krylov_fallbacks"), 0)
    expect_same_state(runner, ref, c, keys=("contact.active_pairs",), tol=1e-8)
    # GMRES itself (the fieldsplit preset's method) that stagnates on a short restart gets the fallback's restart of
    # 100: with GMRES(1) and 20 iterations at most the first solve stops, and the run then converges within them
    # (with the null-space preconditioner GMRES(1) converges within 30).
    g = runner.run(base + ["-contact_solver", "iterative", "-contact_ksp_type", "gmres", "-contact_ksp_gmres_restart",
                           "1", "-contact_ksp_max_it", "20", "-info", ":sys"], "GMRES(1), then GMRES(100)")
    runner.expect_true("GMRES(1) stopped and GMRES(100) took over",
                       re.search(r"RetryKrylov\(\): gmres stopped with DIVERGED_\w+ after \d+ iterations", g.output)
                       is not None)
    runner.expect_equal("GMRES(1): one fallback", g.get("iterations.krylov_fallbacks"), 1)
    expect_same_state(runner, ref, g, keys=("contact.active_pairs",), tol=1e-8)


@test("krylov_fallback_restart")
def krylov_fallback_restart(runner):
    """A Krylov restart (a solve that goes on from where it stopped) that breaks down gets the same fallback as a first
    attempt: the 3D survey's seed 777 case 18 (an svk cube held by its left side and two walls, pulled off them) ended
    in an error on the iterative path, CG stopping with DIVERGED_INDEFINITE_PC in a restart of an inexact Newton step
    on a tangent no longer positive definite; it now ends as on the direct path: out of Newton iterations after the
    load step's cuts (the direct path's verdict, DIVERGED_MAX_IT), with GMRES taking over."""
    args = ["-mesh_file", "meshes/cube.msh", "-material_E", "414.077", "-material_nu", "0.148", "-contact_groups",
            "bottom,front,left", "-material_model", "svk", "-bc_dirichlet", "left:x", "-bc_traction",
            "top:0.0521297:-0.0095594:-0.22092", "-obstacle_planes", "0,0,0,1,0,0,0,0,0,0,1,0", "-obstacle_spheres",
            "0.318687,0.419863,-1.03654,1"]
    outcomes = []
    for solver in ("direct", "iterative"):
        status, out, result = runner.run_any(args + ["-contact_solver", solver, "-info", ":sys"], solver)
        m = re.search(r"signorini: error: the contact solve did not converge at load factor \S+: (DIVERGED_\w+)", out)
        outcomes.append(m.group(1) if m else ("converged" if status == 0 else "another error"))
        if solver == "iterative":
            runner.expect_true("GMRES took over from CG", "RetryKrylov(): cg stopped with DIVERGED_INDEFINITE_PC" in out)
    runner.expect_equal("the same outcome on both paths", outcomes[1], outcomes[0])
    runner.expect_equal("the direct path's verdict", outcomes[0], "DIVERGED_MAX_IT")


@test("elastic_fieldsplit_block_size")
def elastic_fieldsplit_block_size(runner):
    """The iterative path on a case with no multiplier (the octant on a plane out of reach of the search, held by
    supports): GAMG gets the displacement block with its node blocks (bs = 3) as with multipliers, so it coarsens it
    as elasticity, not as a scalar problem (a first coarse level about 4 times larger, and at 824k dofs no end in 12
    minutes); the state is the direct solver's."""
    base = ["-options_file", "options/cube_on_plane.yml", "-obstacle_planes", "0,0,-1,0,0,1",
            "-bc_dirichlet", "left:x,front:y,bottom:z", "-contact_search_radius", "0.5"]
    ref = runner.run(base, "direct")
    runner.expect_equal("no multiplier", ref.get("problem.multipliers"), 0)
    r = runner.run(base + ["-contact_solver", "iterative", "-contact_ksp_view"], "iterative")
    n = r.get("problem.displacement_dofs")
    runner.expect_true("the u block (%d rows) reaches GAMG with bs=3" % n,
                       "rows=%d, cols=%d, bs=3" % (n, n) in r.output)
    expect_same_state(runner, ref, r, keys=("contact.active_pairs",), tol=1e-8)


@test("elastic_gamg")
def elastic_gamg(runner):
    """Linear elasticity without contact by CG + GAMG with the rigid-body near-null space: the direct solution, and
    few iterations (without the near-null space GAMG needs about ten times more on this slender beam)."""
    base = ["-mesh_file", "meshes/cantilever.msh", "-material_E", "1e5", "-bc_dirichlet", "left:x:y",
            "-bc_traction", "right:0:-1"]
    ref = runner.run(base, "cantilever direct")
    r = runner.run(base + ["-contact_ksp_type", "cg", "-contact_pc_type", "gamg"], "cantilever cg gamg",
                   heap_check=False)
    a, b = ref.nodes(), r.nodes()
    runner.expect_close("displacement", displacement(b), displacement(a), 0, 1e-7 * np.abs(displacement(a)).max())
    runner.expect_true("CG + GAMG in fewer than 60 iterations (%d)" % r.get("iterations.krylov"),
                       r.get("iterations.krylov") < 60)


def elimination_flops(output):
    """The elimination flops of the kept factorisation that -info prints (rank 0's line)."""
    m = re.search(r"^\[0\] <sys> \w+\(\): (MUMPS|Cholesky) factors.*: .* ([0-9.e+]+) flops in the elimination",
                  output, re.M)
    return float(m.group(2)) if m else None


@test("orderings")
def orderings(runner):
    """The pivot orders of the kept factorisation give the same state: MUMPS's automatic choice, the nested dissections
    of the node graph given to MUMPS (METIS's, the default from 50k rows and in 3D, computed by all ranks or by rank 0
    alone, and the coordinate cuts, the default for a smaller 2D matrix) and PORD, on the 2D Hertz case and on the 3D
    cube with symmetry supports (a node's first row then holds only its diagonal). On several ranks METIS's ordering
    is computed by all of them (the partition's interface as the top separator, each rank's part by METIS) and its
    factor costs no more than 1.3 times the elimination flops of METIS on the whole graph on rank 0 (2 ranks: 1.10
    times in 2D, 1.21 in 3D; a separator eliminated before its parts, or no separator, costs more)."""
    metis = ["-contact_mat_mumps_icntl_7", "1", "-contact_nested_dissection", "metis", "-info", ":sys"]
    for case, what in ((["-options_file", "options/hertz.yml"], "hertz"),
                       (["-options_file", "options/cube_on_plane.yml"], "cube")):
        ref = runner.run(case + ["-contact_mat_mumps_icntl_7", "7"], "%s, automatic ordering" % what)
        for order, name in ((metis, "METIS"),
                            (metis + ["-contact_nested_dissection_parallel", "false"], "METIS on rank 0"),
                            (["-contact_nested_dissection", "coordinates"], "coordinate cuts"),
                            (["-contact_mat_mumps_icntl_7", "4"], "PORD")):
            r = runner.run(case + order, "%s, %s" % (what, name))
            expect_same_state(runner, ref, r)
            if name == "METIS":
                parallel = r
            elif name == "METIS on rank 0":
                serial = r
        where = "all ranks" if runner.np > 1 else "rank 0"
        runner.expect_true("%s: METIS's nested dissection on %s" % (what, where),
                           "(METIS, %s)" % where in parallel.output)
        runner.expect_true("%s: METIS's nested dissection on rank 0 when asked" % what,
                           "(METIS, rank 0)" in serial.output)
        flops, serial_flops = elimination_flops(parallel.output), elimination_flops(serial.output)
        runner.expect_true("%s: elimination flops %s, METIS on rank 0 %s: at most 1.3 times" % (
            what, flops, serial_flops), flops is not None and serial_flops and flops <= 1.3 * serial_flops)
