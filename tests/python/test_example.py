"""The example a researcher would write (examples/steps_per_structure.py) runs
and writes its plot: every CPU structure traced, one line each, and a PNG."""
import os
import subprocess
import sys

import passtrace

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "steps_per_structure.py")


def test_example_traces_every_cpu_structure_and_plots(tmp_path):
    plot = tmp_path / "steps.png"
    done = subprocess.run([sys.executable, EXAMPLE, "-s", "cornell", "-w", "16", "-o", str(plot)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    cpu_rows = [r["name"] for r in passtrace.structures() if "cpu" in r["renderers"]]
    printed = [line.split()[0] for line in done.stdout.splitlines() if "steps per ray" in line]
    assert printed == cpu_rows
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and plot.stat().st_size > 10000
