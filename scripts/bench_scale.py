#!/usr/bin/env python3
"""Issue 36's scaling benchmark: the fast rows from 10^5 to 10^8 triangles.

    python3 scripts/bench.py --scale [--triangles-list 100000,1000000,5000000,10000000,20000000,100000000]
                                     [--size 512] [--repeats 3] [--no-real-scenes | --scenes spheres,dragon,bunny]

Per scene and row, for primary rays (`-b 1`), frames with shadow rays (`-b 2`,
the thesis's shading: a primary and a shadow ray per pixel) and AO rays
(`--shading ao --ao-samples 4`), one passtrace run each, `--threads 2`, the
minimum of `-m 10` frames (CPU renderers) or `-m 2` (stream path):

  scenes  the procedural sphere field `-s spheres --triangles N` at each N of
          --triangles-list, and the real scenes dragon (871K), conference and
          sibenik where passtrace finds them (--scenes-dir,
          $PASSTRACE_SCENES_DIR, ../shared/scenes/real; skipped with a note
          otherwise), and the small scenes issue 36's goal also names (bunny,
          and BART's kitchen and robots where the BART scenes are found);
          --no-real-scenes leaves the sphere fields only;
  rows    those the registry features in this report (`passtrace --list
          --json`, "featured": "scale"): the fastest CPU rows (-r 1), Embree
          (-r 3) and the fastest and the most compact stream rows (-r 2, at
          passtrace's default -l 0, one pass per bounce); a renderer with none
          in this build (Embree without libembree) is named in a note;
  bare    on every scene (the measurement tools take the spheres of N
          triangles as SCENE spheres:N): bare Embree rtcIntersect1 and
          rtcIntersect16 packets over the CPU renderer's primary rays on 2
          threads (build/tests/measure/measure_bare_embree), and traversal alone
          of primary, shadow and AO rays on 1 thread (measure_ray_kinds).

  machine the memory bandwidth (STREAM triad) on 2 threads, once per round
          (build/tests/measure/measure_machine_peak), for the roofline.

Measured per run: build ms, frame ms and Mrays/s (passtrace --json), the
structure's bytes per triangle (`structure_bytes` / `triangles`) and the
process's peak resident memory (its ru_maxrss, from os.wait4 on that one child):
absolute per triangle and as the slope between consecutive sphere sizes, which
leaves out the constant part (process, GL, image) and is the honest bytes per
triangle. A run the memory check refuses (passtrace's one line "... need about
X GiB; Y GiB available (nothing was built)") is recorded as "does not fit" with
that line, not as a failure, and is not tried again in later rounds.

The roofline puts each CPU row's bytes per ray, as its traversal reads them
(--json: node and triangle tests per ray times the bytes the row states one
of each reads, `structure.node_test_bytes` and `triangle_test_bytes`), times
its rays per second against the triad bandwidth: the traffic if no ray
shared a line with another or found it in a cache, an upper bound on what
the frame could ask of memory.

Rounds: per scene, every row and ray kind runs once (round 1), then again
(round 2), ... (--repeats rounds, default 3), the rows' order rotated each round,
so that a busy minute hits all rows alike; the report keeps each row's minimum
frame time (and median) and computes the ratios within this run, with their
spread over the rounds. Every run's record is OUT/runs/<key>.json: a rerun
skips finished ones (--force reruns them).
"""
import datetime
import json
import os
import pathlib
import re
import statistics
import subprocess
import tempfile
import threading
import time

import bench_ranks
import bench_report
from bench_report import write_atomically
from passtrace_registry import BART_SCENES, featured, scene_available
from report_tables import field, md_table, num

# 10^5 to 10^8, and 5 M and 20 M, where issue 36 sets its goal against Embree.
DEFAULT_TRIANGLES = [100_000, 1_000_000, 5_000_000, 10_000_000, 20_000_000, 100_000_000]
REAL_SCENES = ["dragon", "conference", "sibenik"]
# The small scenes where issue 36 asks the fastest CPU row to stay ahead too.
GOAL_SCENES = ["bunny", "kitchen", "robots"]
# The rows come from the registry (featured in "scale"), grouped by renderer in this order.
RENDERER_ORDER = ["cpu", "embree", "gpu"]
RENDERER_IDS = {"cpu": "1", "gpu": "2", "embree": "3"}
RENDERER_TITLES = {"cpu": "-r 1", "gpu": "-r 2", "embree": "-r 3"}
AO_SAMPLES = 4  # as measure_ray_kinds traces them
KINDS = {
    "primary": ["-b", "1"],
    "shadow": ["-b", "2"],
    "ao": ["--shading", "ao", "--ao-samples", str(AO_SAMPLES)],
}
KIND_TITLES = {"primary": "primary rays (`-b 1`)", "shadow": "frames with shadow rays (`-b 2`)",
               "ao": f"AO rays (`--shading ao --ao-samples {AO_SAMPLES}`)"}
# -m per run, by renderer: the minimum of that many frames; the rounds repeat the runs.
# CPU frames take 10-200 ms, so ten cost a second or two beside a build of
# seconds, and their minimum steps over a busy moment that two do not (5 M
# spheres, primary rays, Embree -r 3 over bvh8-packet: 1.05 in the stop-54
# report at -m 2, 1.18-1.42 per round at -m 10 by hand). Stream frames take up
# to seconds at scale: two.
FRAMES = {"cpu": 10, "embree": 10, "gpu": 2}
THREADS = 2
TOOL_REPEATS = 3
SPHERES_DEFAULT = 1_000_000  # kSphereFieldDefaultTriangles: what the tools load as "spheres"
GOAL = 1.2    # issue 36: the fastest CPU row >= 1.2x Embree -r 3 in frame time
# The scenes and ray kinds of issue 36's "Done when" (5 M and 20 M spheres, the
# dragon, bunny, Kitchen, Robots; primary rays and frames with shadow rays).
GOAL_SPHERES = [5_000_000, 20_000_000]
GOAL_KINDS = ["primary", "shadow"]
MACHINE = "machine"  # the scene label of the bandwidth measurement
REFUSED = re.compile(r"need about .* available \(nothing was built\)")
REFUSED_COUNT = re.compile(r": (\d+) triangles with ")


def tri_label(n):
    """100000 -> '100K', 1000000 -> '1M', 2500 -> '2.5K'."""
    for unit, div in (("M", 1_000_000), ("K", 1_000)):
        if n >= div:
            v = n / div
            return f"{v:g}{unit}"
    return str(n)


def parse_triangles(text):
    try:
        values = [int(float(p)) for p in text.split(",") if p.strip()]
    except ValueError:
        raise SystemExit(f"bench --scale: --triangles-list {text!r}: expected comma-separated counts")
    if not values or any(v <= 0 for v in values):
        raise SystemExit(f"bench --scale: --triangles-list {text!r}: expected positive counts")
    return sorted(set(values))


class Plan:
    """The runs, in execution order: [(kind, meta, args, key)]."""

    def __init__(self, registry, binary, sizes, named, size, rounds, kinds, bart_ok=True):
        self.size, self.rounds, self.kinds = size, rounds, kinds
        self.rows = sorted(featured(registry, "scale"), key=lambda row: RENDERER_ORDER.index(row[1]))
        self.missing = [RENDERER_TITLES[r] for r in RENDERER_ORDER
                        if not any(renderer == r for _, renderer in self.rows)]
        self.skipped = []
        self.scenes = []  # (label, scene args, requested triangles or None, tool scene name or None)
        for n in sizes:
            # The measurement tools take the spheres of N triangles as "spheres:N".
            self.scenes.append((f"spheres-{tri_label(n)}", ["-s", "spheres", "--triangles", str(n)], n,
                                f"spheres:{n}"))
        for s in named:
            if scene_available(registry, s, bart_ok):
                self.scenes.append((s, ["-s", s], None, s))
            else:
                self.skipped.append(s)
        tools = {t: measure_tool(binary, t) for t in ("measure_bare_embree", "measure_ray_kinds",
                                                      "measure_machine_peak")}
        self.tools_missing = [t for t, p in tools.items() if p is None]
        self.jobs = []
        for k in range(rounds if tools["measure_machine_peak"] else 0):
            key = f"scale__{MACHINE}__tool__peak__r{k + 1}"
            self.jobs.append(("tool", {"key": key, "scene": MACHINE, "requested": None, "tool": "peak",
                                       "tool_path": "measure_machine_peak", "round": k + 1}, [str(THREADS)], key))
        for label, scene_args, requested, tool_scene in self.scenes:
            for k in range(rounds):
                rotated = self.rows[k % len(self.rows):] + self.rows[:k % len(self.rows)] if self.rows else []
                for kind in kinds:
                    for name, renderer in rotated:
                        args = scene_args + ["-r", RENDERER_IDS[renderer], "-a", name, "-w", str(size),
                                             "-m", str(FRAMES[renderer]), "--threads", str(THREADS)] + KINDS[kind]
                        key = f"scale__{label}__{renderer}__{name}__{kind}__r{k + 1}"
                        self.jobs.append(("run", {"key": key, "scene": label, "requested": requested,
                                                  "renderer": renderer, "structure": name, "kind": kind,
                                                  "round": k + 1}, args, key))
                for tool, extra, name in (("measure_bare_embree", [], "bare-embree-1"),
                                          ("measure_bare_embree", ["--packet"], "bare-embree-packets"),
                                          ("measure_ray_kinds", [], "ray-kinds")):
                    if tools[tool] is None:
                        continue
                    if tool == "measure_bare_embree":
                        args = [tool_scene, str(size), str(THREADS), str(TOOL_REPEATS)] + extra
                    else:
                        args = [tool_scene, str(size), str(TOOL_REPEATS), str(AO_SAMPLES)]
                    key = f"scale__{label}__tool__{name}__r{k + 1}"
                    self.jobs.append(("tool", {"key": key, "scene": label, "requested": requested,
                                               "tool": name, "tool_path": tool, "round": k + 1}, args, key))


def measure_tool(binary, name):
    path = pathlib.Path(binary).parent / "tests" / "measure" / name
    return path if os.access(path, os.X_OK) else None


def binary_mtime(path):
    """The program's modification time (ISO seconds), which tells the runs of one build from another's."""
    try:
        return datetime.datetime.fromtimestamp(pathlib.Path(path).stat().st_mtime).isoformat(timespec="seconds")
    except OSError:
        return None


def run_child(cmd, timeout, env):
    """Runs CMD alone; (returncode, stdout, stderr, peak resident bytes, wall s, timed out).
    The peak is the child's own ru_maxrss (os.wait4 on its pid), so nothing else
    this process started counts in it."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        proc = subprocess.Popen(cmd, stdout=out, stderr=err, env=env)
        waited = []
        waiter = threading.Thread(target=lambda: waited.append(os.wait4(proc.pid, 0)), daemon=True)
        waiter.start()
        timed_out = False
        try:
            waiter.join(timeout)
            if waiter.is_alive():
                timed_out = True
                proc.kill()
                waiter.join()
        except BaseException:
            proc.kill()
            waiter.join()
            proc.returncode = os.waitstatus_to_exitcode(waited[0][1]) if waited else -9
            raise
        wall = time.monotonic() - start
        _, status, usage = waited[0]
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here: Popen must not wait again
        out.seek(0)
        err.seek(0)
        return (proc.returncode, out.read().decode(errors="replace"), err.read().decode(errors="replace"),
                usage.ru_maxrss * 1024, wall, timed_out)


class Runner:
    """bench.Runner's records and resumption, with each child's peak memory, the
    memory check's refusals recorded as "does-not-fit", and the measurement tools."""

    def __init__(self, bench, binary, out, timeout, force, scenes_dir, bart=None):
        self.base = bench.Runner(binary, bart, out, timeout, force, loop_limit=None)
        self.runs_dir, self.out, self.force, self.timeout = self.base.runs_dir, out, force, timeout
        self.binary, self.scenes_dir, self.bart = binary, scenes_dir, bart
        self.executed = 0

    @staticmethod
    def read(path):
        try:
            return json.loads(pathlib.Path(path).read_text())
        except (OSError, ValueError):
            return None

    def finished(self, record_path, args, extra_files=()):
        """The stored record when this exact run already ended as ok or does-not-fit."""
        if self.force:
            return None
        rec = self.read(record_path)
        if not rec or rec.get("status") not in ("ok", "does-not-fit") or rec.get("args") != args:
            return None
        return rec

    def env(self):
        env = bench_ranks.child_env()
        if self.scenes_dir and "PASSTRACE_SCENES_DIR" not in env:  # the tools look beside the current directory
            env["PASSTRACE_SCENES_DIR"] = str(self.scenes_dir)
        if self.bart and "PASSTRACE_BART_DIR" not in env:  # the tools' kitchen and robots
            env["PASSTRACE_BART_DIR"] = str(self.bart)
        return env

    def execute(self, meta, args, record_path, extra=(), label=""):
        """Runs one job; writes and returns its record (ok, does-not-fit or error)."""
        import bench  # the shown paths and atomic JSON, as the other sections write them
        rec = dict(meta)
        refused = self.refused_earlier(meta)
        if refused is not None:  # the memory check does not change between rounds
            rec.update({"args": args, "command": refused.get("command"), "wall_s": 0.0, "status": "does-not-fit",
                        "error": refused.get("error"), "not_rerun": f"refused in round {refused.get('round')}",
                        "finished_at": refused.get("finished_at"), "host": bench_ranks.HOST,
                        "rank": bench_ranks.rank()})
            bench.write_json_atomic(record_path, rec)
            return rec
        tmp_json = self.runs_dir / f".{record_path.stem}.passtrace.json"
        tmp_json.unlink(missing_ok=True)
        if "tool" in meta:
            tool = measure_tool(self.binary, meta["tool_path"])  # None while it is being relinked, say
            cmd = [str(tool or pathlib.Path(self.binary).parent / "tests" / "measure" / meta["tool_path"])] + list(args)
        else:
            cmd = self.base.command(args, tmp_json)
        self.executed += 1
        built = binary_mtime(cmd[0])
        try:
            code, stdout, stderr, peak, wall, timed_out = run_child(cmd, self.timeout, self.env())
        except OSError as e:  # e.g. the binary being relinked right now: an error record, rerun next time
            rec.update({"args": args, "command": bench.shown_command(cmd), "wall_s": 0.0, "status": "error",
                        "error": f"could not start {bench.shown_path(cmd[0])}: {e.strerror or e}",
                        "finished_at": datetime.datetime.now().isoformat(timespec="seconds"),
                        "host": bench_ranks.HOST, "rank": bench_ranks.rank()})
            bench.write_json_atomic(record_path, rec)
            return rec
        except BaseException:
            tmp_json.unlink(missing_ok=True)
            raise
        rec.update({"args": args, "command": bench.shown_command(["RUN.json" if c == str(tmp_json) else c
                                                                   for c in cmd]),
                    "wall_s": round(wall, 3), "peak_rss_bytes": peak, "returncode": code,
                    "binary_mtime": built if built == binary_mtime(cmd[0]) else "changed during the run",
                    "finished_at": datetime.datetime.now().isoformat(timespec="seconds"),
                    "host": bench_ranks.HOST, "rank": bench_ranks.rank()})
        lines = [l for l in stderr.strip().splitlines() if l.strip()]
        result = None
        if code == 0 and "tool" in meta:
            try:
                found = [json.loads(l) for l in stdout.splitlines() if l.startswith("{")]
            except ValueError:
                found = []
            result = (found if meta["tool"] == "ray-kinds" else found[-1]) if found else None
        elif code == 0:
            result = self.read(tmp_json)
        tmp_json.unlink(missing_ok=True)
        if result is not None:
            rec["status"], rec["result"] = "ok", result
        elif any(REFUSED.search(l) for l in lines):
            rec["status"] = "does-not-fit"
            rec["error"] = next(l for l in lines if REFUSED.search(l))
        else:
            rec["status"] = "error"
            rec["error"] = (f"killed after the {self.timeout} s timeout" if timed_out else
                            lines[-1] if lines else f"exit status {code}, no JSON")
        bench.write_json_atomic(record_path, rec)
        return rec

    def refused_earlier(self, meta):
        """An earlier round's does-not-fit record of the same scene, row and kind, or None."""
        if "tool" in meta:
            return None
        for k in range(1, meta["round"]):
            rec = self.read(self.runs_dir / f"{meta['key'].rsplit('__r', 1)[0]}__r{k}.json")
            if rec and rec.get("status") == "does-not-fit" and not self.force:
                return rec
        return None


# ---------------------------------------------------------------- collecting

def median(xs):
    return statistics.median(xs) if xs else None


class Cell:
    """One (scene, row, kind) over its rounds."""

    def __init__(self, recs):
        self.recs = recs
        self.ok = [r for r in recs if r.get("status") == "ok"]
        self.refused = [r for r in recs if r.get("status") == "does-not-fit"]
        self.failed = [r for r in recs if r.get("status") == "error"]
        res = [r["result"] for r in self.ok]
        self.frame_ms_by_round = {r["round"]: r["result"]["frame_ms"] for r in self.ok
                                  if r["result"].get("frame_ms")}
        frames = list(self.frame_ms_by_round.values())
        self.frame_ms = min(frames) if frames else None
        self.frame_ms_median = median(frames)
        mrays = [x["mrays_per_s"] for x in res if x.get("mrays_per_s")]
        self.mrays = max(mrays) if mrays else None
        self.mrays_median = median(mrays)
        builds = [x["build_ms"] for x in res if x.get("build_ms") is not None]
        self.build_ms = min(builds) if builds else None
        self.triangles = next((x["triangles"] for x in res if x.get("triangles")), None)
        if self.triangles is None:  # the memory check's line names the count: "spheres: N triangles with ..."
            said = [REFUSED_COUNT.search(r.get("error") or "") for r in self.refused]
            self.triangles = next((int(s.group(1)) for s in said if s), None)
        sb = next((field(x, "structure_bytes") for x in res if field(x, "structure_bytes")), None)
        self.structure_bytes, self.structure_from_floats = sb, False
        self.structure_bpt = sb / self.triangles if sb and self.triangles else None
        floats = next((x["accel_floats_per_triangle"] for x in res if x.get("accel_floats_per_triangle")), None)
        if self.structure_bpt is None and floats:  # the row computes no structure_bytes (0): the thesis's floats
            self.structure_bpt, self.structure_from_floats = 4 * floats, True
        peaks = [r["peak_rss_bytes"] for r in self.ok if r.get("peak_rss_bytes")]
        self.peak = median(peaks)
        self.peak_bpt = self.peak / self.triangles if self.peak and self.triangles else None
        self.slope = None  # set by collect() between consecutive sphere sizes

    def status(self):
        if self.ok:
            return "ok"
        if self.refused:
            return "does not fit"
        return "failed" if self.failed else "not run"


def collect(records, plan):
    """{(scene, row, renderer, kind): Cell} and {(scene, tool): [record]}."""
    groups, tools = {}, {}
    for meta, rec in records:
        if "tool" in meta:
            tools.setdefault((meta["scene"], meta["tool"]), []).append(rec)
        else:
            groups.setdefault((meta["scene"], meta["structure"], meta["renderer"], meta["kind"]), []).append(rec)
    cells = {k: Cell(v) for k, v in groups.items()}
    spheres = [label for label, _, requested, _ in plan.scenes if requested]
    for name, renderer in plan.rows:
        for kind in plan.kinds:
            prev = None
            for label in spheres:
                c = cells.get((label, name, renderer, kind))
                if c and c.peak and c.triangles:
                    if prev and c.triangles > prev.triangles:
                        c.slope = (c.peak - prev.peak) / (c.triangles - prev.triangles)
                    prev = c
                else:
                    prev = None  # a slope only between consecutive sizes that both ran
    return cells, tools


def scene_triangles(cells, label):
    return next((c.triangles for (s, *_), c in cells.items() if s == label and c.triangles), None)


def fastest(cells, label, kind, renderer, rows):
    """(name, Cell) of the row of RENDERER with the least frame time, or (None, None)."""
    cands = [(c.frame_ms, n, c) for n, r in rows if r == renderer
             for c in [cells.get((label, n, r, kind))] if c and c.frame_ms]
    if not cands:
        return None, None
    _, n, c = min(cands, key=lambda t: t[0])
    return n, c


# ---------------------------------------------------------------- the report

def cell_note(c, notes):
    """'does not fit [n]' / 'failed [n]' with the message kept as footnote n."""
    if c is None:
        return "not run"
    rec = (c.refused or c.failed or [{}])[0]
    msg = rec.get("error") or "?"
    if msg not in notes:
        notes.append(msg)
    return f"{c.status()} [{notes.index(msg) + 1}]"


def kind_table(cells, plan, kind, notes):
    rows = []
    for label, _, _, _ in plan.scenes:
        tris = scene_triangles(cells, label)
        for name, renderer in plan.rows:
            c = cells.get((label, name, renderer, kind))
            head = [label, num(tris) if tris else "–", f"{name} ({RENDERER_TITLES[renderer]})"]
            if c is None or not c.ok:
                rows.append(head + [cell_note(c, notes)] + ["–"] * 7)
                continue
            rows.append(head + [num(c.mrays, 2), num(c.mrays_median, 2), num(c.frame_ms, 3), num(c.build_ms, 0),
                                num(c.structure_bpt, 1) + (" †" if c.structure_from_floats else ""),
                                num(c.peak / 2**20 if c.peak else None, 0),
                                num(c.peak_bpt, 1), num(c.slope, 1)])
    return md_table(["scene", "triangles", "row", "Mrays/s (best)", "Mrays/s (median)", "frame ms (min)",
                     "build ms", "B/tri structure", "peak MiB", "B/tri peak", "B/tri peak, slope"], rows)


def ratio_table(cells, plan):
    """Embree -r 3 frame time over the fastest CPU row's, per scene and kind; the spread over rounds."""
    rows, verdicts = [], []
    for label, _, _, _ in plan.scenes:
        tris = scene_triangles(cells, label)
        for kind in plan.kinds:
            name, cpu = fastest(cells, label, kind, "cpu", plan.rows)
            emb = cells.get((label, "embree", "embree", kind))
            if cpu is None or emb is None or not emb.frame_ms:
                cpus = [cells.get((label, n, r, kind)) for n, r in plan.rows if r == "cpu"]
                cpu_states = sorted({c.status() if c else "not run" for c in cpus}) or ["no CPU row"]
                why = f"CPU rows: {', '.join(cpu_states)}" if cpu is None else "Embree: not run" if emb is None \
                    else f"Embree: {emb.status()}"
                rows.append([label, num(tris) if tris else "–", kind, name or "–", num(cpu.frame_ms if cpu else None, 3),
                             num(emb.frame_ms if emb else None, 3), f"– ({why})", "–", "–"])
                continue
            best = emb.frame_ms / cpu.frame_ms
            per_round = [emb.frame_ms_by_round[k] / cpu.frame_ms_by_round[k]
                         for k in sorted(emb.frame_ms_by_round) if k in cpu.frame_ms_by_round]
            spread = f"{min(per_round):.2f}–{max(per_round):.2f} ({len(per_round)})" if per_round else "–"
            holds = best >= GOAL
            verdicts.append((label, kind, holds, best))
            rows.append([label, num(tris) if tris else "–", kind, name, num(cpu.frame_ms, 3), num(emb.frame_ms, 3),
                         f"{best:.2f}", spread, "**yes**" if holds else "no"])
    table = md_table(["scene", "triangles", "ray kind", "fastest CPU row", "its frame ms", "Embree -r 3 frame ms",
                      "Embree / CPU row", "per round: min–max (rounds)", f"≥ {GOAL}"], rows)
    return table, verdicts


def goal_summary(verdicts):
    """One paragraph: issue 36's "Done when" cells, met or short, and those this run did not measure."""
    labels = [f"spheres-{tri_label(n)}" for n in GOAL_SPHERES] + ["dragon"] + GOAL_SCENES
    measured = {(label, kind): (holds, best) for label, kind, holds, best in verdicts}
    wanted = [(label, kind) for label in labels for kind in GOAL_KINDS]
    found = [(w, measured[w]) for w in wanted if w in measured]
    short = [f"{label} {kind} {best:.2f}" for (label, kind), (holds, best) in found if not holds]
    missing = [f"{label} {kind}" for label, kind in wanted if (label, kind) not in measured]
    return (f"**Issue 36's goal cells** ({', '.join(labels)}; {' and '.join(GOAL_KINDS)}): met in "
            f"{sum(1 for _, (holds, _) in found if holds)} of the {len(found)} measured"
            + (f"; short of {GOAL}: {'; '.join(short)}" if short else "")
            + (f"; not measured in this run: {', '.join(missing)}" if missing else "") + ".")


def stream_table(cells, plan):
    rows = []
    for label, _, _, _ in plan.scenes:
        for kind in plan.kinds:
            cname, cpu = fastest(cells, label, kind, "cpu", plan.rows)
            sname, st = fastest(cells, label, kind, "gpu", plan.rows)
            if cpu is None and st is None:
                continue
            rows.append([label, kind, f"{sname or '–'} {num(st.mrays if st else None, 2)}",
                         f"{cname or '–'} {num(cpu.mrays if cpu else None, 2)}",
                         num(cpu.frame_ms / st.frame_ms if cpu and st else None, 2)])
    return md_table(["scene", "ray kind", "fastest stream row, Mrays/s", "fastest CPU row, Mrays/s",
                     "stream / CPU (frame time)"], rows)


def tool_best(recs, key="mrays_per_s"):
    vals = [r["result"].get(key) for r in recs if r.get("status") == "ok" and r["result"].get(key)]
    return max(vals) if vals else None


def bare_table(cells, tools, plan):
    rows = []
    for label, _, _, _ in plan.scenes:
        one, packets = tools.get((label, "bare-embree-1"), []), tools.get((label, "bare-embree-packets"), [])
        if not one and not packets:
            continue
        b1, bp = tool_best(one), tool_best(packets)
        _, cpu = fastest(cells, label, "primary", "cpu", plan.rows)
        name, _ = fastest(cells, label, "primary", "cpu", plan.rows)
        r3 = cells.get((label, "embree", "embree", "primary"))
        tris = next((r["result"].get("triangles") for r in one + packets if r.get("status") == "ok"
                     and r["result"].get("triangles")), None) or scene_triangles(cells, label)
        peaks = [r["peak_rss_bytes"] for r in one if r.get("status") == "ok" and r.get("peak_rss_bytes")]
        peak_bpt = median(peaks) / tris if peaks and tris else None
        cm = cpu.mrays if cpu else None
        rows.append([label, num(tris) if tris else "–", num(b1, 2), num(bp, 2), num(r3.mrays if r3 else None, 2),
                     f"{name or '–'} {num(cm, 2)}", num(cm / b1 if cm and b1 else None, 2),
                     num(cm / bp if cm and bp else None, 2), num(peak_bpt, 1)])
    return rows


def roofline_table(cells, tools, plan):
    """Per scene, kind and CPU row: bytes per ray as the traversal reads them, their rate against the triad's;
    None when no bandwidth was measured."""
    triad = [r["result"].get("triad_gb_per_s") for r in tools.get((MACHINE, "peak"), [])
             if r.get("status") == "ok" and r["result"].get("triad_gb_per_s")]
    if not triad:
        return None, None
    bandwidth = max(triad)
    rows = []
    for label, _, _, _ in plan.scenes:
        for kind in plan.kinds:
            for name, renderer in plan.rows:
                c = cells.get((label, name, renderer, kind))
                if renderer != "cpu" or c is None or not c.ok:
                    continue
                best = min(c.ok, key=lambda r: r["result"].get("frame_ms") or float("inf"))["result"]
                nodes, tris = best.get("node_tests_per_ray"), best.get("triangle_tests_per_ray")
                node_bytes, tri_bytes = field(best, "node_test_bytes"), field(best, "triangle_test_bytes")
                if nodes is None or tris is None or not node_bytes or not tri_bytes:
                    continue
                per_ray = nodes * node_bytes + tris * tri_bytes
                gbs = per_ray * best["mrays_per_s"] / 1e3
                rows.append([label, kind, name, num(best["mrays_per_s"], 2), num(nodes, 2), num(tris, 2),
                             num(per_ray, 0), num(c.structure_bytes / 2**20 if c.structure_bytes else None, 1),
                             num(gbs, 1), f"{100 * gbs / bandwidth:.0f} %"])
    table = md_table(["scene", "ray kind", "row", "Mrays/s", "node tests / ray", "triangle tests / ray",
                      "bytes / ray", "structure MiB", "GB/s asked", "of triad"], rows) if rows else None
    return table, bandwidth


KIND_PATHS = ["bvh8-packet", "bvh8", "embree-1", "embree-packets"]


def kinds_table(tools, plan):
    rows = []
    for label, _, _, _ in plan.scenes:
        recs = [r for r in tools.get((label, "ray-kinds"), []) if r.get("status") == "ok"]
        if not recs:
            continue
        by_kind = {}
        for r in recs:
            for line in r["result"]:
                by_kind.setdefault(line.get("kind"), []).append(line)
        for kind, lines in by_kind.items():
            ms = {p: min((l.get("ms", {}).get(p) for l in lines if l.get("ms", {}).get(p)), default=None)
                  for p in KIND_PATHS}
            rows.append([label, kind, num(lines[0].get("rays"))] + [num(ms[p], 2) for p in KIND_PATHS] +
                        [num(ms["embree-packets"] / ms["bvh8-packet"] if ms["embree-packets"] and ms["bvh8-packet"]
                             else None, 2)])
    return rows


def plot(out_dir, cells, plan):
    """The log-log plots; [(title, path)] ([] without matplotlib)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.lines import Line2D
        from matplotlib.ticker import NullFormatter
    except ImportError:
        return []
    (out_dir / "plots").mkdir(exist_ok=True)
    spheres = [label for label, _, requested, _ in plan.scenes if requested]
    real = [label for label, _, requested, _ in plan.scenes if not requested]
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    marks = ["s", "^", "D", "v", "P", "X"]
    paths = []

    def points(name, renderer, kind, value, labels):
        pts = []
        for label in labels:
            c = cells.get((label, name, renderer, kind))
            v = value(c) if c and c.ok else None
            if v and v > 0 and c.triangles:
                pts.append((c.triangles, v))
        return pts

    def draw(ax, kind, value, ylabel, title):
        drawn = False
        for i, (name, renderer) in enumerate(plan.rows):
            colour = colours[i % len(colours)]
            pts = points(name, renderer, kind, value, spheres)
            if pts:
                ax.plot(*zip(*pts), marker="o", color=colour)
                drawn = True
            for j, label in enumerate(real):
                rp = points(name, renderer, kind, value, [label])
                if rp:
                    ax.plot(*zip(*rp), linestyle="none", marker=marks[j % len(marks)], color=colour,
                            markerfacecolor="none", markersize=8)
                    drawn = True
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())  # a narrow range would label every minor tick
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("triangles")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="major", linewidth=0.4)
        ax.grid(True, which="minor", linewidth=0.2)
        return drawn

    def save(fig, name, title):
        handles = [Line2D([], [], color=colours[i % len(colours)], marker="o", label=f"{n} ({RENDERER_TITLES[r]})")
                   for i, (n, r) in enumerate(plan.rows)]
        handles += [Line2D([], [], color="grey", linestyle="none", marker=marks[j % len(marks)],
                           markerfacecolor="none", label=label) for j, label in enumerate(real)]
        fig.legend(handles=handles, loc="lower center", ncol=min(len(handles), 6), fontsize=7, frameon=False)
        fig.tight_layout(rect=(0, 0.1 if len(handles) <= 6 else 0.15, 1, 1))
        fig.savefig(out_dir / "plots" / name, dpi=90)
        paths.append((title, f"plots/{name}"))

    fig, axes = plt.subplots(1, len(plan.kinds), figsize=(4.4 * len(plan.kinds), 4.2), squeeze=False)
    drawn = False
    for ax, kind in zip(axes[0], plan.kinds):
        drawn |= draw(ax, kind, lambda c: c.mrays, "Mrays/s (best round)", kind)
    if drawn:
        save(fig, "mrays.png", "Mrays/s against triangles, per ray kind (spheres: lines; real scenes: hollow markers)")
    plt.close(fig)

    fig, axes = plt.subplots(1, 3, figsize=(13.2, 4.2), squeeze=False)
    drawn = draw(axes[0][0], "primary", lambda c: c.structure_bpt, "bytes / triangle",
                 "structure (structure_bytes, else floats × 4)")
    drawn |= draw(axes[0][1], "primary", lambda c: c.peak_bpt, "bytes / triangle", "peak resident memory / triangles")
    drawn |= draw(axes[0][2], "primary", lambda c: c.slope, "Δ bytes / Δ triangles",
                  "peak memory, slope from the previous size")
    if drawn:
        save(fig, "bytes_per_triangle.png", "bytes per triangle against triangles (the primary-ray runs)")
    plt.close(fig)

    fig, axes = plt.subplots(1, 1, figsize=(5.5, 4.4), squeeze=False)
    if draw(axes[0][0], "primary", lambda c: c.build_ms, "build ms (best round)", "build time"):
        save(fig, "build_ms.png", "build ms against triangles")
    plt.close(fig)
    return paths


def frames_run(records):
    """Per renderer, the -m its runs were made with, as the records say ("2, 10" if they differ): a
    report rewritten from older records (--report-only) then states what was measured."""
    seen = {renderer: set() for renderer in RENDERER_IDS}
    for _, record in records:
        args = record.get("args") or []
        if record.get("renderer") in seen and "-m" in args[:-1]:
            seen[record["renderer"]].add(int(args[args.index("-m") + 1]))
    return {renderer: ", ".join(str(v) for v in sorted(values)) or "?" for renderer, values in seen.items()}


def write_report(out_dir, results, records, plan):
    cells, tools = collect(records, plan)
    p, m = results["parameters"], results["machine"]
    frames = frames_run(records)
    notes = []
    lines = [
        "# Scaling: the fast rows from 10⁵ to 10⁸ triangles (issue 36)", "",
        f"Generated by `{results['command']}` on {results['generated_at']} "
        f"({results['runs_ok']} runs ok, {results['runs_refused']} refused by the memory check, "
        f"{results['runs_failed']} failed, {results['runs_executed']} executed by this invocation, "
        f"{results['wall_s']:.0f} s). Machine: {m.get('cpu')}, {m.get('cores')} cores, {m.get('memory_gib')} GiB; "
        f"GL: {m.get('gl_renderer')}; commit {(m.get('git_commit') or '?')[:10]}"
        f"{' (with local changes)' if m.get('git_dirty') else ''}, {m.get('binary')} built "
        f"{m.get('binary_mtime')}.", "",
        f"{p['size']}² pixels, `--threads {THREADS}`, each run the minimum of `-m {frames['cpu']}` frames on the CPU "
        f"renderers (`-r 1`, `-r 3`) and of `-m {frames['gpu']}` on the stream path; "
        f"{p['rounds']} round(s): per scene every row and ray kind runs once per round, the rows' order rotated "
        "each round, so that a busy minute hits all rows alike. Mrays/s (best) is the best round's, frame ms "
        "the least over the rounds, the ratios are taken within this run. Stream rows (`-r 2`) at passtrace's "
        "default `-l 0` (one pass per bounce). Timings on a shared machine vary by ±20–50 % between runs: "
        "compare the ratios.", "",
        f"Scenes: `-s spheres --triangles N` for N in {', '.join(num(n) for n in p['triangles'])} (at least N "
        "triangles: the table gives the count built), and the named scenes "
        f"{', '.join(p['named_scenes']) or 'none (--no-real-scenes or --scenes)'}. Named scenes skipped (passtrace "
        f"did not find them: --scenes-dir, $PASSTRACE_SCENES_DIR, ../shared/scenes/real; or kitchen and robots "
        f"without the BART scenes): {', '.join(results['skipped']) or 'none'}. Rows missing from this build: "
        f"{', '.join(results['missing']) or 'none'} (no row featured on that renderer).", "",
        "Columns: B/tri structure is `structure_bytes` (nodes and references as the traversal stores them; "
        "Embree reports none) over the triangles; † where a row reports no `structure_bytes` (0), its "
        "`accel_floats_per_triangle` × 4 instead (the thesis's Table 3 accounting: nodes and lists, the "
        "triangles left out), so not the same measure; peak MiB is the passtrace process's peak resident memory "
        "(ru_maxrss from os.wait4, median over the rounds), everything included: the scene, the structure, "
        "the image and ray buffers, the process and the GL; B/tri peak is that over the triangles, and the slope "
        "is Δ peak / Δ triangles between a sphere size and the previous one, which leaves the constant part out "
        "— the honest bytes per triangle. \"does not fit\" is passtrace's memory check refusing the run before "
        "building anything (its line is in the notes), not a failure.", "",
    ]
    builds, scene_builds = {}, {}
    for meta, rec in records:
        if rec.get("binary_mtime") and not rec.get("not_rerun"):
            what = "passtrace" if "tool" not in meta else meta["tool_path"]
            builds.setdefault(what, set()).add(rec["binary_mtime"])
            if meta["scene"] != MACHINE:
                scene_builds.setdefault((meta["scene"], what), set()).add(rec["binary_mtime"])
    changed = {w: sorted(s) for w, s in builds.items() if len(s) > 1}
    if changed:
        mixed = sorted({s for (s, _), b in scene_builds.items() if len(b) > 1},
                       key=[label for label, *_ in plan.scenes].index)
        lines += ["**The programs were rebuilt during these runs**: " +
                  "; ".join(f"{w} built at {', '.join(s)}" for w, s in sorted(changed.items())) +
                  ". The rounds of a scene run back to back, so its ratios come from one build except on " +
                  f"{', '.join(mixed) or 'none'}, whose runs mix builds; between scenes the builds may differ. "
                  "Rerun with `--force` on a build that is not changing for runs of one build.", ""]
    ratio, verdicts = ratio_table(cells, plan)
    met = sum(1 for _, _, h, _ in verdicts if h)
    lines += [
        "## Embree `-r 3` / the fastest CPU row (issue 36's goal: ≥ 1.2)", "",
        "Frame time of Embree through the CPU renderer (`-r 3`, its packets) over that of the fastest CPU row "
        f"(the one of {' and '.join(n for n, r in plan.rows if r == 'cpu') or 'the CPU rows'} with the least "
        "frame time on that scene and ray kind), each the least "
        "over the rounds; per round, the same ratio within each round. Above 1: the CPU row is faster. "
        f"Met in {met} of {len(verdicts)} scene/ray-kind pairs.", "",
        ratio, "",
        goal_summary(verdicts), "",
    ]
    plots = plot(out_dir, cells, plan)
    if plots:
        lines += ["## Plots", ""]
        for title, path in plots:
            lines += [f"![{title}]({path})", ""]
    for kind in plan.kinds:
        lines += [f"## {KIND_TITLES[kind][0].upper() + KIND_TITLES[kind][1:]}", "", kind_table(cells, plan, kind, notes),
                  ""]
    lines += ["## The fastest stream row against the fastest CPU row", "", stream_table(cells, plan), ""]
    lines += ["## Bare Embree", ""]
    bare = bare_table(cells, tools, plan)
    why = []
    if plan.tools_missing:
        why.append(f"not built here: {', '.join(plan.tools_missing)} (cmake --build build --target "
                   f"{' '.join(plan.tools_missing)})")
    lines += [
        "`build/tests/measure/measure_bare_embree SCENE SIZE 2 REPEATS [--packet]`: rtcIntersect1 (and "
        "rtcIntersect16 packets) over the CPU renderer's primary rays on 2 threads, no shading and no frame "
        "buffer, best of the rounds; the CPU row's Mrays/s is its primary-ray frame through the renderer (ray "
        "generation and shading included), so the ratio understates it. Peak B/tri is the bare-Embree "
        "process's peak resident memory (scene included) over the triangles."
        + (" " + "; ".join(why)[0].upper() + "; ".join(why)[1:] + "." if why else ""), "",
    ]
    if bare:
        lines += [md_table(["scene", "triangles", "bare rtcIntersect1 Mrays/s", "bare packets Mrays/s",
                            "-r 3 Mrays/s", "fastest CPU row Mrays/s", "CPU / bare 1", "CPU / bare packets",
                            "bare Embree B/tri peak"], bare), ""]
    kinds_rows = kinds_table(tools, plan)
    if kinds_rows:
        lines += ["### Traversal alone, one thread", "",
                  f"`build/tests/measure/measure_ray_kinds SCENE SIZE {TOOL_REPEATS} {AO_SAMPLES}`: the CPU "
                  "renderer's primary, shadow and AO rays traced with no renderer around them, ms for all rays of "
                  "the kind, least over the repeats and rounds.", "",
                  md_table(["scene", "kind", "rays"] + [f"{x} ms" for x in KIND_PATHS] +
                           ["embree-packets / bvh8-packet"], kinds_rows), ""]
    roofline, bandwidth = roofline_table(cells, tools, plan)
    lines += ["## Roofline: bytes per ray against bandwidth", ""]
    if roofline:
        lines += [
            f"The CPU rows' traffic if every ray read its own nodes and triangles from memory: bytes per ray are "
            "node tests × `structure.node_test_bytes` + triangle tests × `triangle_test_bytes` (--json; a node "
            "test of bvh8 is a visit of an 8-wide node), GB/s asked is that × the row's best Mrays/s, against "
            f"this machine's triad bandwidth on {THREADS} threads, **{bandwidth:.1f} GB/s** "
            f"(`build/tests/measure/measure_machine_peak {THREADS}`, best of the rounds). It is an upper bound: "
            "the rays of a packet share its visits, and a tree smaller than the last-level cache is read from "
            "there. Near or above 100 % a row could be waiting on memory; far below, on the latency of the "
            "misses it does take, or on its own work. Rows that state no bytes per test are left out.", "",
            roofline, ""]
    else:
        lines += ["Not measured: no bandwidth (measure_machine_peak not built or failed) or no row stating its "
                  "bytes per test.", ""]
    if notes:
        lines += ["## Notes: runs that did not fit or failed", ""]
        lines += [f"{i + 1}. {n}" for i, n in enumerate(notes)] + [""]
    lines += bench_report.failed_runs_section(records)
    lines += ["## Commands", "", "Each run's command line and peak memory are in `results.json` "
              "(`runs[].command`, `runs[].peak_rss_bytes`)."]
    write_atomically(out_dir / "REPORT.md", "\n".join(lines) + "\n")


# ---------------------------------------------------------------- the driver

def real_scenes_dir(args):
    if args.scenes_dir:
        return pathlib.Path(args.scenes_dir).resolve()
    if os.environ.get("PASSTRACE_SCENES_DIR"):
        return pathlib.Path(os.environ["PASSTRACE_SCENES_DIR"])
    d = pathlib.Path(__file__).resolve().parent.parent.parent / "shared" / "scenes" / "real"
    return d if d.is_dir() else None


def main(args, binary, registry, out, bart, bart_ok, bench, command):
    """Runs the plan in rounds (skipping runs that finished earlier) and writes the report."""
    sizes = parse_triangles(args.triangles_list) if args.triangles_list else list(DEFAULT_TRIANGLES)
    named_scenes = REAL_SCENES + GOAL_SCENES
    chosen = args.scenes.split(",") if args.scenes else ["spheres"] + named_scenes
    unknown = [s for s in chosen if s not in ["spheres"] + named_scenes]
    if unknown:
        raise SystemExit(f"bench --scale: unknown scene {unknown[0]!r} (expected spheres, {', '.join(named_scenes)})")
    if "spheres" not in chosen:
        sizes = []
    real = [] if args.no_real_scenes else [s for s in named_scenes if s in chosen]
    help_text = subprocess.run([str(binary), "--help"], capture_output=True, text=True,
                               env=bench_ranks.child_env()).stdout
    kinds = [k for k in KINDS if k != "ao" or "--shading" in help_text]
    if "ao" not in kinds:
        bench.log("bench --scale: this passtrace has no --shading: no AO rays")
    size, rounds = args.size or 512, args.repeats or 3
    plan = Plan(registry, binary, sizes, real, size, rounds, kinds, bart_ok)
    for s in plan.skipped:
        bench.log(f"bench --scale: skipping {s}: " + ("no BART scenes (give --bart-dir or $PASSTRACE_BART_DIR)"
                                                      if s in BART_SCENES else
                                                      "passtrace did not find the real scenes (give --scenes-dir or "
                                                      "$PASSTRACE_SCENES_DIR, or put them in ../shared/scenes/real)"))
    for r in plan.missing:
        bench.log(f"bench --scale: no {r} row: this passtrace's registry features none (`passtrace --list --json`)")
    if plan.tools_missing:
        bench.log(f"bench --scale: no bare Embree: {', '.join(plan.tools_missing)} not built")
    runner = Runner(bench, binary, out, args.timeout or 1800, args.force, real_scenes_dir(args), bart)
    bench.log(f"bench --scale: {len(plan.jobs)} runs ({len(plan.scenes)} scenes, {len(plan.rows)} rows, "
              f"{len(kinds)} ray kinds, {rounds} rounds) into {bench.shown_path(out)}; {size}x{size}")
    to_run = 0 if args.report_only else sum(
        1 for _, _, run_args, key in plan.jobs if runner.finished(runner.runs_dir / f"{key}.json", run_args) is None)
    records, wall_s = bench.run_jobs(plan.jobs, runner, args.report_only, "--scale")
    parameters = {"size": size, "rounds": rounds, "frames_per_run": FRAMES, "threads": THREADS,
                  "triangles": sizes, "named_scenes": [s for s in real if s not in plan.skipped],
                  "rows": [f"{n} {RENDERER_TITLES[r]}" for n, r in plan.rows], "kinds": kinds,
                  "ao_samples": AO_SAMPLES, "timeout_s": runner.timeout}
    results = bench.section_results(command, wall_s, parameters, plan.skipped, plan.missing, records, binary)
    results["runs_refused"] = sum(1 for _, r in records if r.get("status") == "does-not-fit")
    results["runs_executed"] = to_run  # the jobs this invocation found unfinished (a rerun: 0)
    results["processes_started"] = runner.executed  # on this rank (refusals copied from an earlier round: none)
    results["tools_missing"] = plan.tools_missing
    if args.report_only:  # the invocation that ran them: its command, time, machine and counts (as --quick does)
        previous = bench.read_json(out / "results.json") or {}
        for key in ("command", "generated_at", "wall_s", "machine", "runs_executed", "processes_started"):
            if key in previous:
                results[key] = previous[key]
    bench.write_json_atomic(out / "results.json", results)
    write_report(out, results, records, plan)
    bench.log(f"bench --scale: {results['runs_ok']} ok, {results['runs_refused']} do not fit, "
              f"{results['runs_failed']} failed, {runner.executed} executed; report: "
              f"{bench.shown_path(out / 'REPORT.md')}")
    return 0 if results["runs_failed"] == 0 else 1
