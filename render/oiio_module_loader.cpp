// Finds and loads libpasstrace_oiio.so (render/oiio_module.h) once.
#include <dlfcn.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/oiio_module.h"

namespace passtrace {
namespace {

namespace fs = std::filesystem;

constexpr const char* kFileName = "libpasstrace_oiio.so";

// Where the module may be, in the order tried.
std::vector<fs::path> candidates() {
  std::vector<fs::path> paths;
  if (const char* env = std::getenv("PASSTRACE_OIIO_MODULE"); env && *env) paths.emplace_back(env);
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back(self.parent_path() / kFileName);
  // The installed copy, then the build tree's (render/CMakeLists.txt).
  paths.emplace_back(PASSTRACE_OIIO_MODULE_INSTALLED);
  paths.emplace_back(PASSTRACE_OIIO_MODULE_BUILT);
  return paths;
}

struct Loaded {
  const OiioModule* module = nullptr;
  std::string why;  // when module is null: what each candidate said
};

Loaded load() {
  Loaded loaded;
  for (const fs::path& path : candidates()) {
    if (!fs::exists(path)) continue;
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      loaded.why += std::string(loaded.why.empty() ? "" : "; ") + ::dlerror();
      continue;
    }
    using Entry = const OiioModule* (*)();
    const auto entry = reinterpret_cast<Entry>(::dlsym(handle, "passtrace_oiio_module"));
    if (entry && (loaded.module = entry())) return loaded;  // kept loaded for the process's life
    loaded.why += std::string(loaded.why.empty() ? "" : "; ") + path.string() + " has no passtrace_oiio_module";
  }
  if (loaded.why.empty()) loaded.why = std::string(kFileName) + " was not found (set PASSTRACE_OIIO_MODULE)";
  return loaded;
}

}  // namespace

const OiioModule& oiioModule(const fs::path& forFile) {
  static const Loaded loaded = load();
  if (!loaded.module)
    throw std::runtime_error(forFile.string() + ": cannot write " + forFile.extension().string() +
                             " images: passtrace's OpenImageIO module did not load: " + loaded.why);
  return *loaded.module;
}

}  // namespace passtrace
