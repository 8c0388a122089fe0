#!/usr/bin/env bash
# Installs the Debian packages cellphase needs (only those missing) and builds it in
# build/. Used by demos/run.sh and tests/run.sh; safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config
  libdolfinx-dev python3-ffcx          # DOLFINx 0.5 (PETSc with MUMPS, Open MPI, HDF5), FFCx
  libdolfinx-mpc-dev                   # dolfinx_mpc 0.5: periodic boundary conditions
  libmumps-dev                         # MUMPS (PETSc's), called directly for the direct solves
  libyaml-cpp-dev libmuparser-dev      # scene files, signed-distance expressions
  libpugixml-dev                       # the XDMF index of the field output
  libgtest-dev                         # C++ tests
  gmsh                                 # meshes/*.geo -> XDMF at build time
  python3-pytest python3-yaml python3-numpy python3-matplotlib python3-h5py  # tests, plots
  python3-pytest-xdist                 # the Python tests on every core, a test file per worker
  libopenblas0-pthread                 # optimised BLAS for MUMPS (see benchmarks/)
  paraview python3-paraview xvfb xauth # tests: the output opened by pvpython, rendered off-screen
  python3-meshio                       # tests: the output read by meshio
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

echo "== building cellphase in build/"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > build.log 2>&1 || { cat build.log; exit 1; }
cmake --build build -j"$(nproc)" >> build.log 2>&1 || { tail -50 build.log; exit 1; }
echo "   built build/cellphase (log in build.log)"
