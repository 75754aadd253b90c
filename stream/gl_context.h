#pragma once
// A headless OpenGL 4.5 core context: EGL (device platform with a hardware
// device, else Mesa's surfaceless platform) or OSMesa. There is no default
// framebuffer; everything renders into framebuffer objects.

#include <memory>
#include <string>

namespace passtrace {

enum class GlBackend {
  Auto,   // EGL, and OSMesa if EGL cannot give a context
  Egl,    // EGL only: a hardware EGL device if any, else surfaceless
  OsMesa  // OSMesa only
};

// Parses "auto", "egl" or "osmesa"; throws std::invalid_argument otherwise.
GlBackend parseGlBackend(const std::string& name);

// What a platform hands back: how to find GL entry points and how to let go.
struct PlatformContext {
  using Proc = void (*)();
  using ProcLoader = Proc (*)(const char*);
  std::string backend;  // "egl-device", "egl-surfaceless" or "osmesa"
  ProcLoader getProcAddress = nullptr;
  void (*release)(void* handle) = nullptr;
  void* handle = nullptr;
};

class GlContext {
 public:
  // Creates and makes current a context. Throws GlError with every backend's
  // reason when none works. `notices` receives one line per fallback taken.
  static std::unique_ptr<GlContext> create(GlBackend backend, std::string* notices = nullptr);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  const std::string& backend() const { return platform_.backend; }
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION
  int maxTextureSize() const { return maxTextureSize_; }

 private:
  explicit GlContext(PlatformContext platform);
  PlatformContext platform_;
  std::string renderer_, version_;
  int maxTextureSize_ = 0;
};

}  // namespace passtrace
