#pragma once
// EGL contexts without a window system: the device platform (which is how a
// headless program reaches an NVIDIA GPU) and Mesa's surfaceless platform.

#include <string>

#include "stream/gl_context.h"

namespace passtrace {

// Tries a hardware EGL device first, then the surfaceless platform, then any
// (software) EGL device. Returns false with `error` set if none gives a 4.5
// core context; the context is current on success.
bool createEglContext(PlatformContext& out, std::string& error);

}  // namespace passtrace
