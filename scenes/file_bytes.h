#pragma once
// A scene file read whole into memory, with the checks every loader that
// reads bytes itself needs: a regular file (a FIFO or directory is refused
// without blocking), no larger than the loader's limit.

#include <cstdint>
#include <filesystem>
#include <string>

namespace passtrace {

// Throws SceneError ("FILE: cannot open: ...", "FILE: file too large ...").
std::string readFileBytes(const std::filesystem::path& file, std::uintmax_t maxBytes);

}  // namespace passtrace
