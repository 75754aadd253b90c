"""The structure registry as `passtrace --list --json` prints it, for the scripts.

The JSON is one object: `version`, `renderers` [{name, id}], `accelerators`
[{name, renderers, number, description}] and `scenes` [{name, number}].
"""
import json
import subprocess

import bench_ranks


def load(binary):
    """Runs `BINARY --list --json`; exits with one message when it cannot."""
    try:
        proc = subprocess.run([str(binary), "--list", "--json"], capture_output=True, text=True, timeout=60,
                              env=bench_ranks.child_env())
    except OSError as e:
        raise SystemExit(f"{binary} --list --json: {e}")
    if proc.returncode != 0:
        last = (proc.stderr.strip().splitlines() or [f"exit status {proc.returncode}"])[-1]
        raise SystemExit(f"{binary} --list --json failed: {last} (a passtrace from before the structure registry?)")
    try:
        registry = json.loads(proc.stdout)
        ids = {r["name"]: r["id"] for r in registry["renderers"]}
        missing = [r for r in registry["accelerators"] if not {"name", "renderers", "number"} <= r.keys()]
        if missing or not ids:
            raise ValueError("accelerators or renderers incomplete")
    except (ValueError, KeyError, TypeError, AttributeError) as e:
        raise SystemExit(f"{binary} --list --json: not the registry's JSON ({e})")
    return registry


# The real benchmark scenes (scenes/real_scenes.h): passtrace finds them itself
# (--scenes-dir, $PASSTRACE_SCENES_DIR, ../shared/scenes/real) and lists in
# `scenes` those it found; a benchmark skips the others.
REAL_SCENES = ["conference", "sibenik", "sponza", "teapot", "dragon"]


# The BART scenes: they need the BART folder (bench.py's --bart-dir).
BART_SCENES = {"robots", "kitchen"}


def scene_available(registry, label, bart_ok=True):
    """False only for a real scene the binary did not find, or a BART scene without the BART folder."""
    if label in BART_SCENES:
        return bart_ok
    return label not in REAL_SCENES or any(s["name"] == label for s in registry.get("scenes", []))


def numbers(registry, renderer):
    """{name: thesis number} of the structures numbered on `renderer`.

    The JSON gives one number per row, but a number belongs to one structure per
    renderer: on a renderer, the first row (registry order) with a number owns
    it, and later rows with the same number are selected there by name only
    (kd-tree owns 2 on the CPU; kd-restart, also 2, owns it on the GPU).
    """
    owner = {}
    for r in registry["accelerators"]:
        if renderer in r["renderers"] and r["number"] is not None:
            owner.setdefault(r["number"], r["name"])
    return {name: n for n, name in owner.items()}


def structures(registry, renderer, numbered_only=False):
    """Names of the structures that `renderer` implements, in the thesis's order:
    the numbered ones by number, then the others in registry order.
    numbered_only keeps the numbered ones."""
    numbered = sorted(numbers(registry, renderer).items(), key=lambda item: item[1])
    names = [name for name, _ in numbered]
    if not numbered_only:
        names += [r["name"] for r in registry["accelerators"] if renderer in r["renderers"] and r["name"] not in names]
    return names


def renderer_id(registry, renderer):
    """The -r number of a renderer name ('gpu' -> '2')."""
    return str(next(r["id"] for r in registry["renderers"] if r["name"] == renderer))


def check_names(registry, renderer, names):
    """Exits naming the first of `names` that `renderer` does not implement."""
    known = structures(registry, renderer)
    for name in names:
        if name not in known:
            raise SystemExit(f"structure {name!r} is not in passtrace's registry for the {renderer} renderer "
                             f"(it lists {', '.join(known) or 'none'})")


def build_flags(structure, grid_multiplier=None, kd_depth=None):
    """The build flags a structure reads, by family (the JSON lists no parameters):
    -g for the grids (names starting 'grid'), -d for the kd-trees ('kd-')."""
    if structure.startswith("grid") and grid_multiplier is not None:
        return ["-g", f"{grid_multiplier:g}"]
    if structure.startswith("kd-") and kd_depth is not None:
        return ["-d", str(kd_depth)]
    return []


def featured(registry, report):
    """[(name, renderer)] of the rows the benchmark REPORT runs ("scale",
    "stages"): the registry's `featured`, in registry order."""
    return [(a["name"], f["renderer"]) for a in registry["accelerators"] for f in a.get("featured", [])
            if f["report"] == report]
