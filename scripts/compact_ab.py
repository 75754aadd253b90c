#!/usr/bin/env python3
"""--compact off, on and always (issue 17, item 3): runs made back to back,
alternated, in one process; the fastest frame of each cell over the rounds.
Usage: python3 scripts/compact_ab.py [rounds [case filter]]   (from the repository root;
the filter keeps the cases whose label contains it, e.g. whitted)"""
import json, subprocess, sys, tempfile, os

ROUNDS = int(sys.argv[1]) if len(sys.argv) > 1 else 2
STRUCTURES = ["kk-bvh", "kd-stack", "bvh-stack"]
CASES = [  # (label, arguments)
    ("bunny 512, -b 1, -l 20", "-s bunny -w 512 -b 1 -l 20 -m 3"),
    ("bunny 512, -b 1, -l 100000", "-s bunny -w 512 -b 1 -l 100000 -m 3"),
    ("bunny 512, -b 3, -l 20", "-s bunny -w 512 -b 3 -l 20 -m 2"),
    ("kitchen 256, whitted -b 6, -l 20", "-s kitchen -w 256 --shading whitted -b 6 -l 20 -m 2"),
    ("cornell 256, whitted -b 6, -l 3", "-s cornell -w 256 --shading whitted -b 6 -l 3 -m 3"),
]
MODES = ["off", "on", "always"]
if len(sys.argv) > 2:
    CASES = [c for c in CASES if sys.argv[2] in c[0]]

best = {}
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "r.json")
    for rnd in range(ROUNDS):
        for label, args in CASES:
            for s in STRUCTURES:
                for compact in MODES:
                    cmd = f"build/passtrace -r 2 -a {s} {args} --compact {compact} --json {out}".split()
                    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                    j = json.load(open(out))
                    key = (label, s, compact)
                    ms = j["frame_ms"]
                    if key not in best or ms < best[key]["ms"]:
                        best[key] = {"ms": ms, "rays": j["rays"], "passes": j["passes"]}
                    print(rnd, label, s, compact, f"{ms:.1f} ms", f"{j['rays'] / ms / 1e3:.3f} Mrays/s",
                          j["passes"], "passes", file=sys.stderr, flush=True)

print("| case | structure | passes | rays | off Mrays/s | on | always | on / off | always / off |")
print("|---|---|---|---|---|---|---|---|---|")
for label, _ in CASES:
    for s in STRUCTURES:
        m = {c: best[(label, s, c)]["rays"] / best[(label, s, c)]["ms"] / 1e3 for c in MODES}
        off = best[(label, s, "off")]
        print(f"| {label} | {s} | {off['passes']:.0f} | {off['rays']:.0f} | {m['off']:.3f} | {m['on']:.3f} | "
              f"{m['always']:.3f} | {m['on'] / m['off']:.2f} | {m['always'] / m['off']:.2f} |")
