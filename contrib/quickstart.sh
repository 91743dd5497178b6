#!/usr/bin/env bash
# glide quick start: installs what is missing (Debian 12, as root), builds in
# Release, then either runs a first contact scene ("run":
# parameters/quickstart.prm, a cylinder pressed onto an elastic block) or the whole test suite
# through ctest ("test"). Used by the README's two commands and by .ci/run.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-run}

# Debian packages glide needs: deal.II with Trilinos/SUNDIALS/p4est/MPI,
# GoogleTest, an optimized BLAS (MUMPS is ten times slower with the
# reference BLAS), Open MPI's mpirun, and for the tests numdiff, Python with
# VTK, NumPy and Matplotlib (the studies' plots), clang-format.
packages="cmake g++ make libdeal.ii-dev libgtest-dev libopenblas0-pthread openmpi-bin
          numdiff python3 python3-vtk9 python3-numpy python3-matplotlib clang-format"
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
    ./build/glide parameters/quickstart.prm
    out=output/quickstart
    cat <<EOF

glide ran parameters/quickstart.prm: a cylinder pressed onto an elastic block
(two elastic bodies, frictionless contact). The results are in $out/:
  $out/quickstart.pvd      open in ParaView; apply Warp By Vector
                           ('displacement') and colour by 'von_Mises'
  $out/contact-hertz.pvd   the contact (slave) nodes: colour by 'CPRESS',
                           render as Point Gaussian over the bodies
  $out/statistics.csv      one row per load step: iterations, reactions,
                           contact force (contact_hertz_force_y = 1e-3 = the
                           load at the last step)
  $out/contact-hertz-0003.csv  per slave node: gap COPEN, pressure CPRESS,
                           status CSTATUS (peak pressure about 0.013)
Next: read parameters/quickstart.prm (its header says what to expect);
'./build/glide --print-parameters' lists every parameter.
EOF
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
