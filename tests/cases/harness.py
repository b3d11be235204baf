"""The case harness: Runner runs the signorini executable under mpiexec and records the checks, Result reads the
files of one run, @test registers a test by name in TESTS, and the helpers below are those several test modules share.

Every run of the executable fails the test on an option that was set but not used and on PETSc memory still
allocated at PetscFinalize (-malloc_dump), whether the run succeeds or fails. A run expected to succeed (Runner.run)
fails the test on a non-zero exit and on a PETSc error message; then its summary.json (and, where a test asks,
nodes.csv or solution.h5) is checked against the test's expectations. A run allowed to fail (Runner.run_any) fails the
test unless it either succeeds as above or fails cleanly: one "signorini: error:" line, no PETSc error message, no
summary.json, after the set-up (whose check of unused options it has then passed).

Each test gets a Runner: runner.run(args, label) runs the executable on runner.np ranks and returns the Result of the
run; runner.expect_* record the checks. Integers (pairs, active-set iterations) are compared exactly; every
floating-point tolerance is justified next to it by the physics or the arithmetic it stands for.
"""

import json
import os
import re
import subprocess
import time

import numpy as np


UNUSED_OPTION = re.compile(r"WARNING! option .* was set but not used|WARNING! There are options you set that were not "
                           r"used|^Option left: ", re.MULTILINE)
LEAKED_MEMORY = re.compile(r"^\[\s*\d+\]\s*\d+ bytes \S+\(\) at ", re.MULTILINE)
PETSC_ERROR = re.compile(r"PETSC ERROR|signorini: error:")
ERROR_LINE = "signorini: error:"
# The program's own refusal of an option that nothing read (Options::CheckUnusedOptions).
NEVER_READ = re.compile(r"set but never read")
# The run's header (PrintHeader), printed once the set-up has checked every option but the saddle-point solver's.
HEADER = re.compile(r"^\s*unknowns:", re.MULTILINE)


class CheckFailed(Exception):
    """A run or an expectation failed; the message says which and by how much."""


class Skipped(Exception):
    """The test cannot run here (a tool it needs is missing); the message says which. Exit status 77 (CTest SKIP)."""


class Result:
    """The files of one run: summary (the parsed summary.json), and on demand the node table and the HDF5 file."""

    def __init__(self, label, directory, output):
        self.label = label
        self.dir = directory
        self.output = output
        with open(os.path.join(directory, "summary.json")) as f:
            self.summary = json.load(f)

    def get(self, path):
        """A summary entry by dotted path, e.g. 'contact.active_pairs' or 'contact.contact_force.1'."""
        value = self.summary
        for key in path.split("."):
            value = value[int(key)] if isinstance(value, list) else value[key]
        return value

    def nodes(self):
        """nodes.csv as a structured array sorted by node_tag (columns node_tag,x,y,u_x,u_y,lambda,pressure,gap,
        active)."""
        table = np.genfromtxt(os.path.join(self.dir, "nodes.csv"), delimiter=",", names=True)
        return np.sort(table, order="node_tag")

    def cell_field(self, name, step=1):
        """A cell field of solution.h5 (one row per cell, in the file's cell order)."""
        import h5py

        with h5py.File(os.path.join(self.dir, "solution.h5"), "r") as f:
            return f["step_%06d/%s" % (step, name)][()]

    def solution(self, step=1):
        """(coordinates N x dim, cells as a list of node-index arrays, displacement N x dim) from solution.h5."""
        import h5py

        with h5py.File(os.path.join(self.dir, "solution.h5"), "r") as f:
            dim = self.get("mesh.dim")
            xyz = f["mesh/coordinates"][:, :dim]
            topo = f["mesh/topology"][()]
            u = f["step_%06d/displacement" % step][:, :dim]
        if topo.ndim == 2:
            cells = list(topo)
        else:  # XDMF mixed topology: a type id (4 triangle, 5 quadrilateral, 6 tetrahedron, 7 pyramid, 9 hexahedron)
            cells, i = [], 0  # before each cell's nodes
            while i < len(topo):
                n = {4: 3, 5: 4, 6: 4, 7: 5, 9: 8}[int(topo[i])]
                cells.append(topo[i + 1:i + 1 + n])
                i += n + 1
        return xyz, cells, u


class Runner:
    """Runs the executable in fresh output directories under one temporary directory and records the checks."""

    def __init__(self, exe, mpiexec, np_, source_dir, workdir, verbose):
        self.exe, self.mpiexec, self.np, self.source_dir = exe, mpiexec, np_, source_dir
        self.workdir, self.verbose = workdir, verbose
        self.failures = []
        self.count = 0  # runs
        self.checks = 0  # recorded checks

    def path(self, relative):
        return os.path.join(self.source_dir, relative)

    def launch(self, args, label, np_, heap_check):
        """Runs `mpiexec -n NP exe args -output_dir DIR [-malloc_debug (NP = 1)] -malloc_dump` in a fresh output
        directory; returns (command, exit status, output, directory). Raises CheckFailed when the output shows an
        option set but not used or PETSc memory leaked, whatever the exit status."""
        self.count += 1
        directory = os.path.join(self.workdir, "%02d_%s_np%d" % (self.count, re.sub(r"\W+", "_", label), np_))
        cmd = [self.mpiexec, "-n", str(np_), self.exe] + [str(a) for a in args] + [
            "-output_dir", directory] + (["-malloc_debug"] if heap_check and np_ == 1 else []) + ["-malloc_dump"]
        start = time.time()
        proc = subprocess.run(cmd, cwd=self.source_dir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        elapsed = time.time() - start
        print("run %-40s np %d  %5.2f s: %s" % (label, np_, elapsed, " ".join(cmd)))
        out = proc.stdout
        if self.verbose:
            print(out)
        problems = []
        if UNUSED_OPTION.search(out) or NEVER_READ.search(out):
            problems.append("an option was set but not used")
        if LEAKED_MEMORY.search(out):
            problems.append("PETSc memory leaked (-malloc_dump)")
        if problems:
            raise CheckFailed("run '%s' failed (%s; exit status %d):\n  %s\n%s" % (
                label, "; ".join(problems), proc.returncode, " ".join(cmd), out))
        return cmd, proc.returncode, out, directory

    def run(self, args, label, np_=None, heap_check=True):
        """Runs `mpiexec -n NP exe args -output_dir DIR -malloc_debug -malloc_dump` and returns its Result; raises
        CheckFailed on a failed run (exit status, PETSc error, unused option, leaked memory). heap_check=False drops
        -malloc_debug (the validation of the whole PETSc heap at every allocation) and keeps the leak check. The
        validation runs on one rank only: the leak check stays on every run, but on 2 ranks the validation slowed a
        GAMG set-up 12 times and five case tests from 47 to 71 s (the suite neared its 20 minutes); every test's
        1-rank runs keep it."""
        cmd, status, out, directory = self.launch(args, label, np_ or self.np, heap_check)
        return self.converged(cmd, status, out, directory, label)

    def converged(self, cmd, status, out, directory, label):
        """The Result of a run that must have succeeded, its certificate checked; CheckFailed otherwise."""
        problems = []
        if status != 0:
            problems.append("exit status %d" % status)
        if PETSC_ERROR.search(out):
            problems.append("an error message in the output")
        if not problems and not os.path.exists(os.path.join(directory, "summary.json")):
            problems.append("no summary.json")
        if problems:
            raise CheckFailed("run '%s' failed (%s):\n  %s\n%s" % (label, "; ".join(problems), " ".join(cmd), out))
        result = Result(label, directory, out)
        self.expect_certificate(result)
        return result

    def expect_certificate(self, result):
        """The state is a contact solution: the status comes from the certificate, and each residual of the
        certificate is within its threshold (the thresholds are the program's, from -contact_gap_tol, c and
        -newton_rtol/-newton_atol); the summary's penetration agrees with the certificate's."""
        label, c = result.label, result.get("certificate")
        self.expect_equal("%s: status" % label, result.get("status"), "converged")
        self.expect_equal("%s: certificate satisfied" % label, c["satisfied"], True)
        for what, value, bound in (("max penetration", c["max_penetration"], c["gap_tol"]),
                                   ("-min active lambda", -c["min_active_lambda"], c["lambda_tol"]),
                                   ("max inactive |lambda|", c["max_inactive_lambda"], c["lambda_tol"]),
                                   ("complementarity", c["complementarity"], c["complementarity_tol"]),
                                   ("equilibrium residual", c["equilibrium"], c["equilibrium_tol"]),
                                   ("summary max penetration", result.get("contact.max_penetration"), c["gap_tol"])):
            self.expect_true("%s: certificate %s %.3g <= %.3g" % (label, what, value, bound), value <= bound)
        self.expect_equal("%s: certificate changes" % label, c["changes"], 0)

    def run_any(self, args, label):
        """Runs like run() but accepts a clean failure: returns (exit status, output, Result or None). A run that exits
        0 is checked as run() checks it (Result); one that fails must have passed the set-up (its header printed: the
        program's own check of unused options passed), print exactly one "signorini: error:" line and no PETSc error
        message, and publish no summary.json; otherwise CheckFailed. Leaks and unused options fail either way. A hang
        is left to CTest's TIMEOUT."""
        cmd, status, out, directory = self.launch(args, label, self.np, heap_check=False)
        if status == 0:
            return status, out, self.converged(cmd, status, out, directory, label)
        problems = []
        # Counted anywhere in a line: with -info, another rank's lines may run into the error line.
        if out.count(ERROR_LINE) != 1:
            problems.append("'%s' %d times, expected once" % (ERROR_LINE, out.count(ERROR_LINE)))
        if "PETSC ERROR" in out:
            problems.append("a PETSc error message in the output")
        if not HEADER.search(out):
            problems.append("it stopped before its header (set-up not passed)")
        if os.path.exists(os.path.join(directory, "summary.json")):
            problems.append("summary.json published by a failed run")
        if problems:
            raise CheckFailed("run '%s' did not fail cleanly (exit status %d; %s):\n  %s\n%s" % (
                label, status, "; ".join(problems), " ".join(cmd), out))
        return status, out, None

    def record(self, ok, text):
        self.checks += 1
        print("  %s %s" % ("ok  " if ok else "FAIL", text))
        if not ok:
            self.failures.append(text)
        return ok

    def expect_equal(self, what, got, want):
        """Exact comparison (integers, strings, flags)."""
        return self.record(got == want, "%s: %r, expected %r" % (what, got, want))

    def expect_close(self, what, got, want, rtol, atol=0.0):
        """|got - want| <= rtol |want| + atol, elementwise for arrays; reports the worst entry."""
        got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
        if got.shape != want.shape:
            return self.record(False, "%s: shape %s, expected %s" % (what, got.shape, want.shape))
        err = np.abs(got - want)
        bound = rtol * np.abs(want) + atol
        ok = bool(np.all(err <= bound)) and bool(np.all(np.isfinite(got)))
        i = int(np.argmax(err / np.maximum(bound, 1e-300))) if err.size else 0
        g, w, e = (got.flat[i], want.flat[i], err.flat[i]) if err.size else (got, want, 0.0)
        scale = abs(w) if abs(w) > 0 else 1.0
        return self.record(ok, "%s: %.12g, expected %.12g (error %.3g, relative %.3g; rtol %g, atol %g%s)" % (
            what, g, w, e, e / scale, rtol, atol, "" if got.size == 1 else ", worst of %d" % got.size))

    def expect_true(self, what, ok):
        return self.record(bool(ok), what)


TESTS = {}


def test(name):
    def register(function):
        TESTS[name] = function
        return function

    return register


def yaml_options(path):
    """The (key, value) pairs of a flat options YAML file, in order (comments and blank lines skipped)."""
    options = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                key, _, value = line.partition(":")
                options.append((key.strip(), value.strip()))
    return options


def options_args(runner, yml, drop=()):
    """The options of a case file as command-line arguments, without the keys in drop; its mesh_file, relative to the
    file's directory, made relative to the source directory as the command line reads it."""
    args = []
    for key, value in yaml_options(runner.path(yml)):
        if key == "mesh_file":
            value = os.path.normpath(os.path.join(os.path.dirname(yml), value))
        if key not in drop:
            args += ["-" + key, value]
    return args


def rate(h, e):
    """Observed convergence rates between successive meshes."""
    return np.log(e[:-1] / e[1:]) / np.log(h[:-1] / h[1:])


def displacement(nodes):
    """Displacements of a node table: (u_x, u_y), and u_z for a 3D mesh."""
    return np.column_stack([nodes[k] for k in ("u_x", "u_y", "u_z") if k in nodes.dtype.names])


def coordinates(nodes):
    """Coordinates of a node table: (x, y), and z for a 3D mesh."""
    return np.column_stack([nodes[k] for k in ("x", "y", "z") if k in nodes.dtype.names])


def check_same_mesh(runner, what, a, b):
    """Both node tables list the same node tags at the same coordinates."""
    runner.expect_true("%s: same node tags (%d)" % (what, len(a)),
                       len(a) == len(b) and np.array_equal(a["node_tag"], b["node_tag"]))
    # Coordinates come from the same mesh file (or the same gmsh run written in another format, %.16g in ASCII).
    runner.expect_close("%s: node coordinates" % what, coordinates(b), coordinates(a), 0, 1e-14)


def accepted_step_iterations(result):
    """[load factor, iterations] of each accepted load step: the last attempt of each step in the history."""
    last = {}
    for r in result.get("iterations.history"):
        if r["step"] not in last or last[r["step"]][0] != r["load_factor"]:
            last[r["step"]] = [r["load_factor"], 0]
        last[r["step"]][1] += 1
    return [last[k] for k in sorted(last)]


def log_event_count(output, event):
    """The count of an event in the -log_view table of a run (summed over the stages), or 0."""
    return sum(int(m.group(1)) for m in re.finditer(r"^%s\s+(\d+)\s" % re.escape(event), output, re.M))


def arc_segments(cx, cy, radius, theta0, theta1, n):
    """The segments X0,Y0,X1,Y1,... of -obstacle_arcs CX,CY,R,THETA0,THETA1,N, as -obstacle_segments text."""
    t = np.radians(theta0 + (theta1 - theta0) * np.arange(n + 1) / n)
    x, y = cx + radius * np.cos(t), cy + radius * np.sin(t)
    return ",".join("%.17g,%.17g,%.17g,%.17g" % (x[k], y[k], x[k + 1], y[k + 1]) for k in range(n))


def expect_same_state(runner, ref, r, keys=("iterations.active_set", "contact.active_pairs", "contact.active_nodes"),
                      tol=1e-10):
    """Two runs of one problem (e.g. the same obstacle given two ways): the same summary integers keys, the same active
    nodes, and displacements and multipliers equal to round-off (tol of the largest value, 1e-10: the same active set
    gives the same linear system, assembled from coordinates that agree to the last digit or two; svk's states from
    two Newton paths agree to its tolerance, 1e-8)."""
    for key in keys:
        runner.expect_equal("%s: %s" % (r.label, key), r.get(key), ref.get(key))
    nodes, ref_nodes = r.nodes(), ref.nodes()
    runner.expect_true("%s: the same %d active nodes" % (r.label, int(ref_nodes["active"].sum())),
                       np.array_equal(nodes["active"], ref_nodes["active"]))
    u = displacement(ref_nodes)
    runner.expect_close("%s: displacement" % r.label, displacement(nodes), u, 0, tol * np.abs(u).max())
    runner.expect_close("%s: lambda" % r.label, nodes["lambda"], ref_nodes["lambda"], 0,
                        tol * np.abs(ref_nodes["lambda"]).max())


def expect_balance(runner, r, what, atol=None):
    """Contact force + reactions + applied load = 0 to round-off (1e-10 of the load unless atol is given)."""
    total = np.array(r.get("contact.contact_force")) + np.array(r.get("contact.reaction_force")) + \
        np.array(r.get("contact.applied_force"))
    load = np.linalg.norm(r.get("contact.applied_force"))
    runner.expect_close("%s: contact force + reactions + load" % what, total, np.zeros(len(total)), 0,
                        1e-10 * load if atol is None else atol)
