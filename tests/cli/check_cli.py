#!/usr/bin/env python3
"""Command-line behaviour: -help and docs/options.md list the same options with the same defaults, a misspelled option is
reported, the built-in default case equals options/hertz.yml, a relative path in an options file is read relative to
that file."""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile

EXE, SOURCE, TEST = sys.argv[1], sys.argv[2], sys.argv[3]
MPIEXEC = sys.argv[4] if len(sys.argv) > 4 else "mpiexec"


def run(args, cwd=SOURCE, np=0):
    """Runs the executable in cwd, directly (np = 0) or under mpiexec with np ranks."""
    launcher = [MPIEXEC, "-n", str(np)] if np else []
    proc = subprocess.run(launcher + [EXE] + args, capture_output=True, text=True, cwd=cwd)
    return proc.returncode, proc.stdout + proc.stderr


def in_order(text, *markers):
    """Every marker is in text, each after the one before it (a missing marker is not "before" anything)."""
    at = [text.find(m) for m in markers]
    return all(i >= 0 for i in at) and at == sorted(at) and len(set(at)) == len(at)


def check(cond, message):
    print(("ok   " if cond else "FAIL ") + message)
    if not cond:
        sys.exit(1)


if TEST == "help":
    rc, out = run(["-help"])
    check(rc == 0, "-help exits 0")
    # docs/options.md against -help, both ways: every option of the program's groups (before PETSc's first group of the
    # solver) is a row of an options table there with -help's default, and every option documented is in -help.
    # A default cell matches when a `literal` in it is -help's value (numbers compared as numbers, "×" as "x", a path
    # by its end), or -help's text says "default: <cell>", or it says none for an empty value, on/off for a flag.
    with open(os.path.join(SOURCE, "docs", "options.md")) as f:
        doc_lines = f.read().splitlines()
    documented, column = {}, None
    for line in doc_lines:
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("|") else []
        if cells and cells[0] == "option":
            column = cells.index("default") if "default" in cells else None
        elif cells and not set(cells[0]) <= set("- ") and cells[0].startswith("`-"):
            if column is None:
                check(False, f"docs/options.md gives a default column for {cells[0]}")
            for option in re.findall(r"`(-[A-Za-z_0-9{},<>*]+)", cells[0]):
                documented[option] = cells[column]
    check(len(documented) >= 30, f"docs/options.md documents {len(documented)} options")
    _, gamg_help = run(["-help", "-options_file", "options/solver/fieldsplit_gamg.yml"])
    ours_end = out.find("Preconditioner (PC) options:")
    check(ours_end > 0, "-help has the solver's PC group after the program's groups")
    ours = {m.group(1): m.group(0) for m in re.finditer(r"^  (-[a-z_0-9]+)\b.*$", out[:ours_end], re.M)}
    check(len(ours) >= 30, f"-help lists {len(ours)} options of the program")
    for option in sorted(ours):
        check(option in documented, f"docs/options.md documents {option} of -help")

    def norm(text):
        text = text.replace("×", "x").strip()
        return re.sub(r"-?\d+\.?\d*(e[-+]?\d+)?", lambda m: "%g" % float(m.group(0)), text)

    for option, cell in sorted(documented.items()):
        if re.search(r"[*<{]", option):  # a family: some option of -help starts with its prefix
            prefix = re.split(r"[*<{]", option)[0]
            check(prefix in out or prefix in gamg_help, f"-help lists options of {option}")
            continue
        check(re.search(r"^\s+" + re.escape(option) + r"\b", out, re.M) is not None, f"-help lists {option}")
        if option not in ours:
            continue
        line = ours[option]
        value = re.search(r"<(?:now )?(.*?) : ", line).group(1).strip()
        literals = [norm(v) for v in re.findall(r"`([^`]*)`", cell)]
        said = "default: " + cell.split(" (")[0] in line
        flag = {"TRUE": "on", "FALSE": "off"}.get(value)
        good = (norm(value) in literals or any(l and norm(value).endswith("/" + l) for l in literals) or said
                or (value == "" and cell.startswith("none")) or (flag is not None and cell.split()[0] == flag))
        check(good, f"docs/options.md gives {option} the default of -help ({value!r}): {cell!r}")
    check("-contact_ksp_type <now preonly" in out, "-help shows the default saddle-point KSP (preonly)")
    check("-contact_pc_type <now cholesky" in out, "-help shows the default PC (cholesky)")
    check(in_order(out, "Mesh options:", "Options for all PETSc programs"),
          "-help lists the program's groups before PETSc's generic options")
    check("-contact_mat_mumps_icntl_24" in out, "-help lists the MUMPS options of the default solver")
    check(re.search(r"^\s+-contact_ksp_rtol, .*-contact_ksp_max_it: not listed: -contact_ksp_type preonly", out, re.M)
          is not None, "-help says that the default direct solver reads no Krylov tolerance")
    # The program's description, then its groups: no empty group, and the solver's groups come before any generic
    # group of PETSc (the stand-in matrix's -mat_* options belong to PETSc's generic list at the end).
    lines = out.splitlines()
    check(lines[0].startswith("signorini: ") and lines[3:5] == ["-" * 40, "Progress:"],
          "-help starts with the program's description and its first group")
    check(in_order(out, "Contact options:", "Preconditioner (PC) options:", "PETSc's own options",
                   "Options for SEQAIJ matrix"),
          "-help lists the program's groups, then the solver's, then PETSc's generic ones (the -mat_* group last)")
    check("-contact_search_radius <now 0.1 x body diagonal" in out, "-help gives a ratio default with its unit")
    check(in_order(out, "Contact options:", "Saddle-point system:", "Preconditioner (PC) options:"),
          "-help lists the program's saddle-point group with the program's, before PETSc's groups of the solver")
    ours = [l for l in lines if re.match(r"^  -(mesh|material|obstacle|load|newton|output|report|bc|contact|progress)",
                                           l) and not re.match(r"^  -contact_(ksp|pc|mat|fieldsplit)_", l)]
    check(len(ours) >= 30 and not [l for l in ours if l.endswith("()")],
          "-help ends none of the program's %d options with an empty manual page '()': %s"
          % (len(ours), [l for l in ours if l.endswith("()")][:2]))
    generic = out.find("PETSc's own options")
    check(generic > 0 and re.search(r"^  -mat_", out[:generic], re.M) is None,
          "-help lists no generic -mat_* option among the program's and the solver's groups")
    with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
        version = re.search(r"project\(signorini VERSION (\S+)", f.read()).group(1)
    rc, out = run(["-version", "-output_dir", "version_out"], cwd=tempfile.gettempdir())
    check(rc == 0 and out.splitlines()[:3] == [f"signorini {version}", out.splitlines()[1], "MUMPS 5.5.1"]
          and out.splitlines()[1].startswith("Petsc Release Version 3.18")
          and "active-set" not in out and not os.path.exists(os.path.join(tempfile.gettempdir(), "version_out")),
          "-version prints the program's, PETSc's, MUMPS's and MPI's versions and runs nothing: %r" % out[:300])
    rc, out = run(["-help", "-options_file", "options/solver/fieldsplit_gamg.yml"])
    check(rc == 0 and "-contact_fieldsplit_u_pc_gamg_threshold" in out,
          "-help with a fieldsplit preset lists the options of its blocks")
    check(re.search(r"^\s+-contact_ksp_rtol <", out, re.M) is not None and "not listed: -contact_ksp_type" not in out,
          "-help with an iterative preset lists -contact_ksp_rtol")
elif TEST == "misspelled":
    with tempfile.TemporaryDirectory() as work:
        out_dir = os.path.join(work, "out")
        rc, out = run(["-material_nuu", "0.3", "-output_dir", out_dir])
        errors = [l for l in out.splitlines() if l.startswith("signorini: error:")]
        check(rc != 0 and len(errors) == 1 and "option -material_nuu 0.3 (on the command line) is set but never read" in errors[0],
              "a misspelled option is an error naming it: " + out[-300:])
        check("unknowns:" not in out and not os.path.exists(out_dir),
              "it stops the run after the set-up, before the output directory is made")
        # The message says where each option was set: PETSC_OPTIONS, an options file, the command line.
        env = dict(os.environ, PETSC_OPTIONS="-materal_E 5")
        proc = subprocess.run([EXE], capture_output=True, text=True, cwd=SOURCE, env=env)
        check(proc.returncode != 0 and "option -materal_E 5 (in PETSC_OPTIONS) is set but never read" in proc.stderr,
              "an unread option of PETSC_OPTIONS is named with its origin: " + proc.stderr[-300:])
        # A solver option is read at the first factorisation: one that nothing reads is refused after the solve,
        # before the output is published.
        rc, out = run(["-contact_mat_mumps_icntl_99", "1", "-output_dir", out_dir])
        errors = [l for l in out.splitlines() if l.startswith("signorini: error:")]
        check(rc != 0 and len(errors) == 1 and "option -contact_mat_mumps_icntl_99 1 (on the command line) is set but never read" in errors[0]
              and "CONVERGED" in out, "an unread solver option is an error after the solve: " + out[-300:])
        check(not os.path.exists(os.path.join(out_dir, "summary.json"))
              and not os.path.exists(os.path.join(out_dir, "incomplete")), "and nothing is published or left behind")
    rc, out = run(["-material_nuu", "0.3", "-options_left", "0"])
    check(rc == 0 and "-material_nuu" not in out, "-options_left 0 lets an unread option pass: " + out[-300:])
    # PETSc's generic options are not refused, whether PETSc reads them at the start, during the solve or at the end.
    generic = ["-log_view", "ascii:" + os.devnull, "-malloc_debug", "-on_error_abort", "-options_view", "-citations",
               "-info", os.devnull, "-options_left", "-malloc_dump", "-memory_view", "-get_total_flops",
               "-options_monitor", "-vec_view", "::ascii_info", "-mat_view", "::ascii_info"]
    rc, out = run(generic, np=2)
    check(rc == 0 and "signorini: error" not in out, "PETSc's generic options are not refused: " + out[-300:])
elif TEST == "default_case":
    rc1, out1 = run([])
    rc2, out2 = run(["-options_file", "options/hertz.yml"])
    strip = lambda s: [l for l in s.splitlines() if not l.strip().startswith("mesh ")]
    check(rc1 == 0 and rc2 == 0, "both runs succeed")
    check(strip(out1) == strip(out2), "the default case prints the same summary as options/hertz.yml")
    check("Hertz (R = 8, P = 10)" in out1, "the default case compares with Hertz")
    # Another traction: the comparison follows the load, and so does the label (it said P = 10 while comparing with 20).
    rc, out = run(["-bc_traction", "top:0:-1.25"])
    check(rc == 0 and "Hertz (R = 8, P = 20): half-width a = 0.962766" in out,
          "with twice the load the report names and uses P = 20: " + out[-400:])
    # README: any option given overrides the default case's value, the mesh too; the rest of the case stays.
    rc3, out3 = run(["-mesh_file", "meshes/hertz.msh"])
    check(rc3 == 0 and strip(out3) == strip(out1),
          "-mesh_file alone runs the default case on that mesh: " + out3[-300:])
    rc4, out4 = run(["-bc_traction", "top:0:-1.25"])
    check(rc4 == 0 and "applied load (0, -20)" in out4, "-bc_traction alone changes only the default case's load: "
          + out4[-300:])
elif TEST.startswith("options_file_paths_np"):
    np = int(TEST[len("options_file_paths_np"):])
    case = os.path.join(SOURCE, "options", "beam_on_floor.yml")
    with tempfile.TemporaryDirectory() as elsewhere:
        rc, out = run(["-options_file", case, "-output_dir", "out"], cwd=elsewhere, np=np)
        check(rc == 0 and "CONVERGED" in out, "a case's options file runs from another directory: " + out[-300:])
        # The run names the file it read, not the options file's relative path (relative to another directory).
        beam = os.path.realpath(os.path.join(SOURCE, "meshes", "beam.msh"))
        with open(os.path.join(elsewhere, "out", "summary.json")) as f:
            named = json.load(f)["mesh"]["file"]
        check(os.path.realpath(named) == beam and os.path.isabs(named) and f"  mesh {named}: " in out,
              "the summary and summary.json name the mesh file read, as an absolute path: " + named)
        # A copy of the case one level deeper than the meshes it names: found neither there nor here.
        os.makedirs(os.path.join(elsewhere, "cases"))
        copy = os.path.join(elsewhere, "cases", "beam.yml")
        shutil.copy(case, copy)
        rc, out = run(["-options_file", copy], cwd=elsewhere, np=np)
        errors = [l for l in out.splitlines() if l.startswith("signorini: error:")]
        check(rc != 0 and len(errors) == 1, "a missing mesh is one error line: " + out[-300:])
        check(os.path.join(elsewhere, "cases", "../meshes/beam.msh") in errors[0] and "options file" in errors[0]
              and "current directory" in errors[0], "the error names both places looked: " + errors[0])
        # The command line is relative to the current directory, and overrides the file's setting.
        rc, out = run(["-options_file", copy, "-mesh_file", os.path.relpath(os.path.join(SOURCE, "meshes", "beam.msh"),
                                                                                elsewhere)], cwd=elsewhere, np=np)
        check(rc == 0, "-mesh_file on the command line is relative to the current directory: " + out[-300:])
elif TEST.startswith("solver_options_np"):
    # The options that the chosen saddle-point solver reads pass; one that it never reads is refused at its set-up.
    np = int(TEST[len("solver_options_np"):])
    beam = ["-options_file", "options/beam_on_floor.yml"]
    rc, out = run(beam + ["-options_file", "options/solver/fieldsplit_gamg.yml", "-contact_ksp_rtol", "1e-8",
                          "-contact_ksp_max_it", "1000"], np=np)
    check(rc == 0 and "CONVERGED" in out, "an iterative preset reads -contact_ksp_rtol and -contact_ksp_max_it: "
          + out[-300:])
    rc, out = run(beam + ["-contact_pc_factor_fill", "3", "-contact_pc_factor_mat_solver_type", "mumps",
                          "-contact_reuse_factorization", "false"], np=np)
    check(rc == 0 and "CONVERGED" in out, "the default direct solver reads its Cholesky options: " + out[-300:])
    rc, out = run(["-version"], np=np)
    check(rc == 0 and out.count("signorini ") == 1 and out.count("MUMPS ") == 1 and "active-set" not in out,
          "-version prints the versions once on %d rank(s) and runs nothing: %r" % (np, out[:300]))
    # -contact_nested_dissection_parallel is an option of METIS's ordering: with auto on a small 2D matrix (coordinate
    # cuts otherwise) it picks METIS rather than being ignored.
    for given, name in (([], "coordinates"), (["-contact_nested_dissection_parallel", "false"], "metis"),
                        (["-contact_nested_dissection_parallel", "true"], "metis")):
        rc, out = run(beam + given + ["-info", ":sys"], np=np)
        check(rc == 0 and f"ICNTL(7) = 1 ({name})" in out, f"{' '.join(given) or 'auto'} orders by {name}: "
              + "".join(l for l in out.splitlines(True) if " factors" in l)[-300:])
    with tempfile.TemporaryDirectory() as work:
        out_dir = os.path.join(work, "out")
        rc, out = run(beam + ["-contact_ksp_rtol", "1e-3", "-output_dir", out_dir], np=np)
        errors = [l for l in out.splitlines() if l.startswith("signorini: error:")]
        check(rc != 0 and len(errors) == 1 and "-contact_ksp_rtol 1e-3 does not apply to the kept MUMPS "
              "factorisation" in errors[0], "a Krylov tolerance with the direct solver is an error naming it: "
              + out[-300:])
        check("unknowns:" not in out and "CONVERGED" not in out and not os.path.exists(out_dir),
              "it stops the run at the solver's set-up, before any solve and before the output directory is made")
elif TEST.startswith("progress_np"):
    np = int(TEST[len("progress_np"):])
    launcher = [MPIEXEC, "-n", str(np)]
    proc = subprocess.run(launcher + [EXE, "-progress"], capture_output=True, text=True, cwd=SOURCE)
    lines = [l for l in proc.stderr.splitlines() if l.startswith("signorini: [")]
    check(proc.returncode == 0, "-progress run succeeds")
    # The solver path chosen, with why (whose words may name phases: it is not one).
    chosen = [l for l in lines if re.match(r"signorini: \[ *[0-9.]+ s\] solver: direct \(auto: ", l)]
    check(len(chosen) == 1, f"-progress says the solver path and why once: {chosen}")
    lines = [l for l in lines if l not in chosen]
    for phase in ["reading ", "partition and distribution", "set-up", "stiffness assembly", "factorisation",
                  "step 1 iteration 1:", "contact solve", "results and output"]:
        begun = [l for l in lines if phase in l and not l.endswith("s)")]
        check(len(begun) == 1, f"-progress prints one line as '{phase}' starts (rank 0 only): {begun}")
        if phase in ("reading ", "partition and distribution", "contact solve", "results and output"):
            ended = [l for l in lines if phase in l and " done (" in l]
            check(len(ended) == 1, f"-progress prints one line as '{phase}' ends, with its duration: {ended}")
    iterations = [l for l in lines if " iteration " in l]
    done = re.search(r"after (\d+) active-set iteration", proc.stdout)
    check(done is not None and len(iterations) == int(done.group(1)),
          f"one line per active-set iteration ({done.group(1) if done else '?'} on the Hertz case): {len(iterations)}")
    proc = subprocess.run(launcher + [EXE], capture_output=True, text=True, cwd=SOURCE)
    check(proc.returncode == 0 and "signorini: [" not in proc.stderr, "quiet without -progress when stderr is a file")
elif TEST.startswith("closed_pipe_np"):
    # `signorini ... | head -1` in a batch script: stdout closes after the first line; the run still finishes and
    # publishes its output (PETSc's handler used to abort on SIGPIPE and leave only the staging directory).
    np = int(TEST[len("closed_pipe_np"):])
    launcher = [MPIEXEC, "-n", str(np)] if np > 1 else []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        proc = subprocess.Popen(launcher + [EXE, "-output_dir", out], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, cwd=SOURCE)
        first = proc.stdout.readline()
        proc.stdout.close()
        _, err = proc.communicate()
        check(first.startswith(b"signorini: 2D linear"), "the first line arrives: %r" % first)
        if np == 1:
            check(proc.returncode == 0, "the run exits 0 with its stdout closed: %s" % err.decode()[-500:])
        else:
            # Under mpiexec the closed pipe is mpiexec's, not a rank's: Open MPI's mpiexec ignores SIGPIPE while the
            # job runs but may take one as it flushes the last lines at its exit, and then dies of it like any writer
            # into a closed pipe (`yes | head -1`). That exit status is mpiexec's; what the ranks owe is the output.
            check(proc.returncode in (0, -signal.SIGPIPE),
                  "mpiexec exits 0 (or of SIGPIPE after the job) with its stdout closed: %d %s"
                  % (proc.returncode, err.decode()[-500:]))
        check(os.path.isfile(os.path.join(out, "summary.json")) and os.path.isfile(os.path.join(out, "nodes.csv")),
              "the output is published: %s" % (os.listdir(out) if os.path.isdir(out) else "no directory"))
elif TEST.startswith("kept_view_np"):
    # The kept factorisation is the saddle-point KSP's PC (type kept): -contact_ksp_view shows it once per run of
    # condensed solves, with who factored, the ordering and the sizes, and the options and presets change what it says.
    np = int(TEST[len("kept_view_np"):])
    rc, out = run(["-contact_ksp_view"], np=np)
    check(rc == 0, "the default case with -contact_ksp_view exits 0: %s" % out[-300:])
    header = re.search(r"unknowns: (\d+) displacements, (\d+) multipliers", out)
    check(header is not None, "the run header gives the unknowns")
    rows, multipliers = int(header.group(1)) + int(header.group(2)), int(header.group(2))
    check(out.count("KSP Object: (contact_)") == 1, "the saddle-point KSP is viewed once")
    check(re.search(r"^PC Object: \(contact_\) .*\n  type: kept$", out, re.M) is not None, "its PC is of type kept")
    check(f"rows: {rows}, of which {multipliers} multipliers in the Schur complement" in out,
          f"the view gives the {rows} rows and the {multipliers} multipliers of the header")
    gathered = " (the matrix gathered from every rank)" if np > 1 else ""
    check("factored by: signorini's supernodal Cholesky on rank 0" + gathered + "\n" in out,
          "the default factors by the supernodal Cholesky" + gathered)
    check("ordering: nested dissection of the node graph (coordinates)" in out,
          "a small 2D matrix is ordered by coordinate cuts")
    check(re.search(r"factor entries: [0-9.e+]+, elimination flops: [0-9.e+]+, null pivots: 0$", out, re.M)
          is not None, "the view gives the factor's entries and flops")
    for extra, who in ((["-contact_kept_solver", "mumps"], "MUMPS LDL^T (SYM = 2)"),
                       (["-options_file", "options/solver/mumps_lu.yml"], "MUMPS LU (SYM = 0)")):
        rc, out = run(["-contact_ksp_view"] + extra, np=np)
        check(rc == 0 and f"factored by: {who}, called directly" in out, f"{' '.join(extra)}: factored by {who}")
    # svk: the first solve of a load step factors the tangent and solves through the KSP, which shows it then.
    rc, out = run(["-contact_ksp_view", "-material_model", "svk"], np=np)
    check(rc == 0 and "type: kept" in out and "kept factorisation of the saddle-point matrix" in out,
          "svk: the KSP shows the kept factorisation")
elif TEST.startswith("stale_file_lock_np"):
    # Open MPI 4.1 opens every MPI-IO file with a shared file pointer whose shared-memory component takes a POSIX
    # semaphore named after the file's base name (/dev/shm/sem.OMPIO_solution.h5 for every run's output). A run killed
    # while it held it left it taken, and every later run writing a solution.h5 waited in MPI_File_open forever.
    # signorini keeps that component out (main.cpp), so a run writes its output past such a semaphore; the control run
    # (the component asked for) shows that the semaphore bites on this machine. The two tests share the semaphore
    # (RESOURCE_LOCK); no other run uses it.
    np = int(TEST[len("stale_file_lock_np"):])
    launcher = [MPIEXEC, "-n", str(np)] if np > 1 else []
    if not os.path.isdir("/dev/shm"):
        print("skip: no /dev/shm, where the semaphore would be")
        sys.exit(77)
    sem = "/dev/shm/sem.OMPIO_solution.h5"

    def attempt(out_dir, env, timeout):
        """Runs the default case into out_dir; returns (exit status, or None if it was still running after timeout s
        and was stopped; its output)."""
        proc = subprocess.Popen(launcher + [EXE, "-output_dir", out_dir], stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, cwd=SOURCE, env=env)
        try:
            out, _ = proc.communicate(timeout=timeout)
            return proc.returncode, out.decode()
        except subprocess.TimeoutExpired:
            proc.terminate() # mpiexec stops its ranks on SIGTERM; a SIGKILL would leave them waiting
            try:
                out, _ = proc.communicate(timeout=30)
            except subprocess.TimeoutExpired:
                proc.kill()
                out, _ = proc.communicate()
            return None, out.decode()

    with tempfile.TemporaryDirectory() as tmp:
        try:
            # A taken semaphore: glibc's named semaphore is a file of 32 bytes, whose count is 0 when they are zero.
            with open(sem, "wb") as f:
                f.write(bytes(32))
            rc, out = attempt(os.path.join(tmp, "run"), None, 120)
            check(rc == 0, "the run writes its output past a semaphore left taken" + (
                "" if rc == 0 else ": still waiting after 120 s" if rc is None else ": exit %d %s" % (rc, out[-400:])))
            check(os.path.isfile(os.path.join(tmp, "run", "solution.h5")) and
                  os.path.isfile(os.path.join(tmp, "run", "summary.json")), "its solution.h5 and summary are written")
            rc, out = attempt(os.path.join(tmp, "control"), dict(os.environ, OMPI_MCA_sharedfp="sm"), 10)
            if rc is not None:
                print("skip: with Open MPI's shared-memory component the run did not wait either (exit %d): this MPI "
                      "takes no such semaphore, nothing to test" % rc)
                sys.exit(77)
            print("ok   the control run (OMPI_MCA_sharedfp=sm) waits at the semaphore, as every run did before")
        finally:
            if os.path.exists(sem):
                os.remove(sem)
else:
    sys.exit("unknown test " + TEST)
