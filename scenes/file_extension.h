#pragma once
// A file's extension in lower case (".ply" for "Bunny.PLY"): what picks a
// loader or an export format.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace passtrace {

inline std::string lowerExtension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace passtrace
