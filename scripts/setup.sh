#!/usr/bin/env bash
# Sets passtrace up on a Debian 12 machine: installs the Debian packages it
# needs (only those missing, so running it again is cheap), then configures
# build/ and builds the program (build/passtrace) and its kernels — with
# --python also the Python package (build/python/passtrace) and matplotlib
# for the report's plots, with --mpi the program with Open MPI (mpirun -np N
# passtrace, docs/cluster.md), with --tests everything: the package, MPI, the
# test binaries and measurement tools too.
#   bash scripts/setup.sh            the program: the README's first command
#   bash scripts/setup.sh --python   the program and the Python package (PYTHONPATH=build/python)
#   bash scripts/setup.sh --mpi      the program with Open MPI, and mpi4py for scripts/bench.py
#   bash scripts/setup.sh --tests    everything: the README's second command
set -euo pipefail
cd "$(dirname "$0")/.."
target=(--target passtrace)
# Python's packages (the Python package, its tests, the report's plots) are
# not needed for the first image, and matplotlib brings 386 MB with it.
python=()
# Open MPI: not for the first image either (68 packages with its build tools).
mpi=(openmpi-bin libopenmpi-dev python3-mpi4py)
case "${1:-}" in
  "") mpi=() ;;
  --python) target=(--target passtrace _passtrace) python=(pybind11-dev python3-dev python3-numpy python3-matplotlib) mpi=() ;;
  --mpi) ;;
  --tests) target=() python=(pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib) ;;
  *) echo "setup: unknown argument '$1' (expected nothing, --python, --mpi or --tests)" >&2; exit 2 ;;
esac

packages=(
  cmake g++ make ninja-build pkg-config
  python3-glad                                  # generates the GL 4.5 core loader at build time
  libegl-dev libegl-mesa0 libgl1-mesa-dri       # headless EGL and Mesa's drivers (llvmpipe)
  libosmesa6-dev                                # the OSMesa backend (optional)
  libglm-dev libcli11-dev nlohmann-json3-dev libgtest-dev   # GoogleTest: the tests (optional)
  libopenexr-dev libopenimageio-dev             # OpenEXR output; the other image formats (loaded when used)
  libtinyobjloader-dev libtinygltf-dev          # scene loaders
  libassimp-dev                                 # Open Asset Import Library: PLY, STL, FBX, COLLADA, 3DS
  libtbb-dev                                    # oneTBB: the CPU renderer's threads
  glmark2-data                                  # the Stanford bunny (bunny.obj)
  libembree-dev                                 # Intel Embree 3, the CPU baseline (-r 3; optional)
  python3                                       # the benchmark (scripts/bench.py)
  "${python[@]}"                                # the Python package (python/), its tests, the report's plots
  "${mpi[@]}"                                   # Open MPI: mpirun -np N passtrace, the benchmark over ranks
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  # Without the packages' recommendations (SciPy, SymPy, OpenBLAS, GDAL, ...):
  # nothing here uses them, and they were a third of a fresh machine's download.
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# ccache, where the machine has it, makes rebuilds in other checkouts cheap;
# it is not installed here.
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# Paths relative to the checkout, so that another clone of the same sources
# hits the cache; the precompiled headers' compiles are cacheable only so.
export CCACHE_BASEDIR="$PWD" CCACHE_SLOPPINESS=pch_defines,time_macros
# Ninja for a new build directory (it schedules the compiles better than make:
# 20 s less of a cold build here); an existing one keeps its generator.
command -v ninja > /dev/null && export CMAKE_GENERATOR=Ninja
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
cmake --build build -j"$(nproc)" "${target[@]}"
