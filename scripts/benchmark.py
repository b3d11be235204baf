#!/usr/bin/python3
"""Performance benchmark of signorini: a matrix of meshes x solver presets x MPI ranks.

Families (each run is the executable with a case options file, a solver preset and a mesh meshed in-process from a
.geo with -mesh_size_factor F, under `mpiexec -n N`):

  hertz  options/hertz.yml on meshes/hertz.geo (the 2D Hertz benchmark; K is singular: only contact holds the cylinder,
         so the Schur fieldsplit presets are expected to fail there; the run is recorded as failed with its reason)
  beam   options/beam_on_floor.yml on meshes/beam_bench.geo (cantilever clamped on the left, pushed onto a floor; K is
         regular, so every preset, the Schur fieldsplits included, applies)
  svk    the nonlinear line: hertz with -material_model svk -load_steps 3 and the default solver (mumps_cholesky)
  hertz3d  options/hertz3d.yml on meshes/hertz3d.geo (3D Hertz: an octant of a ball on a plane, graded towards the
         contact; K is singular as in 2D). Levels up to 556k displacement dofs (F = 0.4: 14.7 GB on one rank) fit
         in 24 GiB with the direct solver; the largest, F = 0.35 (822k dofs), does not (MUMPS asks for 31 GB).
  cylinders  options/cylinders_2d.yml on meshes/cylinders2d.geo (2D Hertz between two deformable cylinders, mortar rows;
         elastic reference: the same mesh without the pair, the upper body clamped at its top, a body force)
  sphere_block  options/sphere_on_block.yml on meshes/sphere_on_block.geo (3D Hertz between an octant of a ball and a
         block; elastic reference as for cylinders)
  cattaneo  options/cattaneo2d.yml on meshes/cattaneo2d.geo (Coulomb friction, mu = 0.3: two equal cylinders
         pressed over 5 load steps, then sheared over 5; MUMPS LU refactored at every change of the sets). Its
         reference is not an elastic solve but the frictionless solve of the same path (-contact_friction 0): ratio =
         frictional / frictionless contact solve, with the iterations of both.
  cattaneo3d  options/cattaneo3d.yml on meshes/cattaneo3d.geo (the 3D Cattaneo-Mindlin case: two equal half balls
         pressed over 3 load steps, sheared over 3; reference: the frictionless solve of the same path). Levels 12.9k,
         38k, 159k, 500k dofs; from about 20k dofs the automatic choice takes the iterative path.
  cube   options/cube_under_sphere.yml on meshes/cube_bench.geo (a unit cube of (16/F)^3 hexahedra, bottom clamped,
         sides on rollers, indented by a rigid sphere; its elastic reference: a pressure on the top, the sphere out of
         reach, so no multiplier). Levels 14.7k, 108k, 824k and 3.06M dofs.
The preset `auto` is no preset file: the automatic solver choice (-contact_solver auto, the program's default).

Per run it records: displacement dofs, multipliers, active-set iterations, Krylov iterations, the time per phase,
the peak memory, the Hertz errors and the ratio (contact solve) / (one elastic solve).

Time per phase (seconds, maximum over ranks):
  mesh, setup, output, contact_solve, total  summary.json "timings" (= the -log_view stages Mesh, Setup, Output,
                                            ContactSolve; total is the wall time inside the executable)
  assembly                                  -log_view event SigAssembly (stage ContactSolve): K, residuals, gaps, rhs
  factor_sym, factor_num                    -log_view events MatCholFctrSym + MatLUFactorSym, MatCholFctrNum +
                                            MatLUFactorNum (all stages, i.e. every factorisation, also the MUMPS
                                            factorisation of a fieldsplit's u block)
  pc_setup                                  -log_view event PCSetUp (stage ContactSolve): the whole preconditioner
                                            set-up (= the factorisations for the direct presets, AMG set-up + u-block
                                            factorisation for the fieldsplits)
  solve                                     SigSolve - PCSetUp: triangular solves / Krylov iterations and the
                                            residual check after each solve
  first_solve                               history[0].solve_time of summary.json: the first saddle-point solve
                                            (symbolic + numeric factorisation + solve)
Peak memory: the maximum resident set size of each rank from `/usr/bin/time -v` (GNU time wraps every rank:
`mpiexec -n N /usr/bin/time -v signorini ...`); the CSV has the maximum over ranks and the sum over ranks (MB).

The elastic-solve ratio.  ratio = contact_solve / elastic_solve, where
  contact_solve  the ContactSolve stage of the contact run (summary timings.contact_solve: every active-set iteration,
                 assembly included, output excluded),
  elastic_solve  the ContactSolve stage of a separate *elastic reference run* on the same mesh, with the same preset and
                 the same ranks, which converges after exactly one saddle-point solve (checked): the same candidate
                 pairs (same matrix size and sparsity) but none ever active, and a support that makes K regular:
                   hertz: the flat top edge clamped (-bc_dirichlet top:x:y), the load an upward body force of the
                          same total (0.1 x area = 10.05; the top traction then acts on fixed dofs only) so the cylinder
                          hangs away from the flat, and the flat lowered by 1e-4 (below the touch tolerance nothing
                          touches at the start);
                   beam:  the pressure on the top reversed (-bc_pressure top:-0.2): the beam bends away from the floor.
  ratio_first = contact_solve / first_solve is also given: the first solve of the contact run (only the initially
  touching pair active) is the cost of one linear solve with that solver (symbolic analysis included), but the
  system is then held by one constraint only (for hertz it is singular in the rotation about the top centre: MUMPS
  still returns a consistent solution), and assembly is not included.

Status per run: ok, failed (non-zero exit; reason = the 'signorini: error:' line), timeout (stopped after --timeout,
or for a non-default preset after --timeout-factor times the default preset's wall time on the same mesh and ranks,
but not before --timeout-min), skipped (the same family/preset/ranks failed or timed out on a smaller mesh; --no-skip
runs it anyway).

Outputs (--out, default scripts/bench_out/, git-ignored): results.csv, results.md (tables), bench_time.png (contact
solve time vs dofs, log-log, per preset and ranks), bench_iterations.png (active-set iterations vs dofs),
bench_breakdown.png (phases of the default preset), meta.json, runs/<run>/ (stdout with -log_view, stderr,
summary.json, result.json).

Usage:
  scripts/benchmark.py --quick                       # small subset, < 2 minutes
  scripts/benchmark.py                               # the full matrix (hours on a 2-core machine)
  scripts/benchmark.py --max-dofs 300000 --presets mumps_cholesky,mumps_lu --ranks 1
  scripts/benchmark.py --report-only                 # tables and plots again from the runs/ already there
The executable is --exe (default $SIGNORINI_EXE, else build/signorini).
"""

import argparse
import csv
import datetime
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_PRESET = "mumps_cholesky"
AUTO_PRESET = "auto"  # no preset: the automatic solver choice (-contact_solver auto)

# Mesh size factors per family, with the displacement dofs they give (measured; the estimate only filters --max-dofs).
HERTZ_LEVELS = [1.0, 0.5, 0.25, 0.16, 0.1103, 0.0765]  # 12.6k, 49k, 195k, 472k, 992k, 2.06M dofs
HERTZ_QUICK = [1.0, 0.7]
BEAM_LEVELS = [0.2, 0.1, 0.05, 0.025, 0.0177, 0.0125]  # 8.4k, 33k, 130k, 516k, 1.03M, 2.06M dofs
BEAM_QUICK = [0.4]
SVK_LEVELS = [1.0, 0.25]
SVK_QUICK = [1.0]
HERTZ3D_LEVELS = [2.0, 1.4, 1.0, 0.7, 0.5, 0.4, 0.35]  # 6.2k, 16k, 40k, 110k, 290k, 556k, 823k dofs (the last does not fit in 24 GiB)
HERTZ3D_QUICK = [2.0]
CUBE_LEVELS = [1.0, 0.5, 0.25, 0.16]  # 14.7k, 108k, 824k, 3.06M dofs
CUBE_QUICK = [1.0]
CYLINDERS_LEVELS = [1.0, 0.5, 0.25, 0.14, 0.1]  # 20k, 77k, 300k, 1M, 2M dofs
CYLINDERS_QUICK = [1.0]
SPHERE_BLOCK_LEVELS = [1.0, 0.7, 0.5, 0.35, 0.28]  # 17k, 45k, 115k, 330k, 640k dofs
SPHERE_BLOCK_QUICK = [1.0]
CATTANEO_LEVELS = [2.0, 1.0, 0.5, 0.29]  # 21k, 83k, 330k, 1M dofs (measured 21,352, 83,368, 329,586)
CATTANEO_QUICK = [2.0]
CATTANEO3D_LEVELS = [1.5, 1.0, 0.6, 0.4]  # 12.9k, 38k, 159k, 500k dofs (measured 12,924, 38,274, 159,387)
CATTANEO3D_QUICK = [2.0]


def hertz_dofs(f):
    return 12100.0 / (f * f)


def hertz3d_dofs(f):
    return 40400.0 / f ** 2.8  # measured 6.2k, 16k, 40k, 110k at F = 2, 1.4, 1, 0.7


def beam_dofs(f):
    return 2.0 * (round(40 / f) + 1) * (round(4 / f) + 1)


def cylinders_dofs(f):
    return 19800.0 / (f * f)


def sphere_block_dofs(f):
    return 17200.0 / f ** 2.8  # measured 17k, 45k, 115k at F = 1, 0.7, 0.5


def cattaneo_dofs(f):
    return 83400.0 / (f * f)


def cattaneo3d_dofs(f):
    return 38300.0 / f ** 2.8


def cube_dofs(f):
    n = round(16 / f)
    return 3.0 * (n + 1) ** 3


FAMILIES = {
    "hertz": dict(case="options/hertz.yml", geo="meshes/hertz.geo", dofs=hertz_dofs, extra=[],
                  elastic=["-bc_dirichlet", "top:x:y", "-bc_body_force", "0,0.1",
                           "-obstacle_segments", "-12,-8.0001,12,-8.0001"]),
    "beam": dict(case="options/beam_on_floor.yml", geo="meshes/beam_bench.geo", dofs=beam_dofs, extra=[],
                 elastic=["-bc_pressure", "top:-0.2"]),
    # Elastic reference as for hertz: the top clamped, an upward body force of about the same total (P / 4 over the
    # octant's volume), the plane lowered by 1e-4.
    "hertz3d": dict(case="options/hertz3d.yml", geo="meshes/hertz3d.geo", dofs=hertz3d_dofs, extra=[],
                    elastic=["-bc_dirichlet", "symmetry_x:x,symmetry_y:y,top:x:y:z", "-bc_body_force", "0,0,0.00716",
                             "-obstacle_planes", "0,0,-10.0001,0,0,1"]),
    # The hexahedral cube indented by a sphere (options/cube_under_sphere.yml); elastic reference: a pressure on the
    # top, the sphere out of reach (no pair: no multiplier).
    "cube": dict(case="options/cube_under_sphere.yml", geo="meshes/cube_bench.geo", dofs=cube_dofs, extra=[],
                 elastic=["-bc_pressure", "top:1", "-obstacle_spheres", "0.5,0.5,3,0.5"]),
    # Two bodies (-contact_pairs); elastic reference: the same mesh and materials without the case file's pair (no
    # multiplier), the upper body clamped at its top as well, a body force of about the load.
    "cylinders": dict(case="options/cylinders_2d.yml", geo="meshes/cylinders2d.geo", dofs=cylinders_dofs, extra=[],
                      elastic_replaces_case=True,
                      elastic=["-material_E", "upper:200,lower:600", "-material_nu", "upper:0.3,lower:0.2",
                               "-bc_dirichlet", "upper_top:x:y,lower_bottom_centre:x,lower_bottom:y",
                               "-bc_body_force", "0,-0.05"]),
    "sphere_block": dict(case="options/sphere_on_block.yml", geo="meshes/sphere_on_block.geo",
                         dofs=sphere_block_dofs, extra=[],
                         elastic_replaces_case=True,
                         elastic=["-material_E", "ball:200,block:100", "-material_nu", "ball:0.3,block:0.35",
                                  "-bc_dirichlet", "symmetry_x:x,symmetry_y:y,block_bottom:z,top:x:y:z",
                                  "-bc_body_force", "0,0,-0.00716"]),
    # Friction: the reference is the frictionless solve of the same case and path (any number of solves).
    "cattaneo": dict(case="options/cattaneo2d.yml", geo="meshes/cattaneo2d.geo", dofs=cattaneo_dofs, extra=[],
                     elastic=["-contact_friction", "0"], reference_is_frictionless=True),
    "cattaneo3d": dict(case="options/cattaneo3d.yml", geo="meshes/cattaneo3d.geo", dofs=cattaneo3d_dofs, extra=[],
                       elastic=["-contact_friction", "0"], reference_is_frictionless=True),
    "svk": dict(case="options/hertz.yml", geo="meshes/hertz.geo", dofs=hertz_dofs,
                extra=["-material_model", "svk", "-load_steps", "3"], elastic=None),
}

EVENTS = ["MatCholFctrSym", "MatCholFctrNum", "MatLUFactorSym", "MatLUFactorNum", "MatSolve", "MatMult", "PCSetUp",
          "PCApply", "KSPSolve", "KSPSetUp", "SigAssembly", "SigSolve", "SigActiveSet", "PCGAMGGraph_AGG",
          "PCGAMGCoarse_AGG", "PCGAMGProl_AGG", "PCGAMGOptProl_AGG", "MatPtAP", "KSPGMRESOrthog"]

CSV_FIELDS = [
    "family", "level", "preset", "ranks", "status", "reason", "dofs", "multipliers", "candidate_nodes", "active_pairs",
    "active_set_iterations", "solves", "load_steps", "krylov", "krylov_max_per_solve",
    "t_mesh", "t_setup", "t_assembly", "t_factor_sym", "t_factor_num", "t_pc_setup", "t_solve", "t_output",
    "t_contact_solve", "t_total", "t_first_solve", "t_wall",
    "elastic_status", "elastic_multipliers", "elastic_solves", "t_elastic_solve", "t_elastic_pc_setup",
    "t_elastic_solve_only", "ratio", "ratio_first",
    "rss_max_mb", "rss_sum_mb", "elastic_rss_max_mb",
    "hertz_a", "hertz_a_computed", "err_a_pct", "hertz_p0", "hertz_p0_computed", "err_p0_pct",
    "load1_before", "t_limit", "run_id"]


# ----------------------------------------------------------------------------------------------------------- parsing
def parse_log_view(text):
    """Stages (avg time) and events (max time over ranks, count) of PETSc's -log_view; events per stage and summed."""
    stages, events, per_stage = {}, {}, {}
    in_stages, stage = False, None
    for line in text.splitlines():
        if line.startswith("Summary of Stages"):
            in_stages = True
            continue
        if in_stages:
            m = re.match(r"^\s*\d+:\s+(.+?):\s+([0-9.eE+-]+)\s", line)
            if m:
                stages[m.group(1).strip()] = float(m.group(2))
                continue
            if line.startswith("---"):
                in_stages = False
            continue
        if line.startswith("Object Type"):
            break
        m = re.match(r"^--- Event Stage \d+: (.+?)\s*$", line)
        if m:
            stage = m.group(1)
            continue
        m = re.match(r"^(\S+)\s+(\d+)\s+[0-9.]+\s+([0-9.eE+-]+)\s+[0-9.]+\s", line)
        if m and stage is not None:
            name, count, t = m.group(1), int(m.group(2)), float(m.group(3))
            per_stage.setdefault(stage, {})[name] = (count, t)
            c0, t0 = events.get(name, (0, 0.0))
            events[name] = (c0 + count, t0 + t)
    return stages, events, per_stage


def parse_rss_kb(text):
    return [int(x) for x in re.findall(r"Maximum resident set size \(kbytes\):\s*(\d+)", text)]


def error_line(stdout, stderr):
    for line in (stderr + "\n" + stdout).splitlines():
        if "signorini: error:" in line:
            return line.strip()[line.strip().find("signorini: error:") + len("signorini: error:"):].strip()
    for line in stderr.splitlines():
        if "Caught signal" in line:  # a crash (PETSc's signal handler), not a reported error
            return "crashed: " + line.split("ERROR:", 1)[-1].strip()
    for line in stderr.splitlines():
        if "PETSC ERROR:" in line and re.search(r"ERROR:\s*\w", line):
            return line.split("ERROR:", 1)[-1].strip()
    return ""


# --------------------------------------------------------------------------------------------------------- execution
def child_env():
    env = dict(os.environ)
    env.pop("PETSC_OPTIONS", None)  # runs must not pick up a user's options
    env.update(OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    if os.geteuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


def command(args, fam, level, preset, ranks, outdir, elastic):
    f = FAMILIES[fam]
    cmd = ["mpiexec", "-n", str(ranks), "--bind-to", "none"]
    if ranks > (os.cpu_count() or 1):
        cmd.append("--oversubscribe")
    # A two-body family's reference replaces the case file (its pair would add multipliers).
    case = [] if elastic and f.get("elastic_replaces_case") else ["-options_file", f["case"]]
    cmd += ["/usr/bin/time", "-v", args.exe] + case + ([] if preset == AUTO_PRESET else
                                           ["-options_file", "options/solver/%s.yml" % preset]) + [
            "-mesh_file", f["geo"], "-mesh_size_factor", repr(level)] + f["extra"]
    if elastic:
        cmd += f["elastic"]
    cmd += ["-output_dir", outdir, "-log_view", "-contact_monitor", "-options_left", "0"]
    return cmd


def run_one(args, fam, level, preset, ranks, elastic=False, limit=None):
    """Runs (or reloads with --resume/--report-only) one executable run; returns its result dict."""
    limit = limit or args.timeout
    run_id = "%s_F%g_%s_np%d%s" % (fam, level, preset, ranks, "_elastic" if elastic else "")
    rdir = os.path.join(args.out, "runs", run_id)
    rfile = os.path.join(rdir, "result.json")
    if (args.resume or args.report_only) and os.path.exists(rfile):
        with open(rfile) as fh:
            res = json.load(fh)
        if res["status"] == "failed":  # the reason again, from the run's own output
            with open(os.path.join(rdir, "stdout.txt")) as fo, open(os.path.join(rdir, "stderr.txt")) as fe:
                res["reason"] = error_line(fo.read(), fe.read()) or res["reason"]
        return res
    if args.report_only:
        return None
    if os.path.isdir(rdir):
        shutil.rmtree(rdir)
    os.makedirs(rdir)
    sol = os.path.join(rdir, "solution")
    cmd = command(args, fam, level, preset, ranks, sol, elastic)
    load1 = os.getloadavg()[0]
    t0 = time.time()
    status = "ok"
    with open(os.path.join(rdir, "stdout.txt"), "w") as out, open(os.path.join(rdir, "stderr.txt"), "w") as err:
        proc = subprocess.Popen(cmd, cwd=REPO, env=child_env(), stdout=out, stderr=err, start_new_session=True)
        try:
            rc = proc.wait(timeout=limit)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGTERM)  # the process group of this run only
            try:
                proc.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
            rc, status = None, "timeout"
    wall = time.time() - t0
    with open(os.path.join(rdir, "stdout.txt")) as fh:
        stdout = fh.read()
    with open(os.path.join(rdir, "stderr.txt")) as fh:
        stderr = fh.read()
    res = dict(run_id=run_id, family=fam, level=level, preset=preset, ranks=ranks, elastic=elastic,
               command=" ".join(cmd), status=status, reason="", t_wall=wall, t_limit=limit, load1_before=load1,
               rss_kb=parse_rss_kb(stderr))
    if status == "timeout":
        res["reason"] = "killed after %.0f s (time limit: see --timeout, --timeout-factor)" % limit
    elif rc != 0:
        res["status"] = "failed"
        res["reason"] = error_line(stdout, stderr) or "exit status %s" % rc
    summary_path = os.path.join(sol, "summary.json")
    if res["status"] == "ok" and os.path.exists(summary_path):
        with open(summary_path) as fh:
            res["summary"] = json.load(fh)
        shutil.copy(summary_path, os.path.join(rdir, "summary.json"))
    elif res["status"] == "ok":
        res["status"], res["reason"] = "failed", "no summary.json"
    # Sizes are printed before a failure too.
    m = re.search(r"unknowns: (\d+) displacements, (\d+) multipliers", stdout)
    if m:
        res["dofs"], res["multipliers"] = int(m.group(1)), int(m.group(2))
    res["stages"], ev, per_stage = parse_log_view(stdout)
    res["events"] = ev
    res["events_contact"] = per_stage.get("ContactSolve", {})
    shutil.rmtree(sol, ignore_errors=True)  # solution.h5 etc. can be hundreds of MB
    with open(rfile, "w") as fh:
        json.dump(res, fh, indent=1)
    return res


# ----------------------------------------------------------------------------------------------------------- records
def ev_time(events, *names):
    return sum(events.get(n, (0, 0.0))[1] for n in names)


def record(res, ela):
    """One CSV row from a contact run and its elastic reference."""
    row = {k: "" for k in CSV_FIELDS}
    row.update(family=res["family"], level=res["level"], preset=res["preset"], ranks=res["ranks"],
               status=res["status"], reason=res.get("reason", ""), run_id=res["run_id"],
               load1_before=round(res.get("load1_before", 0), 2), t_limit=res.get("t_limit", ""))
    if res["status"] == "skipped":
        return row
    row["t_wall"] = res.get("t_wall", "")
    row["dofs"] = res.get("dofs", "")
    row["multipliers"] = res.get("multipliers", "")
    rss = res.get("rss_kb") or []
    if rss:
        row["rss_max_mb"] = round(max(rss) / 1024.0, 1)
        row["rss_sum_mb"] = round(sum(rss) / 1024.0, 1)
    ev, evc = res.get("events", {}), res.get("events_contact", {})
    if ev:
        row["t_factor_sym"] = ev_time(ev, "MatCholFctrSym", "MatLUFactorSym", "SigMumpsAnalysis", "SigCholAnalysis")
        row["t_factor_num"] = ev_time(ev, "MatCholFctrNum", "MatLUFactorNum", "SigMumpsFactor", "SigCholFactor",
                                      "SigSchurFactor")
    s = res.get("summary")
    if s:
        t = s["timings"]
        it = s["iterations"]
        hist = it.get("history", [])
        row.update(dofs=s["problem"]["displacement_dofs"], multipliers=s["problem"]["multipliers"],
                   candidate_nodes=s["problem"]["candidate_nodes"], active_pairs=s["contact"]["active_pairs"],
                   active_set_iterations=it["active_set"], solves=it["solves"], load_steps=it["load_steps"],
                   krylov=it["krylov"], krylov_max_per_solve=max([h["krylov"] for h in hist] or [0]),
                   t_mesh=t["mesh"], t_setup=t["setup"], t_output=t["output"], t_contact_solve=t["contact_solve"],
                   t_total=t["total"], t_first_solve=hist[0]["solve_time"] if hist else "")
        if evc:
            row["t_assembly"] = ev_time(evc, "SigAssembly")
            # Factorisations: the PC's (PCSetUp), or with -contact_reuse_factorization the one MUMPS factorisation
            # and the dense factorisations of the Schur complement.
            fac = ev_time(evc, "PCSetUp", "SigMumpsAnalysis", "SigMumpsFactor", "SigCholAnalysis", "SigCholFactor",
                          "SigSchurFactor")
            row["t_pc_setup"] = fac
            row["t_solve"] = max(0.0, ev_time(evc, "SigSolve") - fac)
        else:
            row["t_assembly"] = t.get("assembly", "")
        if hist:
            row["ratio_first"] = t["contact_solve"] / hist[0]["solve_time"]
        h = s.get("hertz")
        if h:
            row.update(hertz_a=h["a"], hertz_a_computed=h["a_computed"], hertz_p0=h["p0"],
                       hertz_p0_computed=h["p0_computed"],
                       err_a_pct=100 * (h["a_computed"] - h["a"]) / h["a"],
                       err_p0_pct=100 * (h["p0_computed"] - h["p0"]) / h["p0"])
    elif res.get("stages"):
        # A failed or stopped run: the stage times up to the failure (-log_view stage summary, average over ranks).
        st = res["stages"]
        row.update(t_mesh=st.get("Mesh", ""), t_setup=st.get("Setup", ""), t_contact_solve=st.get("ContactSolve", ""),
                   t_factor_sym="", t_factor_num="")
    if ela:
        row["elastic_status"] = ela["status"]
        if ela.get("rss_kb"):
            row["elastic_rss_max_mb"] = round(max(ela["rss_kb"]) / 1024.0, 1)
        es = ela.get("summary")
        if es:
            row["elastic_multipliers"] = es["problem"]["multipliers"]
            row["elastic_solves"] = es["iterations"]["solves"]
            if es["iterations"]["solves"] != 1 and not FAMILIES[res["family"]].get("reference_is_frictionless"):
                row["elastic_status"] = "not one solve (%d)" % es["iterations"]["solves"]
            row["t_elastic_solve"] = es["timings"]["contact_solve"]
            evc = ela.get("events_contact", {})
            if evc:
                row["t_elastic_pc_setup"] = ev_time(evc, "PCSetUp")
                row["t_elastic_solve_only"] = max(0.0, ev_time(evc, "SigSolve") - ev_time(evc, "PCSetUp"))
            if s and row["elastic_status"] == "ok":
                row["ratio"] = s["timings"]["contact_solve"] / es["timings"]["contact_solve"]
        elif ela["status"] != "ok":
            row["elastic_status"] = "%s: %s" % (ela["status"], ela.get("reason", ""))
    return row


def fmt(v, nd=3):
    if v == "" or v is None:
        return ""
    if isinstance(v, float):
        if v == 0:
            return "0"
        if abs(v) >= 100:
            return "%.0f" % v
        return ("%%.%dg" % nd) % v
    return str(v)


def markdown(rows, meta):
    lines = ["# signorini benchmark results", "",
             "Generated by `scripts/benchmark.py` on %s (%s); git %s; executable %s." %
             (meta["date"], meta["machine"], meta["git"], meta["exe"]),
             "Times in seconds (maximum over ranks), memory in MB (peak RSS from /usr/bin/time -v, maximum over ranks).",
             "`factor` = PCSetUp in the contact solve (all factorisations / preconditioner set-ups), `solve` = SigSolve - PCSetUp, "
             "`contact` = the ContactSolve stage, `elastic` = the ContactSolve stage of the elastic reference run (one solve), "
             "`ratio` = contact / elastic, `ratio1` = contact / first solve.", ""]
    head = ("| preset | np | F | dofs | mult | AS its | Krylov | mesh | setup | assembly | factor | solve | "
            "output | contact | elastic | ratio | ratio1 | RSS | a err % | p0 err % | status |")
    for fam in ["hertz", "hertz3d", "cube", "beam", "svk"]:
        fr = [r for r in rows if r["family"] == fam]
        if not fr:
            continue
        lines += ["## %s" % fam, "", head, "|" + "|".join([" --- "] * (head.count("|") - 1)) + "|"]
        skipped = [r for r in fr if r["status"] == "skipped"]
        for r in fr:
            if r["status"] == "skipped":
                continue
            status = r["status"] if r["status"] == "ok" else "%s: %s" % (r["status"], r["reason"][:110])
            if r["status"] in ("failed", "timeout") and r["t_wall"] != "":
                status += " (after %.0f s)" % r["t_wall"]
            lines.append("| " + " | ".join([
                r["preset"], str(r["ranks"]), fmt(r["level"]), fmt(r["dofs"]), fmt(r["multipliers"]),
                fmt(r["active_set_iterations"]), fmt(r["krylov"]), fmt(r["t_mesh"]), fmt(r["t_setup"]),
                fmt(r["t_assembly"]), fmt(r["t_pc_setup"]), fmt(r["t_solve"]), fmt(r["t_output"]),
                fmt(r["t_contact_solve"]), fmt(r["t_elastic_solve"]), fmt(r["ratio"], 2), fmt(r["ratio_first"], 2),
                fmt(r["rss_max_mb"]), fmt(r["err_a_pct"], 2), fmt(r["err_p0_pct"], 2), status.replace("|", "/")])
                + " |")
        if skipped:
            groups = {}
            for r in skipped:
                groups.setdefault((r["preset"], r["ranks"], r["reason"]), []).append(fmt(r["dofs"]) or "F=%g" % r["level"])
            lines += ["", "Not run (the same preset and ranks failed or timed out on a smaller mesh): " + "; ".join(
                "%s np=%s at %s dofs (%s)" % (p, n, ", ".join(d), why) for (p, n, why), d in groups.items()) + "."]
        lines.append("")
    # Speed-up 1 -> 2 ranks.
    sp = speedups(rows)
    if sp:
        lines += ["## Speed-up from 1 to 2 ranks (contact solve; whole run in parentheses)", "",
                  "| family | preset | dofs | 1 rank | 2 ranks | speed-up | speed-up total |",
                  "| --- | --- | --- | --- | --- | --- | --- |"]
        for s in sp:
            lines.append("| %s | %s | %s | %s | %s | %.2f | %.2f |" % (
                s["family"], s["preset"], fmt(s["dofs"]), fmt(s["t1"]), fmt(s["t2"]), s["speedup"], s["speedup_total"]))
        lines.append("")
    return "\n".join(lines) + "\n"


def speedups(rows):
    out = []
    by = {(r["family"], r["level"], r["preset"], int(r["ranks"])): r for r in rows}
    for (fam, level, preset, n), r1 in sorted(by.items(), key=lambda kv: (kv[0][0], kv[0][2], -kv[0][1])):
        r2 = by.get((fam, level, preset, 2))
        if n != 1 or not r2 or r1["status"] != "ok" or r2["status"] != "ok":
            continue
        out.append(dict(family=fam, preset=preset, level=level, dofs=r1["dofs"], t1=r1["t_contact_solve"],
                        t2=r2["t_contact_solve"], speedup=r1["t_contact_solve"] / r2["t_contact_solve"],
                        speedup_total=r1["t_total"] / r2["t_total"]))
    return out


# ------------------------------------------------------------------------------------------------------------- plots
def plots(rows, outdir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("benchmark: matplotlib missing, no plots", file=sys.stderr)
        return []
    def style_axes(ax, title, ylabel):
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("displacement dofs", fontsize=8)
        ax.set_ylabel(ylabel, fontsize=8)
        ax.grid(True, which="both", lw=0.3)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)

    def save_figure(fig, outdir, name):
        fig.tight_layout()
        path = os.path.join(outdir, name)
        fig.savefig(path, dpi=80)
        plt.close(fig)
        return path

    fams = [f for f in ["hertz", "hertz3d", "cube", "beam", "svk"]
            if any(r["family"] == f and r["status"] == "ok" for r in rows)]
    if not fams:
        return []
    presets = sorted({r["preset"] for r in rows})
    colors = dict(zip(presets, ["C0", "C1", "C2", "C3", "C4", "C5", "C6", "C7"]))
    written = []

    def series(fam, preset, n, key):
        pts = sorted((r["dofs"], r[key]) for r in rows if r["family"] == fam and r["preset"] == preset and
                     int(r["ranks"]) == n and r["status"] == "ok" and r[key] != "")
        return [p[0] for p in pts], [p[1] for p in pts]

    # Time vs dofs.
    fig, axes = plt.subplots(1, len(fams), figsize=(5.2 * len(fams), 4.2), squeeze=False)
    for ax, fam in zip(axes[0], fams):
        for preset in presets:
            for n, ls in ((1, "-"), (2, "--")):
                x, y = series(fam, preset, n, "t_contact_solve")
                if x:
                    ax.loglog(x, y, ls, marker="o", ms=3, color=colors[preset], label="%s np=%d" % (preset, n))
            x, y = series(fam, preset, 1, "t_elastic_solve")
            if x and preset == DEFAULT_PRESET:
                ax.loglog(x, y, ":", marker="s", ms=3, color="k", label="elastic solve, %s np=1" % preset)
        xs = [r["dofs"] for r in rows if r["family"] == fam and r["status"] == "ok"]
        if xs:
            x0, x1 = min(xs), max(xs)
            ref = [r["t_contact_solve"] for r in rows if r["family"] == fam and r["status"] == "ok" and
                   r["dofs"] == x0]
            if ref:
                y0 = min(ref)
                ax.loglog([x0, x1], [y0, y0 * (x1 / x0)], color="0.7", lw=0.8, label="O(n)")
        style_axes(ax, {"hertz": "2D Hertz", "hertz3d": "3D Hertz (octant)",
                        "cube": "3D cube under a sphere", "beam": "beam on floor (regular K)",
                        "svk": "Hertz, svk, 3 load steps"}[fam], "contact solve time [s]")
    written.append(save_figure(fig, outdir, "bench_time.png"))

    # Active-set iterations vs dofs.
    fig, axes = plt.subplots(1, len(fams), figsize=(5.2 * len(fams), 3.8), squeeze=False)
    for ax, fam in zip(axes[0], fams):
        for preset in presets:
            for n, ls, mk in ((1, "-", "o"), (2, "--", "x")):
                x, y = series(fam, preset, n, "active_set_iterations")
                if x:
                    ax.semilogx(x, y, ls, marker=mk, ms=4, color=colors[preset], label="%s np=%d" % (preset, n))
        if fam not in ("svk", "hertz3d"):
            ax.axhline(10, color="r", lw=0.8, ls=":", label="target 10")
        ax.set_ylim(bottom=0)
        style_axes(ax, {"hertz": "2D Hertz", "hertz3d": "3D Hertz (octant)",
                        "cube": "3D cube under a sphere", "beam": "beam on floor",
                        "svk": "Hertz, svk, 3 load steps"}[fam],
                   "active-set iterations")
    written.append(save_figure(fig, outdir, "bench_iterations.png"))

    # Phases of the default preset on hertz, 1 rank.
    rr = sorted([r for r in rows if r["family"] == "hertz" and r["preset"] == DEFAULT_PRESET and int(r["ranks"]) == 1
                 and r["status"] == "ok" and r["t_pc_setup"] != ""], key=lambda r: r["dofs"])
    if rr:
        fig, ax = plt.subplots(figsize=(6, 3.8))
        parts = [("t_mesh", "mesh"), ("t_setup", "setup"), ("t_assembly", "assembly"),
                 ("t_pc_setup", "factorisations"), ("t_solve", "solves"), ("t_output", "output")]
        bottom = [0.0] * len(rr)
        labels = ["%.0fk" % (r["dofs"] / 1e3) for r in rr]
        for i, (k, name) in enumerate(parts):
            frac = [r[k] / r["t_total"] for r in rr]
            ax.bar(labels, frac, bottom=bottom, label=name, color="C%d" % i)
            bottom = [b + f for b, f in zip(bottom, frac)]
        ax.set_ylabel("fraction of the run", fontsize=8)
        ax.set_xlabel("displacement dofs (Hertz, %s, 1 rank)" % DEFAULT_PRESET, fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6, loc="lower left")
        written.append(save_figure(fig, outdir, "bench_breakdown.png"))
    return written


# -------------------------------------------------------------------------------------------------------------- main
def git_state():
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True,
                              text=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "src", "include"], cwd=REPO,
                               capture_output=True, text=True).stdout.strip()
        return head + ("+dirty(src)" if dirty else "")
    except OSError:
        return "unknown"


def machine():
    model = ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return "%s, %d cores" % (model or "cpu", os.cpu_count() or 0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--quick", action="store_true",
                    help="small subset, < 2 minutes: hertz F=1, 0.7 and hertz3d F=2 (direct presets), beam F=0.4 "
                         "(all presets), svk F=1")
    ap.add_argument("--max-dofs", type=float, default=2.1e6, help="largest mesh (estimated displacement dofs)")
    ap.add_argument("--presets", default="", help="comma list of options/solver/*.yml names (default: all)")
    ap.add_argument("--ranks", default="1,2", help="comma list of MPI rank counts (default 1,2)")
    ap.add_argument("--families", default="hertz,beam,svk,hertz3d", help="comma list of hertz, beam, svk, hertz3d, cube, "
                    "cylinders, sphere_block, cattaneo, cattaneo3d")
    ap.add_argument("--out", default=os.path.join(REPO, "scripts", "bench_out"), help="output folder")
    ap.add_argument("--exe", default=os.environ.get("SIGNORINI_EXE", os.path.join(REPO, "build", "signorini")))
    ap.add_argument("--timeout", type=float, default=None, help="seconds per run at most (default 1800, --quick 15)")
    ap.add_argument("--timeout-factor", type=float, default=50.0,
                    help="a run is also stopped after this many times the wall time of the default preset on the "
                         "same mesh and ranks (default 50), but not before --timeout-min")
    ap.add_argument("--timeout-min", type=float, default=180.0, help="see --timeout-factor (default 180 s)")
    ap.add_argument("--no-elastic", action="store_true", help="no elastic reference runs (no ratio)")
    ap.add_argument("--no-skip", action="store_true",
                    help="run larger meshes of a family/preset/ranks that failed or timed out on a smaller one")
    ap.add_argument("--resume", action="store_true", help="reuse runs/<run>/result.json already in --out")
    ap.add_argument("--report-only", action="store_true", help="only rebuild the CSV, tables and plots from --out")
    args = ap.parse_args()
    if args.timeout is None:
        args.timeout = 15.0 if args.quick else 1800.0
    args.out = os.path.abspath(args.out)
    args.exe = os.path.abspath(args.exe)
    if not args.report_only and not os.access(args.exe, os.X_OK):
        sys.exit("benchmark: no executable %s (build it, or pass --exe / SIGNORINI_EXE)" % args.exe)
    all_presets = sorted(os.path.basename(p)[:-4] for p in os.listdir(os.path.join(REPO, "options", "solver"))
                         if p.endswith(".yml"))
    all_presets = sorted(all_presets, key=lambda p: (p != DEFAULT_PRESET, p)) + [AUTO_PRESET]
    presets = [p for p in args.presets.split(",") if p] or all_presets
    for p in presets:
        if p not in all_presets:
            sys.exit("benchmark: unknown preset %s; expected one of %s" % (p, ", ".join(all_presets)))
    ranks = [int(n) for n in args.ranks.split(",") if n]
    families = [f for f in args.families.split(",") if f]
    for f in families:
        if f not in FAMILIES:
            sys.exit("benchmark: unknown family %s; expected hertz, beam, svk, hertz3d, cube, cylinders, "
                     "sphere_block, cattaneo, cattaneo3d" % f)
    os.makedirs(os.path.join(args.out, "runs"), exist_ok=True)

    levels = {"hertz": HERTZ_QUICK if args.quick else HERTZ_LEVELS,
              "beam": BEAM_QUICK if args.quick else BEAM_LEVELS,
              "svk": SVK_QUICK if args.quick else SVK_LEVELS,
              "hertz3d": HERTZ3D_QUICK if args.quick else HERTZ3D_LEVELS,
              "cube": CUBE_QUICK if args.quick else CUBE_LEVELS,
              "cylinders": CYLINDERS_QUICK if args.quick else CYLINDERS_LEVELS,
              "sphere_block": SPHERE_BLOCK_QUICK if args.quick else SPHERE_BLOCK_LEVELS,
              "cattaneo": CATTANEO_QUICK if args.quick else CATTANEO_LEVELS,
              "cattaneo3d": CATTANEO3D_QUICK if args.quick else CATTANEO3D_LEVELS}
    plan = []
    for fam in families:
        fam_presets = [DEFAULT_PRESET] if fam == "svk" else presets
        if args.quick and fam in ("hertz", "hertz3d"):
            # Expected to fail there (singular K) and slow to do so: --quick runs the fieldsplits on the beam only.
            fam_presets = [p for p in fam_presets if not p.startswith("fieldsplit")]
        for level in levels[fam]:
            if FAMILIES[fam]["dofs"](level) > args.max_dofs:
                continue
            for preset in fam_presets:
                for n in ranks:
                    plan.append((fam, level, preset, n))
    meta = dict(date=datetime.datetime.now().isoformat(timespec="seconds"), machine=machine(), git=git_state(),
                exe=args.exe, argv=sys.argv, timeout=args.timeout)
    meta_path = os.path.join(args.out, "meta.json")
    if (args.report_only or args.resume) and os.path.exists(meta_path):
        with open(meta_path) as fh:
            old = json.load(fh)  # the runs were made with that build and at that time
        meta = dict(old, **({"report_date": meta["date"]} if args.report_only else
                            {"resumed": old.get("resumed", []) + [meta["date"] + " git " + meta["git"]]}))
    print("benchmark: %d runs (plus elastic references) into %s" % (len(plan), args.out), flush=True)

    rows, failed, walls = [], {}, {}
    t_start = time.time()
    for i, (fam, level, preset, n) in enumerate(plan):
        key = (fam, preset, n)
        if key in failed and not args.no_skip:
            res = dict(run_id="%s_F%g_%s_np%d" % (fam, level, preset, n), family=fam, level=level, preset=preset,
                       ranks=n, status="skipped", reason="%s at F=%g" % failed[key])
            rows.append(record(res, None))
            continue
        limit = args.timeout
        if (fam, level, n) in walls and preset != DEFAULT_PRESET:
            limit = min(args.timeout, max(args.timeout_min, args.timeout_factor * walls[(fam, level, n)]))
        res = run_one(args, fam, level, preset, n, limit=limit)
        if res is None:
            continue
        if preset == DEFAULT_PRESET and res["status"] == "ok":
            walls[(fam, level, n)] = res["t_wall"]
        ela = None
        if res["status"] == "ok" and FAMILIES[fam]["elastic"] and not args.no_elastic:
            ela = run_one(args, fam, level, preset, n, elastic=True, limit=limit)
        if res["status"] != "ok":
            failed[key] = (res["status"], level)
        row = record(res, ela)
        rows.append(row)
        print("[%3d/%d %6.0fs] %-5s F=%-6g %-16s np=%d %-7s dofs=%-8s its=%-3s contact=%-8s ratio=%-6s %s" % (
            i + 1, len(plan), time.time() - t_start, fam, level, preset, n, row["status"], row["dofs"],
            row["active_set_iterations"], fmt(row["t_contact_solve"]), fmt(row["ratio"], 2),
            row["reason"][:80]), flush=True)
        write_outputs(args, rows, meta, plot=False)
    write_outputs(args, rows, meta, plot=True)


def fill_sizes(rows):
    """Failed, stopped and skipped runs print no sizes: take them from a run of the same mesh."""
    sizes = {(r["family"], r["level"]): (r["dofs"], r["multipliers"]) for r in rows if r["status"] == "ok"}
    for r in rows:
        if r["dofs"] == "" and (r["family"], r["level"]) in sizes:
            r["dofs"], r["multipliers"] = sizes[(r["family"], r["level"])]


def write_outputs(args, rows, meta, plot):
    fill_sizes(rows)
    with open(os.path.join(args.out, "results.csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=CSV_FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: (("%.6g" % v) if isinstance(v, float) else v) for k, v in r.items()})
    with open(os.path.join(args.out, "results.md"), "w") as fh:
        fh.write(markdown(rows, meta))
    with open(os.path.join(args.out, "meta.json"), "w") as fh:
        json.dump(meta, fh, indent=1)
    if plot:
        for p in plots(rows, args.out):
            print("benchmark: wrote %s" % p)
        print("benchmark: wrote %s and %s" % (os.path.join(args.out, "results.csv"),
                                               os.path.join(args.out, "results.md")))


if __name__ == "__main__":
    main()
