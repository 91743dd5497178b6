#!/usr/bin/env bash
# glide quick start: installs what is missing (Debian 12, as root), builds in
# Release, then either runs the default scene ("run") or the whole test suite
# through ctest ("test"). Used by the README's two commands and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-run}

# Debian packages glide needs: deal.II with Trilinos/SUNDIALS/p4est/MPI,
# GoogleTest, an optimized BLAS (MUMPS is ten times slower with the
# reference BLAS), Open MPI's mpirun, and for the tests numdiff, Python with
# VTK and NumPy, clang-format.
packages="cmake g++ make libdeal.ii-dev libgtest-dev libopenblas0-pthread openmpi-bin
          numdiff python3 python3-vtk9 python3-numpy clang-format"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "glide: installing$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq $missing
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2

case "$mode" in
  run)
    ./build/glide parameters/default.prm
    echo "Results: output/default/default.pvd (open in ParaView), output/default/statistics.csv"
    ;;
  test)
    cmake --build build --target format_check
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    cd build && ctest -j2 --output-on-failure
    ;;
  *)
    echo "usage: $0 run|test" >&2
    exit 2
    ;;
esac
