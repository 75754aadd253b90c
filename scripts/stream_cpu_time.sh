#!/bin/bash
# Stream rows (-r 2, primary rays, 512^2) alternated: CPU time per frame from perf's
# task-clock, (F frames - 1 frame) / (F - 1) so load, build and shader compilation
# cancel (llvmpipe's threads count too), the minimum over ROUNDS; and the best wall
# Mrays/s the runs printed. On the shared machine CPU time is the steadier measure.
#   scripts/stream_cpu_time.sh SCENE LOOP_LIMIT ROUNDS LABEL:BINARY:ACCEL ...
# e.g. scripts/stream_cpu_time.sh bunny 100000 3 kk:build/passtrace:kk-bvh oct:build/passtrace:bvh-octant
# FRAMES=N (default 11) frames per long run.
S=$1; L=$2; R=$3; shift 3
F=${FRAMES:-11}
tc() { grep task-clock | cut -d, -f1; }
for i in $(seq "$R"); do
  for spec in "$@"; do
    IFS=: read -r l b a <<<"$spec"
    t1=$(perf stat -x, -e task-clock "$b" -r 2 -a "$a" -s "$S" -w 512 -b 1 -m 1 -l "$L" 2>&1 >/dev/null | tc)
    out=$(perf stat -x, -e task-clock "$b" -r 2 -a "$a" -s "$S" -w 512 -b 1 -m "$F" -l "$L" 2>&1)
    tf=$(echo "$out" | tc)
    mr=$(echo "$out" | grep -o '= [0-9.]* Mrays' | grep -o '[0-9.]*')
    echo "$l $(echo "($tf - $t1)/($F - 1)" | bc -l) $mr"
  done
done | awk -v t="$S -l $L" '{ if (!($1 in m) || $2 < m[$1]) m[$1] = $2; if ($3 > w[$1]) w[$1] = $3 }
  END { printf "%s:", t; for (k in m) printf "  %s cpu=%.1f ms wall=%.3f Mrays/s", k, m[k], w[k]; print "" }'
