#pragma once
// The one exception every scene loader throws. Its message is a single line,
// "FILE:LINE: reason" or "FILE: reason", so a command-line tool can print it
// as is and editors can jump to the offending line.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "scenes/one_line_message.h"

namespace passtrace {

struct SceneError : std::runtime_error {
  explicit SceneError(const std::string& message) : std::runtime_error(oneLineMessage(message)) {}
  SceneError(const std::filesystem::path& file, const std::string& reason)
      : SceneError(file.string() + ": " + reason) {}
  SceneError(const std::filesystem::path& file, std::size_t line, const std::string& reason)
      : SceneError(file.string() + ":" + std::to_string(line) + ": " + reason) {}
};

}  // namespace passtrace
