#!/usr/bin/env python3
"""Seed 003's experiments on this machine (Papay 2025: kd-trees on a GPU).

    python3 scripts/bench.py --papay [--size 256] [--quick-10m] ...

Four experiments, each a list of passtrace runs (one record per run in
OUT/runs/, reused by a rerun like the main suite), then OUT/REPORT.md with the
seed's numbers (../shared/docs/seed-systems.md, "Seed 003") beside ours and
each of its claims marked holds / does not hold here:

  traversals  the seven traversals of one kd-tree (Stack, Restart, PushDown,
              RestartShortStack 4 and 8, PushDownShortStack 4 and 8) on both
              renderers, primary rays (-b 1): Mrays/s, steps and triangle tests
              per ray (mean, max);
  builds      exact against binned SAH, with the thesis's and the seed's
              termination rules: build ms, SAH cost, nodes, leaves,
              references, MB, and the trace speed of the tree (CPU kd-tree);
  dynamic     rebuild against two trees against merging, --frames over an
              animation on both renderers: per-frame build-or-merge, trace
              and their sum T_F.

Scenes: the thesis's five, and procedural sphere fields of 1M and 10M
triangles (the 10M scene runs a subset: Restart, PushDown and PushDownSS(4)
with the binned builder and the seed's rules, whose build is the one that
finishes in reasonable time here). The dynamic experiment runs the built-in
tests/data/gltf/dynamic.gltf (static floor, pillars and sphere; a sphere on a
rigid path, a spinning bar and a morphing sphere) and BART Robots. Absolute numbers are llvmpipe's on a
shared 2-core machine; the ratios, taken within one run of this script, are
what the report compares with the seed's RTX 4080 numbers.
"""
import pathlib
import statistics

from report_tables import num, md_table, result, field, verdict
from bench_report import write_atomically
from passtrace_registry import scene_available

# The seed's traversal names, and passtrace's structure and stack size for each.
TRAVERSALS = [
    ("Stack", "kd-stack", None),
    ("Restart", "kd-restart", None),
    ("PushDown", "kd-pushdown", None),
    ("RestartSS(4)", "kd-shortstack", 4),
    ("RestartSS(8)", "kd-shortstack", 8),
    ("PushDownSS(4)", "kd-pushdown-shortstack", 4),
    ("PushDownSS(8)", "kd-pushdown-shortstack", 8),
]
TRAVERSALS_10M = ["Restart", "PushDown", "PushDownSS(4)"]

# (label, passtrace scene arguments)
SCENES = [
    ("cows", ["-s", "cows"]),
    ("robots", ["-s", "robots"]),
    ("kitchen", ["-s", "kitchen"]),
    ("bunny", ["-s", "bunny"]),
    ("cornell", ["-s", "cornell"]),
    ("spheres-1M", ["-s", "spheres", "--triangles", "1000000"]),
    ("spheres-10M", ["-s", "spheres", "--triangles", "10000000"]),
    # The seed's own scenes (scenes/real_scenes.h): Sibenik exactly the seed's,
    # Conference another tessellation, Sponza Dabrovic's original, not Crytek's.
    ("sibenik", ["-s", "sibenik"]),
    ("conference", ["-s", "conference"]),
    ("sponza", ["-s", "sponza"]),
]
BART = {"robots", "kitchen"}

# exact/binned x thesis/papay, on the CPU's stack-traversed kd-tree.
BUILDS = [("exact", "thesis"), ("binned", "thesis"), ("exact", "papay"), ("binned", "papay")]
BUILDS_10M = [("binned", "thesis"), ("binned", "papay"), ("exact", "papay")]

# Animated scenes: (label, scene arguments, frames).
DYNAMIC_GLTF = pathlib.Path(__file__).resolve().parent.parent / "tests" / "data" / "gltf" / "dynamic.gltf"
DYNAMIC_SCENES = [
    ("dynamic.gltf", ["-s", str(DYNAMIC_GLTF)], 30),
    ("robots", ["-s", "robots"], 30),
]
# Papay's Sibenik1/2/3 (scripts/dynamic_sibenik.py): made from the real
# Sibenik when `sibenik` is among the scenes and found, 30 frames each.
SIBENIK_DYNAMIC = [1, 2, 3]
STRATEGIES = ["rebuild", "two-trees", "merge"]
DYNAMIC_STRUCTURE = {"cpu": "kd-tree", "gpu": "kd-pushdown-shortstack"}

# Seed 003's tables as the digest quotes them (RTX 4080, 3840x2160).
SEED_MRAYS = {  # Stack / Restart / PushDown / RestartSS4 / RestartSS8 / PushDownSS4 / PushDownSS8
    "Bistro": [22.48, 113.16, 115.65, 92.47, 69.56, 91.33, 67.76],
    "Buddha": [237.19, 781.04, 836.12, 647.12, 557.86, 651.91, 552.04],
    "Conference": [240.06, 773.57, 944.86, 939.31, 613.96, 932.11, 600.68],
    "FairyForest": [254.28, 845.45, 945.97, 1029.84, 650.53, 1020.29, 643.83],
    "Field": [83.66, 273.10, 288.39, 255.54, 184.11, 251.35, 178.42],
    "Powerplant": [38.92, 112.10, 113.71, 65.82, 64.87, 65.88, 64.35],
    "SanMiguel": [35.59, 168.43, 171.71, 128.89, 99.87, 128.30, 98.54],
    "Sibenik": [190.26, 458.96, 546.62, 682.08, 420.67, 685.03, 416.43],
    "Sponza": [98.03, 250.26, 259.85, 294.40, 194.10, 294.06, 192.92],
    "Street": [142.04, 542.52, 599.05, 588.02, 395.18, 588.26, 391.73],
}
SEED_STEPS = {  # Stack / Restart / PushDown / PushDownSS4
    "Bistro": [225.79, 834.95, 766.18, 239.67], "Buddha": [28.63, 96.47, 79.94, 29.67],
    "Conference": [56.06, 172.10, 131.77, 58.13], "FairyForest": [56.87, 161.07, 138.03, 58.70],
    "Field": [77.50, 275.96, 224.73, 80.97], "Powerplant": [143.18, 594.91, 575.84, 158.16],
    "SanMiguel": [152.16, 530.26, 484.37, 160.04], "Sibenik": [96.44, 312.91, 260.05, 100.86],
    "Sponza": [150.15, 530.52, 489.74, 159.63], "Street": [67.38, 212.27, 169.92, 69.40],
}
# Tables D.47-D.52 (Sibenik with 1, 2, 3 moving objects): per strategy, T_B,S
# (static build, ms), T_B,D (per-frame build or merge, ms), T_TP (GPU upload,
# ms; None on the CPU) and T_F (s per frame). single = rebuild everything,
# double = two trees.
SEED_DYNAMIC = {
    "Sibenik1": {("cpu", "rebuild"): (0.01, 2097.86, None, 2.21), ("cpu", "two-trees"): (1733.11, 127.81, None, 0.16),
                 ("cpu", "merge"): (529.51, 1544.07, None, 1.61), ("gpu", "rebuild"): (0.00, 113.84, 30.19, 0.15),
                 ("gpu", "two-trees"): (92.19, 103.33, 5.05, 0.14)},
    "Sibenik2": {("cpu", "rebuild"): (0.00, 2131.95, None, 2.24), ("cpu", "two-trees"): (1714.91, 230.50, None, 0.26),
                 ("cpu", "merge"): (535.40, 1732.95, None, 1.82), ("gpu", "rebuild"): (0.00, 123.39, 31.07, 0.16),
                 ("gpu", "two-trees"): (92.22, 106.80, 6.67, 0.14)},
    "Sibenik3": {("cpu", "rebuild"): (0.00, 2136.12, None, 2.24), ("cpu", "two-trees"): (1743.84, 351.98, None, 0.40),
                 ("cpu", "merge"): (533.34, 1889.51, None, 1.99), ("gpu", "rebuild"): (0.00, 127.93, 31.04, 0.17),
                 ("gpu", "two-trees"): (91.90, 99.16, 8.29, 0.14)},
}
SEED_BUILD_MS = {  # CPU exact / CPU binned / GPU (Ryzen 5 5600, one thread)
    "Conference": (2722.47, 1945.62, 129.24), "Sibenik": (2180.09, 2131.99, 128.53),
    "Sponza": (8221.02, 6690.59, 184.01), "Buddha": (8756.46, 15092.81, 342.71),
    "Powerplant": (132673.95, 104345.23, 2468.47),
}


def traversal_label(structure, stack):
    return next(label for label, s, k in TRAVERSALS if s == structure and k == stack)


def seed_ratio_range(num, den):
    """(min, max) over the seed's scenes of Mrays(num) / Mrays(den), by traversal label."""
    names = [t[0] for t in TRAVERSALS]
    ratios = [row[names.index(num)] / row[names.index(den)] for row in SEED_MRAYS.values()]
    return min(ratios), max(ratios)


class Plan:
    """The runs of the three experiments: [(kind, meta, args, key)]."""

    def __init__(self, size, repeats, registry, scenes, bart_ok, frames=None, dyn_size=None, more_dynamic=()):
        """Dynamic runs first and the 10M scene last, so that a run cut short still covers every experiment.
        more_dynamic: (label, scene arguments, frames) of generated scenes, run like DYNAMIC_SCENES."""
        self.size, self.repeats = size, repeats
        self.dyn_size = dyn_size or max(32, size // 2)
        known = {r["name"]: r["renderers"] for r in registry["accelerators"]}
        self.missing = sorted({s for _, s, _ in TRAVERSALS if s not in known})
        self.jobs, self.skipped = [], []
        # dynamic.gltf always runs (it is built in); BART Robots when chosen; the generated ones when made.
        chosen = [d for d in DYNAMIC_SCENES if d[0] in scenes or d[0] == "dynamic.gltf"] + list(more_dynamic)
        for label, scene_args, n in chosen:
            if label in BART and not bart_ok:
                continue
            for renderer, rid in (("cpu", "1"), ("gpu", "2")):
                structure = DYNAMIC_STRUCTURE[renderer]
                if structure not in known:
                    continue
                for strategy in STRATEGIES:
                    args = scene_args + ["-r", rid, "-a", structure, "-w", str(self.dyn_size), "-b", "1",
                                         "--frames", str(frames or n), "--dynamic", strategy]
                    key = f"dyn__{label}__{renderer}__{strategy}"
                    self.jobs.append(("dynamic", {"key": key, "scene": label, "renderer": renderer,
                                                  "strategy": strategy, "structure": structure}, args, key))
        for label, scene_args in SCENES:
            if label not in scenes:
                continue
            if (label in BART and not bart_ok) or not scene_available(registry, label):
                self.skipped.append(label)
                continue
            big = label == "spheres-10M"
            for renderer, rid in (("gpu", "2"), ("cpu", "1")):
                for name, structure, stack in TRAVERSALS:
                    if structure not in known or renderer not in known[structure]:
                        continue
                    if big and name not in TRAVERSALS_10M:
                        continue
                    args = scene_args + ["-r", rid, "-a", structure, "-w", str(size), "-b", "1",
                                         "-m", str(repeats)]
                    if stack:
                        args += ["--stack-size", str(stack)]
                    if big:  # the exact thesis-rule build of 10M triangles takes minutes here
                        args += ["--kd-builder", "binned", "--kd-termination", "papay"]
                    key = f"trav__{label}__{renderer}__{name}"
                    self.jobs.append(("traversal", {"key": key, "scene": label, "renderer": renderer,
                                                    "traversal": name, "structure": structure}, args, key))
            if "kd-tree" in known:
                for builder, rules in (BUILDS_10M if big else BUILDS):
                    args = scene_args + ["-r", "1", "-a", "kd-tree", "-w", str(size), "-b", "1", "-m",
                                         str(repeats), "--kd-builder", builder, "--kd-termination", rules]
                    key = f"build__{label}__{builder}__{rules}"
                    self.jobs.append(("build", {"key": key, "scene": label, "builder": builder, "rules": rules},
                                      args, key))


# ---------------------------------------------------------------- the report











def traversal_section(records, scenes):
    out, claims = ["## Traversals: one kd-tree, seven ways (seed 003 ch. 6, Tables D.4–D.40)", ""], []
    names = [t[0] for t in TRAVERSALS]
    by = {(m["scene"], m["renderer"], m["traversal"]): result(rec) for m, rec in records
          if m.get("traversal")}
    for renderer in ("gpu", "cpu"):
        title = "GPU stream (llvmpipe)" if renderer == "gpu" else "CPU (the kernels' algorithms, 2 threads)"
        rows, steps = [], []
        for s in scenes:
            rs = [by.get((s, renderer, n)) for n in names]
            if not any(rs):
                continue
            rows.append([s] + [num(field(r, "mrays_per_s"), 2) for r in rs])
            steps.append([s] + [(f"{num(field(r, 'steps_per_ray'))} ({num(field(r, 'max_steps_per_ray'), 0)})"
                                 if r else "–") for r in rs])
        if not rows:
            continue
        out += [f"### {title}: Mrays/s", "", md_table(["scene"] + names, rows), "",
                f"### {title}: traversal steps per ray, mean (max)", "", md_table(["scene"] + names, steps), ""]

    out += ["### The seed's numbers (RTX 4080, CUDA; Mrays/s, then steps per ray)", "",
            md_table(["scene"] + names, [[s] + [num(v, 2) for v in row] for s, row in SEED_MRAYS.items()]), "",
            md_table(["scene", "Stack", "Restart", "PushDown", "PushDownSS(4)"],
                     [[s] + [num(v, 2) for v in row] for s, row in SEED_STEPS.items()]), ""]

    def ratios(num_name, den_name, key="mrays_per_s"):
        got = []
        for (s, renderer, n), r in by.items():
            if n != num_name or r is None:
                continue
            d = by.get((s, renderer, den_name))
            a, b = field(r, key), field(d, key)
            if a and b:
                got.append((s, renderer, a / b))
        return sorted(got)

    def claim(text, seed, got, holds_if, unit="×"):
        if not got:
            claims.append((text, seed, "not measured (runs missing)", "–"))
            return
        lo, hi = min(g[2] for g in got), max(g[2] for g in got)
        holding = sum(1 for g in got if holds_if(g[2]))
        evidence = (f"{lo:.2f}–{hi:.2f}{unit} over {len(got)} scene/renderer pairs; holds in {holding} of "
                    f"{len(got)}")
        claims.append((text, seed, evidence, verdict(holding == len(got))))

    lo, hi = seed_ratio_range("PushDown", "Restart")
    claim("Push-down beats restart on every scene (Mrays/s)", f"{lo:.3f}–{hi:.3f}×",
          ratios("PushDown", "Restart"), lambda x: x > 1.0)
    steps_seed = [row[2] / row[1] for row in SEED_STEPS.values()]
    claim("Push-down takes fewer steps than restart (steps ratio)",
          f"{min(steps_seed):.2f}–{max(steps_seed):.2f}×", ratios("PushDown", "Restart", "steps_per_ray"),
          lambda x: x < 1.0)
    lo4, hi4 = seed_ratio_range("RestartSS(4)", "RestartSS(8)")
    claim("Short-stack(4) beats short-stack(8), restart variant", f"{lo4:.2f}–{hi4:.2f}×",
          ratios("RestartSS(4)", "RestartSS(8)"), lambda x: x > 1.0)
    lo4, hi4 = seed_ratio_range("PushDownSS(4)", "PushDownSS(8)")
    claim("Short-stack(4) beats short-stack(8), push-down variant", f"{lo4:.2f}–{hi4:.2f}×",
          ratios("PushDownSS(4)", "PushDownSS(8)"), lambda x: x > 1.0)
    best = []
    for (s, renderer, n), r in by.items():
        if n != "Stack" or not field(r, "mrays_per_s"):
            continue
        stackless = [field(by.get((s, renderer, m)), "mrays_per_s") or 0 for m in names if m != "Stack"]
        if max(stackless) > 0:
            best.append((s, renderer, max(stackless) / field(r, "mrays_per_s")))
    seed_best = [max(row[1:]) / row[0] for row in SEED_MRAYS.values()]
    claim("The best stackless traversal beats the full stack (2.6–5.1× in the seed)",
          f"{min(seed_best):.2f}–{max(seed_best):.2f}×", sorted(best), lambda x: x > 1.0)
    return out, claims


def build_section(records, scenes):
    out, claims = ["## Builds: exact against binned SAH (seed 003 §4.1, §9.2)", ""], []
    by = {(m["scene"], m["builder"], m["rules"]): result(rec) for m, rec in records if m.get("builder")}
    rows = []
    for s in scenes:
        for builder, rules in BUILDS:
            r = by.get((s, builder, rules))
            if r is None:
                continue
            mb = field(r, "accel_structure_bytes", "structure_bytes")
            rows.append([s, builder, rules, num(field(r, "build_ms"), 0), num(field(r, "accel_sah_cost", "sah_cost"), 2),
                         field(r, "accel_nodes"), field(r, "accel_leaves"), field(r, "accel_references"),
                         num(mb / 2**20 if mb else None, 1), field(r, "accel_depth"),
                         num(field(r, "mrays_per_s"), 2)])
    out += [md_table(["scene", "builder", "rules", "build ms", "SAH cost", "nodes", "leaves", "references", "MB",
                      "depth", "Mrays/s (CPU)"], rows), "",
            "The seed's builds, ms (CPU exact / CPU binned / GPU; Ryzen 5 5600, one thread for the CPU): " +
            "; ".join(f"{s} {a:,.0f} / {b:,.0f} / {c:,.0f}" for s, (a, b, c) in SEED_BUILD_MS.items()) + ".", ""]

    cost, speed, faster_build = [], [], []
    for s in scenes:
        for rules in ("thesis", "papay"):
            e, b = by.get((s, "exact", rules)), by.get((s, "binned", rules))
            ce, cb = field(e, "accel_sah_cost", "sah_cost"), field(b, "accel_sah_cost", "sah_cost")
            if ce and cb:
                cost.append((s, rules, cb / ce))
            me, mbr = field(e, "mrays_per_s"), field(b, "mrays_per_s")
            if me and mbr:
                speed.append((s, rules, me / mbr))
            be, bb = field(e, "build_ms"), field(b, "build_ms")
            if be and bb:
                faster_build.append((s, rules, be / bb))
    if cost:
        holding = sum(1 for c in cost if c[2] >= 1.0)
        claims.append(("Exact SAH gives a lower SAH cost than binned", "all five scenes",
                       f"binned/exact cost {min(c[2] for c in cost):.3f}–{max(c[2] for c in cost):.3f}; "
                       f"exact lower in {holding} of {len(cost)}", verdict(holding == len(cost))))
    if speed:
        slower = sum(1 for c in speed if c[2] < 1.0)
        claims.append(("…but exact SAH is not always faster to trace", "not always faster",
                       f"exact/binned Mrays/s {min(c[2] for c in speed):.3f}–{max(c[2] for c in speed):.3f}; "
                       f"exact slower in {slower} of {len(speed)}", verdict(slower > 0)))
    if faster_build:
        seed = [a / b for a, b, _ in SEED_BUILD_MS.values()]
        claims.append(("The binned build is faster than the exact one", f"{min(seed):.2f}–{max(seed):.2f}× "
                       "(Buddha: binned slower)",
                       f"exact/binned build time {min(c[2] for c in faster_build):.2f}–"
                       f"{max(c[2] for c in faster_build):.2f}×",
                       verdict(all(c[2] > 1.0 for c in faster_build))))
    return out, claims


def dynamic_section(records, plots):
    out, claims = ["## Dynamic scenes: rebuild, two trees, merge (seed 003 ch. 10)", ""], []
    by = {(m["scene"], m["renderer"], m["strategy"]): result(rec) for m, rec in records if m.get("strategy")}
    rows = []
    tf = {}
    for (s, renderer, strategy), r in sorted(by.items()):
        if r is None or not r.get("sequence"):
            continue
        seq = r["sequence"]
        build = statistics.mean(f["build_ms"] for f in seq)
        trace = statistics.mean(f["frame_ms"] for f in seq)
        total = statistics.mean(f.get("total_ms", f["build_ms"] + f["frame_ms"]) for f in seq)
        tf[(s, renderer, strategy)] = total
        rows.append([s, renderer, r.get("accelerator"), strategy, len(seq),
                     num(r.get("static_build_ms"), 1), num(build, 2), num(trace, 2), num(total, 2)])
    out += [md_table(["scene", "renderer", "structure", "strategy", "frames", "static build ms",
                      "build/merge ms", "trace ms", "T_F ms"], rows), ""]
    if any(s.startswith("sibenik") for s, _, _ in by):
        seed_rows = [[scene, renderer, strategy, num(v[0], 2), num(v[1], 2), num(v[2], 2) if v[2] is not None else "–",
                      num(v[3] * 1000, 0)]
                     for scene, table in SEED_DYNAMIC.items() for (renderer, strategy), v in table.items()]
        out += ["The seed's Sibenik1/2/3 (Tables D.47–D.52; RTX 4080 and a Ryzen 5 5600, 3840×2160, its own "
                "moving objects of 6,658 triangles each; here spheres of 6,656 flying down the nave, "
                "scripts/dynamic_sibenik.py; the seed's GPU did not merge):", "",
                md_table(["scene", "renderer", "strategy", "T_B,S ms", "T_B,D ms", "T_TP ms", "T_F ms"], seed_rows), ""]
    out += [f"![T_F per frame]({p})" for p in plots] + [""]
    never, halves = [], []
    for (s, renderer, strategy), total in tf.items():
        if strategy != "merge":
            continue
        two, rebuild = tf.get((s, renderer, "two-trees")), tf.get((s, renderer, "rebuild"))
        if two:
            never.append((s, renderer, total / two))
        if rebuild:
            halves.append((s, renderer, total / rebuild))
    if never:
        claims.append(("Merging never beats two trees (T_F)", "merge ≥ two trees",
                       ", ".join(f"{s} {r}: {x:.2f}×" for s, r, x in never) + " (merge / two trees)",
                       verdict(all(x >= 1.0 for _, _, x in never))))
    if halves:
        claims.append(("Merging halves T_F against a full rebuild", "≈ 0.5×",
                       ", ".join(f"{s} {r}: {x:.2f}×" for s, r, x in halves) + " (merge / rebuild)",
                       verdict(all(x <= 0.6 for _, _, x in halves))))
    return out, claims


def plot_dynamic(out_dir, records):
    """One PNG per (scene, renderer): T_F of each frame under each strategy."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    groups = {}
    for m, rec in records:
        r = result(rec)
        if m.get("strategy") and r and r.get("sequence"):
            groups.setdefault((m["scene"], m["renderer"]), []).append((m["strategy"], r["sequence"]))
    paths = []
    (out_dir / "plots").mkdir(exist_ok=True)
    for (scene, renderer), series in sorted(groups.items()):
        fig, ax = plt.subplots(figsize=(6, 3.2))
        for strategy, seq in series:
            ax.plot([f["frame"] for f in seq], [f.get("total_ms", f["build_ms"] + f["frame_ms"]) for f in seq],
                    label=strategy)
        ax.set_xlabel("frame")
        ax.set_ylabel("T_F = build/merge + trace, ms")
        ax.set_title(f"{scene}, {renderer}")
        ax.legend()
        fig.tight_layout()
        p = f"plots/dynamic_{scene}_{renderer}.png"
        fig.savefig(out_dir / p, dpi=90)
        plt.close(fig)
        paths.append(p)
    return paths


def plot_traversals(out_dir, records, scenes):
    """Mrays/s of each traversal relative to Restart, per scene (one PNG per renderer)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    names = [t[0] for t in TRAVERSALS]
    by = {(m["scene"], m["renderer"], m["traversal"]): result(rec) for m, rec in records if m.get("traversal")}
    paths = []
    (out_dir / "plots").mkdir(exist_ok=True)
    for renderer in ("gpu", "cpu"):
        shown = [s for s in scenes if field(by.get((s, renderer, "Restart")), "mrays_per_s")]
        if not shown:
            continue
        fig, ax = plt.subplots(figsize=(8, 3.4))
        width = 0.8 / len(names)
        for i, n in enumerate(names):
            vals = [(field(by.get((s, renderer, n)), "mrays_per_s") or 0) /
                    field(by.get((s, renderer, "Restart")), "mrays_per_s") for s in shown]
            ax.bar([x + i * width for x in range(len(shown))], vals, width, label=n)
        ax.axhline(1.0, color="black", linewidth=0.6)
        ax.set_xticks([x + 0.4 - width / 2 for x in range(len(shown))], shown)
        ax.set_ylabel("Mrays/s relative to Restart")
        ax.set_title("GPU stream (llvmpipe)" if renderer == "gpu" else "CPU")
        ax.legend(fontsize=7, ncol=4)
        fig.tight_layout()
        p = f"plots/traversals_{renderer}.png"
        fig.savefig(out_dir / p, dpi=90)
        plt.close(fig)
        paths.append(p)
    return paths


def write_report(out_dir, results, records):
    scenes = ([s for s, _ in SCENES] + [s for s, _, _ in DYNAMIC_SCENES if s not in dict(SCENES)] +
              [f"sibenik{k}" for k in SIBENIK_DYNAMIC])
    t_out, t_claims = traversal_section(records, scenes)
    b_out, b_claims = build_section(records, scenes)
    d_out, d_claims = dynamic_section(records, plot_dynamic(out_dir, records))
    plots = plot_traversals(out_dir, records, scenes)
    p = results["parameters"]
    m = results["machine"]
    lines = [
        "# Seed 003 (Papay 2025) on this machine: kd traversals, binned builds, dynamic scenes", "",
        f"Generated by `{results['command']}` on {results['generated_at']} "
        f"({results['runs_ok']} runs ok, {results['runs_failed']} failed, {results['wall_s']:.0f} s). "
        f"Machine: {m.get('cpu')}, {m.get('cores')} cores; GL: {m.get('gl_renderer')}; commit "
        f"{(m.get('git_commit') or '?')[:10]}.", "",
        f"Primary rays only (`-b 1`), {p['size']}² pixels, the minimum of `-m {p['repeats']}`; the dynamic runs "
        f"at {p['dynamic_size']}². The seed measured on an RTX 4080 at 3840×2160; its absolute numbers are not "
        "comparable with llvmpipe's, its ratios are. Scenes missing here: "
        f"{', '.join(results['skipped']) or 'none'}. Structures missing from this build: "
        f"{', '.join(results['missing']) or 'none'}.", "",
        "## The seed's claims, here", "",
        md_table(["claim", "seed", "here", "verdict"], t_claims + b_claims + d_claims), "",
    ]
    lines += [f"![traversals]({x})" for x in plots] + [""]
    lines += t_out + b_out + d_out
    failed = [(m_["key"], rec.get("error")) for m_, rec in records if rec and rec.get("status") == "error"]
    if failed:
        lines += ["## Failed runs", ""] + [f"- `{k}`: {e}" for k, e in failed] + [""]
    lines += ["## Commands", "", "Each run's command line is in `results.json` (`runs[].command`)."]
    write_atomically(out_dir / "REPORT.md", "\n".join(lines) + "\n")


# ---------------------------------------------------------------- the driver

def main(args, binary, registry, out, bart, bart_ok, bench, command):
    """Runs the plan (skipping runs that finished earlier) and writes the report."""
    scenes = args.scenes.split(",") if args.scenes else [s for s, _ in SCENES]
    unknown = [s for s in scenes if s not in dict(SCENES)]
    if unknown:
        raise SystemExit(f"bench --papay: unknown scene {unknown[0]!r} (expected {', '.join(dict(SCENES))})")
    more_dynamic = []
    if "sibenik" in scenes and scene_available(registry, "sibenik"):
        import dynamic_sibenik
        for k in SIBENIK_DYNAMIC:
            path = dynamic_sibenik.make(binary, k, out / "scenes")
            more_dynamic.append((f"sibenik{k}", ["-s", str(path)] + dynamic_sibenik.VIEW_ARGS, 30))
    plan = Plan(args.size or 256, args.repeats or 3, registry, scenes, bart_ok,
                frames=args.frames, dyn_size=args.dynamic_size, more_dynamic=more_dynamic)
    runner = bench.Runner(binary, bart, out, args.timeout or 900, args.force)
    records, wall_s = bench.run_jobs(plan.jobs, runner, args.report_only, "--papay")
    parameters = {"size": plan.size, "repeats": plan.repeats, "dynamic_size": plan.dyn_size, "scenes": scenes}
    results = bench.section_results(command, wall_s, parameters, plan.skipped, plan.missing, records, binary)
    bench.write_json_atomic(out / "results.json", results)
    write_report(out, results, records)
    bench.log(f"bench --papay: {results['runs_ok']} ok, {results['runs_failed']} failed; report: "
              f"{bench.shown_path(out / 'REPORT.md')}")
    return 0 if results["runs_failed"] == 0 else 1
