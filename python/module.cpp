// The passtrace Python module (_passtrace, re-exported by passtrace/__init__.py):
// the registry, scenes, the camera's rays, every structure on the CPU and
// GPU stream renderers behind numpy arrays, and whole runs of the program.
// Each function's job is in its own file; this one only names them for Python.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "passtrace_version.h"
#include "python/accelerator.h"
#include "python/flag_arguments.h"
#include "python/json_value.h"
#include "python/render_call.h"
#include "python/scene_arrays.h"
#include "render/catalog.h"
#include "render/image_output.h"

namespace py = pybind11;
using namespace passtrace;
using namespace passtrace::python;

namespace {

// A --hits file: t, id, u, v as flat arrays of width*height, with the size.
py::dict readHits(const std::string& path) {
  int width = 0, height = 0;
  std::vector<HitRecord> records;
  try {
    records = readHitBuffer(path, width, height);
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
  py::array_t<float> t(py::ssize_t(records.size())), u(py::ssize_t(records.size())), v(py::ssize_t(records.size()));
  py::array_t<uint32_t> id(py::ssize_t(records.size()));
  for (size_t i = 0; i < records.size(); ++i) {
    t.mutable_data()[i] = records[i].t, u.mutable_data()[i] = records[i].u, v.mutable_data()[i] = records[i].v;
    id.mutable_data()[i] = records[i].id;
  }
  py::dict out;
  out["t"] = t, out["id"] = id, out["u"] = u, out["v"] = v, out["width"] = width, out["height"] = height;
  return out;
}

// An OpenEXR image the program wrote (-o NAME.exr): float32 (height, width, 3).
py::array_t<float> readImageFile(const std::string& path) {
  int width = 0, height = 0;
  std::vector<float> rgb;
  try {
    rgb = readImage(path, width, height);
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
  return py::array_t<float>({py::ssize_t(height), py::ssize_t(width), py::ssize_t(3)}, rgb.data());
}

}  // namespace

PYBIND11_MODULE(_passtrace, m) {
  m.doc() = "passtrace: ray-tracing acceleration structures on the CPU and the GPU stream path";
  m.attr("__version__") = kVersion;

  m.def("structures", [] { return jsonValue(catalogJson()["accelerators"]); },
        "Every registry row, as the 'accelerators' of `passtrace --list --json`.");
  m.def("build_parameters", &buildParameterNames, "The keyword parameters build() takes.");

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A triangle scene: loaded, or made from arrays.")
      .def(py::init(&sceneFromArrays), py::arg("vertices"), py::arg("faces"),
           "A scene of vertices (N, 3) and faces (M, 3) indexing them.")
      .def_property_readonly("triangle_count", [](const Scene& s) { return s.triangles.size(); })
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def("__repr__", [](const Scene& s) {
        return "<passtrace.Scene " + s.name + ", " + std::to_string(s.triangles.size()) + " triangles>";
      });

  m.def("load_scene", &loadScene, py::arg("path_or_name"), py::arg("time") = 0.0f, py::kw_only(),
        py::arg("bart_dir") = py::none(), py::arg("scenes_dir") = py::none(),
        "A scene as the program's -s loads it: a built-in or named scene, or a file.");
  m.def("camera_rays", &cameraRays, py::arg("scene"), py::arg("width"), py::arg("height"), py::arg("eye") = py::none(),
        py::arg("look_at") = py::none(), py::arg("up") = py::none(), py::arg("fov") = py::none(),
        "(origins, directions): float32 (height*width, 3), row by row from the top: the program's camera.");

  py::class_<Accelerator>(m, "Accelerator", "A structure built over a scene; made by passtrace.build().")
      .def("intersect", &Accelerator::intersect, py::arg("origins"), py::arg("directions"),
           py::arg("tmax") = py::none(), py::arg("counters") = false,
           "Closest hits: dict of t, id, u, v (and steps, triangle_tests with counters=True).")
      .def("occluded", &Accelerator::occluded, py::arg("origins"), py::arg("directions"), py::arg("tmax") = py::none(),
           "Any hit before tmax, as a bool array.")
      .def("stats", &Accelerator::stats, "The --json report's structure statistics.")
      .def("__repr__", &Accelerator::repr);

  m.def(
      "build",
      [](std::shared_ptr<Scene> scene, const std::string& structure, const std::string& renderer, py::kwargs params) {
        return std::make_unique<Accelerator>(std::move(scene), structure, renderer, params);
      },
      py::arg("scene"), py::arg("structure"), py::arg("renderer") = "cpu",
      "Builds a registry row over the scene for renderer 'cpu' or 'gpu' (parameters by long flag name).");

  m.def(
      "brute_force",
      [](std::shared_ptr<Scene> scene, const std::string& triangleTest) {
        return Accelerator::bruteForce(std::move(scene), triangleTest);
      },
      py::arg("scene"), py::arg("triangle_test") = "moller-trumbore",
      "Every triangle tested for every ray: the reference to compare structures with.");
  m.def("render", [](py::kwargs settings) { return render(settings); },
        "One run of the program (settings by long flag name): the --json report's keys plus 'image'.");
  m.def("read_hits", &readHits, py::arg("path"), "A --hits file: t, id, u, v arrays and its width and height.");
  m.def("read_image", &readImageFile, py::arg("path"), "An OpenEXR image the program wrote: float32 (height, width, 3).");
}
