#!/usr/bin/env python3
"""Issue 17's speed report: how far each path is from bare Embree and from this machine's limits.

    python3 scripts/bench.py --speed [--size 512] [--repeats 5] [--scenes bunny,kitchen,robots]

Measures, all in one run of this script (ratios within it are what counts on a
shared machine):

  machine     FP32 peak (independent FMA chains, AVX-512 / AVX2 / scalar as the
              CPU has them) and memory bandwidth (STREAM triad), on 2 threads and 1:
              build/tests/measure/measure_machine_peak; and what one texel fetch
              costs a fragment kernel on this GL, the stream rows' unit of work
              (measure_texel_fetch);
  baseline    bare Embree: rtcIntersect1 over the CPU renderer's primary rays
              on 2 threads and 1, no shading (measure_bare_embree);
  ray kinds   traversal alone of the renderer's primary, shadow and AO rays,
              one thread: bvh8-packet and bvh8 against Embree's single-ray
              calls and its packets (measure_ray_kinds);
  stages      the fastest stream rows in the fragment and the compute stage
              (--stage), alternated in rounds; the SMs each stage ran on in the
              last GPU run (scripts/bench_stages.py);
  runs        every registry row (`passtrace --list --json`, so rows added later
              are picked up) on each renderer it runs on, primary rays (-b 1),
              --threads 2; the CPU rows and Embree (-r 3) also on 1 thread on
              the first scene.

The roofline table divides each run's box+triangle tests per second (from
--json's node_tests_per_ray and triangle_tests_per_ray) by the machine's
limits under a stated cost model: a box (slab) test is 12 FP32 operations and
reads 24 bytes, a triangle test (Moller-Trumbore) 40 operations and 36 bytes;
the stream rows' tests per second also over the measured texel-fetch rate, at
one texel per test (a stream kernel reads at least that much).
"""
import json
import os
import pathlib
import subprocess
import bench_ranks
import bench_stages
import bench_report
from bench_report import write_atomically

SCENES = ["bunny", "kitchen", "robots"]
BART = {"kitchen", "robots"}
# The roofline's cost model (FP32 operations, bytes read) per test.
BOX_FLOPS, BOX_BYTES = 12, 24
TRI_FLOPS, TRI_BYTES = 40, 36
RENDERER_IDS = {"cpu": "1", "gpu": "2", "embree": "3"}
# The stream rows run at passtrace's default -l 0 (one pass per bounce); on
# the first scene also at the thesis's -l 20, for the loop-limit table.
THESIS_LOOP_LIMIT = 20


class Plan:
    """The passtrace runs: [(kind, meta, args, key)]."""

    def __init__(self, size, repeats, registry, scenes, bart_ok):
        self.size, self.repeats = size, repeats
        self.jobs, self.skipped, self.missing = [], [], []
        rows = [(a["name"], a["renderers"]) for a in registry["accelerators"]]
        for i, scene in enumerate(scenes):
            if scene in BART and not bart_ok:
                self.skipped.append(scene)
                continue
            for name, renderers in rows:
                for renderer in ("cpu", "embree", "gpu"):
                    if renderer not in renderers:
                        continue
                    threads = [2, 1] if renderer != "gpu" and i == 0 else [2]
                    for t in threads:
                        args = ["-s", scene, "-r", RENDERER_IDS[renderer], "-a", name, "-w", str(size), "-b", "1",
                                "-m", str(repeats), "--threads", str(t)]
                        key = f"speed__{scene}__{renderer}__{name}__t{t}"
                        self.jobs.append(("speed", {"key": key, "scene": scene, "renderer": renderer,
                                                    "structure": name, "threads": t}, args, key))
                    if renderer == "gpu" and i == 0:  # the thesis's loop limit against one pass per bounce
                        args = ["-s", scene, "-r", RENDERER_IDS[renderer], "-a", name, "-w", str(size), "-b", "1",
                                "-m", str(repeats), "--threads", "2", "-l", str(THESIS_LOOP_LIMIT)]
                        key = f"speed__{scene}__{renderer}__{name}__l{THESIS_LOOP_LIMIT}"
                        self.jobs.append(("speed", {"key": key, "scene": scene, "renderer": renderer,
                                                    "structure": name, "threads": 2,
                                                    "loop_limit": THESIS_LOOP_LIMIT}, args, key))


def measure_tool(binary, name):
    path = binary.parent / "tests" / "measure" / name
    return path if os.access(path, os.X_OK) else None


def run_lines(cmd, env=None, timeout=900):
    """The JSON lines a measurement tool prints, or None (with the reason) when it fails."""
    try:
        proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, timeout=timeout,
                              env=bench_ranks.child_env(env))
    except (OSError, subprocess.TimeoutExpired) as e:
        return None, str(e)
    if proc.returncode != 0:
        lines = proc.stderr.strip().splitlines()
        return None, lines[-1] if lines else f"exit status {proc.returncode}"
    try:
        found = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    except ValueError as e:
        return None, f"no JSON ({e})"
    return (found, None) if found else (None, "no JSON")


def run_tool(cmd, env=None, timeout=600):
    """The last JSON line of a measurement tool, or None (with the reason) when it fails."""
    found, err = run_lines(cmd, env, timeout)
    return (found[-1], None) if found else (None, err)


def measure_baselines(binary, scenes, size, repeats, bart, bart_ok, bench):
    """{"machine": {threads: {...}}, "embree": {(scene, threads): {...}}, "errors": [...]}"""
    out = {"machine": {}, "embree": {}, "errors": []}
    peak = measure_tool(binary, "measure_machine_peak")
    if peak is None:
        out["errors"].append("measure_machine_peak not built (cmake --build build --target measure_machine_peak)")
    else:
        for t in (2, 1):
            bench.log(f"machine peak, {t} thread(s) ...")
            r, err = run_tool([peak, t])
            if r:
                out["machine"][str(t)] = r
            else:
                out["errors"].append(f"measure_machine_peak {t}: {err}")
    fetch = measure_tool(binary, "measure_texel_fetch")
    if fetch is None:
        out["errors"].append("measure_texel_fetch not built (cmake --build build --target measure_texel_fetch)")
    else:
        bench.log("texel fetch ...")
        r, err = run_lines([fetch, size, max(repeats, 5)])
        if r:
            out["fetch"] = r
        else:
            out["errors"].append(f"measure_texel_fetch: {err}")
    kinds = measure_tool(binary, "measure_ray_kinds")
    out["kinds"] = {}
    if kinds is None:
        out["errors"].append("measure_ray_kinds not built (cmake --build build --target measure_ray_kinds)")
    for scene in scenes:
        if kinds is None or (scene in BART and not bart_ok):
            continue
        bench.log(f"ray kinds, {scene} ...")
        r, err = run_lines([kinds, scene, size, max(repeats, 5)], dict(os.environ, PASSTRACE_BART_DIR=str(bart)))
        if r:
            out["kinds"][scene] = r
        else:
            out["errors"].append(f"measure_ray_kinds {scene}: {err}")
    bare = measure_tool(binary, "measure_bare_embree")
    if bare is None:
        out["errors"].append("measure_bare_embree not built (needs Embree)")
        return out
    env = dict(os.environ, PASSTRACE_BART_DIR=str(bart))
    for i, scene in enumerate(scenes):
        if scene in BART and not bart_ok:
            continue
        for t in ([2, 1] if i == 0 else [2]):
            bench.log(f"bare Embree, {scene}, {t} thread(s) ...")
            r, err = run_tool([bare, scene, size, t, max(repeats, 5)], env)
            if r:
                out["embree"][f"{scene}/{t}"] = r
            else:
                out["errors"].append(f"measure_bare_embree {scene} {t}: {err}")
    return out


# ---------------------------------------------------------------- the report

def num(v, digits=2):
    return "–" if v is None else f"{v:.{digits}f}"


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def ratio(a, b):
    return a / b if a and b else None


def collect(records, loop_limit=None):
    """{(scene, renderer, structure, threads): result} of the runs that finished at `loop_limit`
    (None: passtrace's default)."""
    by = {}
    for meta, rec in records:
        if rec and rec.get("status") == "ok" and meta.get("loop_limit") == loop_limit:
            by[(meta["scene"], meta["renderer"], meta["structure"], meta["threads"])] = rec["result"]
    return by


def loop_rows(by, by_thesis):
    rows = []
    for (scene, renderer, structure, threads), thesis in sorted(by_thesis.items()):
        r = by.get((scene, renderer, structure, threads)) or {}
        a, b = thesis.get("mrays_per_s"), r.get("mrays_per_s")
        rows.append([scene, structure, num(a), num(thesis.get("passes"), 0), num(b), num(r.get("passes"), 0),
                     num(ratio(b, a))])
    return rows


# The texel-fetch rate the roofline holds stream rows to: a walk's addresses
# form a chain, and primary rays read the same nodes as their neighbours.
STREAM_FETCH_WAY = "chain, coherent"


def fetch_rate(fetch):
    """G texel fetches per second of STREAM_FETCH_WAY, or None."""
    return next((f.get("g_fetches_per_s") for f in fetch or [] if f.get("way") == STREAM_FETCH_WAY), None)


def roofline_rows(by, machine, fetches):
    peak = machine.get("2", {})
    gflops, gbs = peak.get("fp32_gflops"), peak.get("triad_gb_per_s")
    rows = []
    for (scene, renderer, structure, threads), r in sorted(by.items()):
        if threads != 2:
            continue
        nodes, tris = r.get("node_tests_per_ray"), r.get("triangle_tests_per_ray")
        mrays = r.get("mrays_per_s")
        if nodes is None or not mrays:
            rows.append([scene, renderer, structure, num(mrays), "–", "–", "–", "–", "–", "–"])
            continue
        gtests = (nodes + tris) * mrays / 1e3  # giga tests per second
        gflop = (nodes * BOX_FLOPS + tris * TRI_FLOPS) * mrays / 1e3
        gbyte = (nodes * BOX_BYTES + tris * TRI_BYTES) * mrays / 1e3
        rows.append([scene, renderer, structure, num(mrays), num(nodes, 1), num(tris, 1), num(gtests, 3),
                     f"{100 * gflop / gflops:.2f} %" if gflops else "–",
                     f"{100 * gbyte / gbs:.2f} %" if gbs else "–",
                     f"{100 * gtests / fetches:.1f} %" if fetches and renderer == "gpu" else "–"])
    return rows


def best(by, scene, renderer, threads=2, exclude=()):
    cands = [(r.get("mrays_per_s") or 0, s) for (sc, rd, s, t), r in by.items()
             if sc == scene and rd == renderer and t == threads and s not in exclude]
    return max(cands) if cands else (None, None)


def ratio_rows(by, embree, scenes):
    rows = []
    for scene in scenes:
        bare2 = (embree.get(f"{scene}/2") or {}).get("mrays_per_s")
        cpu, cpu_name = best(by, scene, "cpu")
        r3 = (by.get((scene, "embree", "embree", 2)) or {}).get("mrays_per_s")
        gpu, gpu_name = best(by, scene, "gpu")
        if bare2 is None and cpu is None:
            continue
        rows.append([scene, f"{cpu_name or '–'} {num(cpu)}", num(bare2), num(r3), f"{gpu_name or '–'} {num(gpu)}",
                     num(ratio(cpu, bare2)), num(ratio(cpu, r3)), num(ratio(r3, bare2)), num(ratio(gpu, cpu))])
    return rows


KIND_PATHS = ["bvh8-packet", "bvh8", "embree-1", "embree-packets"]


def kind_rows(kinds):
    rows = []
    for scene, lines in kinds.items():
        for k in lines:
            ms = k.get("ms", {})
            rows.append([scene, k.get("kind"), k.get("rays")] + [num(ms.get(p)) for p in KIND_PATHS] +
                        [num(ratio(ms.get("embree-1"), ms.get("bvh8-packet"))),
                         num(ratio(ms.get("embree-packets"), ms.get("bvh8-packet")))])
    return rows


def threads_rows(by, embree, scene):
    rows = []
    cpu, name = best(by, scene, "cpu")
    if name:
        one = (by.get((scene, "cpu", name, 1)) or {}).get("mrays_per_s")
        rows.append([f"best CPU row ({name})", num(cpu), num(one), num(ratio(cpu, one))])
    r3_2 = (by.get((scene, "embree", "embree", 2)) or {}).get("mrays_per_s")
    r3_1 = (by.get((scene, "embree", "embree", 1)) or {}).get("mrays_per_s")
    rows.append(["Embree through passtrace (-r 3)", num(r3_2), num(r3_1), num(ratio(r3_2, r3_1))])
    b2 = (embree.get(f"{scene}/2") or {}).get("mrays_per_s")
    b1 = (embree.get(f"{scene}/1") or {}).get("mrays_per_s")
    rows.append(["bare Embree rtcIntersect1", num(b2), num(b1), num(ratio(b2, b1))])
    return rows


def write_report(out_dir, results, records, baselines, scenes):
    by = collect(records)
    by_thesis = collect(records, THESIS_LOOP_LIMIT)
    machine, embree = baselines["machine"], baselines["embree"]
    p, m = results["parameters"], results["machine"]
    lines = [
        "# Speed: passtrace against bare Embree and against this machine's limits (issue 17)", "",
        f"Generated by `{results['command']}` on {results['generated_at']} "
        f"({results['runs_ok']} runs ok, {results['runs_failed']} failed, {results['wall_s']:.0f} s). "
        f"Machine: {m.get('cpu')}, {m.get('cores')} cores; GL: {m.get('gl_renderer')}; commit "
        f"{(m.get('git_commit') or '?')[:10]}.", "",
        f"Primary rays only (`-b 1`), {p['size']}² pixels, the minimum of `-m {p['repeats']}`, `--threads 2` "
        "unless a column says otherwise; stream rows at `-l 0` (one pass per bounce) unless a table says otherwise. Timings on a shared machine vary by ±20–50 % between runs: compare the "
        "ratios, which were measured within this one run. Scenes skipped (BART missing): "
        f"{', '.join(results['skipped']) or 'none'}.", "",
        "## This machine's limits (measured)", "",
        md_table(["threads", "ISA", "FP32 peak (GFLOP/s)", "STREAM triad (GB/s)"],
                 [[t, v.get("isa"), num(v.get("fp32_gflops"), 1), num(v.get("triad_gb_per_s"), 1)]
                  for t, v in sorted(machine.items(), reverse=True)]), "",
        "`build/tests/measure/measure_machine_peak THREADS`: independent FMA chains (2 FLOPs per lane), best of 3; "
        "triad a = b + s·c over 3 × 128 MB, 12 bytes per element, best of 5.", "",
    ]
    if baselines.get("fetch"):
        lines += [
            "What one texel fetch costs a fragment kernel on this GL, the unit a stream traversal is made of "
            "(bvh-octant reads two texels per box step and three per triangle step). "
            f"`build/tests/measure/measure_texel_fetch {p['size']} REPEATS`: a full-screen pass of {p['size']}² "
            "elements each reading 32 texels of a 2²¹-texel table, less the same pass reading none; a chain takes "
            "each address from the texel before, as a walk does; coherent elements of an 8×8 block read the same "
            "texels, as primary rays do. All of the GL's threads; minimum over the repeats.", "",
            md_table(["way", "ns per fetch per element", "G fetches/s", "pass ms (32 fetches)", "pass ms (none)"],
                     [[f.get("way"), num(f.get("ns_per_fetch"), 3), num(f.get("g_fetches_per_s"), 3),
                       num(f.get("pass_ms")), num(f.get("empty_pass_ms"))] for f in baselines["fetch"]]), "",
        ]
    lines += [
        "## Ratios (issue 17's goals)", "",
        "Bare Embree: `build/tests/measure/measure_bare_embree SCENE SIZE THREADS REPEATS` (rtcIntersect1 over "
        "the CPU renderer's primary rays, no shading). Goals: best CPU row ≥ 1.2× bare Embree; `-r 3` ≥ 0.9× "
        "bare Embree; best stream row ≥ 0.5× the best CPU row.", "",
        md_table(["scene", "best CPU row, Mrays/s", "bare Embree", "-r 3", "best stream row",
                  "CPU / bare Embree", "CPU / -r 3", "-r 3 / bare Embree", "stream / CPU"],
                 ratio_rows(by, embree, scenes)), "",
    ]
    if scenes:
        lines += [f"### 2 threads against 1 ({scenes[0]}; goal ≥ 1.8×)", "",
                  md_table(["path", "2 threads", "1 thread", "ratio"], threads_rows(by, embree, scenes[0])), ""]
    if baselines.get("kinds"):
        lines += ["## Shadow and AO rays, traversal alone (one thread)", "",
                  "`build/tests/measure/measure_ray_kinds SCENE SIZE REPEATS`: the CPU renderer's rays of each kind "
                  "(primary in 8×4 tiles; from their hits shadow rays to the light and 4 AO rays per pixel, in 8×8 "
                  "tiles), traced with no renderer around them: ms for all rays of the kind, minimum over the repeats. "
                  "`embree-1` is rtcIntersect1 / rtcOccluded1 ray by ray, `embree-packets` rtcIntersect16 / "
                  "rtcOccluded16 as `-r 3` calls them. Goal: shadow and diffuse (AO) rays ≥ 1.0× Embree.", "",
                  md_table(["scene", "kind", "rays"] + [f"{p} ms" for p in KIND_PATHS] +
                           ["embree-1 / bvh8-packet", "embree-packets / bvh8-packet"], kind_rows(baselines["kinds"])),
                  ""]
    if by_thesis:
        lines += ["## Loop limit per stream row (item 3)", "",
                  f"Each stream row at the thesis's `-l {THESIS_LOOP_LIMIT}` (steps per ray per pass) and at "
                  "passtrace's default `-l 0`: one pass per bounce, each pass bounded by llvmpipe's shader loop "
                  "cap (stream/shader_loop_budget.h). Passes are per frame.", "",
                  md_table(["scene", "structure", f"-l {THESIS_LOOP_LIMIT} Mrays/s", "passes", "-l 0 Mrays/s",
                            "passes", "-l 0 / -l 20"], loop_rows(by, by_thesis)), ""]
    lines += [
        "## Roofline", "",
        "Node (box) tests per ray as `--stats`/`--json` count them (`node_tests_per_ray`; accel/registry.h, "
        "Structure::cpuStepsVisitNodes: a BVH step tests one node's box, a kd step one split plane, a grid or "
        "octree step one cell; Embree counts nothing). Cost model: a box test "
        f"{BOX_FLOPS} FLOPs and {BOX_BYTES} bytes, a triangle test {TRI_FLOPS} FLOPs and {TRI_BYTES} bytes; "
        "the percentages are the achieved rate under that model over the 2-thread peak and triad bandwidth. "
        f"Stream rows also over the texel-fetch rate ({STREAM_FETCH_WAY}, above) at one texel per test, the "
        "least a stream kernel reads: the whole frame (ray generation, shading) counts against it, so 100 % is "
        "out of reach.", "",
        md_table(["scene", "renderer", "structure", "Mrays/s", "box tests/ray", "triangle tests/ray",
                  "G tests/s", "% of FP32 peak", "% of triad bandwidth", "% of texel-fetch rate"],
                 roofline_rows(by, machine, fetch_rate(baselines.get("fetch")))), "",
    ]
    lines += bench_stages.section(baselines.get("stages"), num, md_table)
    if baselines["errors"]:
        lines += ["## Baselines that failed", ""] + [f"- {e}" for e in baselines["errors"]] + [""]
    lines += bench_report.failed_runs_section(records)
    lines += ["## Commands", "", "Each run's command line is in `results.json` (`runs[].command`); the "
              "baselines' output is in `results.json` (`baselines`)."]
    write_atomically(out_dir / "REPORT.md", "\n".join(lines) + "\n")


# ---------------------------------------------------------------- the driver

def main(args, binary, registry, out, bart, bart_ok, bench, command):
    """Measures the baselines, runs the plan (skipping runs that finished earlier) and writes the report."""
    scenes = args.scenes.split(",") if args.scenes else list(SCENES)
    unknown = [s for s in scenes if s not in SCENES]
    if unknown:
        raise SystemExit(f"bench --speed: unknown scene {unknown[0]!r} (expected {', '.join(SCENES)})")
    size, repeats = args.size or 512, args.repeats or 5
    plan = Plan(size, repeats, registry, scenes, bart_ok)
    out.mkdir(parents=True, exist_ok=True)
    if args.report_only:  # the baselines of the last run, kept in results.json (not in git)
        baselines = (bench.read_json(out / "results.json") or {}).get("baselines") or {
            "machine": {}, "embree": {}, "errors": ["no results.json with baselines"]}
    else:
        baselines = measure_baselines(binary, scenes, size, repeats, bart, bart_ok, bench)
        baselines["stages"] = bench_stages.measure(binary, scenes[0], size, repeats, registry, bench.log)
    # Always rerun (unless --report-only): the ratios against the baselines hold only within one run.
    # The stream rows at passtrace's default -l 0: one pass per bounce (issue 17's tuned loop limit).
    runner = bench.Runner(binary, bart, out, args.timeout or 900, True, loop_limit=None)
    records, wall_s = bench.run_jobs(plan.jobs, runner, args.report_only, "--speed")
    parameters = {"size": size, "repeats": repeats, "scenes": scenes}
    results = bench.section_results(command, wall_s, parameters, plan.skipped, plan.missing, records, binary)
    results["baselines"] = baselines
    bench.write_json_atomic(out / "results.json", results)
    write_report(out, results, records, baselines, [s for s in scenes if s not in plan.skipped])
    bench.log(f"bench --speed: {results['runs_ok']} ok, {results['runs_failed']} failed; report: "
              f"{bench.shown_path(out / 'REPORT.md')}")
    return 0 if results["runs_failed"] == 0 else 1
