#!/bin/bash
# Packs passtrace for a GPU server that has a driver but none of passtrace's
# libraries (the NVIDIA machines docs/bench-speed/GPU.md was measured on):
# a build without OpenImageIO, OSMesa and Embree (their libraries bring
# ~500 MB), the shared libraries left (assimp, oneTBB, OpenEXR and theirs),
# the program, the GL tests, the SM probe, the bunny and, when given, BART
# Kitchen, with measure.py, in one tar.xz.
#
#   scripts/gpu_server/pack.sh OUT.tar.xz [BART_DIR]
# then on the server: tar xJf OUT.tar.xz -C DIR; python3 DIR/measure.py --pack DIR --out OUT
set -euo pipefail
out=$(realpath -m "$1"); bart=${2:-}
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$root/build-gpu-server
bins=(passtrace tests/passtrace_gl_tests tests/measure/measure_sm_probe tests/measure/measure_fragment_vs_compute)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPASSTRACE_IMAGE_OUTPUT=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_OSMesa=ON -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON > /dev/null
cmake --build "$build" -j"$(nproc)" --target passtrace passtrace_gl_tests measure_sm_probe measure_fragment_vs_compute > /dev/null
stage=$(mktemp -d); trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib"
for b in "${bins[@]}"; do cp "$build/$b" "$stage/bin/"; done
strip "$stage/bin/"*
# The libraries the server lacks: all but the C/C++ runtime. glvnd's libEGL
# and libGLdispatch go too: the H200 machine of 2026-11-28 had only the
# driver's vendor library (libEGL_nvidia.so.0, found through glvnd's
# egl_vendor.d), not glvnd's loader, which is vendor-neutral.
for b in "${bins[@]}"; do ldd "$build/$b"; done | awk '$3 ~ /^\// {print $3}' | sort -u |
  grep -Ev '/(libc|libm|libstdc\+\+|libgcc_s)\.so' |
  xargs -I{} cp -L {} "$stage/lib/"
cp /usr/share/glmark2/models/bunny.obj "$stage/"
if [ -n "$bart" ]; then mkdir -p "$stage/bart" && cp -r "$bart/kitchen" "$stage/bart/"; fi
cp "$root/scripts/gpu_server/measure.py" "$stage/"
tar cJf "$out" -C "$stage" .
echo "$out: $(du -h "$out" | cut -f1)"
