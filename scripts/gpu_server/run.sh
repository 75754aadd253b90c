#!/bin/bash
# Runs every stream row on the GPU server from a pack.sh tarball unpacked in
# DIR: primary rays (-b 1, -m 3) and ambient-occlusion rays (--shading ao,
# -m 2) at 1920x1080 on the bunny and (when packed) BART Kitchen, plus a
# 10M-triangle sphere field for bvh-stack; one JSON object per run in OUT.
#   run.sh DIR OUT.jsonl [ROWS...]   (ROWS: default every stream row)
set -uo pipefail
dir=$(realpath "$1"); out=$2; shift 2
export LD_LIBRARY_PATH=$dir/lib PASSTRACE_BART_DIR=$dir/bart
mkdir -p /usr/share/glmark2/models && cp -n "$dir/bunny.obj" /usr/share/glmark2/models/
P=$dir/bin/passtrace
rows=${*:-$($P --list --json | python3 -c "import json,sys; print(' '.join(r['name'] for r in json.load(sys.stdin)['accelerators'] if 'gpu' in r['renderers']))")}
: > "$out"
one() {  # label, passtrace arguments: appends the run's JSON (or its error line) to OUT
  local label=$1; shift
  if timeout 120 "$P" "$@" --json /tmp/gpu_server_run.json -q > /tmp/gpu_server_run.out 2>&1; then
    python3 - "$label" "$*" >> "$out" <<'PY'
import json, sys
j = json.load(open("/tmp/gpu_server_run.json"))
keep = ("scene", "rays", "frame_ms", "mrays_per_s", "passes", "build_ms", "steps_per_ray", "triangles", "gl_renderer")
print(json.dumps(dict({k: j.get(k) for k in keep}, label=sys.argv[1], args=sys.argv[2])))
PY
  else
    python3 -c "import json,sys; print(json.dumps({'label': sys.argv[1], 'args': sys.argv[2], 'error': sys.argv[3]}))" \
      "$label" "$*" "$(tail -1 /tmp/gpu_server_run.out)" >> "$out"
  fi
}
hd=(--width 1920 --height 1080)
scenes=(bunny); [ -d "$dir/bart/kitchen" ] && scenes+=(kitchen)
for s in "${scenes[@]}"; do for r in $rows; do
  one primary -r 2 -a "$r" -s "$s" "${hd[@]}" -b 1 -m 3
  one ao -r 2 -a "$r" -s "$s" "${hd[@]}" --shading ao -m 2
done; done
one primary -r 2 -a bvh-stack -s spheres --triangles 10000000 "${hd[@]}" -b 1 -m 3
one ao -r 2 -a bvh-stack -s spheres --triangles 10000000 "${hd[@]}" --shading ao -m 2
