#include "stream/gl_context.h"

#include <stdexcept>

#include "stream/egl_platform.h"
#include "stream/gl.h"
#include "stream/gl_error.h"
#if PASSTRACE_HAVE_OSMESA
#include "stream/osmesa_platform.h"
#endif

namespace passtrace {

GlBackend parseGlBackend(const std::string& name) {
  if (name == "auto") return GlBackend::Auto;
  if (name == "egl") return GlBackend::Egl;
  if (name == "osmesa") return GlBackend::OsMesa;
  throw std::invalid_argument("unknown GL backend '" + name + "' (expected auto, egl or osmesa)");
}

std::unique_ptr<GlContext> GlContext::create(GlBackend backend, std::string* notices) {
  PlatformContext platform;
  std::string eglError, osmesaError;
  bool ok = false;
#if PASSTRACE_HAVE_OSMESA
  if (backend != GlBackend::OsMesa) ok = createEglContext(platform, eglError);
  if (!ok && backend == GlBackend::Auto && notices)
    *notices += "no EGL context (" + eglError + "); falling back to OSMesa\n";
  if (!ok && backend != GlBackend::Egl) ok = createOsMesaContext(platform, osmesaError);
#else
  // Built without OSMesa (its development files were missing): EGL only.
  (void)notices;  // no fallback to announce
  if (backend == GlBackend::OsMesa)
    throw std::runtime_error("the osmesa GL backend is not available: passtrace was built without OSMesa");
  ok = createEglContext(platform, eglError);
#endif
  if (!ok) {
    std::string why = eglError;
    if (!osmesaError.empty()) why += (why.empty() ? "" : "; ") + osmesaError;
    throw GlError("no OpenGL 4.5 context: " + why);
  }
  return std::unique_ptr<GlContext>(new GlContext(std::move(platform)));
}

GlContext::GlContext(PlatformContext platform) : platform_(std::move(platform)) {
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(platform_.getProcAddress))) {
    platform_.release(platform_.handle);
    throw GlError(platform_.backend + ": could not load the OpenGL 4.5 entry points");
  }
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize_);
  checkGlError("creating the " + platform_.backend + " context");
}

GlContext::~GlContext() { platform_.release(platform_.handle); }

}  // namespace passtrace
