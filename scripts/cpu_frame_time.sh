#!/bin/bash
# CPU time per frame (perf stat task-clock: (F frames - 1 frame) / (F - 1), so the
# scene load and build cancel), the minimum of ROUNDS alternating runs, and
# Embree's time over each other's. The machine is shared: wall clock is noisy,
# CPU time much less so.
#   scripts/cpu_frame_time.sh SCENE BOUNCES ROUNDS LABEL:BINARY:RENDERER:ACCEL ...
# e.g. scripts/cpu_frame_time.sh robots 1 3 embree:build/passtrace:3:embree packet:build/passtrace:1:bvh8-packet
# FRAMES=41 (default 11) times more frames per run: less noise from start-up.
# EXTRA='--shading ao' adds options to every run (word-split).
# A spec whose RENDERER is `bare` times build/tests/measure/measure_bare_embree
# (its BINARY) on the same primary rays, one thread, no shading (BOUNCES 1):
#   scripts/cpu_frame_time.sh bunny 1 3 bare:build/tests/measure/measure_bare_embree:bare: packet:build/passtrace:1:bvh8-packet
S=$1; N=$2; R=$3; shift 3
F=${FRAMES:-11}
read -r -a X <<<"${EXTRA:-}"
tc() { perf stat -x, -e task-clock "$@" 2>&1 >/dev/null | grep task-clock | cut -d, -f1; }
for i in $(seq "$R"); do
  for spec in "$@"; do
    IFS=: read -r l b r a <<<"$spec"
    if [ "$r" = bare ]; then
      t1=$(tc "$b" "$S" 512 1 1)
      t11=$(tc "$b" "$S" 512 1 "$F")
    else
      t1=$(tc "$b" -r "$r" -a "$a" -s "$S" -w 512 -b "$N" -m 1 --threads 1 "${X[@]}")
      t11=$(tc "$b" -r "$r" -a "$a" -s "$S" -w 512 -b "$N" -m "$F" --threads 1 "${X[@]}")
    fi
    echo "$l $(echo "($t11 - $t1)/($F - 1)" | bc -l)"
  done
done | awk -v t="$S b$N" -v x="${EXTRA:+ $EXTRA}" '{ if (!($1 in m) || $2 < m[$1]) m[$1] = $2 }
  END { printf "%s%s: ", t, x; for (k in m) printf "%s=%.2f ms ", k, m[k];
        for (b in m) if (b == "embree" || b == "bare") for (k in m) if (k != b) printf " %s/%s=%.2f", b, k, m[b] / m[k];
        print "" }'
