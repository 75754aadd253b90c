#!/usr/bin/env python3
"""scripts/memory_models.py end to end at tiny sizes (no memory asserted beyond
"measured"), and its fit on made-up peaks whose model is known."""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

SCRIPTS = pathlib.Path(__file__).resolve().parents[2] / "scripts"
sys.path.insert(0, str(SCRIPTS))
import passtrace_registry  # noqa: E402
from memory_models import fit  # noqa: E402


def check(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def check_fit():
    mib = 2**20
    base = 200 * mib
    # Linear: 100 bytes per triangle at both sizes.
    per, growth = fit(base, (1_000_000, base + 100_000_000), (4_000_000, base + 400_000_000))
    check(abs(per - 100) < 1e-9 and abs(growth - 1) < 1e-9, f"linear fit: {per}, {growth}")
    # Bytes per triangle doubling per 4x: growth 1.5, the large size's bytes.
    per, growth = fit(base, (1_000_000, base + 100_000_000), (4_000_000, base + 800_000_000))
    check(abs(per - 200) < 1e-9 and abs(growth - 1.5) < 1e-9, f"growing fit: {per}, {growth}")
    # Falling bytes per triangle: the small size's, never extrapolated lower.
    per, growth = fit(base, (1_000_000, base + 300_000_000), (4_000_000, base + 800_000_000))
    check(abs(per - 300) < 1e-9 and growth == 1.0, f"falling fit: {per}, {growth}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binary", required=True)
    args = parser.parse_args()
    check_fit()
    # The registry's first row on both the CPU and the stream renderer.
    row = next(a["name"] for a in passtrace_registry.load(args.binary)["accelerators"]
               if {"cpu", "gpu"} <= set(a["renderers"]))
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "models.json"
        proc = subprocess.run([sys.executable, str(SCRIPTS / "memory_models.py"), "--binary", args.binary,
                               "--rows", row, "--sizes", "1000,4000", "--json", str(out)],
                              capture_output=True, text=True, timeout=240)
        check(proc.returncode == 0, f"memory_models.py failed: {proc.stderr.strip()}")
        runs = json.loads(out.read_text())["runs"]
        renderers = {r["renderer"] for r in runs}
        check(renderers == {"cpu", "gpu"}, f"{row} measured on {renderers}")
        check(all(r["peak_bytes"] > 10 * 2**20 and r["triangles"] >= 1000 for r in runs), f"runs: {runs}")
        check(f"{row}: .memory = {{{{" in proc.stdout, f"no registry values printed:\n{proc.stdout}")
        refused = subprocess.run([sys.executable, str(SCRIPTS / "memory_models.py"), "--binary", args.binary,
                                  "--rows", "no-such-row"], capture_output=True, text=True, timeout=60)
        check(refused.returncode != 0 and "no-such-row" in refused.stderr, "an unknown row was not refused")
    print("memory_models.py: fit and end to end passed")


if __name__ == "__main__":
    main()
