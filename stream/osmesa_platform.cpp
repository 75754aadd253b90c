#include "stream/osmesa_platform.h"

#include <GL/osmesa.h>

namespace passtrace {
namespace {

struct OsMesaHandle {
  OSMesaContext context = nullptr;
  unsigned char pixel[4] = {};  // OSMesaMakeCurrent needs a buffer; rendering goes to FBOs
};

void releaseOsMesa(void* p) {
  auto* h = static_cast<OsMesaHandle*>(p);
  OSMesaDestroyContext(h->context);
  delete h;
}

}  // namespace

bool createOsMesaContext(PlatformContext& out, std::string& error) {
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
  auto* h = new OsMesaHandle;
  h->context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!h->context) {
    delete h;
    error = "osmesa: no OpenGL 4.5 core context";
    return false;
  }
  if (!OSMesaMakeCurrent(h->context, h->pixel, GL_UNSIGNED_BYTE, 1, 1)) {
    releaseOsMesa(h);
    error = "osmesa: OSMesaMakeCurrent failed";
    return false;
  }
  // libOSMesa does not export every GL function; its GetProcAddress has them all.
  out = PlatformContext{"osmesa", reinterpret_cast<PlatformContext::ProcLoader>(&OSMesaGetProcAddress),
                        &releaseOsMesa, h};
  return true;
}

}  // namespace passtrace
