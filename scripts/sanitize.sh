#!/usr/bin/env bash
# Builds passtrace with AddressSanitizer + UndefinedBehaviorSanitizer in
# build-asan/ (or the directory given as the first argument) and runs its
# GoogleTest binaries there (unit, gl, e2e: the slow label runs once, in the
# suite, unsanitized). Every report is fatal, in the test binary and in the
# passtrace processes the e2e tests spawn, so any report fails the run.
# Running it again only rebuilds what changed.
#
# The binaries run whole, each split into shards (GoogleTest's own sharding)
# that run two at a time, rather than one process per test as ctest runs
# them: a sanitized process takes about 1.2 s to start and end (the runtime,
# Mesa's JIT, the leak check at exit), which over ~950 tests was half of the
# run. A shard stops at its first sanitizer report; the log names the test.
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
command -v ninja > /dev/null && export CMAKE_GENERATOR=Ninja  # for a new build directory, as setup.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DPASSTRACE_SANITIZE=ON "${launcher[@]}"
# Only what the sanitized run uses: not the slow label's binary nor the measurement tools.
targets=(passtrace passtrace_unit_tests passtrace_gl_tests passtrace_image_tests
         passtrace_no_image_output_tests passtrace_fail_writes)
# The e2e tests run the instrumented program, not their own code, under the
# sanitizers: where the unsanitized build (build/, as .ci/run has just made)
# is at hand, its e2e binary runs against this build's passtrace
# (PASSTRACE_TEST_BINARY), saving the instrumented build of its 16 files.
release="$(realpath -m build)"
if [ "$release" != "$build" ] && [ -f "$release/CMakeCache.txt" ] &&
   cmake --build "$release" -j"$(nproc)" --target passtrace_e2e_tests > /dev/null; then
  e2e="$release/tests/passtrace_e2e_tests"
else
  targets+=(passtrace_e2e_tests)
  e2e="$build/tests/passtrace_e2e_tests"
fi
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"
export PASSTRACE_TEST_BINARY="$build/passtrace"
# Mesa unloads its GL driver, and LeakSanitizer would then report what the
# driver's globals held; the preloaded shim keeps libraries loaded (see the file).
# It comes before the ASan runtime in the load order, which ASan allows here.
cc -shared -fPIC -O1 -o "$build/libkeep_libraries_loaded.so" tests/sanitizer/keep_libraries_loaded.c
export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"

# Left out, as code paths the rest already takes under the sanitizers (each
# still runs unsanitized in the suite): the agreement tests' build variants
# (--stack-size 1/8, the binned kd builds, the sbvh builds (bvh-stack,
# bvh-octant, bvh8) and middle builds); the per-mesh suites' sphere, two grids
# and single triangle (the edge cases are in the soup, degenerate, coincident,
# ... meshes); the watertightness tests with Moller-Trumbore (the same builds
# and traversals as with the watertight test: under ASan the CPU ones were
# 250 s of building every structure over the 129K-triangle sphere again);
# Cli.PagedDataRendersTheSameBits (the paged streams are the gl label's
# PagedTraversal tests, sanitized).
# The watertightness tests run 12,000 rays per structure instead of 60,000.
# PASSTRACE_SANITIZE_ALL=1 runs everything.
filter="-"
for variant in stack1 stack8 binned binned_papay sbvh middle; do filter+="*_$variant:*_${variant}_*:"; done
for mesh in sphere gridZ gridX single; do filter+="*/$mesh:*_$mesh:"; done
filter+="*WatertightGpu.AllStructures/moller_trumbore:*WatertightCpu.Structure/*_moller_trumbore*:Cli.PagedDataRendersTheSameBits:"
# The unread-flag warnings are the registry's logic, the same for every row:
# the first row of each set of renderers (CPU and stream, CPU only, stream
# only, Embree) stands for the rest here, chosen from the registry
# (`passtrace --list --json`; each test starts the program a dozen times).
kept=" $("$build/passtrace" --list --json | /usr/bin/python3 -c '
import json, sys
seen = {}
for row in json.load(sys.stdin)["accelerators"]:
    seen.setdefault(tuple(row["renderers"]), row["name"].replace("-", "_"))
print(" ".join(seen.values()))') "
for row in $("$e2e" --gtest_list_tests --gtest_filter='AllStructures/CliParams.*' | awk '/^  /{print $1}'); do
  case "$kept" in *" ${row##*/} "*) ;; *) filter+="AllStructures/CliParams.$row:" ;; esac
done
filter+="EveryStreamRow/ComputeStage.*"  # the compute stage stays sanitized by GlTest.ComputeStage*
if [ "${PASSTRACE_SANITIZE_ALL:-0}" = 1 ]; then filter="*"; fi
export PASSTRACE_WATERTIGHT_RAYS="${PASSTRACE_WATERTIGHT_RAYS:-12000}"

# BINARY SHARDS per line, the longest first (two run at a time).
jobs="$e2e 3
$build/tests/passtrace_unit_tests 3
$build/tests/passtrace_gl_tests 2
$build/tests/passtrace_image_tests 1
$build/tests/passtrace_no_image_output_tests 1"
logs="$build/sanitize-logs"
rm -rf "$logs" && mkdir -p "$logs"
runShard() {  # BINARY INDEX COUNT: one shard, its log kept; the log is printed if it fails
  local name="$(basename "$1")"
  local log="$logs/$name.$2.log" asan="$ASAN_OPTIONS"
  # The passtrace processes the e2e tests start run without LeakSanitizer:
  # its exit-time tracer crashed (signal 11) in GPU-path runs in some
  # checkouts and not in others (the same sources, another path), failing
  # tests for no leak. Leaks are still checked in the unit and gl binaries,
  # which run the same library code in-process; ASan and UBSan stay on.
  [ "$name" = passtrace_e2e_tests ] && asan+=":detect_leaks=0"
  if ASAN_OPTIONS="$asan" LD_PRELOAD="$build/libkeep_libraries_loaded.so" GTEST_TOTAL_SHARDS="$3" GTEST_SHARD_INDEX="$2" \
     timeout 1800 "$1" --gtest_filter="$filter" --gtest_brief=1 > "$log" 2>&1; then
    echo "sanitize: $name shard $(($2 + 1))/$3: $(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran.*' "$log" | head -1)"
  else
    echo "sanitize: $name shard $(($2 + 1))/$3 FAILED (exit $?); its log ($log):"
    cat "$log"
    return 1
  fi
}
export -f runShard
export build logs filter
while read -r binary count; do
  for ((i = 0; i < count; ++i)); do echo "$binary $i $count"; done
done <<< "$jobs" | xargs -P 2 -L 1 bash -c 'runShard "$@"' _
echo "sanitize: every shard passed"
