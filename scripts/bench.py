#!/usr/bin/env python3
"""passtrace's benchmark suite: the thesis's Tables 1 and 3 on this machine.

Runs passtrace once per (scene, renderer, structure) as in thesis 10.1-10.2
(-m repeats keeping the minimum, -n camera-path angles for Cows and Bunny, one
view for Robots, Kitchen and Cornell, -b 3 for Cows and -b 2 elsewhere, the
per-scene grid multipliers and kd depths of thesis 10.2), then one heat-map run
per scene, and writes into the output directory:

  runs/*.json      one file per finished run (kept: a rerun skips them)
  results.json     every run plus the machine block
  results.csv      one row per run
  REPORT.md        Tables 1 and 3 beside the thesis, Mrays/s and the ratio to
                   Embree, per-angle curves, bar charts and heat maps (PNG)

Modes: --quick (default; about 2-3 minutes on a 2-core machine, at the thesis's 512x512, output
docs/bench/), --full (the thesis's parameters, output docs/bench-full/),
--tiny (the plumbing test: Cornell only, 16x16). Ctrl-C stops after writing the
report from the runs that finished. Timings on shared machines vary by
20-50 % from run to run: compare ratios taken in one run.
"""
import argparse
import csv
import datetime
import json
import os
import pathlib
import platform
import shlex
import signal
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))

SCENES = ["cows", "robots", "kitchen", "bunny", "cornell"]
BART_SCENES = {"robots", "kitchen"}
# Structures by renderer, in the order passtrace numbers them.
GPU = ["kk-bvh", "gs-bvh", "kd-restart", "kd-backtrack", "grid"]
CPU = ["kk-bvh", "gs-bvh", "kd-tree", "kd-pbrt", "grid", "kk-bvh-recursive", "gs-bvh-recursive", "octree"]
RENDERERS = {"gpu": ("2", GPU), "cpu": ("1", CPU), "embree": ("3", ["embree"])}

# Thesis 10.2: per-scene parameters. Cows have the one mirror (3 traces per
# path); Cows and Bunny follow the camera path, the others keep one view.
SCENE_DEFAULTS = {
    "cows":    {"bounces": 3, "path": True,  "grid": 1.1, "kd": (24, 33)},
    "robots":  {"bounces": 2, "path": False, "grid": 1.4, "kd": (30, 30)},
    "kitchen": {"bounces": 2, "path": False, "grid": 1.3, "kd": (30, 33)},
    "bunny":   {"bounces": 2, "path": True,  "grid": 1.1, "kd": (30, 30)},
    "cornell": {"bounces": 2, "path": False, "grid": 0.6, "kd": (1, 1)},
}

# Mode parameters. `angles` applies to the path scenes (Cows, Bunny).
MODES = {
    "full": {
        "size": 512, "angles": 100, "repeats": 3, "heat_size": 512, "timeout": 3600,
        "scenes": SCENES, "gpu": GPU, "cpu": CPU, "embree": True, "out": "docs/bench-full",
    },
    "quick": {
        "size": 512, "angles": 4, "repeats": 1, "heat_size": 512, "timeout": 300,
        "scenes": SCENES, "gpu": GPU, "cpu": CPU, "embree": True, "out": "docs/bench",
    },
    "tiny": {
        "size": 16, "angles": 1, "repeats": 1, "heat_size": 16, "timeout": 120,
        "scenes": ["cornell"], "gpu": ["kk-bvh", "grid"], "cpu": ["kk-bvh", "kd-tree"], "embree": True,
        "out": None,
    },
}
HEAT_STRUCTURE = ("gpu", "kk-bvh")  # the structure whose traversal steps are drawn per scene


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def fmt_s(seconds):
    seconds = int(round(max(0.0, seconds)))
    return f"{seconds // 60}:{seconds % 60:02d}"


def parse_scene_map(text, convert):
    """'cows=1.1,bunny=1.2' or '1.1' (every scene) -> {scene: value}."""
    out = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        if "=" in part:
            scene, value = part.split("=", 1)
            if scene not in SCENE_DEFAULTS:
                raise SystemExit(f"bench: unknown scene {scene!r} in {text!r}")
            out[scene] = convert(value)
        else:
            out.update({s: convert(part) for s in SCENE_DEFAULTS})
    return out


def kd_pair(value):
    if "/" in value:
        a, b = value.split("/", 1)
        return (int(a), int(b))
    return (int(value), int(value))


def bart_dir(arg):
    if arg:
        return pathlib.Path(arg)
    if os.environ.get("PASSTRACE_BART_DIR"):
        return pathlib.Path(os.environ["PASSTRACE_BART_DIR"])
    return (REPO / ".." / "shared" / "scenes" / "bart").resolve()


def bart_present(path):
    return (path / "robots").is_dir() and (path / "kitchen").is_dir()


class Plan:
    """The matrix of runs of one invocation, with the arguments of each."""

    def __init__(self, args):
        mode = MODES[args.mode]
        self.mode = args.mode
        self.size = args.size or mode["size"]
        self.angles = args.angles or mode["angles"]
        self.repeats = args.repeats or mode["repeats"]
        self.heat_size = args.heat_size or min(max(self.size, mode["heat_size"]), 512)
        self.timeout = args.timeout or mode["timeout"]
        self.scenes = args.scenes.split(",") if args.scenes else list(mode["scenes"])
        for s in self.scenes:
            if s not in SCENE_DEFAULTS:
                raise SystemExit(f"bench: unknown scene {s!r}")
        renderers = args.renderers.split(",") if args.renderers else ["gpu", "cpu", "embree"]
        self.structures = {
            "gpu": list(mode["gpu"]) if "gpu" in renderers else [],
            "cpu": list(mode["cpu"]) if "cpu" in renderers else [],
            "embree": ["embree"] if ("embree" in renderers and mode["embree"]) else [],
        }
        if args.structures:
            keep = set(args.structures.split(","))
            self.structures = {r: [s for s in names if s in keep] for r, names in self.structures.items()}
        self.grid = {s: d["grid"] for s, d in SCENE_DEFAULTS.items()}
        self.grid.update(parse_scene_map(args.grid_multiplier or "", float))
        self.kd = {s: d["kd"] for s, d in SCENE_DEFAULTS.items()}
        self.kd.update(parse_scene_map(args.kd_depth or "", kd_pair))
        self.bounces = {s: d["bounces"] for s, d in SCENE_DEFAULTS.items()}
        if args.bounces:
            self.bounces = {s: args.bounces for s in SCENE_DEFAULTS}
        self.heatmaps = not args.no_heatmaps

    def scene_angles(self, scene):
        return self.angles if SCENE_DEFAULTS[scene]["path"] else 1

    def run_args(self, scene, renderer, structure):
        """passtrace's arguments for one timing run (no binary, --json or --bart-dir)."""
        rid = RENDERERS[renderer][0]
        a = ["-s", scene, "-r", rid]
        if renderer != "embree":
            a += ["-a", structure]
        a += ["-w", str(self.size), "-b", str(self.bounces[scene]), "-m", str(self.repeats),
              "-n", str(self.scene_angles(scene))]
        if structure == "grid":
            a += ["-g", f"{self.grid[scene]:g}"]
        restart, backtrack = self.kd[scene]
        if structure in ("kd-restart", "kd-tree", "kd-pbrt"):
            a += ["-d", str(restart)]
        elif structure == "kd-backtrack":
            a += ["-d", str(backtrack)]
        return a

    def heat_args(self, scene):
        renderer, structure = HEAT_STRUCTURE
        a = self.run_args(scene, renderer, structure)
        # one view, one repeat, the heat map's own size
        for flag, value in (("-w", str(self.heat_size)), ("-m", "1"), ("-n", "1")):
            a[a.index(flag) + 1] = value
        return a

    def parameters(self):
        return {
            "mode": self.mode, "size": self.size, "path_angles": self.angles, "repeats": self.repeats,
            "heatmap_size": self.heat_size, "heatmap_structure": "/".join(HEAT_STRUCTURE),
            "scenes": self.scenes, "structures": self.structures,
            "per_scene": {s: {"bounces": self.bounces[s], "angles": self.scene_angles(s),
                              "grid_multiplier": self.grid[s], "kd_depth_restart": self.kd[s][0],
                              "kd_depth_backtrack": self.kd[s][1]} for s in self.scenes},
            "loop_limit": 20, "kd_min_elements": 2, "timeout_s": self.timeout,
        }


def run_key(scene, renderer, structure):
    return f"{scene}__{renderer}__{structure}"


def read_json(path):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def write_json_atomic(path, data):
    tmp = path.with_name("." + path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
    os.replace(tmp, path)


class Runner:
    def __init__(self, binary, bart, out, timeout, force):
        self.binary = binary
        self.bart = bart
        self.out = out
        self.timeout = timeout
        self.force = force
        self.runs_dir = out / "runs"
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        (out / "heatmaps").mkdir(exist_ok=True)

    def command(self, args, json_path, extra=()):
        cmd = [str(self.binary)] + args + ["--json", str(json_path), "-q"] + list(extra)
        if args[1] in BART_SCENES:
            cmd += ["--bart-dir", str(self.bart)]
        return cmd

    def finished(self, record_path, args, extra_files=()):
        """The stored record when this exact run already finished (and its files exist)."""
        if self.force:
            return None
        rec = read_json(record_path)
        if not rec or rec.get("status") != "ok" or rec.get("args") != args:
            return None
        if any(not (self.out / f).exists() for f in extra_files):
            return None
        return rec

    def execute(self, meta, args, record_path, extra=(), label=""):
        """Runs passtrace once; writes and returns the run's record (status ok or error)."""
        tmp_json = self.runs_dir / f".{record_path.stem}.passtrace.json"
        tmp_json.unlink(missing_ok=True)
        cmd = self.command(args, tmp_json, extra)
        start = time.monotonic()
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            deadline = start + self.timeout
            while True:
                try:
                    stdout, stderr = proc.communicate(timeout=30)
                    break
                except subprocess.TimeoutExpired:
                    if time.monotonic() > deadline:
                        proc.kill()
                        stdout, stderr = proc.communicate()
                        stderr = (stderr or "") + f"\nbench: killed after the {self.timeout} s timeout"
                        break
                    log(f"      ... {label} still running ({fmt_s(time.monotonic() - start)})")
        except BaseException:
            proc.kill()
            proc.wait()
            tmp_json.unlink(missing_ok=True)
            raise
        wall = time.monotonic() - start
        shown = [c if c != str(tmp_json) else "RUN.json" for c in cmd]
        rec = dict(meta)
        rec.update({"args": args, "command": shlex.join(shown), "wall_s": round(wall, 3),
                    "finished_at": datetime.datetime.now().isoformat(timespec="seconds"),
                    "returncode": proc.returncode})
        result = read_json(tmp_json) if proc.returncode == 0 else None
        if result is not None:
            rec["status"] = "ok"
            rec["result"] = result
        else:
            rec["status"] = "error"
            lines = [l for l in (stderr or "").strip().splitlines() if l.strip()]
            rec["error"] = lines[-1] if lines else f"exit status {proc.returncode}, no JSON written"
        tmp_json.unlink(missing_ok=True)
        write_json_atomic(record_path, rec)
        return rec


def build_jobs(plan, runner, bart_ok):
    """[(kind, meta, args, record_path, extra_args, extra_files)] in execution order."""
    jobs, skipped_scenes = [], []
    for scene in plan.scenes:
        if scene in BART_SCENES and not bart_ok:
            skipped_scenes.append(scene)
            continue
        for renderer in ("gpu", "cpu", "embree"):
            for structure in plan.structures[renderer]:
                key = run_key(scene, renderer, structure)
                meta = {"key": key, "scene": scene, "renderer": renderer, "structure": structure,
                        "angles": plan.scene_angles(scene)}
                jobs.append(("run", meta, plan.run_args(scene, renderer, structure),
                             runner.runs_dir / f"{key}.json", (), ()))
        if plan.heatmaps:
            renderer, structure = HEAT_STRUCTURE
            key = "heat__" + run_key(scene, renderer, structure)
            png = f"heatmaps/{scene}_{renderer}_{structure}.png"
            meta = {"key": key, "scene": scene, "renderer": renderer, "structure": structure,
                    "angles": 1, "heatmap": png}
            jobs.append(("heat", meta, plan.heat_args(scene), runner.runs_dir / f"{key}.json",
                         ("--heatmap", str(runner.out / png)), (png,)))
    return jobs, skipped_scenes


def estimate(job, done):
    """Seconds a pending job is expected to take, from the runs executed so far."""
    _, meta, *_ = job
    def mean(xs):
        return sum(xs) / len(xs) if xs else None
    same_scene = [d["wall_s"] for d in done if d["scene"] == meta["scene"]]
    same_renderer = [d["wall_s"] for d in done if d["renderer"] == meta["renderer"]]
    every = [d["wall_s"] for d in done]
    return mean(same_scene) or mean(same_renderer) or mean(every) or 3.0


def machine_block(runs, binary):
    def read(path):
        try:
            return pathlib.Path(path).read_text()
        except OSError:
            return ""
    cpu = next((l.split(":", 1)[1].strip() for l in read("/proc/cpuinfo").splitlines()
                if l.startswith("model name")), platform.processor() or "unknown")
    mem = next((l.split()[1] for l in read("/proc/meminfo").splitlines() if l.startswith("MemTotal")), None)
    os_name = next((l.split("=", 1)[1].strip().strip('"') for l in read("/etc/os-release").splitlines()
                    if l.startswith("PRETTY_NAME=")), platform.platform())

    def cmd(*c):
        try:
            r = subprocess.run(c, capture_output=True, text=True, cwd=REPO, timeout=30)
            return r.stdout.strip() if r.returncode == 0 else None
        except (OSError, subprocess.SubprocessError):
            return None

    versions = {}
    for pkg in ("libgl1-mesa-dri", "libegl-mesa0", "libembree3-3", "libopenimageio2.4", "llvm-15"):
        v = cmd("dpkg-query", "-W", "-f=${Version}", pkg)
        versions[pkg] = v or None
    try:
        import matplotlib
        versions["matplotlib"] = matplotlib.__version__
    except ImportError:
        versions["matplotlib"] = None
    versions["python"] = platform.python_version()
    gl = next((r["result"] for r in runs if r.get("status") == "ok" and r["result"].get("gl_renderer")), {})
    dirty = cmd("git", "status", "--porcelain", "--untracked-files=no")
    binary_mtime = None
    try:
        binary_mtime = datetime.datetime.fromtimestamp(pathlib.Path(binary).stat().st_mtime).isoformat(
            timespec="seconds")
    except OSError:
        pass
    return {
        "cpu": cpu, "cores": os.cpu_count(),
        "cores_available": len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None,
        "memory_gib": round(int(mem) / 1024 / 1024, 1) if mem else None,
        "os": os_name, "kernel": platform.release(),
        "gl_renderer": gl.get("gl_renderer"), "gl_backend": gl.get("gl_backend"),
        "versions": versions,
        "git_commit": cmd("git", "rev-parse", "HEAD"), "git_dirty": bool(dirty) if dirty is not None else None,
        "binary": str(binary), "binary_mtime": binary_mtime,
    }


def ensure_matplotlib():
    """The plots need matplotlib (Debian python3-matplotlib): when this interpreter
    lacks it (a pyenv or venv python3 first on PATH), rerun under the system one."""
    try:
        import matplotlib  # noqa: F401
        return
    except ImportError:
        pass
    system = "/usr/bin/python3"
    if os.environ.get("PASSTRACE_BENCH_REEXEC") or not os.access(system, os.X_OK) or \
            os.path.realpath(sys.executable) == os.path.realpath(system):
        log("bench: matplotlib is missing (apt-get install python3-matplotlib): the report will have no plots")
        return
    probe = subprocess.run([system, "-c", "import matplotlib"], capture_output=True)
    if probe.returncode != 0:
        log("bench: matplotlib is missing (apt-get install python3-matplotlib): the report will have no plots")
        return
    os.environ["PASSTRACE_BENCH_REEXEC"] = "1"
    os.execv(system, [system, os.path.abspath(__file__)] + sys.argv[1:])


def main(argv=None):
    if argv is None:
        ensure_matplotlib()
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    m = parser.add_mutually_exclusive_group()
    m.add_argument("--quick", dest="mode", action="store_const", const="quick", help="about 2-3 minutes at 512x512 (default)")
    m.add_argument("--full", dest="mode", action="store_const", const="full", help="the thesis's parameters")
    m.add_argument("--tiny", dest="mode", action="store_const", const="tiny", help="Cornell, 16x16: the plumbing test")
    parser.set_defaults(mode="quick")
    parser.add_argument("--binary", default=str(REPO / "build" / "passtrace"))
    parser.add_argument("--out", help="output directory (default docs/bench for --quick, docs/bench-full for --full)")
    parser.add_argument("--bart-dir", help="BART scenes (default $PASSTRACE_BART_DIR, else ../shared/scenes/bart)")
    parser.add_argument("--scenes", help="comma-separated subset of " + ",".join(SCENES))
    parser.add_argument("--renderers", help="comma-separated subset of gpu,cpu,embree")
    parser.add_argument("--structures", help="comma-separated structure names to keep (e.g. kk-bvh,grid,embree)")
    parser.add_argument("--size", type=int, help="image side N (NxN)")
    parser.add_argument("--angles", type=int, help="camera-path angles for Cows and Bunny (-n)")
    parser.add_argument("--repeats", type=int, help="timed repeats, minimum kept (-m)")
    parser.add_argument("--bounces", type=int, help="traces per path for every scene (default: 3 Cows, 2 others)")
    parser.add_argument("--grid-multiplier", help="-g per scene: 'cows=1.1,robots=1.4' or one value for all")
    parser.add_argument("--kd-depth", help="-d per scene as RESTART/BACKTRACK: 'cows=24/33,cornell=1/1'")
    parser.add_argument("--heat-size", type=int, help="heat-map image side")
    parser.add_argument("--no-heatmaps", action="store_true")
    parser.add_argument("--timeout", type=int, help="seconds one passtrace run may take")
    parser.add_argument("--force", action="store_true", help="rerun runs that already finished")
    parser.add_argument("--report-only", action="store_true", help="write the report from finished runs, run nothing")
    args = parser.parse_args(argv)

    plan = Plan(args)
    if args.out:
        out = pathlib.Path(args.out)
    elif MODES[plan.mode]["out"]:
        out = REPO / MODES[plan.mode]["out"]
    else:
        parser.error("--tiny needs --out")
    out = out.resolve()
    binary = pathlib.Path(args.binary).resolve()
    if not args.report_only and not os.access(binary, os.X_OK):
        parser.error(f"no passtrace binary at {binary} (bash scripts/setup.sh builds it)")
    bart = bart_dir(args.bart_dir)
    bart_ok = bart_present(bart)
    runner = Runner(binary, bart, out, plan.timeout, args.force)
    jobs, skipped_scenes = build_jobs(plan, runner, bart_ok)
    for scene in skipped_scenes:
        log(f"bench: skipping {scene}: the BART scenes are not at {bart} "
            f"(give --bart-dir or $PASSTRACE_BART_DIR)")

    bench_cmd = shlex.join(["python3", "scripts/bench.py"] + (argv if argv is not None else sys.argv[1:]))
    # SIGTERM stops like Ctrl-C: the report is still written from what finished.
    signal.signal(signal.SIGTERM, lambda *_: (_ for _ in ()).throw(KeyboardInterrupt()))

    started = time.monotonic()
    executed, records, interrupted = [], {}, False
    n_runs = sum(1 for j in jobs if j[0] == "run")
    log(f"bench: {plan.mode} mode, {n_runs} runs + {len(jobs) - n_runs} heat maps into {out}; "
        f"{plan.size}x{plan.size}, -m {plan.repeats}, -n {plan.angles} on Cows/Bunny")
    try:
        for i, job in enumerate(jobs):
            kind, meta, run_args, record_path, extra, extra_files = job
            label = (f"{meta['scene']} {meta['renderer'].upper()} {meta['structure']}"
                     f"{' heat map' if kind == 'heat' else ''}, {meta['angles']} angle(s)")
            if args.report_only:
                rec = read_json(record_path)
                if rec and rec.get("args") == run_args:
                    records[meta["key"]] = rec
                continue
            rec = runner.finished(record_path, run_args, extra_files)
            if rec is not None:
                log(f"[{i + 1}/{len(jobs)}] {label}: skip (finished earlier, {rec['wall_s']:.1f} s; --force reruns)")
                records[meta["key"]] = rec
                continue
            pending = jobs[i:]
            remaining = sum(estimate(j, executed) for j in pending)
            log(f"[{i + 1}/{len(jobs)}] {label} ... elapsed {fmt_s(time.monotonic() - started)}, "
                f"about {fmt_s(remaining)} left")
            rec = runner.execute(meta, run_args, record_path, extra, label)
            records[meta["key"]] = rec
            executed.append({"scene": meta["scene"], "renderer": meta["renderer"], "wall_s": rec["wall_s"]})
            if rec["status"] == "ok":
                r = rec["result"]
                log(f"      {r['frame_ms']:.1f} ms/frame, {r['mrays_per_s']:.3f} Mrays/s, build "
                    f"{r['build_ms']:.0f} ms ({rec['wall_s']:.1f} s)")
            else:
                log(f"      failed ({rec['wall_s']:.1f} s): {rec['error']}")
    except KeyboardInterrupt:
        interrupted = True
        log("bench: interrupted; writing the report from the runs that finished")
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    elapsed = time.monotonic() - started

    import bench_report
    runs = [records[j[1]["key"]] if j[1]["key"] in records else dict(j[1], status="pending", args=j[2])
            for j in jobs if j[0] == "run"]
    heats = [records[j[1]["key"]] for j in jobs if j[0] == "heat" and j[1]["key"] in records]
    runs_wall = sum(r.get("wall_s", 0) for r in records.values())
    previous = (read_json(out / "results.json") or {}) if args.report_only else {}
    results = {
        "schema": 1,
        "generated_at": datetime.datetime.now().isoformat(timespec="seconds"),
        "command": previous.get("command", bench_cmd),
        "interrupted": previous.get("interrupted", interrupted),
        # --report-only keeps the timing of the invocation that ran the suite
        "wall_s": previous.get("wall_s", round(elapsed, 1)),
        "runs_executed": previous.get("runs_executed", len(executed)),
        "runs_skipped": previous.get("runs_skipped", len(records) - len(executed)),
        "runs_wall_s": round(runs_wall, 1),
        "parameters": plan.parameters(),
        "bart_dir": str(bart), "skipped_scenes": skipped_scenes,
        "machine": machine_block(list(records.values()), binary),
        "runs": runs,
        "heatmaps": heats,
    }
    bench_report.write_all(out, results, MODES, SCENE_DEFAULTS)
    log(f"bench: {sum(r['status'] == 'ok' for r in runs)} ok, {sum(r['status'] == 'error' for r in runs)} failed, "
        f"{sum(r['status'] == 'pending' for r in runs)} not run; {fmt_s(elapsed)} elapsed; "
        f"report: {out / 'REPORT.md'}")
    return 130 if interrupted else 0


if __name__ == "__main__":
    sys.exit(main())
