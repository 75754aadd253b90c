#pragma once
// The command-line fuzz target's input format and what parseOptions
// promises, shared with the regression test over its findings: the bytes are
// argv words separated by NUL or newline (argv[0] is "passtrace"), and a
// successful parse leaves every option inside its documented range.

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "apps/cli_options.h"

namespace passtrace::fuzz {

inline std::vector<std::string> splitArguments(std::string_view bytes) {
  std::vector<std::string> words{"passtrace"};
  std::string word;
  for (char c : bytes) {
    if (c == '\0' || c == '\n') {
      words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

// Calls parseOptions on the words (argv as main receives it).
inline int parseWords(std::vector<std::string> words, Options& options) {
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  return parseOptions(static_cast<int>(words.size()), argv.data(), options);
}

// Empty when the parsed options are inside the ranges `--help` documents.
inline std::string optionsProblem(const Options& o) {
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (o.renderer < 0 || o.renderer > 3) return "renderer out of range";
  if (o.width < 1 || o.width > kMaxImageSide || o.height < 1 || o.height > kMaxImageSide) return "image size out of range";
  if (o.bounces < 1 || o.bounces > 64) return "bounces out of range";
  if (!std::isfinite(o.time) || std::fabs(o.time) > 1e6f) return "time not finite or out of range";
  if (!(o.gridMultiplier >= 0.001f && o.gridMultiplier <= 1000.0f)) return "grid multiplier out of range";
  if (o.fov && !(*o.fov >= 0.001f && *o.fov <= 179.999f)) return "fov out of range";
  if ((o.eye && !finite(*o.eye)) || (o.lookAt && !finite(*o.lookAt)) || (o.up && !finite(*o.up)))
    return "camera vector not finite";
  if (o.gsTries < 1 || o.kdMinElements < 1 || o.kdMaxDepth < 0 || o.kdMaxDepth > 64 || o.repeats < 1 ||
      o.angles < 1 || o.loopLimit < 0 || o.swapChildren < 0 || o.swapChildren > 2)
    return "a count is out of range";
  if (o.threads > kMaxThreads) return "thread count out of range";
  return {};
}

}  // namespace passtrace::fuzz
