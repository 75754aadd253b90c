#pragma once
// The one exception every scene loader throws. Its message is a single line,
// "FILE:LINE: reason" or "FILE: reason", so a command-line tool can print it
// as is and editors can jump to the offending line.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace passtrace {

struct SceneError : std::runtime_error {
  explicit SceneError(const std::string& message) : std::runtime_error(oneLine(message)) {}
  SceneError(const std::filesystem::path& file, const std::string& reason)
      : SceneError(file.string() + ": " + reason) {}
  SceneError(const std::filesystem::path& file, std::size_t line, const std::string& reason)
      : SceneError(file.string() + ":" + std::to_string(line) + ": " + reason) {}

 private:
  // Third-party messages (tinyobjloader's) may span lines; keep ours to one.
  static std::string oneLine(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    for (char& c : s)
      if (c == '\n' || c == '\r') c = ' ';
    return s;
  }
};

}  // namespace passtrace
