#pragma once
// The JSON the program writes, as the Python objects json.loads makes of it:
// the module's dicts have exactly the keys and values of --json and --list --json.
#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace passtrace::python {

pybind11::object jsonValue(const nlohmann::json& value);

}  // namespace passtrace::python
