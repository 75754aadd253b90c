#include "python/json_value.h"

namespace passtrace::python {

// Through the text: the reports are small, and json.loads is the reference
// for how a --json file reads in Python (NaN and infinity included).
pybind11::object jsonValue(const nlohmann::json& value) {
  // Never destroyed: a static Python object would be released after the
  // interpreter has finalized.
  static auto* loads = new pybind11::object(pybind11::module_::import("json").attr("loads"));
  return (*loads)(value.dump());
}

}  // namespace passtrace::python
