#!/usr/bin/env bash
# Builds passtrace with AddressSanitizer + UndefinedBehaviorSanitizer in
# build-asan/ (or the directory given as the first argument) and runs the whole
# test suite there. Every report is fatal, in the test binary and in the
# passtrace processes the tests spawn, so any report fails its test.
# Running it again only rebuilds what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(realpath -m "${1:-build-asan}")"

# gcc 12's sanitizer runtimes; g++ usually brings them already.
missing=()
for p in libasan8 libubsan1; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "sanitize: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi

# Exported before building too: gtest_discover_tests runs the test binary.
# exitcode=23 tells a sanitizer report from passtrace's own error status (1).
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:exitcode=23:detect_leaks=1:check_initialization_order=1:strict_init_order=1:print_stacktrace=1"
export UBSAN_OPTIONS="halt_on_error=1:exitcode=23:print_stacktrace=1"
# Leaks inside Mesa/LLVM/Assimp only; why each is there is in the file.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"

launcher=()  # ccache where the machine has it, as setup.sh and fuzz.sh
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# Paths relative to the checkout, so that another clone of the same sources
# hits the cache; the precompiled headers' compiles are cacheable only so.
export CCACHE_BASEDIR="$PWD" CCACHE_SLOPPINESS=pch_defines,time_macros
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DPASSTRACE_SANITIZE=ON "${launcher[@]}"
cmake --build "$build" -j"$(nproc)"
# Mesa unloads its GL driver, and LeakSanitizer would then report what the
# driver's globals held; the preloaded shim keeps libraries loaded (see the file).
# It comes before the ASan runtime in the load order, which ASan allows here.
cc -shared -fPIC -O1 -o "$build/libkeep_libraries_loaded.so" tests/sanitizer/keep_libraries_loaded.c
export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
# Every test except the `slow` label (tests/slow/: each structure through the
# CLI on several scenes, the BART scenes, the large builds, the benchmark
# plumbing), code paths the rest already covers with many more processes and
# larger inputs; the watertightness test runs 12,000 rays per structure instead
# of 60,000. Sanitized code runs about 5x slower.
# PASSTRACE_SANITIZE_ALL=1 runs everything.
# The slow label runs once (unsanitized) in CI; so do the agreement tests'
# build variants (--stack-size 1/8, the binned kd builds, the sbvh builds (bvh-stack, bvh-octant, bvh8) and
# middle builds), whose code paths the default cases already take under the
# sanitizers; and every structure x mesh matrix (CpuStructureAgreement,
# GpuTraversalAgreement, the Meshes/ suites) on the meshes that hold the edge
# cases (soup, degenerate, coincident, ...) rather than all: the sphere, the
# two grids and the single triangle take no code path the others do not.
# ctest's names of parameterised tests end in "  # GetParam() = ...", hence
# "( |$)" rather than "$".
redundantMeshes="[/_](sphere|gridZ|gridX|single)( |$)"
select=(-LE slow -E "_stack[18]_|_binned|_sbvh(_| |$)|_middle_|$redundantMeshes")
if [ "${PASSTRACE_SANITIZE_ALL:-0}" = 1 ]; then select=(); fi
LD_PRELOAD="$build/libkeep_libraries_loaded.so" PASSTRACE_WATERTIGHT_RAYS="${PASSTRACE_WATERTIGHT_RAYS:-12000}" \
  ctest --test-dir "$build" --output-on-failure -j2 "${select[@]}"
