#!/usr/bin/env bash
# Set up a Debian 12 machine for signorini, build it, then run the default case or the test suite.
#   scripts/bootstrap.sh          install what is missing, build (Release), run the default case
#   scripts/bootstrap.sh --test   install what is missing, build (Release), run the whole test suite
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${SIGNORINI_BUILD_DIR:-$here/build}
mode=run
case "${1:-}" in
  "") ;;
  --test) mode=test ;;
  *) echo "usage: scripts/bootstrap.sh [--test]" >&2; exit 2 ;;
esac

packages=(petsc-dev libmumps-dev libyaml-dev liblapack-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev gmsh
          libgmsh-dev libopenblas0-serial cmake pkg-config g++ make libgtest-dev
          python3 python3-numpy python3-h5py python3-matplotlib python3-paraview xvfb
          strace)  # xvfb: plot.py's 3D pictures (ParaView draws through X); strace: the bad-input tests inject failures
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "bootstrap: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
# mpiexec otherwise waits 2 s after a rank exits non-zero (docs/running.md, MPI).
export OMPI_MCA_odls_base_sigkill_timeout=0
# nproc honours OMP_NUM_THREADS (set to 1 above for the runs): the cores without it, for the build and CTest.
jobs=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
# Configure where nothing was generated yet (also after a configure that failed, say before the packages were there).
if [ ! -f "$build_dir/CMakeCache.txt" ] || [ ! -f "$build_dir/Makefile" ]; then
  cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build_dir" -j "$jobs"

if [ "$mode" = run ]; then
  cd "$here"
  exec "$build_dir/signorini"
fi
cd "$build_dir"
exec ctest --output-on-failure -j "$jobs"
