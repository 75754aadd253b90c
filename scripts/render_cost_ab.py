#!/usr/bin/env python3
"""The CPU renderer's cost around the traversal (issue 17, item 2): bare Embree
(measure_bare_embree, rtcIntersect1 and --packet) against -r 3 and CPU rows of
several passtrace binaries, primary rays, run alternated back to back in rounds;
each cell is the minimum over the rounds of the run's own minimum frame time
(-m REPEATS). The machine is shared, so read ratios within one table.
--cpu-time: each cell is processor time per frame instead, from perf stat's
task-clock of a run of REPEATS frames minus a run of one, over REPEATS - 1 (the
load, build and start-up cancel; the per-frame set-up outside the timed frame,
the same code in every binary, stays). Under a load above the core count, wall
clock counts other processes' time slices; processor time much less so.

  scripts/render_cost_ab.py [--cpu-time] [--rounds 3] [--repeats 10] [--size 512] [--scenes bunny,kitchen,robots]
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


CPU_TIME = False
BOUNCES = 1  # -b of the passtrace runs; the bare loops trace primary rays only


def task_clock_ms(cmd):
    out = subprocess.run(["perf", "stat", "-x,", "-e", "task-clock"] + cmd, check=True, capture_output=True,
                         text=True).stderr
    return float(next(line for line in out.splitlines() if "task-clock" in line).split(",")[0])


def per_frame_cpu_ms(make_cmd, repeats):
    return (task_clock_ms(make_cmd(repeats)) - task_clock_ms(make_cmd(1))) / (repeats - 1)


def bare(scene, size, threads, repeats, packet):
    cmd = lambda m: [BARE, scene, str(size), str(threads), str(m)] + (["--packet"] if packet else [])
    if CPU_TIME:
        return per_frame_cpu_ms(cmd, repeats)
    return json.loads(subprocess.run(cmd(repeats), check=True, capture_output=True, text=True).stdout)["min_ms"]


def passtrace(binary, renderer, accel, scene, size, threads, repeats):
    if CPU_TIME:
        return per_frame_cpu_ms(lambda m: [binary, "-r", renderer, "-a", accel, "-s", scene, "-w", str(size), "-b",
                                           str(BOUNCES), "-m", str(m), "--threads", str(threads), "-q"], repeats)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "run.json")
        subprocess.run([binary, "-r", renderer, "-a", accel, "-s", scene, "-w", str(size), "-b", str(BOUNCES), "-m",
                        str(repeats), "--threads", str(threads), "--json", out, "-q"], check=True)
        with open(out) as f:
            return json.load(f)["frame_ms"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--cpu-time", action="store_true", help="processor time per frame instead of wall clock")
    p.add_argument("--bounces", type=int, default=1, help="-b of the passtrace runs (bare: primary rays only)")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--repeats", type=int, default=10)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--scenes", default="bunny,kitchen,robots")
    p.add_argument("--threads", default="1,2")
    p.add_argument("--rows", default="3:embree,1:bvh8,1:bvh8-packet")
    p.add_argument("binaries", nargs="+", help="LABEL=BINARY")
    a = p.parse_args()
    global CPU_TIME, BOUNCES
    CPU_TIME, BOUNCES = a.cpu_time, a.bounces
    if CPU_TIME and a.repeats < 2:
        p.error("--cpu-time needs --repeats of at least 2")
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
            what = "processor time per frame" if CPU_TIME else "min frame time"
            print(f"\n{scene}, {a.size}^2, {threads} thread(s), -b {BOUNCES}, {what}, "
                  f"min of {a.rounds} rounds x -m {a.repeats}")
            print("| run | ms/frame | Mrays/s | bare rtcIntersect1 / run |\n|---|---|---|---|")
            for name, ms in cells.items():
                print(f"| {name} | {ms:.2f} | {a.size * a.size / ms / 1000:.1f} | {base / ms:.2f} |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
