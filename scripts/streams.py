#!/usr/bin/python3
"""The machine's memory bandwidth on 1..N MPI ranks: the ceiling of the iterative path's speed-up on several ranks.

The idea of PETSc's `make streams` (src/benchmarks/streams/MPIVersion.c, not in Debian's packages): every rank runs the
STREAM triad a[i] = b[i] + s c[i] on arrays of its own, between barriers, the best of 10 repetitions; the bandwidth is
the bytes moved by all ranks over the slowest rank's time. Matrix-vector products and the V-cycles' smoothing move
the matrix once per product and are bound by this bandwidth, so a solve on N ranks is at most about
(bandwidth on N) / (bandwidth on 1) times faster than on one (docs/performance.md, issue 37 item 5).

The triad is compiled here with mpicc (Debian package libopenmpi-dev) and run under mpiexec for 1..N ranks, the rank
counts alternated over --rounds rounds (a shared machine's bandwidth drifts); it prints each run's bandwidth and, per
rank count, the median and best and their ratios to one rank's.

  scripts/streams.py [--ranks 1,2] [--rounds 5] [--mb 480]
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

TRIAD = r"""
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
int main(int argc, char **argv) {
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  long n = atol(argv[1]);
  double *a = malloc(n * sizeof(double)), *b = malloc(n * sizeof(double)), *c = malloc(n * sizeof(double));
  if (!a || !b || !c) MPI_Abort(MPI_COMM_WORLD, 1);
  for (long i = 0; i < n; i++) a[i] = 1, b[i] = 2, c[i] = 0.5;
  double best = 1e300;
  for (int k = 0; k < 10; k++) {
    MPI_Barrier(MPI_COMM_WORLD);
    double t = MPI_Wtime();
    for (long i = 0; i < n; i++) a[i] = b[i] + 3.0 * c[i];
    double mine = MPI_Wtime() - t, slowest;
    MPI_Allreduce(&mine, &slowest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (slowest < best) best = slowest;
  }
  double sum = 0, all;
  for (long i = 0; i < n; i += 4096) sum += a[i];
  MPI_Reduce(&sum, &all, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  if (rank == 0) printf("%.6e %.17g\n", 3.0 * sizeof(double) * n * size / best, all);
  free(a), free(b), free(c);
  MPI_Finalize();
  return 0;
}
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ranks", default="1,2", help="rank counts, comma-separated (default 1,2)")
    parser.add_argument("--rounds", type=int, default=5, help="runs of each rank count, alternated (default 5)")
    parser.add_argument("--mb", type=float, default=480.0,
                        help="the three arrays' size per rank in MB, far beyond the caches (default 480)")
    parser.add_argument("--mpiexec", default="mpiexec")
    args = parser.parse_args()
    try:
        ranks = [int(r) for r in args.ranks.split(",")]
    except ValueError:
        ranks = []
    if not ranks or min(ranks) < 1 or args.rounds < 1 or not args.mb > 0:
        sys.exit("streams.py: error: --ranks needs positive integers (e.g. 1,2), --rounds and --mb positive numbers")
    mpicc = shutil.which("mpicc")
    if not mpicc:
        sys.exit("streams.py: error: mpicc not found (Debian package libopenmpi-dev)")
    n = max(1, int(args.mb * 1e6 / 24))
    env = dict(os.environ, OMP_NUM_THREADS="1")
    work = tempfile.mkdtemp(prefix="signorini_streams_")
    try:
        with open(os.path.join(work, "triad.c"), "w") as f:
            f.write(TRIAD)
        exe = os.path.join(work, "triad")
        subprocess.run([mpicc, "-O2", os.path.join(work, "triad.c"), "-o", exe], check=True)
        rates = {r: [] for r in ranks}
        for _ in range(args.rounds):
            for r in ranks:
                cmd = [args.mpiexec, "-n", str(r)] + (["--oversubscribe"] if r > os.cpu_count() else []) + [exe, str(n)]
                run = subprocess.run(cmd, capture_output=True, text=True, env=env)
                if run.returncode != 0:
                    sys.exit("streams.py: error: %s failed:\n%s%s" % (" ".join(cmd), run.stdout, run.stderr))
                rate = float(run.stdout.split()[0]) / 1e6
                rates[r].append(rate)
                print("ranks %d: triad %.0f MB/s" % (r, rate), flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    base = ranks[0]
    print("ranks  median MB/s  best MB/s  median ratio  best ratio (to %d rank%s)" % (base, "" if base == 1 else "s"))
    for r in ranks:
        med, best = statistics.median(rates[r]), max(rates[r])
        print("%5d  %11.0f  %9.0f  %12.2f  %10.2f" % (r, med, best, med / statistics.median(rates[base]),
                                                       best / max(rates[base])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
