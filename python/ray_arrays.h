#pragma once
// numpy arrays of rays in, numpy arrays of hits out: the checks every array
// passes (a bad one is a ValueError naming the argument and the ray), the
// scene's power-of-two rescaling applied on the way in and undone on the way
// out, and the output arrays shaped like the input's leading dimensions.
#include <string>
#include <vector>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include "accel/geometry/geometry.h"
#include "accel/traversal_stats.h"

namespace passtrace::python {

namespace py = pybind11;

// float32, C-contiguous: what the module reads. An array that is already so
// is used in place (no copy); anything else numpy can convert is converted.
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// `value` as a FloatArray, or a ValueError naming `what`.
FloatArray floatArray(const py::handle& value, const char* what);

// Rays of the shape (..., 3) arrays origins and directions (equal shapes,
// at least one ray, finite, no zero direction) and tmax (None: infinity, a
// scalar, or an array of the leading shape; positive, not NaN), in the
// scene's units: positions and tmax times 2^scaleExponent.
struct RayArrays {
  std::vector<Ray> rays;
  std::vector<py::ssize_t> shape;  // the leading shape: origins.shape[:-1]
};
RayArrays readRays(const py::handle& origins, const py::handle& directions, const py::handle& tmax, int scaleExponent);

// Intersect's dict: t (float32, inf on a miss, in the caller's units), id
// (uint32, 4294967295 on a miss), u, v (float32), and with `stats` steps and
// triangle_tests (uint32), each of `shape`.
py::dict hitArrays(const std::vector<Hit>& hits, const std::vector<RayStats>* stats,
                   const std::vector<py::ssize_t>& shape, int scaleExponent);

// occluded(): true where a hit was found.
py::array_t<bool> foundArray(const std::vector<Hit>& hits, const std::vector<py::ssize_t>& shape);

// "(4, 2)": numpy's way of writing a shape, for messages.
std::string shapeText(const py::array& array);

}  // namespace passtrace::python
