#include "scenes/shared_scene_dir.h"

#include <cstdlib>
#include <system_error>

namespace passtrace {

namespace fs = std::filesystem;

fs::path findSharedSceneDir(const char* environmentVariable, std::string_view subfolder) {
  if (const char* env = std::getenv(environmentVariable); env != nullptr && *env != '\0') return fs::path(env);
  std::error_code ec;
  const fs::path relative = fs::path("..") / "shared" / "scenes" / subfolder;
  const fs::path cwd = fs::current_path(ec);
  if (!ec && fs::is_directory(cwd / relative, ec)) return (cwd / relative).lexically_normal();
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::is_directory(exe.parent_path().parent_path() / relative, ec))
    return (exe.parent_path().parent_path() / relative).lexically_normal();
  return {};
}

}  // namespace passtrace
