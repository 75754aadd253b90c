#!/usr/bin/env bash
# Fuzzes the scene loaders (OBJ, AFF/NFF, glTF, PLY, OFF, 3DS through Assimp) and the
# command-line parser with libFuzzer under AddressSanitizer and UBSan: installs clang 14 if
# missing, builds tests/fuzz/ in build-fuzz/, then runs the targets one per core
# at a time, for the given seconds of wall time in all (default 300) shared
# equally, each on a copy of its seed corpus. Exits non-zero
# naming the target and the reproducer when any target finds something; a
# reproducer is fixed at its root and kept in tests/data/fuzz_regressions/.
#   bash scripts/fuzz.sh [total-seconds]
set -euo pipefail
cd "$(dirname "$0")/.."
total="${1:-300}"

packages=(clang-14 libclang-rt-14-dev cmake make libglm-dev libcli11-dev nlohmann-json3-dev
          libtinyobjloader-dev libtinygltf-dev libassimp-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "fuzz: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# Paths relative to the checkout, so that another clone of the same sources
# hits the cache; the precompiled headers' compiles are cacheable only so.
export CCACHE_BASEDIR="$PWD" CCACHE_SLOPPINESS=pch_defines,time_macros
cmake -S tests/fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 "${launcher[@]}" > /dev/null
cmake --build build-fuzz -j"$(nproc)"

# Corpus copies and findings live outside the source tree.
work="build-fuzz/run"
rm -rf "$work"
# The targets' scratch files too (tests/fuzz/fuzz_input_file.h).
mkdir -p "$work/tmp"
export TMPDIR="$PWD/$work/tmp"
# Leaks inside Assimp (and the GL libraries) only; why each is there is in the file.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
# target:max_len (bytes). Text scenes (and PLY, 3DS) need room for a few commands or elements; glTF for a
# JSON document with an embedded buffer; a command line is short.
targets=(obj:4096 aff:8192 gltf:16384 ply:4096 off:4096 3ds:4096 cli:1024)
cores="$(nproc)"
seconds=$((total * cores / ${#targets[@]}))
((seconds > 0)) || seconds=1
fuzzOne() {  # TARGET:MAX_LEN; leaves $work/TARGET.failed when it finds something
  local target="${1%%:*}"
  mkdir -p "$work/corpus-$target" "$work/findings-$target"
  cp tests/fuzz/corpus/"$target"/* "$work/corpus-$target/"
  if ! "build-fuzz/fuzz_$target" "$work/corpus-$target" -dict="tests/fuzz/$target.dict" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="${1#*:}" \
      -artifact_prefix="$work/findings-$target/" -print_final_stats=1 > "$work/$target.log" 2>&1; then
    touch "$work/$target.failed"
  fi
}
running=0
for entry in "${targets[@]}"; do
  echo "fuzz: ${entry%%:*} for ${seconds}s"
  fuzzOne "$entry" &
  if ((++running >= cores)); then wait -n; running=$((running - 1)); fi
done
wait
failed=()
for entry in "${targets[@]}"; do
  target="${entry%%:*}"
  if [ -e "$work/$target.failed" ]; then
    tail -n 40 "$work/$target.log"
    findings="$(ls "$work/findings-$target"/* 2>/dev/null | tr '\n' ' ' || true)"
    failed+=("$target: ${findings}(log: $work/$target.log)")
  fi
  grep -E "^stat::number_of_executed_units|^Done" "$work/$target.log" | sed "s/^/fuzz: $target: /" || true
done

if ((${#failed[@]})); then
  printf 'fuzz: FOUND %s\n' "${failed[@]}" >&2
  exit 1
fi
echo "fuzz: no findings"
