"""The speed report's section on the stream path's two stages (issue 38).

On this machine: the fastest stream rows in the fragment stage and in the
compute stage (`-r 2 --stage`), primary rays, the rows and stages alternated
in rounds so that the ratios come from one run; the SM probe says what it can
(llvmpipe has no SMs). From the last GPU run committed under
docs/bench-speed/gpu-*/ (scripts/gpu_server/measure.py): the SMs each stage
ran on, measured, and the best rows' rates per GPU and per SM.
"""
import json
import pathlib
import subprocess
import tempfile

import bench_ranks
from passtrace_registry import featured

# The rows the stage comparison runs are those the registry features in
# "stages" (--list --json): the fastest stream rows of the speed report.
STAGES = ("fragment", "compute")
ROUNDS = 3
GPU_DIR = pathlib.Path(__file__).resolve().parent.parent / "docs" / "bench-speed"


def stage_rows(registry):
    """The stream rows the registry features in the stage comparison, in registry order."""
    return [name for name, renderer in featured(registry, "stages") if renderer == "gpu"]


def measure(binary, scene, size, repeats, registry, log):
    """{"runs": {row: {stage: [frame_ms per round]}}, "probe": {...} or None, "errors": [...]}"""
    rows = stage_rows(registry)
    out = {"scene": scene, "size": size, "repeats": repeats, "runs": {r: {s: [] for s in STAGES} for r in rows},
           "errors": []}
    with tempfile.TemporaryDirectory() as tmp:
        report = pathlib.Path(tmp) / "run.json"
        for k in range(ROUNDS):
            log(f"stages, round {k + 1} of {ROUNDS} ...")
            for row in rows:
                for stage in (STAGES if k % 2 == 0 else STAGES[::-1]):  # who goes first alternates
                    cmd = [str(binary), "-r", "2", "-a", row, "-s", scene, "-w", str(size), "-b", "1", "-m",
                           str(repeats), "--stage", stage, "--json", str(report), "-q"]
                    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=900,
                                          env=bench_ranks.child_env())
                    if proc.returncode != 0:
                        out["errors"].append(f"{row} --stage {stage}: {proc.stderr.strip().splitlines()[-1:]}")
                        continue
                    out["runs"][row][stage].append(json.loads(report.read_text())["frame_ms"])
    probe = pathlib.Path(binary).parent / "tests" / "measure" / "measure_sm_probe"
    if probe.exists():
        proc = subprocess.run([str(probe), "64"], capture_output=True, text=True, timeout=120,
                              env=bench_ranks.child_env())
        out["probe"] = json.loads(proc.stdout) if proc.returncode == 0 else {"error": proc.stderr.strip()}
    return out


def last_gpu_run():
    """(folder, sm_probe, runs) of the newest docs/bench-speed/gpu-*/, or None."""
    folders = sorted(GPU_DIR.glob("gpu-*/sm_probe.json"))
    if not folders:
        return None
    folder = folders[-1].parent
    runs = []
    for path in sorted(folder.glob("runs*.jsonl")):
        runs += [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    return folder, json.loads(folders[-1].read_text()), runs


def section(stages, num, md_table):
    """The report's lines."""
    lines = ["## Fragment and compute stages (issue 38)", ""]
    if stages:
        lines += [f"`-r 2 --stage fragment|compute`, {stages['scene']} primary rays (`-b 1`), "
                  f"{stages['size']}², the minimum of `-m {stages['repeats']}` per run and of {ROUNDS} rounds; "
                  "in each round every row runs in both stages back to back, the first stage alternating. "
                  "Goal (on llvmpipe): the compute stage within 10 % of the fragment stage's frame time.", ""]
        rows = []
        for row, by_stage in stages["runs"].items():
            f, c = (min(by_stage[s]) if by_stage[s] else None for s in STAGES)
            rows.append([row, num(f), num(c), num(c / f if f and c else None), "yes" if f and c and c <= 1.1 * f
                         else "no" if f and c else "–"])
        lines += [md_table(["structure", "fragment ms", "compute ms", "compute / fragment", "within 10 %"], rows), ""]
        probe = stages.get("probe") or {}
        if probe.get("shader_thread_group"):
            lines += [f"SMs here (`measure_sm_probe`): fragment {probe['fragment']['sms']}, compute "
                      f"{probe['compute']['sms']} of {probe.get('sm_count')}.", ""]
        else:
            lines += [f"`measure_sm_probe` here: {probe.get('gl_renderer', 'not run')} has no "
                      "`GL_NV_shader_thread_group`; both stages run on the same CPU threads, so per-SM rates "
                      "do not apply.", ""]
        lines += [f"- {e}" for e in stages["errors"]] + ([""] if stages["errors"] else [])
    gpu = last_gpu_run()
    if gpu:
        folder, probe, runs = gpu
        sms = {s: (probe.get(s) or {}).get("sms") for s in STAGES}
        lines += [f"On a GPU ({probe.get('gl_renderer')}, [{folder.name}/]({folder.name}/), "
                  "[GPU.md](GPU.md)): the SMs each stage ran on, measured with `measure_sm_probe` "
                  f"(`gl_SMIDNV`): fragment **{sms['fragment']}**, compute **{sms['compute']}** of the driver's "
                  f"`GL_SM_COUNT_NV` {probe.get('sm_count')}. Rates at 1920×1080, primary rays, per GPU and per "
                  "SM the stage ran on:", ""]
        by = {(r["scene"], r["row"], r["stage"]): r.get("mrays_per_s") for r in runs
              if r.get("mix") == "primary" and "error" not in r}
        rows = []
        # The rows of this run's stage table, else every row of the GPU run.
        shown = list(stages["runs"]) if stages else list(dict.fromkeys(r["row"] for r in runs))
        for scene in dict.fromkeys(r["scene"] for r in runs):
            for row in shown:
                f, c = by.get((scene, row, "fragment")), by.get((scene, row, "compute"))
                if f is None and c is None:
                    continue
                fs = f / sms["fragment"] if f and sms["fragment"] else None
                cs = c / sms["compute"] if c and sms["compute"] else None
                rows.append([scene, row, num(f, 1), num(c, 1), num(fs), num(cs), num(fs / cs if fs and cs else None)])
        lines += [md_table(["scene", "structure", "fragment Mrays/s", "compute Mrays/s", "fragment per SM",
                            "compute per SM", "per SM, fragment / compute"], rows), ""]
    return lines
