#include "python/ray_arrays.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace passtrace::python {

namespace {

bool finite(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// A (..., 3) array of at least one row, or a ValueError.
FloatArray vectors(const py::handle& value, const char* what) {
  FloatArray a = floatArray(value, what);
  if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
    throw py::value_error(std::string(what) + ": expected an array of shape (..., 3), got shape " + shapeText(a));
  if (a.size() == 0) throw py::value_error(std::string(what) + ": no rays (the array is empty)");
  return a;
}

template <typename T>
py::array_t<T> shaped(const std::vector<py::ssize_t>& shape) {
  return py::array_t<T>(shape);
}

}  // namespace

std::string shapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i)
    text += (i ? ", " : "") + std::to_string(array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

FloatArray floatArray(const py::handle& value, const char* what) {
  FloatArray a = FloatArray::ensure(value);
  if (!a) {
    PyErr_Clear();
    throw py::value_error(std::string(what) + ": not an array of numbers");
  }
  return a;
}

RayArrays readRays(const py::handle& origins, const py::handle& directions, const py::handle& tmax, int scaleExponent) {
  const FloatArray o = vectors(origins, "origins"), d = vectors(directions, "directions");
  if (o.ndim() != d.ndim() || !std::equal(o.shape(), o.shape() + o.ndim(), d.shape()))
    throw py::value_error("directions: shape " + shapeText(d) + " differs from origins' " + shapeText(o));
  RayArrays out;
  out.shape.assign(o.shape(), o.shape() + o.ndim() - 1);
  const size_t n = size_t(o.size() / 3);

  // tmax: one value for every ray (a 0-d array), or one per ray.
  FloatArray t;  // a default array_t is an empty array, not null: hence hasT
  const bool hasT = !tmax.is_none();
  bool tScalar = false;
  if (hasT) {
    t = floatArray(tmax, "tmax");
    tScalar = t.ndim() == 0;
    const bool perRay = size_t(t.ndim()) == out.shape.size() && std::equal(out.shape.begin(), out.shape.end(), t.shape());
    if (!tScalar && !perRay) {
      std::string leading = "(";
      for (size_t i = 0; i < out.shape.size(); ++i) leading += (i ? ", " : "") + std::to_string(out.shape[i]);
      leading += out.shape.size() == 1 ? ",)" : ")";
      throw py::value_error("tmax: expected a number or an array of shape " + leading + " (one per ray), got shape " +
                            shapeText(t));
    }
  }
  const float* op = o.data();
  const float* dp = d.data();
  const float* tp = hasT ? t.data() : nullptr;
  out.rays.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float* oi = op + 3 * i;
    const float* di = dp + 3 * i;
    if (!finite(oi)) throw py::value_error("origins: ray " + std::to_string(i) + " is not finite");
    if (!finite(di)) throw py::value_error("directions: ray " + std::to_string(i) + " is not finite");
    if (di[0] == 0.0f && di[1] == 0.0f && di[2] == 0.0f)
      throw py::value_error("directions: ray " + std::to_string(i) + " is the zero vector");
    float tMax = std::numeric_limits<float>::infinity();
    if (tp) {
      tMax = tp[tScalar ? 0 : i];
      if (!(tMax > 0.0f)) throw py::value_error("tmax: ray " + std::to_string(i) + " is not positive (" + std::to_string(tMax) + ")");
    }
    Ray& r = out.rays[i];
    r.origin = glm::vec3(std::ldexp(oi[0], scaleExponent), std::ldexp(oi[1], scaleExponent), std::ldexp(oi[2], scaleExponent));
    r.direction = glm::vec3(di[0], di[1], di[2]);
    r.tMax = std::ldexp(tMax, scaleExponent);
    if (!finite(&r.origin.x))
      throw py::value_error("origins: ray " + std::to_string(i) + " is too far from the scene for single precision "
                            "(the scene is rescaled by 2^" + std::to_string(scaleExponent) + ")");
  }
  return out;
}

py::dict hitArrays(const std::vector<Hit>& hits, const std::vector<RayStats>* stats,
                   const std::vector<py::ssize_t>& shape, int scaleExponent) {
  auto t = shaped<float>(shape), u = shaped<float>(shape), v = shaped<float>(shape);
  auto id = shaped<uint32_t>(shape);
  float* tp = t.mutable_data();
  float* up = u.mutable_data();
  float* vp = v.mutable_data();
  uint32_t* ip = id.mutable_data();
  for (size_t i = 0; i < hits.size(); ++i) {
    const Hit& h = hits[i];
    const bool found = h.found();
    // 2^-k undoes the rescaling exactly, as the program's --hits does.
    tp[i] = found ? std::ldexp(h.t, -scaleExponent) : std::numeric_limits<float>::infinity();
    up[i] = found ? h.u : 0.0f;
    vp[i] = found ? h.v : 0.0f;
    ip[i] = found ? h.id : kNoHit;
  }
  py::dict out;
  out["t"] = t, out["id"] = id, out["u"] = u, out["v"] = v;
  if (stats) {
    auto steps = shaped<uint32_t>(shape), tests = shaped<uint32_t>(shape);
    uint32_t* sp = steps.mutable_data();
    uint32_t* xp = tests.mutable_data();
    for (size_t i = 0; i < stats->size(); ++i) sp[i] = (*stats)[i].steps, xp[i] = (*stats)[i].triangleTests;
    out["steps"] = steps, out["triangle_tests"] = tests;
  }
  return out;
}

py::array_t<bool> foundArray(const std::vector<Hit>& hits, const std::vector<py::ssize_t>& shape) {
  auto found = shaped<bool>(shape);
  bool* p = found.mutable_data();
  for (size_t i = 0; i < hits.size(); ++i) p[i] = hits[i].found();
  return found;
}

}  // namespace passtrace::python
