#pragma once
// Where the tests find the BART scenes: where the command line would
// (PASSTRACE_BART_DIR, ../shared beside the working directory or the binary's
// folder), else ../shared beside the checkout, since the test binaries live
// one folder deeper than passtrace. Empty when absent: the tests then skip.

#include <filesystem>
#include <system_error>

#include "scenes/scene_registry.h"

namespace passtrace::test {

inline std::filesystem::path bartDir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::path dir = defaultBartDir(); !dir.empty() && fs::is_directory(dir, ec)) return dir;
  const fs::path beside = (fs::path(PASSTRACE_TEST_DATA) / ".." / ".." / ".." / "shared" / "scenes" / "bart").lexically_normal();
  return fs::is_directory(beside, ec) ? beside : fs::path();
}

}  // namespace passtrace::test
