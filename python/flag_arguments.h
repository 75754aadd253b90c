#pragma once
// Keyword arguments as the program's flags: build() and render() take the
// command line's long flag names with '_' for '-' (kd_builder="binned" is
// --kd-builder=binned) and parse them with the program's own parser
// (apps/cli_options.h), so every value is checked, and every bad one
// reported, exactly as on the command line.
#include <string>
#include <vector>
#include <pybind11/pybind11.h>
#include "apps/cli_options.h"

namespace passtrace::python {

namespace py = pybind11;

// name=value as "--name=value": True is the flag alone, False and None
// leave it out, a sequence of three numbers is "x,y,z", and a list of such
// sequences gives the flag once per entry (light=[(0, 5, 0), (2, 5, 0)]).
// Numbers are written as Python's repr writes them (exact for floats).
std::vector<std::string> flagArguments(const py::dict& kwargs);

// Parses `args` as passtrace's command line. A bad flag or value is a
// ValueError carrying the program's one-line message.
Options parseFlags(const std::vector<std::string>& args);

// A ValueError with `message` on one line, as the program prints errors.
[[noreturn]] void throwValueError(const std::string& message);

}  // namespace passtrace::python
