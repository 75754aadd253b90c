#!/usr/bin/env python3
"""The CPU renderer's cost around the traversal (issue 17, item 2): bare Embree
(measure_bare_embree, rtcIntersect1 and --packet) against -r 3 and CPU rows of
several passtrace binaries, primary rays, run alternated back to back in rounds;
each cell is the minimum over the rounds of the run's own minimum frame time
(-m REPEATS). The machine is shared, so read ratios within one table.

  scripts/render_cost_ab.py [--rounds 3] [--repeats 10] [--size 512] [--scenes bunny,kitchen,robots]
                            [--threads 1,2] LABEL=BINARY ...
Rows per binary: -r 3 embree, -r 1 bvh8, -r 1 bvh8-packet (--rows to change).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BARE = os.path.join(ROOT, "build", "tests", "measure", "measure_bare_embree")


def bare(scene, size, threads, repeats, packet):
    cmd = [BARE, scene, str(size), str(threads), str(repeats)] + (["--packet"] if packet else [])
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)["min_ms"]


def passtrace(binary, renderer, accel, scene, size, threads, repeats):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "run.json")
        subprocess.run([binary, "-r", renderer, "-a", accel, "-s", scene, "-w", str(size), "-b", "1", "-m",
                        str(repeats), "--threads", str(threads), "--json", out, "-q"], check=True)
        with open(out) as f:
            return json.load(f)["frame_ms"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--repeats", type=int, default=10)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--scenes", default="bunny,kitchen,robots")
    p.add_argument("--threads", default="1,2")
    p.add_argument("--rows", default="3:embree,1:bvh8,1:bvh8-packet")
    p.add_argument("binaries", nargs="+", help="LABEL=BINARY")
    a = p.parse_args()
    binaries = [b.split("=", 1) for b in a.binaries]
    rows = [r.split(":", 1) for r in a.rows.split(",")]
    for scene in a.scenes.split(","):
        for threads in [int(t) for t in a.threads.split(",")]:
            cells = {}
            for _ in range(a.rounds):
                runs = [("bare rtcIntersect1", lambda: bare(scene, a.size, threads, a.repeats, False)),
                        ("bare packets", lambda: bare(scene, a.size, threads, a.repeats, True))]
                for label, binary in binaries:
                    for renderer, accel in rows:
                        runs.append((f"{label} -r {renderer} {accel}",
                                     lambda b=binary, r=renderer, x=accel: passtrace(b, r, x, scene, a.size, threads,
                                                                                     a.repeats)))
                for name, run in runs:
                    ms = run()
                    cells[name] = min(cells.get(name, ms), ms)
            base = cells["bare rtcIntersect1"]
            print(f"\n{scene}, {a.size}^2, {threads} thread(s), -b 1, min of {a.rounds} rounds x -m {a.repeats}")
            print("| run | ms/frame | Mrays/s | bare rtcIntersect1 / run |\n|---|---|---|---|")
            for name, ms in cells.items():
                print(f"| {name} | {ms:.2f} | {a.size * a.size / ms / 1000:.1f} | {base / ms:.2f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
