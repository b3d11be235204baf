"""The tables of scripts/bench_cholmod/RESULTS.md from run.sh's results.txt: median [min-max] per case and route, and
each CHOLMOD route's time over ours run by run (the runs alternate: the ratio of neighbours is steadier on a loaded
machine than either time)."""
import statistics
import sys
from collections import defaultdict

runs = defaultdict(list)
loads = defaultdict(list)
for line in open(sys.argv[1]):
    words = line.split()
    if len(words) < 3 or not words[1].startswith("load="):
        continue
    fields = dict(w.split("=", 1) for w in words[1:] if "=" in w)
    solver = fields["solver"] + ("_" + fields["w"] if fields.get("w", "solve2") != "solve2" else "")
    runs[(words[0], solver)].append(fields)
    loads[words[0]].append(float(fields["load"]))


def cell(rows, key, scale=1.0, digits=3):
    values = sorted(scale * key(r) for r in rows)
    med = statistics.median(values)
    if len(values) == 1:
        return f"{med:.{digits}g}"
    return f"{med:.{digits}g} [{values[0]:.{digits}g}-{values[-1]:.{digits}g}]"


print("| case | rows (multipliers) | solver | ordering (s) | analysis s | factor + Schur s | factor; W; S from W or L22 s "
      "| forward + backward ms | peak MiB (after load) | factor entries | runs |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for (name, solver), rows in sorted(runs.items(), key=lambda kv: (kv[0][0], kv[0][1] != "ours", kv[0][1])):
    r0 = rows[0]
    own = "own" in solver
    ordering = r0["ordering"].replace("metis_nodes", "METIS nodes") + (
        " (in analysis)" if own else f" ({cell(rows, lambda r: float(r['order']), digits=2)})")
    analyse = cell(rows, lambda r: float(r["analyse"]))
    fs = cell(rows, lambda r: float(r["factor"]) + float(r["schur"]))
    factor = cell(rows, lambda r: float(r["factor"]), digits=2)
    if solver == "ours":
        parts = factor + "; (in factor)"
    elif solver.endswith("_shift"):
        parts = factor + "; -; " + cell(rows, lambda r: float(r["schur"]), digits=2)
    else:
        parts = "; ".join([factor, cell(rows, lambda r: float(r["w_s"]), digits=2),
                           cell(rows, lambda r: float(r["schur"]) - float(r["w_s"]), digits=2)])
    solves = cell(rows, lambda r: float(r["forward"]) + float(r["backward"]), 1e3)
    peak = cell(rows, lambda r: float(r["peak_mib"]), digits=4)
    print(f"| {name} | {r0['n']} ({r0['m']}) | {solver} | {ordering} | {analyse} | {fs} | {parts} | {solves} "
          f"| {peak} ({float(r0['load_peak_mib']):.0f}) | {float(r0['entries']):.3g} | {len(rows)} |")
print()
for name, values in sorted(loads.items()):
    print(f"{name}: load average {min(values):.2f}-{max(values):.2f} (median {statistics.median(values):.2f})")
print()
print("| case | route | factor + Schur, route / ours, paired runs: median [min-max] | pairs |")
print("|---|---|---|---|")
for (name, solver), rows in sorted(runs.items()):
    ours = runs.get((name, "ours"))
    if solver == "ours" or not ours:
        continue
    n = min(len(rows), len(ours))
    ratios = sorted((float(rows[i]["factor"]) + float(rows[i]["schur"])) /
                    (float(ours[i]["factor"]) + float(ours[i]["schur"])) for i in range(n))
    print(f"| {name} | {solver} | {statistics.median(ratios):.2f} [{ratios[0]:.2f}-{ratios[-1]:.2f}] | {n} |")
