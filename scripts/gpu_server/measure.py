#!/usr/bin/env python3
"""The one command a GPU machine runs (issue 38), within a device-time budget.

1. the SM probe (measure_sm_probe): which SMs each stage runs on, and the
   driver's SM count;
2. every stream row in both stages (--stage fragment, compute), primary rays
   (-b 1) and AO rays (--shading ao), at 1920x1080 on the bunny, BART Kitchen
   (where packed) and a 10M-triangle sphere field, in that order of priority:
   the budget ends the matrix where it must, and the table says what did not run;
3. the GL test suite (passtrace_gl_tests) in both stages, sharded, several
   shards at a time;
4. OUT/TABLE.md: the numbers as Markdown, rates per GPU and per SM the stage
   can use, the issue's goals with their figures; OUT/runs.jsonl,
   OUT/sm_probe.json and OUT/gl_tests.json hold the raw results.

On the server, from a pack.sh tarball unpacked in DIR:
    python3 DIR/measure.py --pack DIR --out OUT
From a build tree (the test suite runs it on llvmpipe with --tiny):
    python3 scripts/gpu_server/measure.py --build build --out OUT --tiny

No timing is asserted; a failed run is a row with its error line.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

MIXES = {
    "primary": ["-b", "1", "-m", "3"],
    "ao": ["--shading", "ao", "-m", "2"],
}
STAGES = ("fragment", "compute")


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--pack", type=Path, help="an unpacked pack.sh tarball (bin/, lib/, bunny.obj, bart/)")
    where.add_argument("--build", type=Path, help="a build tree (passtrace, tests/passtrace_gl_tests, ...)")
    p.add_argument("--out", type=Path, required=True, help="folder for TABLE.md and the raw results")
    p.add_argument("--budget", type=float, default=450, help="seconds for everything (default 450)")
    p.add_argument("--gl-seconds", type=float, default=150, help="of the budget, kept for the GL tests")
    p.add_argument("--gl-shards", type=int, default=8, help="shards per stage (default 8)")
    p.add_argument("--gl-parallel", type=int, default=8, help="shards at a time (default 8)")
    p.add_argument("--size", default="1920x1080", help="WIDTHxHEIGHT (default 1920x1080)")
    p.add_argument("--big-triangles", type=int, default=10_000_000, help="the sphere field's triangles")
    p.add_argument("--rows", nargs="*", help="stream rows (default: every one the registry lists)")
    p.add_argument("--scenes", nargs="*", help="of bunny, kitchen, spheres (default: all three)")
    p.add_argument("--no-gl-tests", action="store_true", help="leave the GL tests out")
    p.add_argument("--check", action="store_true",
                   help="exit 1 unless every run gave a number and every GL test ran and passed (the test suite's use)")
    p.add_argument("--tiny", action="store_true",
                   help="llvmpipe end to end: 32x24, Cornell and 2,000 sphere triangles, two GL tests per stage")
    return p.parse_args()


class Tools:
    """Where the binaries are, and the environment they run in."""

    def __init__(self, args):
        self.env = dict(os.environ)
        if args.pack:
            d = args.pack.resolve()
            self.passtrace, self.gl_tests, self.probe = d / "bin/passtrace", d / "bin/passtrace_gl_tests", d / "bin/measure_sm_probe"
            self.env["LD_LIBRARY_PATH"] = str(d / "lib")
            self.env["PASSTRACE_BART_DIR"] = str(d / "bart")
            self.bart = d / "bart"
            self.bunny = d / "bunny.obj"
        else:
            d = args.build.resolve()
            self.passtrace, self.gl_tests, self.probe = d / "passtrace", d / "tests/passtrace_gl_tests", d / "tests/measure/measure_sm_probe"
            self.bart = Path(self.env.get("PASSTRACE_BART_DIR", d.parent.parent / "shared/scenes/bart"))
            self.bunny = None

    def run(self, argv, timeout):
        """(exit status, stdout, last stderr line); a timeout is status 124."""
        try:
            r = subprocess.run(argv, env=self.env, capture_output=True, text=True, timeout=max(timeout, 1))
        except subprocess.TimeoutExpired:
            return 124, "", f"timed out after {timeout:.0f} s"
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        return r.returncode, r.stdout, lines[-1] if lines else ""


def stream_rows(tools):
    """(every stream row, those the registry features in the stage table), in registry order."""
    status, out, err = tools.run([str(tools.passtrace), "--list", "--json"], 60)
    if status != 0:
        sys.exit(f"measure.py: {tools.passtrace} --list --json: {err}")
    rows = [r for r in json.loads(out)["accelerators"] if "gpu" in r["renderers"]]
    featured = [r["name"] for r in rows if {"report": "stages", "renderer": "gpu"} in r.get("featured", [])]
    return [r["name"] for r in rows], featured


def scenes(args, tools, rows, first):
    """(label, passtrace scene arguments, rows in order) in priority order. On
    the big scene the stage table's rows (FIRST: the fastest stream rows)
    come first, so that a run cut short by the device time still has them."""
    if args.tiny:
        return [("cornell", ["-s", "cornell"], rows), ("spheres 2K", ["-s", "spheres", "--triangles", "2000"], rows)]
    found = [("bunny", ["-s", "bunny"], rows)]
    if (tools.bart / "kitchen").is_dir():
        found.append(("kitchen", ["-s", "kitchen"], rows))
    millions = args.big_triangles / 1e6
    big = [r for r in first if r in rows] + [r for r in rows if r not in first]
    found.append((f"spheres {millions:g}M", ["-s", "spheres", "--triangles", str(args.big_triangles)], big))
    return [f for f in found if not args.scenes or f[0].split()[0] in args.scenes]


def measure_runs(args, tools, rows, first, deadline, out):
    width, height = args.size.split("x")
    runs = []
    with open(out / "runs.jsonl", "w") as log, tempfile.TemporaryDirectory() as tmp:
        for label, scene, scene_rows in scenes(args, tools, rows, first):
            for row in scene_rows:
                for mix, flags in MIXES.items():
                    for stage in STAGES:  # the two stages of one row and mix run back to back
                        run = {"scene": label, "row": row, "mix": mix, "stage": stage}
                        left = deadline - time.monotonic()
                        if left < 5:
                            run["error"] = "not run: the budget was spent"
                        else:
                            report = Path(tmp) / "run.json"
                            argv = [str(tools.passtrace), "-r", "2", "-a", row, *scene, "--width", width,
                                    "--height", height, "--stage", stage, *flags, "--json", str(report), "-q"]
                            status, _, err = tools.run(argv, min(left, 240))
                            if status == 0:
                                j = json.loads(report.read_text())
                                run.update({k: j.get(k) for k in ("rays", "frame_ms", "mrays_per_s", "passes",
                                                                  "build_ms", "triangles", "gl_renderer")})
                            else:
                                run["error"] = err or f"exit status {status}"
                        runs.append(run)
                        log.write(json.dumps(run) + "\n")
                        log.flush()
    return runs


def gl_tests(args, tools, deadline, out):
    """Both stages, sharded; per stage the tests that passed and those that failed."""
    results = {}
    jobs = [(stage, k) for stage in STAGES for k in range(args.gl_shards)]
    pending, running = list(jobs), []
    with tempfile.TemporaryDirectory() as tmp:
        while pending or running:
            while pending and len(running) < args.gl_parallel:
                stage, k = pending.pop(0)
                report = Path(tmp) / f"{stage}_{k}.json"
                env = dict(tools.env, PASSTRACE_STREAM_STAGE=stage, GTEST_TOTAL_SHARDS=str(args.gl_shards),
                           GTEST_SHARD_INDEX=str(k))
                argv = [str(tools.gl_tests), f"--gtest_output=json:{report}"]
                if args.tiny:
                    argv.append("--gtest_filter=GlTest.ComputeStage*")
                proc = subprocess.Popen(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                running.append((stage, k, report, proc))
            time.sleep(0.2)
            for item in list(running):
                stage, k, report, proc = item
                timed_out = time.monotonic() > deadline
                if proc.poll() is None and not timed_out:
                    continue
                if proc.poll() is None:
                    proc.kill()
                    proc.wait()
                running.remove(item)
                r = results.setdefault(stage, {"passed": 0, "failed": [], "shards_unfinished": 0})
                if not report.exists():
                    r["shards_unfinished"] += 1
                    continue
                for suite in json.loads(report.read_text()).get("testsuites", []):
                    for t in suite.get("testsuite", []):
                        if t.get("result") == "SKIPPED" or t.get("status") == "NOTRUN":
                            continue
                        name = f"{suite['name']}.{t['name']}"
                        if t.get("failures"):
                            r["failed"].append(name)
                        else:
                            r["passed"] += 1
    (out / "gl_tests.json").write_text(json.dumps(results, indent=1) + "\n")
    return results


def rate(run):
    return run.get("mrays_per_s") if "error" not in run else None


def fmt(x, digits=1):
    return "–" if x is None else f"{x:,.{digits}f}"


def table(args, probe, runs, gl, rows, out):
    sms = {s: (probe.get(s) or {}).get("sms") for s in STAGES}
    device = next((r["gl_renderer"] for r in runs if r.get("gl_renderer")), probe.get("gl_renderer", "?"))
    lines = [f"# Stream path, both stages: {device}", "",
             f"`scripts/gpu_server/measure.py`, {time.strftime('%Y-%m-%d')}, {args.size}, `-r 2 -l 0`; primary "
             f"`-b 1 -m 3`, AO `--shading ao -m 2` (minimum of the frames). Mrays/s per GPU, and per SM the stage "
             f"can use (the SM probe's count).", "",
             "## SMs each stage ran on (`measure_sm_probe`)", ""]
    if probe.get("shader_thread_group"):
        lines += [f"Driver's `GL_SM_COUNT_NV`: {probe.get('sm_count')}.", "",
                  "| stage | SMs seen | elements | ids |", "|---|---|---|---|"]
        for s in STAGES:
            p = probe[s]
            ids = p["sm_ids"]
            span = f"{ids[0]}–{ids[-1]}" if ids else "–"
            lines.append(f"| {s} | {p['sms']} | {p['elements']:,} | {span} |")
    else:
        lines.append(f"Not measured here: {probe.get('error', 'no GL_NV_shader_thread_group')} "
                     f"({probe.get('gl_renderer', '?')}); per-SM columns are left empty.")
    lines.append("")
    by = {(r["scene"], r["row"], r["mix"], r["stage"]): r for r in runs}
    for scene in dict.fromkeys(r["scene"] for r in runs):
        lines += [f"## {scene}", "",
                  "| structure | primary fragment | primary compute | compute / fragment | AO fragment | AO compute "
                  "| primary fragment per SM | primary compute per SM | per-SM ratio fragment / compute |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for row in rows:
            get = lambda mix, stage: rate(by.get((scene, row, mix, stage), {"error": ""}))
            pf, pc, af, ac = get("primary", "fragment"), get("primary", "compute"), get("ao", "fragment"), get("ao", "compute")
            per = lambda x, s: x / sms[s] if x is not None and sms[s] else None
            pfs, pcs = per(pf, "fragment"), per(pc, "compute")
            lines.append(f"| {row} | {fmt(pf)} | {fmt(pc)} | {fmt(pc / pf if pf and pc else None, 2)} | {fmt(af)} "
                         f"| {fmt(ac)} | {fmt(pfs, 2)} | {fmt(pcs, 2)} | {fmt(pfs / pcs if pfs and pcs else None, 2)} |")
        errors = [r for r in runs if r["scene"] == scene and "error" in r]
        if errors:
            lines += ["", "Runs without a number:", ""]
            lines += [f"- {r['row']} {r['mix']} {r['stage']}: {r['error']}" for r in errors]
        lines.append("")
    lines += ["## GL tests (`passtrace_gl_tests`, `PASSTRACE_STREAM_STAGE`)", ""]
    if not gl:
        lines.append("Not run (`--no-gl-tests`).")
    else:
        lines += ["| stage | passed | failed | shards unfinished |", "|---|---|---|---|"]
    for s in STAGES if gl else ():
        g = gl.get(s, {"passed": 0, "failed": [], "shards_unfinished": args.gl_shards})
        lines.append(f"| {s} | {g['passed']} | {len(g['failed'])} | {g['shards_unfinished']} |")
    failed = [(s, name) for s in STAGES for name in gl.get(s, {}).get("failed", [])]
    if failed:
        lines += ["", "Failed:", ""] + [f"- {s}: `{name}`" for s, name in failed]
    first = next(iter(dict.fromkeys(r["scene"] for r in runs)), None)
    best = max((r for r in runs if r["scene"] == first and r["mix"] == "primary" and rate(r) is not None),
               key=rate, default=None)
    best_c = max((r for r in runs if r["scene"] == first and r["mix"] == "primary" and r["stage"] == "compute"
                  and rate(r) is not None), key=rate, default=None)
    lines += ["", "## The issue's goals", ""]
    lines.append(f"- compute stage, {first} primary, best row: "
                 + (f"{best_c['row']} {fmt(rate(best_c))} Mrays/s (goal ≥ 3,000)" if best_c else "not measured"))
    if best_c and sms["fragment"] and sms["compute"]:
        f = by.get((first, best_c["row"], "primary", "fragment"), {})
        if rate(f):
            ratio = (rate(f) / sms["fragment"]) / (rate(best_c) / sms["compute"])
            lines.append(f"- per SM, fragment / compute for {best_c['row']}: {ratio:.2f} (goal 0.8–1.25)")
    if best:
        lines.append(f"- fastest run of all: {best['row']} ({best['stage']}) {fmt(rate(best))} Mrays/s")
    text = "\n".join(lines) + "\n"
    (out / "TABLE.md").write_text(text)
    return text


def main():
    args = parse_args()
    if args.tiny:
        args.size, args.gl_shards, args.gl_parallel = "32x24", 2, 2
    start = time.monotonic()
    deadline = start + args.budget
    tools = Tools(args)
    if tools.bunny and tools.bunny.exists():  # the packed bunny, where passtrace looks for it
        target = Path("/usr/share/glmark2/models/bunny.obj")
        if not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(tools.bunny.read_bytes())
    args.out.mkdir(parents=True, exist_ok=True)
    rows, first = stream_rows(tools)
    rows = args.rows or rows

    status, stdout, err = tools.run([str(tools.probe), "4096" if not args.tiny else "64"], 60)
    probe = json.loads(stdout) if status == 0 else {"error": err or f"exit status {status}"}
    (args.out / "sm_probe.json").write_text(json.dumps(probe, indent=1) + "\n")

    runs = measure_runs(args, tools, rows, first, deadline - args.gl_seconds, args.out)
    gl = {} if args.no_gl_tests else gl_tests(args, tools, deadline, args.out)
    print(table(args, probe, runs, gl, rows, args.out), end="")
    print(f"measure.py: {time.monotonic() - start:.0f} s", file=sys.stderr)
    if args.check:
        problems = [f"{r['scene']} {r['row']} {r['mix']} {r['stage']}: {r['error']}" for r in runs if "error" in r]
        if "error" in probe:
            problems.append(f"SM probe: {probe['error']}")
        for s in STAGES:
            g = gl.get(s, {"passed": 0, "failed": [], "shards_unfinished": args.gl_shards})
            problems += [f"GL test {name} failed ({s})" for name in g["failed"]]
            if g["shards_unfinished"] or g["passed"] == 0:
                problems.append(f"GL tests ({s}): {g['shards_unfinished']} shards unfinished, {g['passed']} passed")
        for p in problems:
            print(f"measure.py: {p}", file=sys.stderr)
        sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
