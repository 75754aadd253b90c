#!/usr/bin/env bash
# ctest's InstalledPackage: installs the build tree into a temporary prefix,
# configures and builds tests/package_consumer/ against it with
# find_package(passtrace CONFIG REQUIRED), runs the program and checks its line.
#   check_install.sh BUILD_DIR VERSION HAVE_EMBREE [extra cmake arguments for the consumer...]
set -euo pipefail
build="$1" version="$2" embree="$3"
shift 3
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d "${TMPDIR:-/tmp}/passtrace-package.XXXXXX")"
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$here" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" "$@"
cmake --build "$work/build"
out="$("$work/build/consumer")"
echo "$out"
expected="passtrace $version: cornell has 32 triangles, finite bounds, embree $embree"
if [ "$out" != "$expected" ]; then
  echo "check_install: expected: $expected" >&2
  exit 1
fi
# What the package promises besides the target.
for f in bin/passtrace include/passtrace/accel/kd/kd_tree.h include/passtrace/glad/gl.h \
         include/passtrace/passtrace_version.h share/passtrace/kernels_glsl/kd/kd_traverse.frag; do
  [ -e "$work/prefix/$f" ] || { echo "check_install: $f is not installed" >&2; exit 1; }
done
# The Python package, where the build has it: imported from the prefix alone.
if [ -n "${PASSTRACE_CHECK_PYTHON:-}" ]; then
  site="$work/prefix/$PASSTRACE_PYTHON_SITE"
  got="$(cd "$work" && PYTHONPATH="$site" "$PASSTRACE_CHECK_PYTHON" -c '
import sys, passtrace
assert passtrace.__file__.startswith(sys.argv[1]), passtrace.__file__
scene = passtrace.load_scene("cornell")
origins, directions = passtrace.camera_rays(scene, 8, 8)
hits = passtrace.build(scene, "bvh8").intersect(origins, directions)
print(passtrace.__version__, int((hits["id"] != 4294967295).sum()))' "$site")"
  echo "python: $got"
  [ "$got" = "$version 64" ] || { echo "check_install: the installed Python package answered '$got'" >&2; exit 1; }
fi
echo "check_install: ok"
