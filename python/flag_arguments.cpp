#include "python/flag_arguments.h"

#include <exception>

namespace passtrace::python {

namespace {

bool isSequence(const py::handle& value) {
  return !py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value) && py::isinstance<py::sequence>(value);
}

// A number as Python writes it; an error naming the flag for anything else.
std::string numberText(const std::string& flag, const py::handle& value) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
                                            py::hasattr(value, "__index__") || py::hasattr(value, "__float__")))
    throwValueError(flag + ": expected a number, got " + std::string(py::repr(value)));
  return std::string(py::repr(py::float_(py::reinterpret_borrow<py::object>(value))));
}

// x,y,z from a sequence of three numbers.
std::string vectorText(const std::string& flag, const py::handle& value) {
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  if (py::len(items) != 3) throwValueError(flag + ": expected three numbers x, y, z, got " + std::string(py::repr(value)));
  return numberText(flag, items[0]) + "," + numberText(flag, items[1]) + "," + numberText(flag, items[2]);
}

}  // namespace

void throwValueError(const std::string& message) {
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  throw py::value_error(line);
}

std::vector<std::string> flagArguments(const py::dict& kwargs) {
  std::vector<std::string> args;
  for (const auto& [key, value] : kwargs) {
    std::string flag = "--" + key.cast<std::string>();
    for (char& c : flag)
      if (c == '_') c = '-';
    if (value.is_none() || (py::isinstance<py::bool_>(value) && !value.cast<bool>())) continue;
    if (py::isinstance<py::bool_>(value)) {
      args.push_back(flag);
    } else if (py::isinstance<py::str>(value)) {
      args.push_back(flag + "=" + value.cast<std::string>());
    } else if (isSequence(value) && py::len(value) > 0 && isSequence(py::reinterpret_borrow<py::sequence>(value)[0])) {
      for (const py::handle item : py::reinterpret_borrow<py::sequence>(value)) args.push_back(flag + "=" + vectorText(flag, item));
    } else if (isSequence(value)) {
      args.push_back(flag + "=" + vectorText(flag, value));
    } else if (py::isinstance<py::int_>(value) || py::hasattr(value, "__index__")) {
      args.push_back(flag + "=" + std::string(py::str(py::int_(py::reinterpret_borrow<py::object>(value)))));
    } else {
      args.push_back(flag + "=" + numberText(flag, value));
    }
  }
  return args;
}

Options parseFlags(const std::vector<std::string>& args) {
  std::vector<std::string> storage = {"passtrace"};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : storage) argv.push_back(a.data());
  Options options;
  try {
    if (parseOptions(int(argv.size()), argv.data(), options) < 0) throwValueError("help: not a setting");
  } catch (const py::error_already_set&) {
    throw;
  } catch (const py::value_error&) {
    throw;
  } catch (const std::exception& e) {
    throwValueError(e.what());
  }
  return options;
}

}  // namespace passtrace::python
