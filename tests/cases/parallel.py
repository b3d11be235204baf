"""Parallel identity: the same case on 1 and 2 ranks gives the same integers, fields to round-off and the same output
files."""

import os
import re

import numpy as np

from harness import accepted_step_iterations, check_same_mesh, displacement, test


RANK_CASES = {"hertz": [], "beam_on_floor": ["-options_file", "options/beam_on_floor.yml"],
              "cube_on_sphere": ["-options_file", "options/cube_on_sphere.yml"],
              "cube_on_sphere_svk": ["-options_file", "options/cube_on_sphere.yml", "-material_model", "svk"],
              "plate_on_arc": ["-options_file", "options/plate_on_arc.yml"],
              "block_in_notch": ["-options_file", "options/block_in_notch.yml"],
              "punch_on_plate": ["-options_file", "options/punch_on_plate.yml"],
              "punch_on_plate_svk": ["-options_file", "options/punch_on_plate.yml", "-material_model", "svk"],
              "hertz3d": ["-options_file", "options/hertz3d.yml"],
              "block_on_cylinder": ["-options_file", "options/block_on_cylinder.yml"],
              "block_on_floor": ["-options_file", "options/block_on_floor.yml"],
              # A load path (load_paths.py): nothing in step 1, pressed in step 2, sheared and pulled in 3 and 4.
              "block_on_floor_ramps": ["-options_file", "options/block_on_floor.yml", "-load_steps", "4",
                                       "-bc_pressure", "top:2@0.25:0.5", "-bc_traction", "top:0.2:0@0.5:1",
                                       "-bc_dirichlet", "left:x=0.01@0.5:1"],
              # Pairs of bodies (the mortar rows): the interface split between the ranks.
              "cylinders_2d": ["-options_file", "options/cylinders_2d.yml"],
              "sphere_on_block": ["-options_file", "options/sphere_on_block.yml"],
              "patch3d_tet_on_hex": ["-options_file", "options/patch3d.yml", "-mesh_file",
                                     "meshes/patch3d_tet_on_hex.msh"],
              "cube_mixed_conforming": ["-options_file", "options/cube_on_plane.yml", "-mesh_file",
                                        "meshes/cube_mixed_conforming.msh"],
              "cube_mixed_conforming_svk": ["-options_file", "options/cube_on_plane.yml", "-mesh_file",
                                            "meshes/cube_mixed_conforming.msh", "-material_model", "svk"],
              # Random case 163 of seed 4242 (svk block held by contact alone on a floor and an inclined wall): a
              # full Newton step squeezes a cell to a det F of round-off size, whose sign then decided the path; with
              # 0 as the limit 1 rank took 19 iterations in 1 load step and 2 ranks 83 in 4 (MIN_DET_F).
              "svk_degenerate_cell": ["-mesh_file", "meshes/block.msh", "-material_E", "3836.49", "-material_nu",
                                      "0.410", "-contact_groups", "bottom,left,right", "-material_model", "svk",
                                      "-bc_traction", "top:1.12515:-5.9179", "-obstacle_segments",
                                      "-0.5,-0.0031266,2.5,-0.0031266,1.73622,-0.0031266,2.73622,1.25979"]}


def check_same_files(runner, one, two):
    """The output files of 1 and 2 ranks: each rank writes its block of the file's order, so solution.h5 has the same
    datasets, the geometry (mesh, obstacle, contact boundary) byte for byte, and the step fields in the same rows; the
    XDMF files are the same text; nodes.csv has the same header and the same node tags and coordinates, as text, row
    by row. The fields themselves are the two solves' (equal to round-off, as compared in rank_independence)."""
    import h5py

    def datasets(result):
        found = {}
        with h5py.File(os.path.join(result.dir, "solution.h5"), "r") as f:
            f.visititems(lambda name, obj: found.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
        return found

    a, b = datasets(one), datasets(two)
    runner.expect_equal("solution.h5 datasets on 2 ranks", sorted(b), sorted(a))
    # The solves agree to round-off amplified by the conditioning (rank_independence): 1e-8 of the largest value, or of
    # the largest displacement for the gaps (n . (X + u - P): the round-off of u), which vanish where pairs are active.
    u_max = max(np.abs(v).max() for k, v in a.items() if k.endswith("/displacement"))
    for name in sorted(set(a) & set(b)):
        x, y = a[name], b[name]
        if x.dtype != y.dtype or x.shape != y.shape:
            runner.expect_true("solution.h5 %s: %s %s on 2 ranks, %s %s on 1" % (name, y.dtype, y.shape, x.dtype,
                                                                                x.shape), False)
        elif not name.startswith("step_"):
            runner.expect_true("solution.h5 %s: the same bytes on 1 and 2 ranks" % name, x.tobytes() == y.tobytes())
        else:
            runner.expect_true("solution.h5 %s: NaN in the same rows" % name, np.array_equal(np.isnan(x), np.isnan(y)))
            x, y = np.nan_to_num(x), np.nan_to_num(y)
            runner.expect_close("solution.h5 %s, row by row" % name, y, x, 0, 1e-8 * max(np.abs(x).max(), u_max))
    for name in ("solution.xdmf", "body.xdmf", "obstacle.xdmf", "contact_boundary.xdmf"):
        there = [os.path.exists(os.path.join(r.dir, name)) for r in (one, two)]
        runner.expect_equal("%s written on 2 ranks as on 1" % name, there[1], there[0])
        if not all(there):
            continue
        with open(os.path.join(one.dir, name)) as f, open(os.path.join(two.dir, name)) as g:
            runner.expect_true("%s: the same text on 1 and 2 ranks" % name, f.read() == g.read())
    with open(os.path.join(one.dir, "nodes.csv")) as f, open(os.path.join(two.dir, "nodes.csv")) as g:
        rows_a, rows_b = f.read().splitlines(), g.read().splitlines()
    runner.expect_equal("nodes.csv header on 2 ranks", rows_b[0], rows_a[0])
    runner.expect_equal("nodes.csv rows on 2 ranks", len(rows_b), len(rows_a))
    lead = 1 + one.get("mesh.dim")  # node_tag and coordinates
    runner.expect_true("nodes.csv: the same node tags and coordinates (text) in the same rows",
                       [r.split(",")[:lead] for r in rows_a] == [r.split(",")[:lead] for r in rows_b])
    x = np.array([[float(v) for v in r.split(",")[lead:]] for r in rows_a[1:]])
    y = np.array([[float(v) for v in r.split(",")[lead:]] for r in rows_b[1:]])
    runner.expect_true("nodes.csv: NaN in the same places", np.array_equal(np.isnan(x), np.isnan(y)))
    x, y = np.nan_to_num(x), np.nan_to_num(y)
    for k, column in enumerate(rows_a[0].split(",")[lead:]):
        runner.expect_close("nodes.csv %s, row by row" % column, y[:, k], x[:, k], 0,
                            1e-8 * max(np.abs(x[:, k]).max(), u_max))


@test("rank_independence")
def rank_independence(runner, case):
    """The same case on 1 and 2 ranks: identical active set and iteration counts, equal displacements, the same
    output files (check_same_files). An attempt that failed and was cut (svk punch: its first step cycles) amplifies
    round-off, which on 2 ranks varies from run to run (MUMPS's parallel factorisation sums contributions in the order
    messages arrive: 24, 27 or 29 iterations in all, the same state): there the accepted steps' iterations and the
    number of cuts must agree."""
    one = runner.run(RANK_CASES[case], case, np_=1)
    two = runner.run(RANK_CASES[case], case, np_=2)
    counts = ("iterations.step_cuts",) if one.get("iterations.step_cuts") else ("iterations.active_set",
                                                                                 "iterations.solves")
    for key in ("mesh.nodes", "contact.pairs", "contact.active_pairs", "contact.active_nodes",
                "iterations.load_steps") + counts:
        runner.expect_equal("%s on 2 ranks" % key, two.get(key), one.get(key))
    if one.get("iterations.step_cuts"):
        runner.expect_equal("iterations of the accepted steps on 2 ranks", accepted_step_iterations(two),
                            accepted_step_iterations(one))
    a, b = one.nodes(), two.nodes()
    check_same_mesh(runner, "1 and 2 ranks", a, b)
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    # A direct solve in another elimination order: equal to round-off amplified by the conditioning of the
    # saddle-point matrix; 1e-8 of the largest value is far above that and far below any physical difference.
    runner.expect_close("displacement", displacement(b), displacement(a), 0, 1e-8 * np.abs(displacement(a)).max())
    runner.expect_close("lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
    # Pressures divide by tributary lengths summed over the ranks sharing a node.
    runner.expect_close("contact pressure", b["pressure"], a["pressure"], 0, 1e-8 * np.abs(a["pressure"]).max())
    extent = "contact.contact_area" if one.get("mesh.dim") == 3 else "contact.contact_length"
    runner.expect_close(extent, two.get(extent), one.get(extent), 1e-8)
    runner.expect_close("contact force", two.get("contact.contact_force"), one.get("contact.contact_force"), 1e-8,
                        1e-8 * np.abs(one.get("contact.contact_force")).max())
    check_same_files(runner, one, two)


@test("svk_rank_independence")
def svk_rank_independence(runner):
    """St. Venant-Kirchhoff with contact and load steps on 1 and 2 ranks: the same iterations, active set, displacements,
    multipliers and contact force."""
    args = ["-options_file", "options/beam_on_floor.yml", "-material_model", "svk", "-load_steps", "2"]
    one = runner.run(args, "beam svk", np_=1)
    two = runner.run(args, "beam svk", np_=2)
    for key in ("contact.active_pairs", "contact.active_nodes", "iterations.active_set", "iterations.load_steps"):
        runner.expect_equal("%s on 2 ranks" % key, two.get(key), one.get(key))
    a, b = one.nodes(), two.nodes()
    check_same_mesh(runner, "1 and 2 ranks", a, b)
    runner.expect_true("same active nodes", np.array_equal(a["active"], b["active"]))
    # Two Newton paths to the same state, each to the Newton tolerance (1e-9 of the force scale): 1e-8 of the largest
    # value (rank_independence).
    runner.expect_close("displacement", displacement(b), displacement(a), 0, 1e-8 * np.abs(displacement(a)).max())
    runner.expect_close("lambda", b["lambda"], a["lambda"], 0, 1e-8 * np.abs(a["lambda"]).max())
    runner.expect_close("contact force", two.get("contact.contact_force"), one.get("contact.contact_force"), 1e-8,
                        1e-8 * np.abs(one.get("contact.contact_force")).max())


# Systems whose rows cross the partition: K of tetrahedra and hexahedra on either path, the nested fieldsplit matrix
# (B^T's rows of another rank's pairs), the monolithic one, mortar rows between two bodies.
PREALLOCATION_CASES = {
    "hertz3d_iterative": ["-options_file", "options/hertz3d.yml", "-contact_solver", "iterative"],
    "cube_hex_direct": ["-options_file", "options/cube_under_sphere.yml", "-contact_solver", "direct"],
    "cylinders_2d_iterative": ["-options_file", "options/cylinders_2d.yml", "-contact_solver", "iterative"],
    "cylinders_2d_direct": ["-options_file", "options/cylinders_2d.yml", "-contact_solver", "direct"],
}
MALLOCS = re.compile(r"MatAssemblyEnd_SeqAIJ\(\): Number of mallocs during MatSetValues\(\) is (\d+)")


@test("preallocation")
def preallocation(runner):
    """On 2 ranks every matrix's rows are counted before its pattern is inserted: no entry is allocated during an
    assembly (PETSc's -info counts the reallocations of each block). The rows on the partition's interface get entries
    from both ranks' cells and pairs; counted as twice one side's, the 824k-dof cube's blocks were reallocated 561
    times on 2 ranks (5 s of its set-up)."""
    for name, args in PREALLOCATION_CASES.items():
        status, out, _ = runner.run_any(args + ["-info", ":mat"], name)
        runner.expect_equal("%s: exit status" % name, status, 0)
        counts = [int(n) for n in MALLOCS.findall(out)]
        # Each rank reports each block it assembles (a diagonal and an off-diagonal one per matrix): the test sees them.
        runner.expect_true("%s: the blocks' assembly reports seen (%d)" % (name, len(counts)), len(counts) >= 4)
        runner.expect_equal("%s: blocks reallocated during an assembly" % name, sum(n > 0 for n in counts), 0)
