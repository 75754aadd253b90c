#!/usr/bin/env bash
# Sets passtrace up on a Debian 12 machine: installs the Debian packages it
# needs (only those missing, so running it again is cheap), then configures
# and builds everything in build/.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config
  python3-glad                                  # generates the GL 4.5 core loader at build time
  libegl-dev libegl-mesa0 libgl1-mesa-dri       # headless EGL and Mesa's drivers (llvmpipe)
  libosmesa6-dev                                # the OSMesa backend (optional)
  libglm-dev libcli11-dev nlohmann-json3-dev libgtest-dev   # GoogleTest: the tests (optional)
  libopenimageio-dev                            # image and OpenEXR output
  libtinyobjloader-dev libtinygltf-dev          # scene loaders
  libassimp-dev                                 # Open Asset Import Library: PLY, STL, FBX, COLLADA, 3DS
  libtbb-dev                                    # oneTBB: the CPU renderer's threads
  glmark2-data                                  # the Stanford bunny (bunny.obj)
  libembree-dev                                 # Intel Embree 3, the CPU baseline (-r 3; optional)
  python3 python3-matplotlib                    # the benchmark report and its plots
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
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
