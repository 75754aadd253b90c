"""Every registry row on each renderer equals brute force (ties aside), through
the module: on random rays, on the camera's rays against the program's own
--hits, occluded() against intersect(), and the per-ray counters against the
program's totals."""
import numpy as np
import pytest

import passtrace
from conftest import NO_HIT, ROWS, assert_hits_match, bumpy_sphere_with_floor, program_json, row_id

# The GPU stream kernels round in GLSL (llvmpipe's), not as the C++ tests do:
# a ray grazing an edge may go either way there.
GPU_ALLOWED = 3


def allowed(renderer, rays):
    return GPU_ALLOWED if renderer == "gpu" else 0


@pytest.fixture(scope="module")
def built(scene):
    cache = {}

    def get(name, renderer):
        if (name, renderer) not in cache:
            cache[(name, renderer)] = passtrace.build(scene, name, renderer)
        return cache[(name, renderer)]
    return get


def test_brute_force_is_a_reference(brute, random_rays):
    """The reference itself against numpy's Moller-Trumbore in double
    precision (at most one ray grazing an edge may round the other way)."""
    origins, directions = random_rays[0][:300], random_rays[1][:300]
    hits = brute.intersect(origins, directions)
    vertices, faces = bumpy_sphere_with_floor()
    tri = vertices[faces].astype(np.float64)
    v0, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    differ = []
    for i in range(len(origins)):
        o, d = origins[i].astype(np.float64), directions[i].astype(np.float64)
        p = np.cross(d, e2)
        det = np.einsum("ij,ij->i", e1, p)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            inv = 1.0 / det
            s = o - v0
            u = np.einsum("ij,ij->i", s, p) * inv
            q = np.cross(s, e1)
            v = (q @ d) * inv
            t = np.einsum("ij,ij->i", e2, q) * inv
            ok = (np.abs(det) > 1e-12) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
        best = np.min(t[ok]) if ok.any() else np.inf
        if np.isinf(best) != (hits["id"][i] == NO_HIT) or (np.isfinite(best) and abs(hits["t"][i] - best) > 1e-4 * best):
            differ.append((i, float(hits["t"][i]), best))
    assert (hits["id"] != NO_HIT).sum() > 100
    assert len(differ) <= 1, differ


@pytest.mark.parametrize("row", ROWS, ids=row_id)
def test_intersect_equals_brute_force_on_random_rays(row, built, brute, random_rays):
    name, renderer = row
    origins, directions = random_rays
    expected = brute.intersect(origins, directions)
    got = built(name, renderer).intersect(origins, directions)
    assert_hits_match(got, expected, allowed(renderer, len(origins)), f"{name} on {renderer}")
    # Directions of any length: t in units of the direction's length.
    longer = built(name, renderer).intersect(origins, 3 * directions)
    assert_hits_match(longer, brute.intersect(origins, 3 * directions), allowed(renderer, len(origins)),
                      f"{name} on {renderer}, directions of length 3")
    # Hits before a shorter tmax only: the same rays cut at half the reference's distance.
    tmax = np.where(np.isinf(expected["t"]), 10.0, expected["t"] * 0.5).astype(np.float32)
    cut = built(name, renderer).intersect(origins, directions, tmax=tmax)
    assert np.all(cut["t"][cut["id"] != NO_HIT] < tmax[cut["id"] != NO_HIT])


@pytest.mark.parametrize("row", ROWS, ids=row_id)
def test_occluded_agrees_with_intersect(row, built, random_rays):
    name, renderer = row
    origins, directions = random_rays
    accel = built(name, renderer)
    tmax = np.full(len(origins), 2.0, np.float32)
    closest = accel.intersect(origins, directions, tmax=tmax)
    occluded = accel.occluded(origins, directions, tmax)
    assert occluded.dtype == np.bool_ and occluded.shape == (len(origins),)
    disagree = np.flatnonzero(occluded != (closest["id"] != NO_HIT))
    assert len(disagree) <= allowed(renderer, len(origins)), f"rays {disagree[:5]}"
    assert occluded.any() and not occluded.all()


@pytest.mark.parametrize("row", ROWS, ids=row_id)
def test_camera_rays_equal_the_programs_hits(row, built, scene, scene_file, binary, tmp_path):
    name, renderer = row
    width, height = 40, 30
    hits_file = tmp_path / "hits.exr"
    renderer_id = {"cpu": 1, "gpu": 2, "embree": 3}[renderer]
    eye, look_at = (0.4, 0.6, 2.8), (0.0, -0.2, 0.0)
    report = program_json(binary, tmp_path, "-s", scene_file, "-r", str(renderer_id), "-a", name, "--width", str(width),
                          "--height", str(height), "-b", "1", "--hits", str(hits_file), "--eye", "0.4,0.6,2.8",
                          "--look-at", "0,-0.2,0")
    program = passtrace.read_hits(str(hits_file))
    assert (program["width"], program["height"]) == (width, height)
    origins, directions = passtrace.camera_rays(scene, width, height, eye=eye, look_at=look_at)
    got = built(name, renderer).intersect(origins, directions, counters=True)
    assert (got["id"] != NO_HIT).mean() > 0.5
    # The GPU's raygen computes the directions in GLSL: last-bit differences.
    assert_hits_match(got, program, allowed(renderer, width * height), f"{name} on {renderer} against --hits")
    if renderer == "embree":
        return  # Embree counts nothing
    # The counters: the program's totals over the same primary rays (-b 1).
    # Packet and batch tracers (the registry's cpu_ray_groups) group the rays
    # by image tiles or a whole frame in the program, by consecutive rays here;
    # their counts differ.
    grouping = next(s["cpu_ray_groups"] for s in passtrace.structures() if s["name"] == name)
    if renderer == "cpu" and grouping != "none":
        assert got["steps"].sum() > 0 and got["triangle_tests"].sum() > 0
        return
    steps, tests = int(got["steps"].sum()), int(got["triangle_tests"].sum())
    tolerance = 0.002 if renderer == "gpu" else 0.0  # the GPU's few edge rays walk on
    assert abs(steps - report["steps"]) <= tolerance * report["steps"], (steps, report["steps"])
    assert abs(tests - report["triangle_tests"]) <= tolerance * report["triangle_tests"], (tests, report["triangle_tests"])
