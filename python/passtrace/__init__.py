"""passtrace from Python: every acceleration structure of the registry on the
CPU renderer and the GPU stream path, behind numpy arrays.

    import passtrace
    scene = passtrace.load_scene("bunny")
    origins, directions = passtrace.camera_rays(scene, 256, 256)
    bvh = passtrace.build(scene, "bvh8")
    hits = bvh.intersect(origins, directions, counters=True)   # t, id, u, v, steps, triangle_tests

See docs/python.md for the whole interface.
"""
from ._passtrace import (
    Accelerator,
    Scene,
    __version__,
    brute_force,
    build,
    build_parameters,
    camera_rays,
    load_scene,
    read_hits,
    read_image,
    render,
    structures,
)

__all__ = [
    "Accelerator", "Scene", "__version__", "brute_force", "build", "build_parameters", "camera_rays", "load_scene",
    "read_hits", "read_image", "render", "structures",
]
