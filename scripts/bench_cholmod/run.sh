#!/usr/bin/env bash
# Writes the Hertz saddle-point matrices and times SchurCholesky against CHOLMOD on them (bench_cholmod.cpp),
# one process per run, the solvers alternating; then prints the table of scripts/bench_cholmod/RESULTS.md.
#   scripts/bench_cholmod/run.sh BUILD_DIR OUT_DIR REPEATS CASE...
# CASE is 2d:F or 3d:F, F the mesh size factor of meshes/hertz.geo or meshes/hertz3d.geo (2d:0.79 ~ 20k rows,
# 2d:0.25 ~ 195k, 2d:0.11 ~ 1M, 3d:1.4 ~ 16k, 3d:0.74 ~ 110k). BUILD_DIR was configured with
# -DSIGNORINI_BENCH_CHOLMOD=ON and holds signorini and bench_cholmod. BLOCKS=1 adds W on dense blocks (-w blocks);
# CHECKS lists the comparisons run once per case (default "-w solve2;-w shift", separated by ';').
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=$1 out=$2 repeats=$3
shift 3
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

# The saddle-point matrix at its final assembly (-mat_view binary; the linear Hertz cases assemble it once).
write_matrix() {
  local dim=$1 factor=$2 name=$3 options geo
  if [ "$dim" = 2 ]; then options=options/hertz.yml geo=meshes/hertz.geo; else options=options/hertz3d.yml geo=meshes/hertz3d.geo; fi
  [ -f "$out/$name.bin" ] && grep -q "unknowns:" "$out/$name.log" && return 0
  rm -f "$out/$name.bin"
  (cd "$here" && "$build/signorini" -options_file "$options" -mesh_file "$geo" -mesh_size_factor "$factor" \
     -mat_view "binary:$out/$name.bin" >"$out/$name.log" 2>&1)
}

for case in "$@"; do
  dim=${case%%:*}; dim=${dim%d}; factor=${case#*:}
  name=hertz${dim}d_$factor
  write_matrix "$dim" "$factor" "$name"
  m=$(sed -n 's/.*unknowns: [0-9]* displacements, \([0-9]*\) multipliers.*/\1/p' "$out/$name.log")
  bench=("$build/scripts/bench_cholmod/bench_cholmod" -file "$out/$name.bin" -m "$m" -dim "$dim")
  echo "== $name: $(grep unknowns: "$out/$name.log" | sed 's/^ *//')" | tee -a "$out/results.txt"
  IFS=';' read -ra checks <<<"${CHECKS:--w solve2;-w shift}"
  for check in "${checks[@]}"; do
    # shellcheck disable=SC2086
    "${bench[@]}" -check $check | sed "s/^/$name /" | tee -a "$out/checks.txt"
  done
  for ((r = 0; r < repeats; ++r)); do
    variants=("-solver ours" "-solver cholmod -order given" "-solver cholmod -order own"
              "-solver cholmod -order given -w shift" "-solver cholmod -order own -w shift")
    [ "${BLOCKS:-0}" = 1 ] && variants+=("-solver cholmod -order given -w blocks")
    for variant in "${variants[@]}"; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      # shellcheck disable=SC2086
      echo "$name load=$load $("${bench[@]}" $variant)" | tee -a "$out/results.txt"
    done
  done
done
python3 "$here/scripts/bench_cholmod/summary.py" "$out/results.txt"
grep "check:" "$out/checks.txt"
