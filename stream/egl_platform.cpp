#include "stream/egl_platform.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace passtrace {
namespace {

struct EglHandle {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

void releaseEgl(void* p) {
  auto* h = static_cast<EglHandle*>(p);
  eglMakeCurrent(h->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (h->context != EGL_NO_CONTEXT) eglDestroyContext(h->display, h->context);
  eglTerminate(h->display);
  delete h;
}

std::string eglErrorString() {
  char buf[32];
  std::snprintf(buf, sizeof buf, "EGL error 0x%04x", eglGetError());
  return buf;
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Initialises `display` and creates a current GL 4.5 core context on it with no surface.
bool makeContext(EGLDisplay display, EglHandle& h, std::string& error) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    error = "eglInitialize failed (" + eglErrorString() + ")";
    return false;
  }
  h.display = display;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    error = "eglBindAPI(EGL_OPENGL_API) failed (" + eglErrorString() + ")";
    return false;
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_NONE};
  const char* exts = eglQueryString(display, EGL_EXTENSIONS);
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!hasExtension(exts, "EGL_KHR_no_config_context")) {
    // Drivers without configless contexts still accept any GL-renderable config.
    const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1) {
      error = "no EGL config renders OpenGL";
      return false;
    }
  }
  h.context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
  if (h.context == EGL_NO_CONTEXT) {
    error = "no OpenGL 4.5 core context (" + eglErrorString() + ")";
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, h.context)) {
    error = "eglMakeCurrent without a surface failed (" + eglErrorString() + ")";
    return false;
  }
  return true;
}

// EGL devices, hardware ones first (Mesa marks its software device).
std::vector<EGLDeviceEXT> listDevices(size_t& hardwareCount) {
  hardwareCount = 0;
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (!queryDevices || !queryString) return {};
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!queryDevices(16, devices, &count)) return {};
  std::vector<EGLDeviceEXT> hardware, software;
  for (EGLint i = 0; i < count; ++i) {
    const bool isSoftware = hasExtension(queryString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
    (isSoftware ? software : hardware).push_back(devices[i]);
  }
  hardwareCount = hardware.size();
  hardware.insert(hardware.end(), software.begin(), software.end());
  return hardware;
}

// The hardware device this process uses (egl_platform.h), of `count`; the
// variable is read only where there are hardware devices to choose from.
size_t chosenHardwareDevice(size_t count) {
  if (const char* given = std::getenv("PASSTRACE_EGL_DEVICE")) {
    char* end = nullptr;
    const long k = std::strtol(given, &end, 10);
    if (end == given || *end != '\0' || k < 0 || size_t(k) >= count)
      throw std::runtime_error("PASSTRACE_EGL_DEVICE=" + std::string(given) + ": not one of the " +
                               std::to_string(count) + " hardware EGL devices (0 to " + std::to_string(count - 1) + ")");
    return size_t(k);
  }
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_RANK", "SLURM_LOCALID", "MPI_LOCALRANKID"})
    if (const char* local = std::getenv(name)) return size_t(std::strtoul(local, nullptr, 10)) % count;
  return 0;
}

bool tryDisplay(EGLDisplay display, const char* backend, PlatformContext& out, std::string& error) {
  auto* h = new EglHandle;
  std::string why;
  if (display != EGL_NO_DISPLAY && makeContext(display, *h, why)) {
    out = PlatformContext{backend, reinterpret_cast<PlatformContext::ProcLoader>(&eglGetProcAddress), &releaseEgl, h};
    return true;
  }
  if (display == EGL_NO_DISPLAY) why = "no display (" + eglErrorString() + ")";
  error += std::string(error.empty() ? "" : "; ") + backend + ": " + why;
  if (h->display != EGL_NO_DISPLAY) eglTerminate(h->display);
  delete h;
  return false;
}

}  // namespace

bool createEglContext(PlatformContext& out, std::string& error) {
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) {
    error = "EGL lacks eglGetPlatformDisplayEXT";
    return false;
  }
  size_t hardwareCount = 0;
  std::vector<EGLDeviceEXT> devices = listDevices(hardwareCount);
  const bool anyHardware = hardwareCount > 0;
  // The chosen device first; the others stay fallbacks.
  if (anyHardware) std::swap(devices[0], devices[chosenHardwareDevice(hardwareCount)]);
  if (anyHardware &&
      tryDisplay(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices.front(), nullptr), "egl-device", out, error))
    return true;
  if (tryDisplay(getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                 "egl-surfaceless", out, error))
    return true;
  for (size_t i = anyHardware ? 1 : 0; i < devices.size(); ++i)
    if (tryDisplay(getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "egl-device", out, error))
      return true;
  if (devices.empty()) error += std::string(error.empty() ? "" : "; ") + "no EGL devices";
  return false;
}

}  // namespace passtrace
