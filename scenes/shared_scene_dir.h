#pragma once
// Where scenes that passtrace does not ship are found: the BART scenes and the
// real benchmark scenes (Conference, Sibenik, ...) live in ../shared/scenes/
// beside a checkout, or wherever an environment variable says.

#include <filesystem>
#include <string_view>

namespace passtrace {

// $ENV when set (even if it does not exist, so that a wrong setting is
// reported rather than silently bypassed); else the first existing one of
// ../shared/scenes/SUBFOLDER relative to the current directory and relative
// to the parent of the executable's directory (build/passtrace beside the
// checkout's shared/); else empty.
std::filesystem::path findSharedSceneDir(const char* environmentVariable, std::string_view subfolder);

}  // namespace passtrace
