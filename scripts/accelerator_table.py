#!/usr/bin/env python3
"""Every acceleration structure on both ray tracers, side by side with the
thesis's Tables 1 (ms per frame, GeForce 6800) and 3 (floats per triangle).

Runs build/passtrace once per (scene, renderer, structure) in one session and
prints a Markdown table; the per-run JSON goes to --out. The structures are
every one `passtrace --list --json` lists for each renderer, in the thesis's
order (so the CPU rows include the GPU kernels' CPU mirrors). Timings are the
minimum of -m repeats; compare them as ratios within one run.
"""
import argparse
import json
import pathlib
import subprocess
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import passtrace_registry  # noqa: E402
from bench_report import THESIS_FLOATS, THESIS_MS  # noqa: E402  (Tables 1 and 3, one copy)

# Thesis 10.2: per-scene grid resolution multipliers.
GRID_MULTIPLIER = {"bunny": 1.1, "cornell": 0.6}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--binary", default="build/passtrace")
    parser.add_argument("--scenes", default="bunny,cornell")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--bounces", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default="accelerator_table")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    registry = passtrace_registry.load(args.binary)
    lists = [(passtrace_registry.renderer_id(registry, r), passtrace_registry.structures(registry, r))
             for r in ("gpu", "cpu")]

    print("| scene | renderer | structure | frame ms | Mrays/s | floats/tri | steps/ray | tests/ray | build ms "
          "| thesis ms (6800) | ratio to thesis | thesis floats/tri |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for scene in args.scenes.split(","):
        for renderer, names in lists:
            for name in names:
                result = out / f"{scene}_r{renderer}_{name}.json"
                cmd = [args.binary, "-s", scene, "-r", renderer, "-a", name, "-w", str(args.size),
                       "-b", str(args.bounces), "-m", str(args.repeats)]
                cmd += passtrace_registry.build_flags(name, grid_multiplier=GRID_MULTIPLIER.get(scene, 1.0))
                cmd += ["--json", str(result), "-q"]
                run = subprocess.run(cmd, capture_output=True, text=True)
                if run.returncode != 0:
                    print(f"| {scene} | {renderer} | {name} | failed: {run.stderr.strip()} |")
                    continue
                j = json.loads(result.read_text())
                thesis_ms = THESIS_MS.get(name, {}).get(scene) if renderer == "2" else None
                thesis_floats = THESIS_FLOATS.get({"kd-tree": "kd-restart"}.get(name, name) if renderer == "1" else name,
                                                  {}).get(scene)
                ratio = f"{j['frame_ms'] / thesis_ms:.2f}" if thesis_ms else ""
                print(f"| {scene} | {'GPU' if renderer == '2' else 'CPU'} | {name} | {j['frame_ms']:.1f} | "
                      f"{j['mrays_per_s']:.3f} | {j['accel_floats_per_triangle']:.2f} | {j['steps_per_ray']:.1f} | "
                      f"{j['triangle_tests_per_ray']:.1f} | {j['build_ms']:.0f} | {thesis_ms or ''} | {ratio} | "
                      f"{thesis_floats if thesis_floats is not None else ''} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
