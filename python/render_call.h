#pragma once
// passtrace.render(**settings): one run of the program, settings by long
// flag name, returning the --json report's keys plus the image.
#include <pybind11/pybind11.h>

namespace passtrace::python {

pybind11::dict render(const pybind11::dict& settings);

}  // namespace passtrace::python
