#!/usr/bin/env python3
"""The benchmark matrix over MPI ranks (scripts/bench_ranks.py): `bench.py --tiny`
under `mpirun -np 2` runs the same runs as one process, each exactly once,
both ranks taking some, every record naming its host and rank, with the same
non-timing results (passtrace's children not joining the job: each reports one
rank), and the report naming the hosts; a rerun runs nothing again.
Exits 77 (skipped) without mpirun or mpi4py. No timing is asserted.

    python3 tests/mpi/bench_ranks_test.py --binary build/passtrace --work /tmp/bench_ranks
"""
import argparse
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

REPO = pathlib.Path(__file__).resolve().parents[2]
BENCH = REPO / "scripts" / "bench.py"
# Results of a run that do not depend on its timing or on the rank that ran it.
SAME_FIELDS = ("rays", "steps", "triangle_tests", "passes", "triangles", "accel_nodes", "accel_references",
               "max_steps_per_ray")
LIMIT_S = 120  # one bench.py --tiny takes a few seconds

sys.path.insert(0, str(REPO / "tests"))
from script_checks import any_failed, check, summary  # noqa: E402


def python_with_mpi4py():
    """This interpreter, or Debian's (bench.py reruns itself there for matplotlib), if it has mpi4py."""
    for python in (sys.executable, "/usr/bin/python3"):
        if os.access(python, os.X_OK) and subprocess.run([python, "-c", "import mpi4py"],
                                                         capture_output=True).returncode == 0:
            return python
    return None


def run(cmd, env):
    """(exit status, stderr) of CMD; on the time limit mpirun is asked to end its job (SIGTERM) first."""
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        _, err = proc.communicate(timeout=LIMIT_S)
    except subprocess.TimeoutExpired:
        proc.terminate()
        try:
            _, err = proc.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            _, err = proc.communicate()
        err += f"\n(killed after {LIMIT_S} s)"
    return proc.returncode, err


def records(out):
    return {p.stem: json.loads(p.read_text()) for p in sorted((out / "runs").glob("*.json"))}


def counts(out):
    """(ok, failed) over the runs and heat maps of results.json."""
    try:
        results = json.loads((out / "results.json").read_text())
    except (OSError, ValueError):
        return None, {}
    runs = results.get("runs", []) + results.get("heatmaps", [])
    return (sum(r.get("status") == "ok" for r in runs), sum(r.get("status") == "error" for r in runs)), results


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--binary", default=str(REPO / "build" / "passtrace"))
    parser.add_argument("--work", required=True, help="a folder for the two runs' outputs (one/, two/)")
    args = parser.parse_args()
    mpirun = shutil.which("mpirun")
    python = python_with_mpi4py()
    if not mpirun or not python:
        print(f"skip: {'mpirun' if not mpirun else 'mpi4py'} is missing (apt-get install openmpi-bin python3-mpi4py)")
        return 77

    work = pathlib.Path(args.work).resolve()
    one, two = work / "one", work / "two"
    for out in (one, two):
        shutil.rmtree(out, ignore_errors=True)  # a fresh matrix each time: the two-rank run must run every job
    work.mkdir(parents=True, exist_ok=True)
    bench = [python, str(BENCH), "--tiny", "--binary", str(pathlib.Path(args.binary).resolve())]
    env = dict(os.environ)
    if os.geteuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    two_ranks = [mpirun, "-q", "-np", "2"] + bench + ["--out", str(two)]

    status, err = run(bench + ["--out", str(one)], env)
    if not check(status == 0, f"bench.py --tiny in one process exits 0 (got {status})"):
        print(err[-3000:])
    status, err = run(two_ranks, env)
    if not check(status == 0, f"bench.py --tiny under mpirun -np 2 exits 0 (got {status})"):
        print(err[-3000:])

    single, ranked = records(one), records(two)
    check(bool(single) and set(single) == set(ranked),
          f"the same run keys in runs/ ({sorted(single)} against {sorted(ranked)})")
    (n_one, _), (n_two, results) = counts(one), counts(two)
    check(n_one is not None and n_one == n_two, f"the same (ok, failed) counts in results.json ({n_one}, {n_two})")
    started = re.findall(r"^\[(\d+)/\d+\] .* on rank (\d+) \(", err, re.M)
    check(bool(started) and sorted(int(i) for i, _ in started) == list(range(1, len(ranked) + 1)),
          f"each job handed out exactly once ({started})")
    check(all(r.get("host") and isinstance(r.get("rank"), int) for r in ranked.values()),
          "every record of the two-rank run names its host and rank")
    check({r.get("rank") for r in ranked.values()} == {0, 1},
          f"both ranks ran jobs ({ {k: r.get('rank') for k, r in ranked.items()} })")
    check(results.get("ranks") == 2 and sum(results.get("hosts", {}).values()) == len(ranked),
          f"results.json has the ranks and the runs per host ({results.get('ranks')}, {results.get('hosts')})")
    report = (two / "REPORT.md").read_text() if (two / "REPORT.md").exists() else ""
    check("host / rank" in report and "one rank per node" in report,
          "REPORT.md names each run's host and recommends one rank per node")
    for key in sorted(set(single) & set(ranked)):
        a, b = single[key].get("result") or {}, ranked[key].get("result") or {}
        differ = [f for f in SAME_FIELDS if a.get(f) != b.get(f)]
        check(bool(a) and not differ, f"{key}: the same {', '.join(SAME_FIELDS)} in both ({differ} differ)")
        check(b.get("ranks", 1) == 1, f"{key}: passtrace ran as one process, not as a rank of the job")

    # A rerun skips every finished run: no record is written again (finished_at and all).
    if any_failed():
        print("skip: the rerun (the two-rank run above failed)")
    else:
        before = {p.name: (p.stat().st_mtime_ns, p.read_text()) for p in (two / "runs").glob("*.json")}
        status, err = run(two_ranks, env)
        check(status == 0, f"the two-rank rerun exits 0 (got {status})")
        after = {p.name: (p.stat().st_mtime_ns, p.read_text()) for p in (two / "runs").glob("*.json")}
        check(bool(before) and before == after, "the rerun runs nothing again (every record unchanged)")
        check(err.count(": skip (finished earlier") == len(before), f"the rerun skips all {len(before)} runs")

    return summary()


if __name__ == "__main__":
    sys.exit(main())
