#!/usr/bin/env python3
"""Plumbing test of the scaling benchmark (scripts/bench.py --scale, issue 36):
two small sphere fields at 16x16 in two rounds write a report and results.json
with a record for every planned row x size x ray kind x round (a run or the
memory check's "does not fit"), positive Mrays/s and bytes per triangle, the
bandwidth and the roofline's bytes per ray, no
absolute paths, and a rerun runs nothing. No timing is asserted.

    python3 tests/slow/bench_scale_test.py --binary build/passtrace [--work DIR]
"""
import argparse
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

SIZES = [2000, 8000]
ROUNDS = 2


def run_scale(binary, out):
    cmd = [sys.executable, str(BENCH), "--scale", "--triangles-list", ",".join(map(str, SIZES)), "--size", "16",
           "--repeats", str(ROUNDS), "--no-real-scenes", "--out", str(out), "--binary", str(binary)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=280)


def read_json(path):
    try:
        return json.loads(pathlib.Path(path).read_text())
    except (OSError, ValueError) as e:
        print(f"{path}: {e}")
        return None


def has_matplotlib():
    """Whether bench.py plots: it reruns itself under Debian's python3 when this one lacks matplotlib."""
    for python in (sys.executable, "/usr/bin/python3"):
        try:
            if subprocess.run([python, "-c", "import matplotlib"], capture_output=True).returncode == 0:
                return True
        except OSError:
            pass
    return False


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--binary", default=str(REPO / "build" / "passtrace"))
    parser.add_argument("--work", help="a folder for the output (default: a temporary one)")
    args = parser.parse_args()

    import bench_scale
    import passtrace_registry
    registry = passtrace_registry.load(args.binary)
    rows = passtrace_registry.featured(registry, "scale")
    check({"cpu", "gpu"} <= {r for _, r in rows},
          f"the registry features CPU and stream rows in the scaling benchmark ({rows})")
    help_text = subprocess.run([args.binary, "--help"], capture_output=True, text=True).stdout
    kinds = [k for k in bench_scale.KINDS if k != "ao" or "--shading" in help_text]
    labels = [f"spheres-{bench_scale.tri_label(n)}" for n in SIZES]
    expected = {(s, n, r, k, rnd) for s in labels for n, r in rows for k in kinds for rnd in range(1, ROUNDS + 1)}

    with tempfile.TemporaryDirectory(prefix="bench_scale_") as tmp:
        work = pathlib.Path(args.work) if args.work else pathlib.Path(tmp)
        out = work / "scale"
        if out.exists():  # a folder kept from an earlier run of this test: start afresh
            import shutil
            shutil.rmtree(out)
        proc = run_scale(args.binary, out)
        if not check(proc.returncode == 0, f"bench.py --scale exits 0 (got {proc.returncode})"):
            print(proc.stdout[-3000:], proc.stderr[-3000:], sep="\n")
        results = read_json(out / "results.json") or {}
        report = (out / "REPORT.md").read_text() if (out / "REPORT.md").exists() else ""
        check(bool(results), "results.json exists and parses")
        check(bool(report), "REPORT.md exists")
        for key in ("machine", "runs", "parameters", "command", "wall_s", "runs_executed"):
            check(key in results, f"results.json has '{key}'")
        runs = [r for r in results.get("runs", []) if "tool" not in r.get("meta", {})]
        got = [(r["meta"].get("scene"), r["meta"].get("structure"), r["meta"].get("renderer"), r["meta"].get("kind"),
                r["meta"].get("round")) for r in runs]
        check(len(got) == len(set(got)) and set(got) == expected,
              f"one record per row x size x ray kind x round ({len(expected)} expected, {len(got)} got)")
        statuses = {r.get("status") for r in runs}
        check(statuses <= {"ok", "does-not-fit"}, f"every run ran or did not fit (statuses {sorted(statuses)})")
        for r in runs:
            if r.get("status") == "does-not-fit":
                check("need about" in (r.get("error") or ""), f"{r['key']}: 'does not fit' keeps the memory "
                      "check's line")
        ok = [r for r in runs if r.get("status") == "ok"]
        check(len(ok) > 0, f"some runs ran ({len(ok)})")
        bad = []
        for r in ok:
            res = r["result"]
            tris = res.get("triangles") or 0
            sb = (res.get("structure") or {}).get("structure_bytes", res.get("structure_bytes"))
            values = {"mrays_per_s": res.get("mrays_per_s"), "peak B/tri": (r.get("peak_rss_bytes") or 0) / tris
                      if tris else None, "build_ms": res.get("build_ms")}
            if r["meta"]["renderer"] != "embree":  # Embree reports neither (the report's † fallback for 0 bytes)
                floats = res.get("accel_floats_per_triangle")
                values["structure B/tri"] = sb / tris if sb and tris else 4 * floats if floats else None
            for name, v in values.items():
                if not isinstance(v, (int, float)) or v < 0 or (name != "build_ms" and v <= 0):
                    bad.append(f"{r['key']} {name}={v}")
        check(not bad, f"Mrays/s and bytes per triangle are positive numbers ({bad[:5]})")
        check(ok and all(r["result"].get("triangles", 0) >= r["meta"]["requested"] for r in ok),
              "the sphere fields have at least the triangles asked for")
        check("Embree `-r 3` / the fastest CPU row" in report and all(f"| {s} |" in report for s in labels),
              "the report has the ratio table and every size")
        check("**Issue 36's goal cells**" in report and "not measured in this run: spheres-5M primary" in report,
              "the report sums up the goal's cells, naming those this run left out")
        for kind in kinds:
            check(f"## {bench_scale.KIND_TITLES[kind][0].upper()}" in report, f"the report has a table for {kind}")
        peaks = [r for r in results.get("runs", []) if r.get("meta", {}).get("tool") == "peak"]
        check(len(peaks) == ROUNDS and all((r.get("result") or {}).get("triad_gb_per_s", 0) > 0 for r in peaks),
              f"the bandwidth is measured once per round ({len(peaks)} records)")
        check("## Roofline" in report and all(f"| {s} | {k} | bvh8-packet |" in report for s in labels for k in kinds),
              "the roofline has bvh8-packet's bytes per ray on every size and ray kind")
        text = (out / "results.json").read_text() + report
        check(str(REPO) not in text and "/tmp/" not in text, "no absolute paths in results.json or REPORT.md")
        if has_matplotlib():
            check((out / "plots" / "mrays.png").exists() and (out / "plots" / "bytes_per_triangle.png").exists(),
                  "the log-log plots are written")
        else:
            print("skip: matplotlib is missing (the plots)")

        # Resumable: the same command again runs nothing and leaves every record as it was.
        before = {p.name: p.stat().st_mtime_ns for p in (out / "runs").glob("*.json")}
        proc = run_scale(args.binary, out)
        check(proc.returncode == 0, f"a rerun exits 0 (got {proc.returncode})")
        again = read_json(out / "results.json") or {}
        check(again.get("runs_executed") == 0 and again.get("processes_started") == 0,
              f"a rerun runs nothing (runs_executed {again.get('runs_executed')}, "
              f"processes_started {again.get('processes_started')})")
        after = {p.name: p.stat().st_mtime_ns for p in (out / "runs").glob("*.json")}
        check(before == after and len(before) >= len(expected), "a rerun leaves every record as it was")
        check(len(again.get("runs", [])) == len(results.get("runs", [])), "a rerun reports the same runs")
        # Bad sizes: one line naming the option, a non-zero exit, no output folder.
        for bad in ("abc", "0"):
            bad_out = pathlib.Path(work) / f"bad_{bad}"
            proc = subprocess.run([sys.executable, str(BENCH), "--scale", "--triangles-list", bad, "--out",
                                   str(bad_out), "--binary", str(args.binary)], capture_output=True, text=True,
                                  timeout=60)
            lines = proc.stderr.strip().splitlines()
            check(proc.returncode != 0 and len(lines) == 1 and "--triangles-list" in lines[0]
                  and not bad_out.exists(), f"--triangles-list {bad}: one line, exit {proc.returncode}: {lines}")
        # An unknown scene: one line naming it and the valid ones, no output folder.
        bad_out = pathlib.Path(work) / "bad_scene"
        proc = subprocess.run([sys.executable, str(BENCH), "--scale", "--scenes", "spheres,atlantis", "--out",
                               str(bad_out), "--binary", str(args.binary)], capture_output=True, text=True, timeout=60)
        lines = proc.stderr.strip().splitlines()
        check(proc.returncode != 0 and len(lines) == 1 and "'atlantis'" in lines[0] and "kitchen" in lines[0]
              and not bad_out.exists(), f"--scenes atlantis: one line, exit {proc.returncode}: {lines}")
    return summary()


if __name__ == "__main__":
    sys.exit(main())
