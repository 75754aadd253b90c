#!/usr/bin/env python3
"""Plumbing test of the benchmark suite (scripts/bench.py): the modes' structure
lists follow `passtrace --list --json`, a --tiny run writes well-formed results
with no absolute paths, a second run skips what finished, and --report-only
rewrites the report from runs/ (and refuses without them). No timing is asserted.

    python3 tests/slow/bench_test.py --binary build/passtrace
"""
import argparse
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

REPO = pathlib.Path(__file__).resolve().parents[2]
BENCH = REPO / "scripts" / "bench.py"
sys.path.insert(0, str(REPO / "scripts"))
sys.path.insert(0, str(REPO / "tests"))
from script_checks import check, summary  # noqa: E402


def run_bench(binary, out, *extra):
    cmd = [sys.executable, str(BENCH), "--tiny", "--out", str(out), "--binary", str(binary), *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=280)


def check_write_atomically():
    """A record is replaced whole or not at all: a write that fails part-way
    (here: text the encoder refuses) keeps the old
    record and leaves no temporary file."""
    from bench_report import write_atomically
    with tempfile.TemporaryDirectory() as d:
        path = pathlib.Path(d) / "results.json"
        write_atomically(path, "old\n")
        try:
            write_atomically(path, "n\udcffew")  # a lone surrogate: the UTF-8 write raises
            check(False, "a failed record write raises")
        except UnicodeEncodeError:
            check(True, "a failed record write raises")
        check(path.read_text() == "old\n", "a failed record write keeps the old record")
        check(sorted(p.name for p in pathlib.Path(d).iterdir()) == ["results.json"],
              "a failed record write leaves no temporary file")


def check_merge_report():
    """--merge-into: a section's report spliced into another between markers,
    replaced (not repeated) by a second merge, the rest kept, links rewritten,
    and each claim's verdict set beside the rest of the report's."""
    import bench
    table = "| claim | seed | here | verdict |\n|---|---|---|---|\n| A beats B | yes | {} | {} |\n"
    with tempfile.TemporaryDirectory() as d:
        main_report, section = pathlib.Path(d) / "REPORT.md", pathlib.Path(d) / "real" / "REPORT.md"
        section.parent.mkdir()
        main_report.write_text("# Main\n\n" + table.format("1.2×", "holds") + "\n## Commands\n")
        section.write_text("# Section\n\n" + table.format("0.8×", "**does not hold**") + "![p](plots/x.png)\n")
        bench.merge_report(main_report, section, "Real scenes")
        bench.merge_report(main_report, section, "Real scenes")
        text = main_report.read_text()
        check(text.count("<!-- merged from real/REPORT.md -->") == 1, "a second merge replaces the first")
        check(text.startswith("# Main") and "## Commands" in text, "a merge keeps the rest of the report")
        check("](real/plots/x.png)" in text, "a merge points the section's links into its folder")
        check("| A beats B | holds | does not hold | **yes** |" in text, "a merge sets verdicts side by side")


def check_dynamic_sibenik(binary, registry):
    """Papay's Sibenik2 as scripts/dynamic_sibenik.py makes it loads with the
    cathedral's triangles plus two moving spheres, the spheres moving."""
    import dynamic_sibenik
    import passtrace_registry
    if not passtrace_registry.scene_available(registry, "sibenik"):
        print("skip: the real scenes are absent (dynamic Sibenik)")
        return
    with tempfile.TemporaryDirectory() as d:
        path = dynamic_sibenik.make(binary, 2, d)
        out = pathlib.Path(d) / "run.json"
        proc = subprocess.run([str(binary), "-s", str(path), *dynamic_sibenik.VIEW_ARGS, "-r", "1", "-a", "kd-tree",
                               "-w", "16", "--frames", "2", "--dynamic", "merge", "--json", str(out), "-q",
                               "-o", str(pathlib.Path(d) / "f.png")], capture_output=True, text=True, timeout=120)
        if not check(proc.returncode == 0, f"dynamic Sibenik2 renders ({proc.stderr.strip()[-200:]})"):
            return
        result = json.loads(out.read_text())
        check(result["triangles"] == 75284 + 2 * dynamic_sibenik.OBJECT_TRIANGLES,
              f"dynamic Sibenik2 has the cathedral and two spheres ({result['triangles']} triangles)")
        check(result["sequence"][0].get("moving_triangles") == 2 * dynamic_sibenik.OBJECT_TRIANGLES,
              "dynamic Sibenik2 moves exactly the spheres")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--binary", default=str(REPO / "build" / "passtrace"))
    args = parser.parse_args()

    check_write_atomically()
    check_merge_report()
    import bench  # the modes, from the script itself
    import passtrace_registry
    registry = passtrace_registry.load(args.binary)
    check_dynamic_sibenik(args.binary, registry)
    modes = bench.resolve_modes(registry)
    implementing = {r: [a["name"] for a in registry["accelerators"] if r in a["renderers"]] for r in bench.RENDERERS}
    for name in ("quick", "full"):
        for r in ("gpu", "embree"):
            check(sorted(modes[name][r]) == sorted(implementing[r]),
                  f"--{name} runs every {r} structure of the registry ({modes[name][r]})")
    check(sorted(modes["full"]["cpu"]) == sorted(implementing["cpu"]),
          f"--full runs every cpu structure of the registry ({modes['full']['cpu']})")
    numbered = passtrace_registry.structures(registry, "cpu", numbered_only=True)
    check(modes["quick"]["cpu"] == numbered and set(numbered) <= set(modes["full"]["cpu"]),
          f"--quick runs the numbered cpu structures in number order ({modes['quick']['cpu']})")
    check(modes["full"]["cpu"][:len(numbered)] == numbered, "--full lists the numbered cpu structures first")
    try:
        passtrace_registry.check_names(registry, "cpu", ["kk-bvh", "no-such-structure"])
        check(False, "a structure name the registry lacks is an error")
    except SystemExit:
        check(True, "a structure name the registry lacks is an error")
    flags = {n: passtrace_registry.build_flags(n, grid_multiplier=1.5, kd_depth=7)
             for a in registry["accelerators"] for n in [a["name"]]}
    check(all(f == [] or (f[0] == "-g") == n.startswith("grid") for n, f in flags.items()),
          f"-g only for the grids, -d only for the kd-trees ({flags})")

    tiny = modes["tiny"]
    expected = {(s, r, st) for s in tiny["scenes"] for r in bench.RENDERERS for st in tiny[r]}

    with tempfile.TemporaryDirectory(prefix="bench_test_") as tmp:
        out = pathlib.Path(tmp) / "bench"
        proc = run_bench(args.binary, out)
        if not check(proc.returncode == 0, f"bench.py --tiny exits 0 (got {proc.returncode})"):
            print(proc.stdout[-3000:], proc.stderr[-3000:], sep="\n")

        # results.json
        try:
            results = json.loads((out / "results.json").read_text())
        except (OSError, ValueError) as e:
            results = None
            print(f"results.json: {e}")
        check(results is not None, "results.json exists and parses")
        results = results or {}
        for key in ("machine", "runs", "parameters", "command", "wall_s", "heatmaps"):
            check(key in results, f"results.json has '{key}'")
        machine = results.get("machine", {})
        for key in ("cpu", "cores", "memory_gib", "os", "gl_renderer", "gl_backend", "versions", "git_commit",
                    "git_dirty"):
            check(key in machine, f"machine block has '{key}'")
        runs = results.get("runs", [])
        got = [(r.get("scene"), r.get("renderer"), r.get("structure")) for r in runs]
        check(len(got) == len(set(got)) and set(got) == expected,
              f"one run per (scene, renderer, structure) of the tiny matrix ({len(expected)} expected, got {got})")
        for run in runs:
            status = run.get("status")
            check(status in ("ok", "error"), f"{run.get('key')}: finished with status ok or error ({status})")
            if status == "ok":
                r = run.get("result", {})
                for key in ("frame_ms", "rays", "mrays_per_s", "passes", "build_ms", "accel_floats_per_triangle",
                            "steps_per_ray", "triangle_tests_per_ray", "width", "height", "frames"):
                    check(key in r, f"{run['key']}: result has '{key}'")
                check(r.get("width") == tiny["size"], f"{run['key']}: rendered at the tiny size")
            elif status == "error":
                check(bool(run.get("error")), f"{run.get('key')}: a failed run records its error")
        # Only the Embree renderer may be missing from a build (it is optional); everything
        # else must have worked.
        bad = [r["key"] for r in runs if r.get("status") != "ok" and r.get("renderer") != "embree"]
        check(not bad, f"every GPU and CPU run succeeded (failed: {bad})")
        # scripts/sanitize.sh makes every sanitizer report end passtrace with status 23.
        reports = [r["key"] for r in runs if r.get("returncode") == 23]
        check(not reports, f"no run ended in a sanitizer report (exit status 23: {reports})")
        for h in results.get("heatmaps", []):
            if h.get("status") == "ok":
                check((out / h["heatmap"]).is_file(), f"heat map {h['heatmap']} written")

        # results.csv
        try:
            with open(out / "results.csv", newline="") as f:
                rows = list(csv.reader(f))
        except OSError:
            rows = []
        check(bool(rows) and "frame_ms" in rows[0] and "scene" in rows[0], "results.csv has a header")
        check(len(rows) - 1 == len(runs), f"results.csv has one row per run ({len(rows) - 1} rows, {len(runs)} runs)")

        # REPORT.md
        report = (out / "REPORT.md").read_text() if (out / "REPORT.md").exists() else ""
        check(bool(report), "REPORT.md exists")
        check("Table 1" in report and "thesis" in report, "REPORT.md has the thesis's Table 1 analogue")
        check("Table 3" in report, "REPORT.md has the Table 3 analogue")
        check("Embree" in report, "REPORT.md has the ratio to Embree")
        csv_text = (out / "results.csv").read_text() if (out / "results.csv").exists() else ""
        for name, text in (("REPORT.md", report), ("results.csv", csv_text)):
            leaks = [p for p in (str(pathlib.Path(tmp).resolve()), str(REPO), "/tmp/", "/work/", "/home/", "/root/")
                     if p in text]
            check(not leaks, f"{name} holds no absolute path ({leaks})")

        # A second invocation skips the finished runs.
        before = {r["key"]: r.get("finished_at") for r in runs if r.get("status") == "ok"}
        proc2 = run_bench(args.binary, out)
        check(proc2.returncode == 0, f"second bench.py --tiny exits 0 (got {proc2.returncode})")
        skips = proc2.stderr.count(": skip (finished earlier")
        n_ok = len(before) + sum(1 for h in results.get("heatmaps", []) if h.get("status") == "ok")
        check(skips == n_ok, f"second invocation skips the {n_ok} finished runs (skipped {skips})")
        try:
            again = json.loads((out / "results.json").read_text())
        except (OSError, ValueError):
            again = {}
        after = {r["key"]: r.get("finished_at") for r in again.get("runs", []) if r.get("status") == "ok"}
        check(all(after.get(k) == v for k, v in before.items()), "finished runs are kept, not rerun")

        # --report-only rewrites the report from runs/, and refuses where there are none.
        (out / "REPORT.md").unlink()
        proc3 = run_bench(args.binary, out, "--report-only")
        check(proc3.returncode == 0 and (out / "REPORT.md").exists(), "--report-only rewrites REPORT.md from runs/")
        empty = pathlib.Path(tmp) / "empty"
        proc4 = run_bench(args.binary, empty, "--report-only")
        check(proc4.returncode != 0 and not (empty / "REPORT.md").exists(),
              f"--report-only without runs/ fails and writes no report (exit {proc4.returncode})")

    # --cones (seed 000): every aperture and ray count for both structures, the claims table filled.
    with tempfile.TemporaryDirectory(prefix="bench_cones_") as tmp:
        out = pathlib.Path(tmp) / "cones"
        cmd = [sys.executable, str(BENCH), "--cones", "--scenes", "cornell", "--size", "8", "--out", str(out),
               "--binary", str(args.binary)]
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=280)
        if not check(proc.returncode == 0, f"bench.py --cones exits 0 (got {proc.returncode})"):
            print(proc.stdout[-3000:], proc.stderr[-3000:], sep="\n")
        results = json.loads((out / "results.json").read_text()) if (out / "results.json").exists() else {}
        keys = {r["meta"]["key"] for r in results.get("runs", []) if r.get("status") == "ok"}
        check(len(keys) == 20, f"--cones runs 5 cones and 3 ray counts per structure and 4 stream-path cones "
                              f"({len(keys)} ok)")
        report = (out / "REPORT.md").read_text() if (out / "REPORT.md").exists() else ""
        check(report.count("| cornell |") == 2 and "hold" in report, "--cones marks both claims for the scene")
        check(all(r["result"]["cone"]["nodes_per_pixel"] > 0 for r in results.get("runs", [])
                  if r.get("status") == "ok" and r["meta"]["kind"] == "cone"), "every cone run reports its nodes")

    return summary()


if __name__ == "__main__":
    sys.exit(main())
