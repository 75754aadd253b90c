#pragma once
// The loaders read paths, not memory: each fuzz input is written to a file in
// a directory private to this process (so parallel fuzzers never share one)
// under $TMPDIR, removed at a normal exit. libFuzzer ends with _Exit, which
// skips that, so scripts/fuzz.sh points TMPDIR into build-fuzz/run/.

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace passtrace::fuzz {

inline const std::filesystem::path& inputDirectory() {
  static const std::filesystem::path directory = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "passtrace-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror("passtrace fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(inputDirectory(), ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return directory;
}

// Writes `size` bytes to `name` in the private directory, replacing it.
inline std::filesystem::path writeInputFile(const std::string& name, const void* data, std::size_t size) {
  const std::filesystem::path path = inputDirectory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::perror(("passtrace fuzz: cannot write " + path.string()).c_str());
    std::abort();
  }
  return path;
}

}  // namespace passtrace::fuzz
