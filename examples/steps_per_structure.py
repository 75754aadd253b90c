#!/usr/bin/env python3
"""Steps per ray, structure by structure: what a researcher scripts with the
passtrace module. Traces the camera's rays of one scene that hit it through
every structure the CPU renderer has, with the per-ray counters on, and plots
the distribution of traversal steps per ray (median, quartiles, 5th-95th
percentiles) for each structure, sorted by the median. Steps are what each
traversal counts (docs/outputs.md): a box or cell visited and a triangle
tested, where some CPU rows (kd-tree, kd-pbrt, grid, octree-descent) test a leaf's
triangles within one step.

    bash scripts/setup.sh --python
    PYTHONPATH=build/python python3 examples/steps_per_structure.py -s bunny -o steps.png

Runs under Debian's python3 (numpy, matplotlib): started under another
interpreter that lacks them, it starts itself again under /usr/bin/python3.
"""
import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def use_debian_python():
    """numpy and matplotlib from Debian's packages: rerun under /usr/bin/python3 if missing."""
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError:
        system = "/usr/bin/python3"
        if os.path.realpath(sys.executable) == os.path.realpath(system) or not os.access(system, os.X_OK):
            sys.exit("steps_per_structure: needs numpy and matplotlib (apt-get install python3-numpy python3-matplotlib)")
        os.execv(system, [system, os.path.abspath(__file__)] + sys.argv[1:])


def import_passtrace():
    """The module from PYTHONPATH, else from the checkout's build/python."""
    try:
        import passtrace
    except ImportError:
        sys.path.insert(0, os.path.join(HERE, "..", "build", "python"))
        try:
            import passtrace
        except ImportError:
            sys.exit("steps_per_structure: no passtrace module: build it (bash scripts/setup.sh --python) "
                     "and set PYTHONPATH=build/python")
    return passtrace


def main():
    use_debian_python()
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-s", "--scene", default="bunny", help="a scene name or file (as the program's -s)")
    parser.add_argument("-w", "--resolution", type=int, default=128, help="camera rays: N x N (default 128)")
    parser.add_argument("-o", "--output", default="steps_per_structure.png", help="the plot (PNG)")
    parser.add_argument("--skip", nargs="*", default=[], help="structures to leave out")
    args = parser.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    passtrace = import_passtrace()

    scene = passtrace.load_scene(args.scene)
    origins, directions = passtrace.camera_rays(scene, args.resolution, args.resolution)
    rows = [r["name"] for r in passtrace.structures() if "cpu" in r["renderers"] and r["name"] not in args.skip]
    # The rays that hit the scene: a miss that leaves the root's box at once
    # costs every structure a step or none, and would swamp the plot.
    hit = passtrace.brute_force(scene).intersect(origins, directions)["id"] != np.uint32(4294967295)
    steps = {}
    print(f"{scene.name}: {scene.triangle_count} triangles, {len(origins)} camera rays, {hit.sum()} of them hit")
    for name in rows:
        started = time.monotonic()
        accel = passtrace.build(scene, name)
        hits = accel.intersect(origins[hit], directions[hit], counters=True)
        steps[name] = hits["steps"].astype(np.float64)
        print(f"  {name:24s} {np.mean(steps[name]):8.1f} steps per ray "
              f"(build and trace {time.monotonic() - started:.1f} s)")

    order = sorted(steps, key=lambda n: np.median(steps[n]))
    fig, ax = plt.subplots(figsize=(8, 0.32 * len(order) + 1.2))
    ax.boxplot([steps[n] for n in order], vert=False, labels=order, whis=(5, 95), showfliers=False)
    ax.set_xscale("log")
    ax.set_xlabel("traversal steps per camera ray that hits (box: quartiles; whiskers: 5th-95th percentile)")
    ax.set_title(f"{scene.name}, {args.resolution}x{args.resolution} camera rays, CPU structures, default parameters",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
