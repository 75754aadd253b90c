#!/usr/bin/env python3
"""Writes results.json, results.csv, the plots and REPORT.md of a benchmark run.

Used by scripts/bench.py (`python3 scripts/bench.py --report-only` rewrites the
report from the finished runs in runs/ without running anything). Only
REPORT.md, results.csv and the PNGs are kept in git.
"""
import csv
import io
import json
import os
import pathlib

SCENES = ["cows", "robots", "kitchen", "bunny", "cornell", "conference", "sibenik", "sponza", "teapot", "dragon"]
# The thesis's scenes by its names; the seeds' real scenes as passtrace names them.
SCENE_TITLES = {"cows": "Cows", "robots": "Robots", "kitchen": "Kitchen", "bunny": "Bunny", "cornell": "Cornell",
                "conference": "conference", "sibenik": "sibenik", "sponza": "sponza", "teapot": "teapot",
                "dragon": "dragon"}
# Thesis Table 1 (ms per frame, GeForce 6800 Ultra, 512x512) and Table 3 (floats
# per triangle, triangles excluded), in the thesis's row order.
THESIS_ROWS = [("grid", "Uniform grid"), ("kd-restart", "Kd-tree (Restart)"), ("kd-backtrack", "Kd-tree (Backtrack)"),
               ("kk-bvh", "BVH (Kay/Kajiya)"), ("gs-bvh", "BVH (Goldsmith/Salmon)")]
THESIS_MS = {
    "grid":         {"cows": 770, "robots": 4626, "kitchen": 3269, "bunny": 667, "cornell": 205},
    "kd-restart":   {"cows": 728, "robots": 2771, "kitchen": 1961, "bunny": 1299, "cornell": 203},
    "kd-backtrack": {"cows": 567, "robots": 2619, "kitchen": 1908, "bunny": 913, "cornell": 220},
    "kk-bvh":       {"cows": 195, "robots": 1017, "kitchen": 556, "bunny": 257, "cornell": 143},
    "gs-bvh":       {"cows": 183, "robots": 825, "kitchen": 476, "bunny": 275, "cornell": 103},
}
THESIS_FLOATS = {
    "gs-bvh":       {"cows": 4.1, "robots": 3.6, "kitchen": 4.1, "bunny": 4.6, "cornell": 5.0},
    "kk-bvh":       {"cows": 8.0, "robots": 8.0, "kitchen": 8.0, "bunny": 8.0, "cornell": 7.8},
    "grid":         {"cows": 24.1, "robots": 154.0, "kitchen": 140.0, "bunny": 38.6, "cornell": 6.1},
    "kd-restart":   {"cows": 66.0, "robots": 109.2, "kitchen": 68.5, "bunny": 109.4, "cornell": 2.5},
    "kd-backtrack": {"cows": 371.4, "robots": 192.8, "kitchen": 158.5, "bunny": 197.1, "cornell": 3.3},
}
THESIS_FIGURES = {"cows": 29, "robots": 30, "kitchen": 31, "bunny": 32, "cornell": 33}
RENDERER_TITLES = {"gpu": "GPU", "cpu": "CPU", "embree": "Embree"}
CSV_FIELDS = ["key", "scene", "renderer", "structure", "status", "width", "height", "bounces", "angles", "repeats",
              "triangles", "rays", "frame_ms", "mrays_per_s", "mrays_ratio_to_embree", "passes", "build_ms",
              "accel_floats_per_triangle", "steps_per_ray", "triangle_tests_per_ray", "wall_s", "gl_renderer",
              "gl_backend", "error", "command"]
NA = "n/a"


def fmt_s(seconds):
    seconds = int(round(max(0.0, seconds)))
    if seconds >= 3600:
        return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"
    return f"{seconds // 60} min {seconds % 60:02d} s"


def num(value, digits=1):
    if value is None:
        return NA
    if abs(value) >= 100 and digits <= 1:
        return f"{value:.0f}"
    return f"{value:.{digits}f}"


def ok(run):
    return run is not None and run.get("status") == "ok"


def index(runs):
    return {(r["scene"], r["renderer"], r["structure"]): r for r in runs}


def embree_mrays(by, scene):
    run = by.get((scene, "embree", "embree"))
    return run["result"]["mrays_per_s"] if ok(run) and run["result"].get("mrays_per_s") else None


def ratio_to_embree(by, run):
    if not ok(run):
        return None
    e = embree_mrays(by, run["scene"])
    return run["result"]["mrays_per_s"] / e if e else None


def pixel_scale(run):
    """Factor that takes a frame time at the run's size to the thesis's 512x512."""
    r = run["result"]
    return (512 * 512) / (r["width"] * r["height"])


def estimate_full(results, modes, scene_defaults):
    """Seconds the full mode is expected to take, from this run's measurements."""
    full = modes["full"]
    total, missing = 0.0, []
    size_full = full["size"]
    all_runs = list(results["runs"]) + list(results.get("heatmaps", []))
    for run in all_runs:
        if not ok(run):
            missing.append(run["key"])
            continue
        r = run["result"]
        quick_frames = r.get("angles", run.get("angles", 1)) * r.get("repeats", 1) + 1  # +1: untimed warm-up frame
        frame_s = r["frame_ms"] / 1000.0
        build_s = r["build_ms"] / 1000.0
        other = max(0.0, run["wall_s"] - build_s - quick_frames * frame_s)
        is_heat = run["key"].startswith("heat__")
        if is_heat:
            angles, repeats, side = 1, 1, min(size_full, 512)
        else:
            angles = full["angles"] if scene_defaults[run["scene"]]["path"] else 1
            repeats, side = full["repeats"], size_full
        scale = (side * side) / (r["width"] * r["height"])
        total += other + build_s + frame_s * scale * (angles * repeats + 1)
    return total, missing


def write_atomically(path, text):
    """Writes text to path whole or not at all: a temporary file beside it,
    flushed and synced, then renamed over it; removed again on any error
    (a full disk, say), so no record is ever half-written."""
    path = pathlib.Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with open(tmp, "w", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def ranks_note(ranks, hosts, runs):
    """Where the runs ran and what that means for their timings, when more than
    one MPI rank ran them (in this invocation or an earlier one); else None."""
    if ranks <= 1 and len(hosts) <= 1 and not any(r.get("rank") for r in runs):
        return None
    listing = ", ".join(f"`{h}` ({n} run{'s' if n != 1 else ''})" for h, n in hosts.items()) or "unknown hosts"
    return (f"This invocation had {ranks} MPI rank{'s' if ranks != 1 else ''}; the runs ran on {listing}. Ranks "
            "that share a machine perturb each other's timings (they compete for its cores, caches and memory "
            "bandwidth): for timings, run one rank per node (Open MPI: `mpirun --map-by ppr:1:node`).")


def placed(run):
    """A run's host and rank, as the table of all runs shows them."""
    return f"{run['host']} / {run.get('rank', 0)}" if run.get("host") else NA


def write_csv(path, runs, by):
    with io.StringIO(newline="") as f:
        w = csv.DictWriter(f, fieldnames=CSV_FIELDS)
        w.writeheader()
        for run in runs:
            r = run.get("result") or {}
            row = {k: r.get(k) for k in CSV_FIELDS if k in r}
            row.update({"key": run["key"], "scene": run["scene"], "renderer": run["renderer"],
                        "structure": run["structure"], "status": run["status"], "angles": run.get("angles"),
                        "wall_s": run.get("wall_s"), "error": run.get("error"), "command": run.get("command")})
            ratio = ratio_to_embree(by, run)
            row["mrays_ratio_to_embree"] = round(ratio, 4) if ratio is not None else None
            w.writerow(row)
        write_atomically(path, f.getvalue())


def plot_scene(out, scene, by, structures, params):
    """Per-angle curves (path scenes, thesis figures 29 and 32) or bars (30, 31, 33)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    groups = [(renderer, [(s, by.get((scene, renderer, s))) for s in structures.get(renderer, [])])
              for renderer in ("gpu", "cpu", "embree")]
    groups = [(g, [(s, r) for s, r in items if ok(r)]) for g, items in groups]
    groups = [(g, items) for g, items in groups if items]
    if not groups:
        return None
    ps = params["per_scene"][scene]
    size = params["size"]
    title = (f"{SCENE_TITLES[scene]}: ms per frame, {size}x{size}, -b {ps['bounces']}, min of -m {params['repeats']}"
             + (f" (cf. thesis figure {THESIS_FIGURES[scene]})" if scene in THESIS_FIGURES else ""))
    path_scene = ps["angles"] > 1
    name = f"plots/{scene}.png"
    (out / "plots").mkdir(exist_ok=True)
    if path_scene:
        panels = [("GPU stream renderer", [i for g, items in groups if g == "gpu" for i in items]),
                  ("CPU renderer and Embree", [i for g, items in groups if g != "gpu" for i in items])]
        panels = [p for p in panels if p[1]]
        fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 4.2), squeeze=False)
        for ax, (panel_title, items) in zip(axes[0], panels):
            for structure, run in items:
                frames = run["result"].get("frames") or []
                xs = [f["angle"] for f in frames]
                ys = [f["frame_ms"] for f in frames]
                ax.plot(xs, ys, marker="o" if len(xs) <= 20 else None, markersize=3, label=structure)
            ax.set_title(panel_title, fontsize=10)
            ax.set_xlabel(f"camera-path angle (of {ps['angles']})")
            ax.set_ylabel("ms per frame")
            ax.set_ylim(bottom=0)
            ax.xaxis.get_major_locator().set_params(integer=True)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
    else:
        items = [(f"{RENDERER_TITLES[g]} {s}" if g != "embree" else "Embree", r, g)
                 for g, group in groups for s, r in group]
        colours = {"gpu": "tab:blue", "cpu": "tab:orange", "embree": "tab:green"}
        fig, ax = plt.subplots(figsize=(8, 0.32 * len(items) + 1.4))
        ys = list(range(len(items)))[::-1]
        values = [r["result"]["frame_ms"] for _, r, _ in items]
        ax.barh(ys, values, color=[colours[g] for _, _, g in items])
        ax.set_yticks(ys)
        ax.set_yticklabels([label for label, _, _ in items], fontsize=8)
        for y, v in zip(ys, values):
            ax.text(v, y, f" {v:.1f}", va="center", fontsize=7)
        ax.set_xlabel("ms per frame")
        ax.set_xlim(0, max(values) * 1.15 if values else 1)
        ax.grid(axis="x", alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out / name, dpi=90)
    plt.close(fig)
    return name


def failed_runs_section(records):
    """The report's "Failed runs" lines: each (meta, record) whose record says status "error"."""
    failed = [(meta["key"], rec.get("error")) for meta, rec in records if rec and rec.get("status") == "error"]
    return ["## Failed runs", ""] + [f"- `{k}`: {e}" for k, e in failed] + [""] if failed else []


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def write_report(out, results, modes, scene_defaults, plots):
    runs, params, machine = results["runs"], results["parameters"], results["machine"]
    by = index(runs)
    scenes = [s for s in SCENES if s in params["scenes"]]
    mode = params["mode"]
    size = params["size"]
    L = []
    L.append(f"# passtrace benchmark: {mode} mode")
    L.append("")
    L.append("Generated by one command, `" + results["command"] + "`, on " + results["generated_at"] + ".")
    L.append("The thesis is Thrane & Simonsen 2005 (tracy); its numbers are from a GeForce 6800 Ultra, 512x512.")
    L.append("")
    n_ok = sum(ok(r) for r in runs)
    n_err = sum(r["status"] == "error" for r in runs)
    n_pending = sum(r["status"] == "pending" for r in runs)
    L.append(f"- **Wall clock of this invocation:** {fmt_s(results['wall_s'])} ({results.get('runs_executed', 0)} "
             f"passtrace runs executed, {results.get('runs_skipped', 0)} skipped as finished earlier; the runs' own "
             f"wall times sum to {fmt_s(results.get('runs_wall_s', 0))}). Runs: {n_ok} ok, {n_err} failed, "
             f"{n_pending} not run, plus {len(results.get('heatmaps', []))} heat-map runs.")
    if mode != "full":
        est, missing = estimate_full(results, modes, scene_defaults)
        note = ""
        if missing:
            note = f" (without the {len(missing)} runs that did not finish here, e.g. {missing[0]})"
        f = modes["full"]
        L.append(f"- **Full mode estimate:** about {fmt_s(est)}{note}, extrapolated run by run from these "
                 f"measurements to {f['size']}x{f['size']}, -n {f['angles']} angles on Cows and Bunny, "
                 f"-m {f['repeats']} (frame time scaled by pixels, angles and repeats; build and start-up as measured).")
    L.append(f"- **Machine:** {machine['cpu']}, {machine['cores']} cores, {machine['memory_gib']} GiB; "
             f"{machine['os']}; GL: {machine['gl_renderer']} ({machine['gl_backend']}); "
             f"git {str(machine['git_commit'])[:12]}{' (dirty tree)' if machine['git_dirty'] else ''}.")
    placement = ranks_note(results.get("ranks", 1), results.get("hosts", {}),
                           list(runs) + list(results.get("heatmaps", [])))
    if placement:
        L.append(f"- **Ranks:** {placement} The table of all runs names each run's host and rank.")
    if results.get("interrupted"):
        L.append("- **Interrupted:** this report covers only the runs that finished; rerun the same command to "
                 "complete it (finished runs are skipped).")
    for scene in results.get("skipped_scenes", []):
        L.append(f"- **{SCENE_TITLES[scene]} skipped:** " +
                 (f"the BART scenes are not at `{results['bart_dir']}` (`--bart-dir` or `$PASSTRACE_BART_DIR`)."
                  if scene in ("robots", "kitchen") else
                  "passtrace did not find the real scenes (`--scenes-dir` or `$PASSTRACE_SCENES_DIR`)."))
    L.append("")
    L.append("> Timings on shared machines vary by ±20–50 % from run to run. Compare ratios taken within one run "
             "(structure against structure, renderer against Embree), not absolute numbers across runs or "
             "machines.")
    L.append("")

    # Parameters
    L.append("## Parameters")
    L.append("")
    L.append(f"Mode `{mode}`: {size}x{size} images, minimum of `-m {params['repeats']}` repeats, "
             f"`-n {params['path_angles']}` camera-path angles for Cows and Bunny (one view for the others; "
             f"passtrace averages the per-angle minima), `-l {params['loop_limit']}`, `-e {params['kd_min_elements']}`"
             f", every other flag at passtrace's default. Heat maps: {params['heatmap_structure']}, "
             f"{params['heatmap_size']}x{params['heatmap_size']}, one view. The modes:")
    L.append("")
    mrows = []
    for name in ("tiny", "quick", "full"):
        m = modes[name]
        sel = m["selection"]
        mrows.append([f"`--{name}`", f"{m['size']}²", m["angles"], m["repeats"], ", ".join(m["scenes"]),
                      sel["gpu"], sel["cpu"], "yes" if m["embree"] else "no", f"{m['heat_size']}²",
                      m["out"] or "(--out required)"])
    L.append(md_table(["mode", "size", "-n (Cows, Bunny)", "-m", "scenes", "GPU structures", "CPU structures",
                       "Embree", "heat maps", "default output"], mrows))
    L.append("")
    L.append("Structures from `passtrace --list --json`: *all* every one the renderer implements, *numbered* those "
             "the thesis numbers (Table 4), in its order.")
    L.append("")
    L.append("Per scene (thesis 10.2; `--grid-multiplier`, `--kd-depth`, `--bounces` override them): `-d` backtrack "
             "applies to kd-backtrack, `-d` restart to the other kd structures (`kd-*`), `-g` to the grids "
             "(`grid*`); no other structure is given either flag.")
    L.append("")
    prow = []
    for s in scenes:
        ps = params["per_scene"][s]
        prow.append([SCENE_TITLES[s], ps["bounces"], ps["angles"], ps["grid_multiplier"],
                     f"{ps['kd_depth_restart']} / {ps['kd_depth_backtrack']}"])
    L.append(md_table(["scene", "-b", "-n", "-g", "-d restart / backtrack"], prow))
    L.append("")

    # Table 1
    scale_note = ""
    if size != 512:
        scale_note = (f" Frames here are {size}x{size}; to set them beside the thesis's 512x512 the measured ms are "
                      f"multiplied by the pixel ratio {512 * 512 / (size * size):.2f} (shown in bold; the raw ms are "
                      "in the table of all runs). Small frames carry the fixed per-pass cost of llvmpipe, so the "
                      "scaled numbers overstate a 512x512 frame: `--full` measures it. Cows and Bunny here average "
                      f"{params['path_angles']} angles, the thesis 100.")
    L.append("## Table 1: ms per frame, GPU stream renderer (`-r 2`) against the thesis's GeForce 6800")
    L.append("")
    L.append("Each cell: **ours** / thesis (ratio ours ÷ thesis; below 1 is faster here)." + scale_note)
    L.append("")
    rows = []
    for structure, title in THESIS_ROWS:
        row = [title]
        for s in scenes:
            run = by.get((s, "gpu", structure))
            thesis = THESIS_MS[structure].get(s)  # none on the real scenes
            if ok(run):
                ms = run["result"]["frame_ms"] * pixel_scale(run)
                row.append(f"**{num(ms)}** / {thesis} ({ms / thesis:.2f})" if thesis else f"**{num(ms)}** / –")
            else:
                row.append(f"{NA} / {thesis or '–'}")
        rows.append(row)
    L.append(md_table(["structure"] + [SCENE_TITLES[s] for s in scenes], rows))
    L.append("")

    # Table 3
    L.append("## Table 3: memory in floats per triangle (triangles excluded)")
    L.append("")
    L.append("Each cell: **ours** / thesis, for the GPU layouts (passtrace's JSON `accel_floats_per_triangle`).")
    L.append("")
    rows = []
    for structure, title in [THESIS_ROWS[i] for i in (4, 3, 0, 1, 2)]:
        row = [title]
        for s in scenes:
            run = by.get((s, "gpu", structure))
            thesis = THESIS_FLOATS[structure].get(s, "–")
            if ok(run) and run["result"].get("accel_floats_per_triangle") is not None:
                row.append(f"**{num(run['result']['accel_floats_per_triangle'])}** / {thesis}")
            else:
                row.append(f"{NA} / {thesis}")
        rows.append(row)
    L.append(md_table(["structure"] + [SCENE_TITLES[s] for s in scenes], rows))
    L.append("")

    # Mrays/s
    L.append("## Mrays/s of every structure, and the ratio to Embree")
    L.append("")
    L.append("Each cell: Mrays/s (that ÷ Embree's Mrays/s on the same scene, measured in this run). Rays are all "
             "rays of a frame: primary, shadow and reflection.")
    L.append("")
    rows = []
    for renderer in ("gpu", "cpu", "embree"):
        for structure in params["structures"].get(renderer, []):
            row = [RENDERER_TITLES[renderer], structure]
            for s in scenes:
                run = by.get((s, renderer, structure))
                if ok(run):
                    ratio = ratio_to_embree(by, run)
                    row.append(f"{num(run['result']['mrays_per_s'], 2)}"
                               + (f" (×{num(ratio, 2)})" if ratio is not None and renderer != "embree" else ""))
                else:
                    row.append(NA)
            rows.append(row)
    L.append(md_table(["renderer", "structure"] + [SCENE_TITLES[s] for s in scenes], rows))
    L.append("")
    no_embree = [SCENE_TITLES[s] for s in scenes if embree_mrays(by, s) is None]
    if no_embree:
        L.append(f"No Embree measurement (so no ratio) on: {', '.join(no_embree)}; see the failed runs below.")
        L.append("")
    # CPU against Embree, the closing note's numbers
    summary = []
    for s in scenes:
        e = embree_mrays(by, s)
        cpu_runs = [by.get((s, "cpu", st)) for st in params["structures"].get("cpu", [])]
        cpu_runs = [r for r in cpu_runs if ok(r)]
        if not cpu_runs:
            continue
        best = max(cpu_runs, key=lambda r: r["result"]["mrays_per_s"])
        kk = by.get((s, "cpu", "kk-bvh"))
        if e:
            text = (f"{SCENE_TITLES[s]}: best CPU structure {best['structure']} "
                    f"{best['result']['mrays_per_s']:.2f} Mrays/s = ×{best['result']['mrays_per_s'] / e:.2f} Embree "
                    f"({e:.2f})")
            if ok(kk):
                text += f"; CPU kk-bvh ×{kk['result']['mrays_per_s'] / e:.2f}"
        else:
            text = (f"{SCENE_TITLES[s]}: best CPU structure {best['structure']} "
                    f"{best['result']['mrays_per_s']:.2f} Mrays/s; Embree {NA}")
        summary.append("- " + text)
    if summary:
        L.append("CPU renderer against Embree:")
        L.append("")
        L += summary
        L.append("")

    # Figures
    L.append("## Figures")
    L.append("")
    L.append("Cows and Bunny: ms per frame at each camera-path angle (thesis figures 29 and 32). Robots, Kitchen and "
             "Cornell: one view, bars (thesis figures 30, 31 and 33).")
    L.append("")
    for s in scenes:
        if plots.get(s):
            L.append(f"![{SCENE_TITLES[s]}]({plots[s]})")
            L.append("")
    if not any(plots.values()):
        L.append(f"{NA} (no finished runs, or matplotlib missing)")
        L.append("")

    # Heat maps
    L.append("## Heat maps of traversal steps")
    L.append("")
    heats = {h["scene"]: h for h in results.get("heatmaps", []) if ok(h)}
    L.append(f"Per-pixel traversal steps (all bounces; `--heatmap`, scaled to the 99th percentile), "
             f"{params['heatmap_structure']}, one view per scene (Cows and Bunny: angle 0 of the path).")
    L.append("")
    if heats:
        shown = [s for s in scenes if s in heats]
        L.append("| " + " | ".join(SCENE_TITLES[s] for s in shown) + " |")
        L.append("|" + "---|" * len(shown))
        L.append("| " + " | ".join(f"![{s} steps]({heats[s]['heatmap']})" for s in shown) + " |")
        L.append("| " + " | ".join(f"{heats[s]['result']['steps_per_ray']:.1f} steps/ray" for s in shown) + " |")
    else:
        L.append(NA)
    L.append("")

    # All runs
    L.append("## All runs")
    L.append("")
    L.append(f"Measured values as passtrace wrote them (frame ms at {size}x{size}); `results.csv` holds the "
             "same and more (and `results.json`, not kept in git, everything).")
    L.append("")
    rows = []
    for run in runs:
        r = run.get("result") or {}
        ratio = ratio_to_embree(by, run)
        status = run["status"] if run["status"] != "error" else "error"
        rows.append([SCENE_TITLES[run["scene"]], RENDERER_TITLES[run["renderer"]], run["structure"], status,
                     num(r.get("frame_ms")), f"{int(r['rays']):,}" if r.get("rays") is not None else NA,
                     num(r.get("mrays_per_s"), 3), num(ratio, 2), num(r.get("passes")), num(r.get("build_ms"), 0),
                     num(r.get("accel_floats_per_triangle"), 2), num(r.get("steps_per_ray")),
                     num(r.get("triangle_tests_per_ray")), num(run.get("wall_s"))]
                    + ([placed(run)] if placement else []))
    L.append(md_table(["scene", "renderer", "structure", "status", "frame ms", "rays", "Mrays/s", "÷ Embree",
                       "passes", "build ms", "floats/tri", "steps/ray", "tests/ray", "wall s"] +
                      (["host / rank"] if placement else []), rows))
    L.append("")
    errors = [r for r in runs if r["status"] == "error"]
    if errors:
        L.append("Failed runs (shown as n/a above):")
        L.append("")
        for r in errors:
            L.append(f"- `{r['key']}`: {r.get('error')}")
        L.append("")

    # Machine
    L.append("## Machine")
    L.append("")
    mrows = [["CPU", machine["cpu"]], ["cores", f"{machine['cores']} ({machine.get('cores_available')} available)"],
             ["memory", f"{machine['memory_gib']} GiB"], ["OS", f"{machine['os']}, Linux {machine['kernel']}"],
             ["GL renderer", machine["gl_renderer"]], ["GL backend", machine["gl_backend"]]]
    mrows += [[k, v if v else "not installed"] for k, v in machine["versions"].items()]
    mrows += [["git commit", f"{machine['git_commit']}{' (tree dirty)' if machine['git_dirty'] else ' (clean)'}"],
              ["binary", f"{machine['binary']} (built {machine['binary_mtime']})"]]
    L.append(md_table(["", ""], mrows))
    L.append("")

    # Commands
    L.append("## Commands")
    L.append("")
    L.append("The suite: `" + results["command"] + "` (from the repository root). `--force` reruns finished runs; "
             "`--report-only` rewrites this report from them. Each passtrace run (`RUN.json` is the run's "
             "`--json` file, kept in `runs/` on the machine that ran it):")
    L.append("")
    L.append("```")
    for run in list(runs) + list(results.get("heatmaps", [])):
        if run.get("command"):
            L.append(run["command"])
    L.append("```")
    L.append("")
    write_atomically(out / "REPORT.md", "\n".join(L))


def write_all(out, results, modes, scene_defaults):
    out = pathlib.Path(out)
    runs = results["runs"]
    write_atomically(out / "results.json", json.dumps(results, indent=1, sort_keys=True) + "\n")
    by = index(runs)
    write_csv(out / "results.csv", runs, by)
    plots = {s: plot_scene(out, s, by, results["parameters"]["structures"], results["parameters"])
             for s in SCENES if s in results["parameters"]["scenes"]}
    write_report(out, results, modes, scene_defaults, plots)
