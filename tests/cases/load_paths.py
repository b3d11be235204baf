"""Load paths: each load and prescribed displacement with its own ramp @T0:T1 over the load steps' pseudo-time."""

import numpy as np

from harness import expect_same_state, options_args, test

# The block on the rigid floor (options/block_on_floor.yml: 2 x 1, E = 1000, nu = 0.3) without its pressure, which
# each test gives with its own ramps, and its left edge held in x (left:x) unless a test prescribes it otherwise.
BLOCK = "options/block_on_floor.yml"


def block(runner, *args):
    args = [str(a) for a in args]
    return options_args(runner, BLOCK, drop=("bc_pressure", "bc_dirichlet")) + args + (
        [] if "-bc_dirichlet" in args else ["-bc_dirichlet", "left:x"])


def step_displacement(result, step):
    """The displacement of load step `step` from solution.h5, and the node coordinates (file order)."""
    xyz, _, u = result.solution(step)
    return xyz, u


def step_iterations(result):
    """The active-set iterations of each load step of the history, {step: count}."""
    counts = {}
    for r in result.get("iterations.history"):
        counts[r["step"]] = counts.get(r["step"], 0) + 1
    return counts


@test("ramps_end_state")
def ramps_end_state(runner):
    """Every kind of item split over ramps that all end at t = 1 (pressures, traction, point force, body force and a
    prescribed displacement, each on its own part of the path): the final state of the linear material is that of the
    same loads in one proportional step."""
    whole = block(runner, "-bc_pressure", "top:2", "-bc_traction", "top:0.1:0", "-bc_point_force", "right:0.01:-0.02",
                  "-bc_body_force", "0,-1", "-bc_dirichlet", "left:x=0.001")
    ramped = block(runner, "-load_steps", 4, "-bc_pressure", "top:1@0:0.5,top:1@0.25:1", "-bc_traction",
                   "top:0.1:0@0.5:1", "-bc_point_force", "right:0.01:-0.02@0.75:1", "-bc_body_force", "0,-1@0.1:1",
                   "-bc_dirichlet", "left:x=0.001@0.2:0.9")
    ref = runner.run(whole, "one proportional step")
    r = runner.run(ramped, "ramped over 4 steps")
    runner.expect_equal("load steps", r.get("iterations.load_steps"), 4)
    # A linear problem whose contact solution is unique: the path does not matter, the same active set gives the same
    # linear system (1e-10 of the largest value: its round-off).
    expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"))
    for key in ("contact.contact_force", "contact.applied_force", "contact.reaction_force"):
        runner.expect_close(key, r.get(key), ref.get(key), 0, 1e-10 * np.abs(ref.get("contact.applied_force")).max())


@test("ramps_mid_path")
def ramps_mid_path(runner):
    """Press, then shear: with -load_steps 2, a pressure @0:0.5 and a traction @0.5:1, step 1 is the state of the
    pressure alone (one step) and step 2 that of both (one step)."""
    r = runner.run(block(runner, "-load_steps", 2, "-bc_pressure", "top:2@0:0.5", "-bc_traction", "top:0.2:0@0.5:1"),
                   "press then shear")
    pressed = runner.run(block(runner, "-bc_pressure", "top:2"), "pressure alone")
    both = runner.run(block(runner, "-bc_pressure", "top:2", "-bc_traction", "top:0.2:0"), "pressure and traction")
    for step, ref in ((1, pressed), (2, both)):
        u = step_displacement(ref, 1)[1]
        runner.expect_close("step %d: displacement" % step, step_displacement(r, step)[1], u, 0,
                            1e-10 * np.abs(u).max())
    # The traction's x component reaches the applied load at the end only.
    runner.expect_close("applied load", r.get("contact.applied_force"), both.get("contact.applied_force"), 1e-12)


@test("ramps_dirichlet")
def ramps_dirichlet(runner):
    """A prescribed displacement ramped @0.5:1 with -load_steps 2: 0 after step 1, whole after step 2 (the pressure
    proportional); with the pressure ramped @0.5:1 too, nothing moves in step 1, which keeps the unloaded state
    without a solve."""
    ux = 0.01
    ref = runner.run(block(runner, "-bc_pressure", "top:2", "-bc_dirichlet", "left:x=%g" % ux), "one step")
    for pressure, idle in (("top:2", False), ("top:2@0.5:1", True)):
        label = "pressure %s" % pressure
        r = runner.run(block(runner, "-load_steps", 2, "-bc_pressure", pressure, "-bc_dirichlet",
                             "left:x=%g@0.5:1" % ux), label)
        xyz, u1 = step_displacement(r, 1)
        left = xyz[:, 0] == 0.0
        runner.expect_true("%s: left edge nodes (%d)" % (label, left.sum()), left.sum() >= 2)
        runner.expect_equal("%s: step 1 u_x on the left edge" % label, np.abs(u1[left, 0]).max(), 0.0)
        runner.expect_close("%s: step 2 u_x on the left edge" % label, step_displacement(r, 2)[1][left, 0],
                            np.full(left.sum(), ux), 1e-12)
        if idle:
            runner.expect_equal("%s: step 1 all zero" % label, np.abs(u1).max(), 0.0)
            runner.expect_equal("%s: active-set iterations of step 1" % label, step_iterations(r).get(1, 0), 0)
        else:
            runner.expect_true("%s: step 1 is loaded (max |u| %.3g)" % (label, np.abs(u1).max()), np.abs(u1).max() > 0)
        expect_same_state(runner, ref, r, keys=("contact.active_pairs", "contact.active_nodes"))
