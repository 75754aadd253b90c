#!/bin/bash
# Primary rays against bare Embree, wall clock as the benchmark report times
# them, but alternated: each round runs bare rtcIntersect1
# (measure_bare_embree SCENE 512 THREADS REPEATS, its min_ms) and then each
# LABEL:BINARY:RENDERER:ACCEL (-b 1 -w 512 -m REPEATS --threads THREADS,
# --json's frame_ms), so a busy moment of the shared machine hits them alike.
# Prints each round, then the minimum per label and bare/label.
#   scripts/primary_vs_bare.sh SCENE ROUNDS LABEL:BINARY:RENDERER:ACCEL ...
# e.g. scripts/primary_vs_bare.sh bunny 3 r3:build/passtrace:3:embree packet:build/passtrace:1:bvh8-packet
# THREADS=2 and REPEATS=10 by default; BART scenes need PASSTRACE_BART_DIR.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE ROUNDS LABEL:BINARY:RENDERER:ACCEL ..." >&2
  exit 2
fi
S=$1; R=$2; shift 2
T=${THREADS:-2}; M=${REPEATS:-10}
bare=$(dirname "$0")/../build/tests/measure/measure_bare_embree
json=$(mktemp); trap 'rm -f "$json"' EXIT
field() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$@"; }
for i in $(seq "$R"); do
  "$bare" "$S" 512 "$T" "$M" >"$json"
  echo "$i bare $(field "$json" min_ms)"
  for spec in "$@"; do
    IFS=: read -r l b r a <<<"$spec"
    "$b" -r "$r" -a "$a" -s "$S" -w 512 -b 1 -m "$M" --threads "$T" --json "$json" >/dev/null
    echo "$i $l $(field "$json" frame_ms)"
  done
done | tee /dev/stderr | awk -v t="$S, $T threads" '{ if (!($2 in m) || $3 < m[$2]) m[$2] = $3 }
  END { printf "%s, ms: ", t; for (k in m) printf "%s=%.3f ", k, m[k];
        for (k in m) if (k != "bare") printf " bare/%s=%.2f", k, m["bare"] / m[k]; print "" }'
