#!/usr/bin/env python3
"""Seed 001's experiments on this machine (Mora 2011: divide-and-conquer ray tracing).

    python3 scripts/bench.py --dacrt [--size 256] [--scenes bunny,cornell] ...

Five experiments, each a list of passtrace runs (one record per run in
OUT/runs/, reused by a rerun like the main suite), then OUT/REPORT.md with the
seed's numbers (../shared/docs/seed-systems.md, "Seed 001"; its Fig. 8 and
Fig. 14) beside ours and each of its claims marked holds / does not hold here:

  frame      one frame, primary + shadow rays (-b 2): DACRT's whole time
             (build_ms is 0) against build + trace of kd-tree, kk-bvh, gs-bvh
             (CPU renderer) and Embree (-r 3);
  animation  --frames over BART robots, every frame rebuilt for the others,
             nothing to build for DACRT: mean build + trace per frame;
  limits     a small rLimit x pLimit sweep (primary rays);
  split      the seed's sampled-mean split against the spatial median
             (--dacrt-split), on scenes above 10,000 triangles;
  cones      conic packets against plain rays: the filter counters of the
             seed's Fig. 8 (ray/box, cone/box, triangle/box, ray/triangle,
             nodes), primary rays and primary + shadow.

Scenes: the thesis's five, and procedural sphere fields of 1M and 10M
triangles (the 10M scene without gs-bvh, whose insertion build takes hours
here). Absolute numbers are a shared 2-core machine's; the ratios within one
run of this script are what the report compares with the seed's.
"""
import statistics

from report_tables import num, md_table, result, verdict
from bench_report import write_atomically
from passtrace_registry import scene_available

SCENES = [
    ("cows", ["-s", "cows"]),
    ("robots", ["-s", "robots"]),
    ("kitchen", ["-s", "kitchen"]),
    ("bunny", ["-s", "bunny"]),
    ("cornell", ["-s", "cornell"]),
    ("spheres-1M", ["-s", "spheres", "--triangles", "1000000"]),
    ("spheres-10M", ["-s", "spheres", "--triangles", "10000000"]),
    # The seed's own room (scenes/real_scenes.h): 331,179 triangles here, the
    # seed's 282K Conference another tessellation; seen from inside.
    ("conference", ["-s", "conference"]),
]
BART = {"robots", "kitchen"}

# (label, renderer id, structure, extra flags): what a DACRT frame is set against.
FRAME_RUNS = [
    ("dacrt", "1", "dacrt", []),
    ("dacrt-cones", "1", "dacrt", ["--dacrt-cones"]),
    ("kd-tree", "1", "kd-tree", []),
    ("kk-bvh", "1", "kk-bvh", []),
    ("gs-bvh", "1", "gs-bvh", []),
    ("embree", "3", "embree", []),
]
NOT_ON_10M = {"gs-bvh"}
OTHERS = ["kd-tree", "kk-bvh", "gs-bvh", "embree"]

ANIMATION = ("robots", ["-s", "robots"], 10)
RLIMITS = [4, 8, 20, 64]
PLIMITS = [4, 8, 16, 64]
SWEEP_SCENES = ["bunny", "kitchen"]
SPLIT_SCENES = ["robots", "kitchen", "bunny", "spheres-1M", "conference"]  # above 10,000 triangles

# Seed 001, Fig. 14 (1024², primary rays, conic packets; fps): DACRT on one
# Core 2 core, the seed's reference SAH kd-tree packet tracer (static: build
# not counted), and Shevtsov et al.'s kd-tree build alone on 4 cores.
SEED_FIG14 = {  # scene: (triangles, DACRT fps, reference kd fps, Shevtsov build-only fps or None)
    "Erw6": (804, 15.3, 5.1, None), "Bunny": (69_000, 9.5, 3.38, None), "Fairy": (174_000, 6.8, 3.7, None),
    "Conference": (282_000, 10.1, 3.6, None), "Buddha": (1_080_000, 4.2, 4.2, 2.1),
    "Soda Hall": (2_200_000, 8.7, 6.9, 2.1), "Dragon": (7_200_000, 1.56, 2.24, 0.58),
    "Thai Statue": (10_000_000, 1.28, 1.46, 0.4), "Lucy": (28_000_000, 0.45, 0.73, None),
}
# Seed 001, Fig. 8 (1280x800): basic / conic packets, primary rays.
SEED_FIG8 = {  # scene: (ray/box basic, ray/box cones, cone/box cones, triangle/box basic, nodes basic)
    "Erw6": (29.5e6, 2e3, 1.1e6, 32e3, 888), "Conference": (47e6, 1.54e6, 1.27e6, 5.63e6, 42e3),
    "Blade": (27.5e6, 6.73e6, 486e3, 31.7e6, 208e3), "(4th scene)": (66.5e6, 5.6e6, 1.7e6, 154e6, 157e3),
}


class Plan:
    """The runs of the five experiments: [(kind, meta, args, key)]."""

    def __init__(self, size, repeats, registry, scenes, bart_ok, frames=None, anim_size=None, image_dir=None):
        self.size, self.repeats = size, repeats
        self.anim_size = anim_size or max(32, size // 2)
        known = {r["name"]: r["renderers"] for r in registry["accelerators"]}
        self.missing = sorted({s for _, _, s, _ in FRAME_RUNS if s not in known})
        self.jobs, self.skipped = [], []
        renderer_name = {"1": "cpu", "3": "embree"}

        def add(kind, meta, args, key):
            self.jobs.append((kind, dict(meta, key=key), args, key))

        for label, scene_args in SCENES:
            if label not in scenes:
                continue
            if (label in BART and not bart_ok) or not scene_available(registry, label):
                self.skipped.append(label)
                continue
            base = scene_args + ["-w", str(size), "-m", str(repeats)]
            for name, rid, structure, extra in FRAME_RUNS:
                if structure not in known or renderer_name[rid] not in known[structure]:
                    continue
                if label == "spheres-10M" and name in NOT_ON_10M:
                    continue
                add("frame", {"scene": label, "run": name}, base + ["-r", rid, "-a", structure, "-b", "2"] + extra,
                    f"frame__{label}__{name}")
            if "dacrt" not in known:
                continue
            for cones in (False, True):  # Fig. 8's counters, primary rays alone
                extra = ["--dacrt-cones"] if cones else []
                add("cones", {"scene": label, "cones": cones}, base + ["-r", "1", "-a", "dacrt", "-b", "1"] + extra,
                    f"cones__{label}__{'cones' if cones else 'rays'}")
            if label in SWEEP_SCENES:
                for r in RLIMITS:
                    for p in PLIMITS:
                        add("limits", {"scene": label, "rlimit": r, "plimit": p},
                            base + ["-r", "1", "-a", "dacrt", "-b", "1", "--dacrt-rlimit", str(r),
                                    "--dacrt-plimit", str(p)], f"limits__{label}__r{r}_p{p}")
            if label in SPLIT_SCENES:
                for split in ("mean", "median"):
                    add("split", {"scene": label, "split": split},
                        base + ["-r", "1", "-a", "dacrt", "-b", "2", "--dacrt-split", split],
                        f"split__{label}__{split}")
        label, scene_args, n = ANIMATION
        if label in scenes and bart_ok:
            for name, rid, structure, extra in FRAME_RUNS:
                if structure not in known or renderer_name[rid] not in known[structure]:
                    continue
                add("animation", {"scene": label, "run": name},
                    scene_args + ["-r", rid, "-a", structure, "-w", str(self.anim_size), "-b", "2",
                                  "--frames", str(frames or n)] + extra +
                    # --frames writes an image per frame: into runs/, not the working directory
                    (["-o", str(image_dir / f"anim__{label}__{name}.png")] if image_dir else []),
                    f"anim__{label}__{name}")


# ---------------------------------------------------------------- the report



def big(v):
    if v is None:
        return "–"
    for unit, scale in (("G", 1e9), ("M", 1e6), ("K", 1e3)):
        if v >= scale:
            return f"{v / scale:.2f} {unit}"
    return f"{v:.0f}"








def whole_ms(r):
    """A frame's whole cost: build + trace (DACRT builds nothing: build_ms is 0)."""
    return None if r is None else r["build_ms"] + r["frame_ms"]


def frame_section(records, scenes):
    out, claims = ["## One frame: DACRT against build + trace (primary + shadow rays)", ""], []
    by = {(m["scene"], m["run"]): result(rec) for m, rec in records if m["key"].startswith("frame__")}
    names = [n for n, _, _, _ in FRAME_RUNS]
    rows, speedups = [], []
    for s in scenes:
        rs = {n: by.get((s, n)) for n in names}
        if not any(rs.values()):
            continue
        cells = []
        for n in names:
            r = rs[n]
            cells.append("–" if r is None else (f"{num(r['frame_ms'])}" if n.startswith("dacrt")
                                                else f"{num(r['build_ms'])} + {num(r['frame_ms'])}"))
        dacrt = min((whole_ms(rs[n]) for n in ("dacrt", "dacrt-cones") if rs[n]), default=None)
        others = [(whole_ms(rs[n]), n) for n in OTHERS if rs[n]]
        best = min(others) if others else None
        kd = whole_ms(rs["kd-tree"])
        if dacrt and best:
            speedups.append((s, best[0] / dacrt, best[1], kd / dacrt if kd else None))
        tri = next((r["triangles"] for r in rs.values() if r), None)
        rows.append([s, num(tri)] + cells + [f"{best[1]} {num(best[0])}" if best else "–",
                                             f"{best[0] / dacrt:.2f}×" if dacrt and best else "–"])
    out += ["ms per frame: DACRT's whole frame; the others' build + trace. The last columns: the best other "
            "structure's whole frame and its ratio to DACRT's best (above 1: DACRT faster).", "",
            md_table(["scene", "triangles"] + names + ["best other", "best other / DACRT"], rows), "",
            "The seed's Fig. 14 (1024², primary rays with conic packets, fps; one Core 2 core for DACRT; the "
            "reference kd-tree's build is not counted; Shevtsov et al.'s kd build alone on 4 cores):", "",
            md_table(["scene", "triangles", "DACRT fps", "reference kd fps (trace only)", "kd build alone fps"],
                     [[s, num(t), num(d, 2), num(k, 2), num(b, 2)] for s, (t, d, k, b) in SEED_FIG14.items()]), ""]
    kd_ratios = [(s, x) for s, _, _, x in speedups if x]
    if kd_ratios:
        lo, hi = min(x for _, x in kd_ratios), max(x for _, x in kd_ratios)
        claims.append(("Up to 7.5× faster than building a kd-tree and tracing it, for one frame", "≤ 7.5× (640×480)",
                       f"kd-tree (build + trace) / DACRT {lo:.2f}–{hi:.2f}× over {len(kd_ratios)} scenes: " +
                       ", ".join(f"{s} {x:.2f}×" for s, x in kd_ratios),
                       verdict(hi > 1.0)))
    if speedups:
        wins = [s for s, x, _, _ in speedups if x > 1.0]
        claims.append(("A whole DACRT frame beats build + trace of the dynamic alternatives",
                       "faster than Shevtsov's kd build alone above 1M triangles",
                       f"best other / DACRT: " + ", ".join(f"{s} {x:.2f}× (vs {n})" for s, x, n, _ in speedups) +
                       f"; DACRT faster on {len(wins)} of {len(speedups)}", verdict(len(wins) == len(speedups))))
    return out, claims


def animation_section(records):
    out, claims = ["## Animation: every frame rebuilt for the others, nothing for DACRT", ""], []
    rows, tf = [], {}
    for m, rec in records:
        if not m["key"].startswith("anim__"):
            continue
        r = result(rec)
        if r is None or not r.get("sequence"):
            rows.append([m["scene"], m["run"], "–", "failed", "", ""])
            continue
        seq = r["sequence"]
        build = statistics.mean(f["build_ms"] for f in seq)
        trace = statistics.mean(f["frame_ms"] for f in seq)
        tf[m["run"]] = build + trace
        rows.append([m["scene"], m["run"], len(seq), num(build, 1), num(trace, 1), num(build + trace, 1)])
    out += [md_table(["scene", "run", "frames", "build ms", "trace ms", "build + trace ms"], rows), ""]
    dacrt = min((tf[n] for n in ("dacrt", "dacrt-cones") if n in tf), default=None)
    others = {n: v for n, v in tf.items() if n in OTHERS}
    if dacrt and others:
        best = min(others, key=others.get)
        claims.append(("Over an animation DACRT's frames cost less than rebuilding and tracing",
                       "the motivation (Fig. 9: steady frame rates)",
                       f"mean per frame: DACRT {num(dacrt)} ms, best other {best} {num(others[best])} ms "
                       f"({others[best] / dacrt:.2f}×)", verdict(others[best] > dacrt)))
    return out, claims


def limits_section(records):
    out, claims = ["## rLimit × pLimit (primary rays, plain rays)", ""], []
    by = {}
    for m, rec in records:
        if m["key"].startswith("limits__") and result(rec):
            by[(m["scene"], m["rlimit"], m["plimit"])] = result(rec)["frame_ms"]
    for s in SWEEP_SCENES:
        if not any(k[0] == s for k in by):
            continue
        rows = [[f"rLimit {r}"] + [num(by.get((s, r, p)), 1) for p in PLIMITS] for r in RLIMITS]
        out += [f"### {s}: frame ms", "", md_table([""] + [f"pLimit {p}" for p in PLIMITS], rows), ""]
        best = min(((v, r, p) for (sc, r, p), v in by.items() if sc == s), default=None)
        default = by.get((s, 20, 16))
        if best and default:
            claims.append((f"rLimit 20, pLimit 16 are the best limits ({s})", "20 / 16",
                           f"best here rLimit {best[1]}, pLimit {best[2]} at {num(best[0])} ms; 20/16 "
                           f"{num(default)} ms ({default / best[0]:.2f}× the best)",
                           verdict(default <= 1.1 * best[0])))
    return out, claims


def split_section(records):
    out, claims = ["## Split position: the sampled mean against the median (primary + shadow rays)", ""], []
    by = {(m["scene"], m["split"]): result(rec) for m, rec in records if m["key"].startswith("split__")}
    rows, ratios = [], []
    for s in SPLIT_SCENES:
        mean, median = by.get((s, "mean")), by.get((s, "median"))
        if not (mean and median):
            continue
        ratios.append((s, median["frame_ms"] / mean["frame_ms"]))
        rows.append([s, num(mean["triangles"]), num(mean["frame_ms"]), num(median["frame_ms"]),
                     f"{ratios[-1][1]:.2f}×"])
    out += [md_table(["scene", "triangles", "mean ms", "median ms", "median / mean"], rows), ""]
    if ratios:
        claims.append(("The sampled-mean split is about 20 % faster than the median", "≈ 1.2×",
                       ", ".join(f"{s} {x:.2f}×" for s, x in ratios) + " (median / mean time)",
                       verdict(all(x >= 1.1 for _, x in ratios))))
    return out, claims


def cones_section(records):
    out, claims = ["## Conic packets: the seed's Fig. 8 counters (primary rays)", ""], []
    by = {(m["scene"], m["cones"]): result(rec) for m, rec in records if m["key"].startswith("cones__")}
    rows, cuts = [], []
    for (s, cones), r in sorted(by.items()):
        if r is None or "dacrt" not in r:
            continue
        d = r["dacrt"]
        rows.append([s, "cones" if cones else "rays", num(r["frame_ms"]), big(d["ray_box_tests"]),
                     big(d["cone_box_tests"]), big(d["triangle_box_tests"]), big(d["ray_triangle_tests"]),
                     big(d["nodes"])])
    for s in sorted({s for s, _ in by}):
        a, c = by.get((s, False)), by.get((s, True))
        if a and c and "dacrt" in a and "dacrt" in c:
            plain = a["dacrt"]["ray_box_tests"]
            packed = c["dacrt"]["ray_box_tests"] + c["dacrt"]["cone_box_tests"]
            if packed:
                cuts.append((s, plain / packed, a["frame_ms"] / c["frame_ms"]))
    out += [md_table(["scene", "run", "frame ms", "ray/box", "cone/box", "triangle/box", "ray/triangle", "nodes"],
                     rows), "",
            "The seed's Fig. 8 (1280×800, primary rays): " +
            "; ".join(f"{s}: ray/box {big(a)} → {big(b)} + {big(c)} cone/box, triangle/box {big(t)}, nodes {big(n)}"
                      for s, (a, b, c, t, n) in SEED_FIG8.items()) + ".", ""]
    seed_cuts = [a / (b + c) for a, b, c, _, _ in SEED_FIG8.values()]
    if cuts:
        claims.append(("Conic packets cut the box tests by an order of magnitude",
                       f"ray/box ÷ (ray/box + cone/box) {min(seed_cuts):.1f}–{max(seed_cuts):.1f}×",
                       ", ".join(f"{s} {x:.1f}× (time {t:.2f}×)" for s, x, t in cuts),
                       verdict(all(x >= 10 for _, x, _ in cuts))))
    return out, claims


def write_report(out_dir, results, records):
    scenes = [s for s, _ in SCENES]
    sections = [frame_section(records, scenes), animation_section(records), limits_section(records),
                split_section(records), cones_section(records)]
    p, m = results["parameters"], results["machine"]
    claims = [c for _, cs in sections for c in cs]
    lines = [
        "# Seed 001 (Mora 2011) on this machine: divide-and-conquer ray tracing", "",
        f"Generated by `{results['command']}` on {results['generated_at']} "
        f"({results['runs_ok']} runs ok, {results['runs_failed']} failed, {results['wall_s']:.0f} s). "
        f"Machine: {m.get('cpu')}, {m.get('cores')} cores; commit {(m.get('git_commit') or '?')[:10]}.", "",
        f"{p['size']}² pixels, the minimum of `-m {p['repeats']}`; the animation at {p['animation_size']}². "
        "DACRT stores no structure: its `build_ms` is 0 and all its work is in `frame_ms`. The seed measured one "
        "Core 2 core at 1024² (Fig. 14) and 640×480 (the 7.5× claim); its absolute numbers are not comparable, "
        "its ratios are. Scenes missing here: "
        f"{', '.join(results['skipped']) or 'none'}. Structures missing from this build: "
        f"{', '.join(results['missing']) or 'none'}.", "",
        "Timings on this machine are noisy (2 cores shared with builds): compare within a table, and rerun "
        "with more repeats (`--repeats`) before trusting a ratio near 1.", "",
        "## The seed's claims, here", "",
        md_table(["claim", "seed", "here", "verdict"], claims), "",
    ]
    for out, _ in sections:
        lines += out
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
        raise SystemExit(f"bench --dacrt: unknown scene {unknown[0]!r} (expected {', '.join(dict(SCENES))})")
    runner = bench.Runner(binary, bart, out, args.timeout or 1800, args.force)
    plan = Plan(args.size or 256, args.repeats or 3, registry, scenes, bart_ok,
                frames=args.frames, anim_size=args.dynamic_size, image_dir=runner.runs_dir)
    records, wall_s = bench.run_jobs(plan.jobs, runner, args.report_only, "--dacrt")
    parameters = {"size": plan.size, "repeats": plan.repeats, "animation_size": plan.anim_size, "scenes": scenes}
    results = bench.section_results(command, wall_s, parameters, plan.skipped, plan.missing, records, binary)
    bench.write_json_atomic(out / "results.json", results)
    write_report(out, results, records)
    bench.log(f"bench --dacrt: {results['runs_ok']} ok, {results['runs_failed']} failed; report: "
              f"{bench.shown_path(out / 'REPORT.md')}")
    return 0 if results["runs_failed"] == 0 else 1
