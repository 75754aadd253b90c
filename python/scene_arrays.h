#pragma once
// Scenes for the Python module: loaded as the program loads them (files in
// every format it reads, the built-in and named scenes), or made from numpy
// vertex and face arrays; and the camera's rays as numpy arrays.
#include <memory>
#include <optional>
#include <string>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include "scenes/scene.h"

namespace passtrace::python {

namespace py = pybind11;

// The program's -s: a built-in or named scene or a file, at animation time
// `time`. A file it cannot read is a ValueError with the loader's line.
std::shared_ptr<Scene> loadScene(const std::string& nameOrPath, float time, const std::optional<std::string>& bartDir,
                                 const std::optional<std::string>& scenesDir);

// vertices (N, 3) numbers, faces (M, 3) integers indexing them; one diffuse
// material, a view and a light framed on the bounds (as a file without them
// gets), rescaled into single precision's safe range like any loaded scene.
std::shared_ptr<Scene> sceneFromArrays(const py::handle& vertices, const py::handle& faces);

// (origins, directions), float32 (height*width, 3), pixels row by row from
// the top row: the program's camera (render/camera.h) from the scene's own
// view, with any of eye, look_at (the file's units), up and fov replaced.
py::tuple cameraRays(const Scene& scene, int width, int height, const py::handle& eye, const py::handle& lookAt,
                     const py::handle& up, const py::handle& fov);

}  // namespace passtrace::python
