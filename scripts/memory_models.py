#!/usr/bin/env python3
"""Measures the registry's memory models (accel/registry.h, MemoryModel).

Every structure on every renderer it runs on is run on the procedural spheres
at a small and a large size, and once at the smallest size for the base (the
process, its libraries and the GL), each run alone, its peak resident set taken
from the kernel (ru_maxrss of the child):

    passtrace -s spheres --triangles N -r R -a A -w 64 -b 1

with the default thread count and an image written, as a run is. The model
is the run's bytes beyond the base: bytes per triangle, the larger of the two
sizes', and the growth e of c * N^e through them, at least 1, with which the
memory check extrapolates above the large size. Prints a Markdown table and
the registry's `.memory` values.

    python3 scripts/memory_models.py [--binary build/passtrace]
        [--sizes 1000000,4000000] [--rows NAME ...] [--json OUT]

The runs are long (about 40 minutes for every row at 4 M on 2 cores); the
memory they need is the model's, so the machine must hold the largest row's
peak at the large size (kd-pbrt's: about 14 GiB at 4 M).
"""
import argparse
import json
import math
import os
import pathlib
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import passtrace_registry  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parent.parent
RENDERERS = ["cpu", "gpu", "embree"]
BASE_TRIANGLES = 1000  # the scene's smallest
TIMEOUT_S = 900


def peak_run(binary, args):
    """(peak resident bytes, the run's --json) of one run; exits naming the run if it fails."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp)
        cmd = [str(binary)] + args + ["-o", str(out / "image.png"), "--json", str(out / "run.json"), "-q"]
        start = time.monotonic()
        pid = os.fork()
        if pid == 0:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, 1)
            os.dup2(devnull, 2)
            os.execv(cmd[0], cmd)
        _, status, usage = os.wait4(pid, 0)
        if os.waitstatus_to_exitcode(status) != 0:
            raise SystemExit(f"failed ({os.waitstatus_to_exitcode(status)}): {' '.join(cmd)}")
        result = json.loads((out / "run.json").read_text())
        result["wall_s"] = time.monotonic() - start
        return usage.ru_maxrss * 1024, result


def fit(base, small, large):
    """(bytes per triangle, growth) from (triangles, peak) pairs: the larger of the two sizes'
    bytes per triangle beyond the base, and the exponent through them, at least 1 (a row whose
    bytes per triangle fall with size keeps its small size's, and is never extrapolated lower)."""
    (n1, p1), (n2, p2) = small, large
    per1, per2 = max(p1 - base, 1) / n1, max(p2 - base, 1) / n2
    growth = math.log(per2 * n2 / (per1 * n1)) / math.log(n2 / n1)
    return max(per1, per2), max(1.0, growth)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(REPO / "build" / "passtrace"))
    parser.add_argument("--sizes", default="1000000,4000000", help="the small and the large size (triangles)")
    parser.add_argument("--rows", nargs="*", help="structures to measure (default: every row)")
    parser.add_argument("--json", help="write every run's triangles and peak here")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    if len(sizes) != 2 or not 1000 <= sizes[0] < sizes[1]:
        raise SystemExit("--sizes: two sizes, the smaller first, at least 1000")

    registry = passtrace_registry.load(args.binary)
    ids = {r: passtrace_registry.renderer_id(registry, r) for r in RENDERERS}
    rows = [a for a in registry["accelerators"] if not args.rows or a["name"] in args.rows]
    if args.rows and len(rows) != len(args.rows):
        raise SystemExit(f"--rows: not in the registry: {set(args.rows) - {a['name'] for a in rows}}")
    common = ["-w", "64", "-b", "1"]
    runs = []
    bases = {}
    for renderer in ("cpu", "gpu"):
        name = next(a["name"] for a in registry["accelerators"] if renderer in a["renderers"])
        bases[renderer], _ = peak_run(args.binary, ["-s", "spheres", "--triangles", str(BASE_TRIANGLES),
                                                    "-r", ids[renderer], "-a", name] + common)
    bases["embree"] = bases["cpu"]
    print("| structure | renderer | peak at " + " | peak at ".join(f"{n:,}" for n in sizes) +
          " | bytes per triangle | growth |")
    print("|---|---|---|---|---|---|")
    initializers = {}
    for row in rows:
        for renderer in RENDERERS:
            if renderer not in row["renderers"]:
                continue
            points = []
            for n in sizes:
                peak, result = peak_run(args.binary, ["-s", "spheres", "--triangles", str(n), "-r", ids[renderer],
                                                      "-a", row["name"]] + common)
                points.append((result["triangles"], peak))
                runs.append({"structure": row["name"], "renderer": renderer, "triangles": result["triangles"],
                             "peak_bytes": peak, "wall_s": round(result["wall_s"], 1)})
            per, growth = fit(bases[renderer], *points)
            initializers.setdefault(row["name"], {})["gpu" if renderer == "gpu" else "cpu"] = (per, growth)
            print(f"| {row['name']} | {renderer} | " + " | ".join(f"{p / 2**20:,.0f} MiB" for _, p in points) +
                  f" | {per:.0f} | {growth:.2f} |", flush=True)
    print(f"\nbase (-r 1, -r 2 at {BASE_TRIANGLES} triangles): {bases['cpu'] / 2**20:.0f} MiB, "
          f"{bases['gpu'] / 2**20:.0f} MiB\n")
    for name, models in initializers.items():
        cpu, gpu = models.get("cpu", (0, 1)), models.get("gpu", (0, 1))
        print(f"{name}: .memory = {{{{{cpu[0]:.0f}, {cpu[1]:.2f}}}, {{{gpu[0]:.0f}, {gpu[1]:.2f}}}}}")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps({"sizes": sizes, "bases": bases, "runs": runs}, indent=1) + "\n")


if __name__ == "__main__":
    main()
