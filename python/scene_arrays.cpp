#include "python/scene_arrays.h"

#include <cmath>
#include <exception>

#include "python/flag_arguments.h"
#include "python/ray_arrays.h"
#include "render/camera.h"
#include "scenes/scene_registry.h"
#include "scenes/scene_scale.h"

namespace passtrace::python {

namespace {

// x,y,z of a three-number argument, or a ValueError naming it.
glm::vec3 vectorArgument(const py::handle& value, const char* what) {
  const FloatArray a = floatArray(value, what);
  if (a.size() != 3) throwValueError(std::string(what) + ": expected three numbers x, y, z, got shape " + shapeText(a));
  const glm::vec3 v(a.data()[0], a.data()[1], a.data()[2]);
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throwValueError(std::string(what) + ": not finite");
  return v;
}

}  // namespace

std::shared_ptr<Scene> loadScene(const std::string& nameOrPath, float time, const std::optional<std::string>& bartDir,
                                 const std::optional<std::string>& scenesDir) {
  SceneOptions options;
  options.time = time;
  if (bartDir) options.bartDir = *bartDir;
  if (scenesDir) options.realScenesDir = *scenesDir;
  try {
    py::gil_scoped_release released;
    return std::make_shared<Scene>(passtrace::loadScene(nameOrPath, options));
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
}

std::shared_ptr<Scene> sceneFromArrays(const py::handle& vertices, const py::handle& faces) {
  const FloatArray v = floatArray(vertices, "vertices");
  if (v.ndim() != 2 || v.shape(1) != 3)
    throwValueError("vertices: expected an array of shape (N, 3), got shape " + shapeText(v));
  using IndexArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;
  const py::array facesArray = py::array::ensure(faces);
  if (!facesArray || !(facesArray.dtype().kind() == 'i' || facesArray.dtype().kind() == 'u')) {
    PyErr_Clear();
    throwValueError("faces: expected an integer array of shape (M, 3)");
  }
  const IndexArray f = IndexArray::ensure(facesArray);
  if (f.ndim() != 2 || f.shape(1) != 3) throwValueError("faces: expected an array of shape (M, 3), got shape " + shapeText(f));

  auto scene = std::make_shared<Scene>();
  scene->name = "arrays";
  const float* p = v.data();
  const int64_t* idx = f.data();
  const int64_t n = v.shape(0);
  for (int64_t i = 0; i < n * 3; ++i)
    if (!std::isfinite(p[i])) throwValueError("vertices: vertex " + std::to_string(i / 3) + " is not finite");
  const auto vertex = [&](int64_t face, int k) {
    const int64_t i = idx[3 * face + k];
    if (i < 0 || i >= n)
      throwValueError("faces: face " + std::to_string(face) + " indexes vertex " + std::to_string(i) + " of " +
                      std::to_string(n));
    return glm::vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  };
  scene->triangles.reserve(size_t(f.shape(0)));
  for (int64_t m = 0; m < f.shape(0); ++m) scene->triangles.push_back(Triangle{vertex(m, 0), vertex(m, 1), vertex(m, 2)});
  scene->materials = {Material{}};
  scene->materialIds.assign(scene->triangles.size(), 0);
  normalizeSceneScale(*scene);
  if (!scene->triangles.empty()) {
    scene->camera = framedCamera(scene->bounds());
    scene->light = framedLight(scene->bounds());
  }
  scene->lightIsDefault = true;
  return scene;
}

py::tuple cameraRays(const Scene& scene, int width, int height, const py::handle& eye, const py::handle& lookAt,
                     const py::handle& up, const py::handle& fov) {
  if (width < 1 || height < 1)
    throwValueError("camera_rays: width and height must be at least 1, got " + std::to_string(width) + "x" +
                    std::to_string(height));
  CameraSpec view = scene.camera;
  const int k = scene.scaleExponent;
  // As the program's --eye and --look-at: the file's units, rescaled like the scene.
  if (!eye.is_none()) view.eye = scaleByPowerOfTwo(vectorArgument(eye, "eye"), k);
  if (!lookAt.is_none()) view.lookAt = scaleByPowerOfTwo(vectorArgument(lookAt, "look_at"), k);
  if (!up.is_none()) view.up = vectorArgument(up, "up");
  if (!fov.is_none()) view.fovDegrees = fov.cast<float>();
  CameraBasis basis;
  try {
    basis = makeCameraBasis(view, width, height);
  } catch (const std::exception& e) {
    throwValueError(std::string("camera_rays: ") + e.what());
  }
  const py::ssize_t count = py::ssize_t(width) * height;
  py::array_t<float> origins({count, py::ssize_t(3)}), directions({count, py::ssize_t(3)});
  float* o = origins.mutable_data();
  float* d = directions.mutable_data();
  const glm::vec3 eyeInFile = scaleByPowerOfTwo(basis.eye, -k);  // exact: a power of two
  {
    py::gil_scoped_release released;
    for (int y = 0; y < height; ++y) {
      const float sy = cameraScreenY(basis, y);
      for (int x = 0; x < width; ++x) {
        const glm::vec3 dir = cameraDirection(basis, cameraScreenX(basis, x), sy);
        const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
        o[i] = eyeInFile.x, o[i + 1] = eyeInFile.y, o[i + 2] = eyeInFile.z;
        d[i] = dir.x, d[i + 1] = dir.y, d[i + 2] = dir.z;
      }
    }
  }
  return py::make_tuple(origins, directions);
}

}  // namespace passtrace::python
