"""The module's interface contract (issue 39), each entry checked against the
program or against the camera contract's formula."""
import subprocess

import numpy as np
import pytest

import passtrace
from conftest import NO_HIT, bumpy_sphere_with_floor, program_json, run_program


def test_version_is_the_programs(binary):
    assert run_program(binary, "--version").stdout.split() == ["passtrace", passtrace.__version__]


def test_structures_are_the_lists_accelerators(binary):
    import json
    listed = json.loads(subprocess.run([binary, "--list", "--json"], capture_output=True, text=True, check=True).stdout)
    assert passtrace.structures() == listed["accelerators"]
    assert {"name", "renderers", "number", "description"} <= set(passtrace.structures()[0])


def test_load_scene_reads_names_and_files(scene_file, tmp_path):
    assert passtrace.load_scene("cornell").triangle_count > 0
    assert passtrace.load_scene("bunny").triangle_count == 69666
    assert passtrace.load_scene("cows").triangle_count > 0
    vertices, faces = bumpy_sphere_with_floor()
    assert passtrace.load_scene(scene_file).triangle_count == len(faces)
    with pytest.raises(ValueError, match="nowhere.obj"):
        passtrace.load_scene(str(tmp_path / "nowhere.obj"))
    with pytest.raises(ValueError, match="unknown scene"):
        passtrace.load_scene("no-such-scene")


def test_scene_from_arrays_traces_like_its_file(scene, random_rays):
    vertices, faces = bumpy_sphere_with_floor()
    from_arrays = passtrace.Scene(vertices, faces.astype(np.int32))
    assert from_arrays.triangle_count == scene.triangle_count == len(faces)
    a = passtrace.brute_force(from_arrays).intersect(*random_rays)
    b = passtrace.brute_force(scene).intersect(*random_rays)
    for key in ("t", "id", "u", "v"):
        np.testing.assert_array_equal(a[key], b[key])


def test_scene_arrays_are_checked():
    v = np.zeros((3, 3), np.float32)
    with pytest.raises(ValueError, match=r"vertices: expected an array of shape \(N, 3\)"):
        passtrace.Scene(np.zeros((3, 2)), np.array([[0, 1, 2]]))
    with pytest.raises(ValueError, match="faces: face 0 indexes vertex 3 of 3"):
        passtrace.Scene(v, np.array([[0, 1, 3]]))
    with pytest.raises(ValueError, match="faces: expected an integer array"):
        passtrace.Scene(v, np.array([[0.0, 1.0, 2.0]]))
    with pytest.raises(ValueError, match="vertex 1 is not finite"):
        passtrace.Scene(np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]]), np.array([[0, 1, 2]]))


def test_camera_rays_follow_the_camera_contract(scene):
    width, height = 7, 5
    eye, look_at, up, fov = (0.5, 1.0, 4.0), (0.0, 0.2, 0.0), (0.0, 1.0, 0.0), 50.0
    origins, directions = passtrace.camera_rays(scene, width, height, eye=eye, look_at=look_at, up=up, fov=fov)
    assert origins.dtype == np.float32 and directions.dtype == np.float32
    assert origins.shape == directions.shape == (width * height, 3)
    np.testing.assert_array_equal(origins, np.tile(np.float32(eye), (width * height, 1)))
    # README's contract: pixel (px, py), py = 0 the top row.
    forward = np.subtract(look_at, eye) / np.linalg.norm(np.subtract(look_at, eye))
    right = np.cross(forward, up) / np.linalg.norm(np.cross(forward, up))
    true_up = np.cross(right, forward)
    k = np.tan(np.radians(fov) / 2)
    py, px = np.divmod(np.arange(width * height), width)
    sx = (2 * (px + 0.5) / width - 1) * k * width / height
    sy = (1 - 2 * (py + 0.5) / height) * k
    d = forward + sx[:, None] * right + sy[:, None] * true_up
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    np.testing.assert_allclose(directions, d, atol=2e-6)
    # The scene's own view where nothing is given: its rays see the scene.
    o, d = passtrace.camera_rays(scene, 16, 16)
    assert (passtrace.brute_force(scene).intersect(o, d)["id"] != NO_HIT).mean() > 0.1
    with pytest.raises(ValueError, match="width and height"):
        passtrace.camera_rays(scene, 0, 4)


def test_intersect_keeps_the_leading_shape(scene, brute, random_rays):
    origins, directions = random_rays[0][:24], random_rays[1][:24]
    flat = brute.intersect(origins, directions, counters=True)
    shaped = brute.intersect(origins.reshape(2, 3, 4, 3), directions.reshape(2, 3, 4, 3), counters=True,
                             tmax=np.full((2, 3, 4), np.inf, np.float32))
    assert set(flat) == {"t", "id", "u", "v", "steps", "triangle_tests"}
    for key, value in shaped.items():
        assert value.shape == (2, 3, 4), key
        np.testing.assert_array_equal(value.reshape(-1), flat[key])
    assert flat["t"].dtype == np.float32 and flat["id"].dtype == np.uint32 and flat["steps"].dtype == np.uint32
    assert np.all(np.isinf(flat["t"][flat["id"] == NO_HIT]))
    # float64 input is converted; the answers are those of its float32 values.
    np.testing.assert_array_equal(brute.intersect(origins.astype(np.float64), directions)["id"], flat["id"])


@pytest.mark.parametrize("bad, message", [
    (lambda o, d: (o[:, :2], d[:, :2]), r"origins: expected an array of shape \(\.\.\., 3\), got shape \(10, 2\)"),
    (lambda o, d: (o, d[:5]), r"directions: shape \(5, 3\) differs from origins' \(10, 3\)"),
    (lambda o, d: (o[:0], d[:0]), "origins: no rays"),
    (lambda o, d: (np.where(np.arange(10)[:, None] == 4, np.nan, o), d), "origins: ray 4 is not finite"),
    (lambda o, d: (o, np.where(np.arange(10)[:, None] == 2, np.inf, d)), "directions: ray 2 is not finite"),
    (lambda o, d: (o, np.where(np.arange(10)[:, None] == 3, 0.0, d)), "directions: ray 3 is the zero vector"),
    (lambda o, d: ("origins", d), "origins: not an array of numbers"),
])
def test_bad_arrays_are_value_errors(brute, random_rays, bad, message):
    origins, directions = random_rays[0][:10], random_rays[1][:10]
    with pytest.raises(ValueError, match=message):
        brute.intersect(*bad(origins, directions))
    with pytest.raises(ValueError, match=message):
        brute.occluded(*bad(origins, directions), 1.0)


def test_bad_tmax_is_a_value_error(brute, random_rays):
    origins, directions = random_rays[0][:10], random_rays[1][:10]
    with pytest.raises(ValueError, match=r"tmax: expected a number or an array of shape \(10,\)"):
        brute.intersect(origins, directions, tmax=np.ones(3))
    with pytest.raises(ValueError, match="tmax: ray 0 is not positive"):
        brute.intersect(origins, directions, tmax=np.full(10, np.nan))
    with pytest.raises(ValueError, match="tmax: ray 1 is not positive"):
        brute.occluded(origins, directions, np.array([1, 0, 1, 1, 1, 1, 1, 1, 1, 1], np.float32))


def test_build_reads_the_programs_parameters(scene, brute, random_rays):
    accel = passtrace.build(scene, "kd-shortstack", kd_builder="binned", stack_size=8, triangle_test="watertight",
                            threads=1)
    expected = passtrace.brute_force(scene, triangle_test="watertight").intersect(*random_rays)
    got = accel.intersect(*random_rays)
    np.testing.assert_array_equal(got["id"], expected["id"])
    gpu = passtrace.build(scene, "kd-restart", "gpu", loop_limit=0, page_texels=4096, stage="compute")
    np.testing.assert_array_equal(gpu.intersect(*random_rays)["id"] != NO_HIT, expected["id"] != NO_HIT)


@pytest.mark.parametrize("call, message", [
    (lambda s: passtrace.build(s, "no-such-tree"), "unknown accelerator 'no-such-tree' .valid on the CPU renderer"),
    (lambda s: passtrace.build(s, "bvh8", "gpu"), "accelerator 'bvh8' does not run on the GPU stream renderer"),
    (lambda s: passtrace.build(s, "bvh8", "tpu"), "renderer: 'tpu' is not one of cpu, gpu, embree"),
    (lambda s: passtrace.build(s, "bvh8", output="x.png"), "build: 'output' is not a build or traversal parameter"),
    (lambda s: passtrace.build(s, "bvh8", grid_multiplier=2), "-g/--grid-multiplier is not read by bvh8 on the CPU"),
    (lambda s: passtrace.build(s, "kd-shortstack", stack_size=99), "--stack-size: Value 99 not in range 1 to 8"),
    (lambda s: passtrace.build(s, "kd-tree", kd_builder="magic"), "--kd-builder"),
    (lambda s: passtrace.build(s, "bvh8", stage="compute"), "--stage is read by the gpu renderer only"),
])
def test_bad_build_arguments_are_value_errors(scene, call, message):
    with pytest.raises(ValueError, match=message):
        call(scene)


def test_stats_are_the_reports_structure_keys(scene, scene_file, binary, tmp_path):
    report = program_json(binary, tmp_path, "-s", scene_file, "-r", "1", "-a", "kd-tree", "-w", "8", "-b", "1")
    stats = passtrace.build(scene, "kd-tree").stats()
    assert set(stats) == {"accelerator", "build_ms", "accel_floats_per_triangle", "accel_nodes", "accel_leaves",
                          "accel_depth", "accel_references", "structure"}
    for key in stats:
        if key != "build_ms":
            assert stats[key] == report[key], key


def test_render_returns_the_report_and_the_image(scene_file, binary, tmp_path):
    settings = dict(scene=scene_file, renderer=1, accel="bvh8", width=24, height=16, bounces=2, shading="ao",
                    ao_samples=2, light=[(0.0, 3.0, 2.0)], eye=(0.0, 0.5, 4.0))
    result = passtrace.render(**settings)
    image = result.pop("image")
    assert image.shape == (16, 24, 3) and image.dtype == np.float32 and image.max() > 0.05
    args = ["-s", scene_file, "-r", "1", "-a", "bvh8", "--width", "24", "--height", "16", "-b", "2", "--shading", "ao",
            "--ao-samples", "2", "--light", "0,3,2", "--eye", "0,0.5,4"]
    report = program_json(binary, tmp_path, *args)
    assert set(result) == set(report)
    for key in ("scene", "triangles", "renderer", "accelerator", "rays", "steps", "triangle_tests", "shading"):
        assert result[key] == report[key], key
    # The image is the one -o writes.
    exr = tmp_path / "image.exr"
    run_program(binary, *args, "-o", str(exr))
    np.testing.assert_array_equal(image, passtrace.read_image(str(exr)))
    with pytest.raises(ValueError, match="unknown accelerator 'zzz'"):
        passtrace.render(scene=scene_file, renderer=1, accel="zzz")
    with pytest.raises(ValueError, match="--bounces"):
        passtrace.render(scene=scene_file, bounces=0)


def test_render_on_the_gpu_stream_path(scene_file):
    result = passtrace.render(scene=scene_file, renderer=2, accel="bvh-stack", width=16, height=16, bounces=1)
    assert result["renderer"] == "gpu" and result["image"].shape == (16, 16, 3) and result["gl_renderer"]


def test_read_hits_reads_the_programs_file(scene_file, binary, tmp_path):
    hits = tmp_path / "hits.exr"
    run_program(binary, "-s", scene_file, "-r", "1", "-a", "bvh8", "--width", "9", "--height", "4", "-b", "1",
                "--hits", str(hits))
    read = passtrace.read_hits(str(hits))
    assert (read["width"], read["height"]) == (9, 4) and read["t"].shape == (36,)
    with pytest.raises(ValueError, match="nothing.exr"):
        passtrace.read_hits(str(tmp_path / "nothing.exr"))
