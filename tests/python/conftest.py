"""Shared fixtures of the Python module's tests (ctest label `python`).

The module is imported from PYTHONPATH (ctest sets it to build/python); the
program for the command-line comparisons is $PASSTRACE_BINARY. The scene is
a small deterministic mesh written to an OBJ file, so that the module and the
program load the very same triangles.
"""
import json
import os
import subprocess

import numpy as np
import pytest

import passtrace

NO_HIT = np.uint32(4294967295)
# The structures' rows and the renderers each runs on, as the module names them.
ROWS = [(row["name"], renderer) for row in passtrace.structures() for renderer in row["renderers"]
        if renderer in ("cpu", "gpu", "embree")]


def row_id(row):
    return f"{row[0]}-{row[1]}"


def bumpy_sphere_with_floor(rings=20, segments=36, clutter=60, seed=7):
    """A perturbed UV sphere over a floor quad, plus a few random triangles:
    about 1,500 triangles with shared edges, thin slivers and empty space."""
    rng = np.random.default_rng(seed)
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    radius = 1.0 + 0.08 * np.sin(5 * t) * np.cos(3 * p)
    vertices = np.stack([radius * np.sin(t) * np.cos(p), radius * np.cos(t), radius * np.sin(t) * np.sin(p)], -1)
    vertices = vertices.reshape(-1, 3)
    faces = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            faces += [[a, c, b], [b, c, d]]
    faces = np.array(faces)
    floor = np.array([[-2, -1.2, -2], [2, -1.2, -2], [2, -1.2, 2], [-2, -1.2, 2]], float)
    base = len(vertices)
    vertices = np.vstack([vertices, floor])
    faces = np.vstack([faces, [[base, base + 2, base + 1], [base, base + 3, base + 2]]])
    centres = rng.uniform(-1.6, 1.6, (clutter, 3))
    corners = centres[:, None, :] + rng.normal(0.0, 0.3, (clutter, 3, 3))
    base = len(vertices)
    vertices = np.vstack([vertices, corners.reshape(-1, 3)])
    faces = np.vstack([faces, base + np.arange(3 * clutter).reshape(-1, 3)])
    return vertices.astype(np.float32), faces


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            # repr of the float32 as a double: read back as exactly that float32.
            f.write("v %r %r %r\n" % (float(v[0]), float(v[1]), float(v[2])))
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


@pytest.fixture(scope="session")
def scene_file(tmp_path_factory):
    vertices, faces = bumpy_sphere_with_floor()
    path = tmp_path_factory.mktemp("scene") / "bumpy.obj"
    write_obj(path, vertices, faces)
    return str(path)


@pytest.fixture(scope="session")
def scene(scene_file):
    return passtrace.load_scene(scene_file)


@pytest.fixture(scope="session")
def brute(scene):
    return passtrace.brute_force(scene)


@pytest.fixture(scope="session")
def random_rays(scene):
    """3,000 rays from points in and around the scene (inside the sphere too),
    in random directions: about half of them hit something."""
    rng = np.random.default_rng(11)
    origins = rng.uniform(-2.0, 2.0, (3000, 3)).astype(np.float32)
    directions = rng.normal(size=(3000, 3)).astype(np.float32)
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return origins, directions


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("PASSTRACE_BINARY")
    if not path or not os.path.exists(path):
        pytest.skip("PASSTRACE_BINARY is not set to the passtrace program (ctest sets it)")
    return path


def run_program(binary, *args):
    """Runs passtrace; returns its --json report when one was asked for."""
    done = subprocess.run([binary, "-q", *args], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done


def program_json(binary, tmp_path, *args):
    report = tmp_path / "run.json"
    run_program(binary, *args, "--json", str(report))
    return json.loads(report.read_text())


def assert_hits_match(got, expected, allowed_mismatches=0, what=""):
    """Equal ids with t within 1e-5 relative, or a tie (two triangles met at
    the same t: a shared edge or vertex); at most `allowed_mismatches` other
    rays may differ (the GPU's own rounding of edge-grazing rays)."""
    same = got["id"] == expected["id"]
    found = expected["id"] != NO_HIT
    with np.errstate(invalid="ignore"):  # inf - inf where both miss
        t_close = np.abs(got["t"] - expected["t"]) <= 1e-5 * np.where(found, expected["t"], 1.0)
    assert np.all(np.isinf(got["t"][same & ~found])), what + ": a miss with a finite t"
    assert np.all(t_close[same & found]), what + ": same triangle, different t"
    tie = ~same & found & (got["id"] != NO_HIT) & t_close
    mismatches = np.flatnonzero(~same & ~tie)
    assert len(mismatches) <= allowed_mismatches, (
        f"{what}: {len(mismatches)} rays differ from the reference, e.g. ray {mismatches[:5]}: "
        f"got id {got['id'][mismatches[:5]]} t {got['t'][mismatches[:5]]}, "
        f"expected id {expected['id'][mismatches[:5]]} t {expected['t'][mismatches[:5]]}")
