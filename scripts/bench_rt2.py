#!/usr/bin/env python3
"""Seed 002's experiment on this machine (Santos, Teichrieb & Lindoso 2014, RT²).

    python3 scripts/bench.py --rt2 [--size 512] [--repeats 3] [--scenes bunny,cornell]

The seed's Fig. 3 in passtrace's terms: per scene and structure, on both
renderers, the structure's memory (MB), leaves, maximum depth and build ms,
then a Whitted run (`--shading whitted`, `-b 10`: reflection, refraction,
hard shadows to every light) with its ms per frame, Mrays/s, traversal steps
and triangle tests per ray as mean (max), and an ambient-occlusion run
(`--shading ao --ao-samples 16`) with its Mrays/s. One passtrace run per
(scene, renderer, structure, ray mix), each the minimum of `-m` repeats; the
records live in OUT/runs/ and a rerun reuses them. The report, OUT/REPORT.md,
puts the seed's numbers (../shared/docs/seed-systems.md, "Seed 002") beside
ours and marks each of its claims holds / does not hold here, with the ratios
measured in this one invocation.

Scenes: the thesis's five, a procedural sphere field of 1M triangles and,
where passtrace finds the real scenes, sponza: Dabrovic's original 69K Sponza
(scenes/real_scenes.h), the atrium of the seed's Crytek Sponza 262K but not
its mesh. The seed's Land Rover and Fairy Forest are not available.
Structures are found in `passtrace --list --json`; the seed's that this build
lacks are listed as missing, not run.
"""
import statistics

import bench_ranks
from report_tables import field, md_table, num, result, verdict
from bench_report import write_atomically
from passtrace_registry import scene_available

# The seed's structure names, with passtrace's row and the arguments that select its builder.
STRUCTURES = [
    ("KD Ropes (SAH)", "kd-ropes", []),
    ("BVH (SBVH)", "bvh-stack", ["--bvh-builder", "sbvh"]),
    ("BVH (SAH)", "bvh-stack", ["--bvh-builder", "sah"]),
    ("BVH (middle)", "bvh-stack", ["--bvh-builder", "middle"]),
    ("KD Standard (SAH)", "kd-compact", []),  # the seed's 8-byte-node stack traversal
    ("KD Stack (SAH)", "kd-stack", []),
    ("BIH", "bih", []),
    ("Grid", "grid", []),
    ("Octree", "octree", []),
]
# (label, passtrace scene arguments)
SCENES = [
    ("cows", ["-s", "cows"]),
    ("robots", ["-s", "robots"]),
    ("kitchen", ["-s", "kitchen"]),
    ("bunny", ["-s", "bunny"]),
    ("cornell", ["-s", "cornell"]),
    ("spheres-1M", ["-s", "spheres", "--triangles", "1000000"]),
    ("sponza", ["-s", "sponza"]),
]
BART = {"robots", "kitchen"}
# The ray mixes: Whitted with the seed's 10 bounces, AO with its 16 rays per primary hit.
MIXES = {
    "whitted": ["--shading", "whitted", "-b", "10"],
    "ao": ["--shading", "ao", "--ao-samples", "16"],
}
FALLBACK = {"whitted": ["-b", "3"]}  # a build without --shading: the thesis's diffuse, shadow and mirror rays

# Seed 002's Fig. 3 as the digest quotes it (GTX 780 Ti, 1920x1080):
# MB, leaves x 10^3, max depth, build ms, Whitted Mrays/s, steps/ray mean (max), isect/ray mean (max).
SEED_LAND_ROVER = {
    "KD Ropes (SAH)": (17.0, 108, 46, 590, 698.9, "11.20 (147)", "5.03 (180)"),
    "BVH (SBVH)": (1.9, 22, 21, 2171, 540.2, "16.21 (134)", "6.08 (123)"),
    "BVH (SAH)": (1.6, 18, 22, 127, 521.3, None, None),
    "KD Standard (SAH)": (2.9, 106, 46, 532, 516.8, "26.18 (217)", None),
    "BIH": (0.7, 13, 34, 16, 261.9, "39.95 (304)", "23.96 (487)"),
    "Grid": (None, None, None, None, 219.5, None, None),
    "Octree": (3.2, 35, 12, 330, 171.6, None, None),
}
SEED_MRAYS = {  # Whitted Mrays/s on the seed's other scenes
    "Fairy Forest 174k": {"KD Ropes (SAH)": 545.1, "BVH (SBVH)": 434.6, "BVH (SAH)": 437.9,
                          "KD Standard (SAH)": 402.1, "BIH": 226.9, "Octree": 157.6, "Grid": 79.0},
    "Crytek Sponza 262k": {"KD Ropes (SAH)": 274.1, "BVH (SBVH)": 243.6, "KD Standard (SAH)": 232.8,
                           "BVH (SAH)": 198.2, "Grid": 135.3, "Octree": 123.6, "BIH": 66.9},
}


class Plan:
    """The runs: [(kind, meta, args, key)], one per scene, renderer, structure and ray mix."""

    def __init__(self, size, repeats, registry, scenes, bart_ok, mixes_known):
        self.size, self.repeats = size, repeats
        known = {r["name"]: r["renderers"] for r in registry["accelerators"]}
        self.missing = sorted({row for _, row, _ in STRUCTURES if row not in known})
        mixes = MIXES if mixes_known else FALLBACK
        self.mixes = list(mixes)
        self.jobs, self.skipped = [], []
        for label, scene_args in SCENES:
            if label not in scenes:
                continue
            if (label in BART and not bart_ok) or not scene_available(registry, label):
                self.skipped.append(label)
                continue
            for renderer, rid in (("gpu", "2"), ("cpu", "1")):
                for name, row, extra in STRUCTURES:
                    if row not in known or renderer not in known[row]:
                        continue
                    for mix in self.mixes:
                        args = scene_args + ["-r", rid, "-a", row, "-w", str(size), "-m", str(repeats)]
                        args += extra + mixes[mix]
                        key = f"{label}__{renderer}__{row}{'-' + extra[1] if extra else ''}__{mix}"
                        self.jobs.append(("run", {"key": key, "scene": label, "renderer": renderer,
                                                  "structure": name, "mix": mix}, args, key))


# ---------------------------------------------------------------- the report

def megabytes(r):
    """The structure's size: its own byte count where it reports one, else floats per triangle."""
    b = field(r, "structure_bytes")  # 0: the structure does not report its bytes
    if not b and field(r, "accel_floats_per_triangle") is not None:
        b = field(r, "accel_floats_per_triangle") * 4 * field(r, "triangles")
    return None if b is None else b / 1e6


def mean_max(r, mean, peak):
    return f"{num(field(r, mean), 2)} ({num(field(r, peak), 0)})" if r else "–"


def fig3_section(by, scenes):
    out = ["## Fig. 3, here: per scene and structure", ""]
    header = ["structure", "MB", "floats/tri", "leaves ×10³", "depth", "build ms", "Whitted ms", "Whitted Mrays/s",
              "steps/ray (max)", "isect/ray (max)", "AO Mrays/s"]
    for renderer, title in (("gpu", "GPU stream (llvmpipe)"), ("cpu", "CPU (2 threads)")):
        for s in scenes:
            rows = []
            for name, _, _ in STRUCTURES:
                w, a = by.get((s, renderer, name, "whitted")), by.get((s, renderer, name, "ao"))
                r = w or a
                if r is None:
                    continue
                leaves = field(r, "accel_leaves")
                rows.append([name, num(megabytes(r), 2), num(field(r, "accel_floats_per_triangle"), 1), num(leaves / 1e3 if leaves is not None else None, 1),
                             num(field(r, "accel_depth"), 0), num(field(r, "build_ms"), 0),
                             num(field(w, "frame_ms"), 1), num(field(w, "mrays_per_s"), 3),
                             mean_max(w, "steps_per_ray", "max_steps_per_ray"),
                             mean_max(w, "triangle_tests_per_ray", "max_triangle_tests_per_ray"),
                             num(field(a, "mrays_per_s"), 3)])
            if rows:
                out += [f"### {s}, {title}", "", md_table(header, rows), ""]
    seed_rows = [[n] + [num(v, 1) if isinstance(v, float) else (v if v is not None else "–") for v in vals]
                 for n, vals in SEED_LAND_ROVER.items()]
    out += ["### The seed's numbers (GTX 780 Ti, CUDA, 1920×1080)", "",
            "Land Rover, 77.2k triangles:", "",
            md_table(["structure", "MB", "leaves ×10³", "depth", "build ms", "Whitted Mrays/s",
                      "steps/ray (max)", "isect/ray (max)"], seed_rows), ""]
    names = [n for n, _, _ in STRUCTURES if any(n in v for v in SEED_MRAYS.values())]
    out += ["Whitted Mrays/s on its other scenes:", "",
            md_table(["scene"] + names, [[s] + [num(v.get(n), 1) for n in names] for s, v in SEED_MRAYS.items()]),
            ""]
    # The same table here, scene by scene, so a reader sets `sponza` beside the seed's `Crytek Sponza 262k`
    # (passtrace's is Dabrovic's 69K original: the same atrium, another mesh).
    for renderer, title in (("gpu", "GPU stream (llvmpipe)"), ("cpu", "CPU (2 threads)")):
        rows = [[s] + [num(field(by.get((s, renderer, n, "whitted")), "mrays_per_s"), 3) for n in names]
                for s in scenes if any(by.get((s, renderer, n, "whitted")) for n in names)]
        if rows:
            out += [f"Whitted Mrays/s here, {title}, in the same columns:", "", md_table(["scene"] + names, rows), ""]
    return out


def claims(by, scenes):
    """The seed's claims, each over every (scene, renderer) pair that has the runs it needs."""
    found = []

    def speed(s, renderer, name):
        return field(by.get((s, renderer, name, "whitted")), "mrays_per_s")

    def memory(s, renderer, name):
        r = by.get((s, renderer, name, "whitted")) or by.get((s, renderer, name, "ao"))
        return megabytes(r)

    def pairs():
        return [(s, renderer) for s in scenes for renderer in ("gpu", "cpu")]

    def claim(text, seed, ratios, holds_if, unit="×"):
        if not ratios:
            found.append((text, seed, "not measured (runs or structures missing)", "–"))
            return
        holding = sum(1 for x in ratios if holds_if(x))
        found.append((text, seed, f"{min(ratios):.2f}–{max(ratios):.2f}{unit} over {len(ratios)} scene/renderer "
                                  f"pairs; holds in {holding}", verdict(holding == len(ratios))))

    bvhs = ["BVH (SBVH)", "BVH (SAH)", "BVH (middle)"]
    ropes, best_bvh, mem_ratio = [], [], []
    for s, renderer in pairs():
        rope = speed(s, renderer, "KD Ropes (SAH)")
        bvh = [speed(s, renderer, b) for b in bvhs if speed(s, renderer, b)]
        if rope and bvh:
            ropes.append(rope / max(bvh))
        others = [speed(s, renderer, n) for n, _, _ in STRUCTURES if n != "KD Ropes (SAH)" and speed(s, renderer, n)]
        if rope and others:
            best_bvh.append(rope / max(others))
        m_rope, m_bvh = memory(s, renderer, "KD Ropes (SAH)"), memory(s, renderer, "BVH (SAH)")
        if m_rope and m_bvh:
            mem_ratio.append(m_rope / m_bvh)
    claim("Ropes are faster than the best BVH (Whitted Mrays/s)", "1.12–1.39×", ropes, lambda x: x > 1.0)
    claim("Ropes are the fastest structure", "fastest on every scene", best_bvh, lambda x: x >= 1.0)
    claim("…at several times the BVH's memory (ropes MB / BVH SAH MB)", "≥ 4× (17.0 / 1.6 MB on Land Rover)",
          mem_ratio, lambda x: x >= 4.0)
    for slow in ("Octree", "Grid", "BIH"):
        ratios = []
        for s, renderer in pairs():
            fast = [speed(s, renderer, n) for n in ("KD Standard (SAH)", "KD Stack (SAH)", *bvhs)
                    if speed(s, renderer, n)]
            if speed(s, renderer, slow) and fast:
                ratios.append(speed(s, renderer, slow) / max(fast))
        claim(f"{slow} under half the speed of the best kd-tree/BVH", "< 0.5×", ratios, lambda x: x < 0.5)
    bih_mem = []
    for s, renderer in pairs():
        kd = memory(s, renderer, "KD Standard (SAH)") or memory(s, renderer, "KD Stack (SAH)")
        bih = memory(s, renderer, "BIH")
        if kd and bih:
            bih_mem.append(kd / bih)
    claim("BIH needs about 4× less memory than the kd-tree (kd MB / BIH MB)", "≈ 4× (2.9 / 0.7 MB)",
          bih_mem, lambda x: x >= 3.0)
    return found


def mixes_line(mixes):
    if "ao" in mixes:
        return f"Whitted `{' '.join(MIXES['whitted'])}`, AO `{' '.join(MIXES['ao'])}`."
    return ("This build has no `--shading`: the Whitted columns are the thesis's shading "
            f"(`{' '.join(FALLBACK['whitted'])}`) and there is no AO column.")


def write_report(out_dir, results, records):
    scenes = [s for s, _ in SCENES]
    by = {(m["scene"], m["renderer"], m["structure"], m["mix"]): result(rec) for m, rec in records}
    p, m = results["parameters"], results["machine"]
    lines = [
        "# Seed 002 (RT², Santos et al. 2014) on this machine: six traversals, Whitted and AO rays", "",
        f"Generated by `{results['command']}` on {results['generated_at']} "
        f"({results['runs_ok']} runs ok, {results['runs_failed']} failed, {results['wall_s']:.0f} s). "
        f"Machine: {m.get('cpu')}, {m.get('cores')} cores; GL: {m.get('gl_renderer')}; commit "
        f"{(m.get('git_commit') or '?')[:10]}.", "",
        f"{p['size']}² pixels, the minimum of `-m {p['repeats']}`. The seed measured on a GTX 780 Ti at 1920×1080; its absolute numbers "
        "are not comparable with llvmpipe's or 2 CPU cores', its orderings and ratios are. Scenes missing here: "
        f"{', '.join(results['skipped']) or 'none'}. Structures missing from this build: "
        f"{', '.join(results['missing']) or 'none'}. {mixes_line(p['mixes'])}", "",
        "MB is the structure as the renderer holds it (`structure_bytes` where the structure reports it, else "
        "its floats per triangle × 4 bytes × triangles); steps are node visits, isect triangle tests.", "",
        "## The seed's claims, here", "",
        md_table(["claim", "seed", "here", "verdict"], claims(by, scenes)), "",
    ]
    lines += fig3_section(by, scenes)
    failed = [(m_["key"], rec.get("error")) for m_, rec in records if rec and rec.get("status") == "error"]
    if failed:
        lines += ["## Failed runs", ""] + [f"- `{k}`: {e}" for k, e in failed] + [""]
    lines += ["## Commands", "", "Each run's command line is in `results.json` (`runs[].command`)."]
    write_atomically(out_dir / "REPORT.md", "\n".join(lines) + "\n")


# ---------------------------------------------------------------- the driver

def main(args, binary, registry, out, bart, bart_ok, bench, command):
    """Runs the plan (skipping runs that finished earlier) and writes the report."""
    import subprocess
    scenes = args.scenes.split(",") if args.scenes else [s for s, _ in SCENES]
    unknown = [s for s in scenes if s not in dict(SCENES)]
    if unknown:
        raise SystemExit(f"bench --rt2: unknown scene {unknown[0]!r} (expected {', '.join(dict(SCENES))})")
    help_text = subprocess.run([str(binary), "--help"], capture_output=True, text=True,
                               env=bench_ranks.child_env()).stdout
    plan = Plan(args.size or 512, args.repeats or 3, registry, scenes, bart_ok, "--shading" in help_text)
    runner = bench.Runner(binary, bart, out, args.timeout or 1800, args.force)
    records, wall_s = bench.run_jobs(plan.jobs, runner, args.report_only, "--rt2")
    parameters = {"size": plan.size, "repeats": plan.repeats, "scenes": scenes, "mixes": plan.mixes,
                  "median_wall_s": statistics.median([r["wall_s"] for _, r in records]) if records else None}
    results = bench.section_results(command, wall_s, parameters, plan.skipped, plan.missing, records, binary)
    bench.write_json_atomic(out / "results.json", results)
    write_report(out, results, records)
    bench.log(f"bench --rt2: {results['runs_ok']} ok, {results['runs_failed']} failed; report: "
              f"{bench.shown_path(out / 'REPORT.md')}")
    return 0 if results["runs_failed"] == 0 else 1
