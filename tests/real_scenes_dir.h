#pragma once
// Where the tests find the real benchmark scenes (Conference, Sibenik, ...):
// $PASSTRACE_SCENES_DIR, else ../shared/scenes/real beside the checkout.
// Empty when absent: the tests that use them then skip (a user's machine has none).

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "scenes/scene_registry.h"

namespace passtrace::test {

inline constexpr const char* kRealScenesAbsent =
    "the real scenes (../shared/scenes/real or $PASSTRACE_SCENES_DIR) are absent";

inline std::filesystem::path realScenesDir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* dir = std::getenv("PASSTRACE_SCENES_DIR"); dir && fs::is_directory(dir, ec)) return dir;
  const fs::path beside = (fs::path(PASSTRACE_TEST_DATA) / ".." / ".." / ".." / "shared" / "scenes" / "real").lexically_normal();
  return fs::is_directory(beside, ec) ? beside : fs::path();
}

// Scene options that find the real scenes in `dir`.
inline SceneOptions realSceneOptions(const std::filesystem::path& dir) {
  SceneOptions options;
  options.realScenesDir = dir;
  return options;
}

}  // namespace passtrace::test
