#pragma once
// Every GL failure becomes a GlError whose message says what was being done
// (the kernel, the stream) and what the driver reported.

#include <stdexcept>
#include <string>

namespace passtrace {

struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws GlError naming `what` if glGetError reports anything; GL_OUT_OF_MEMORY
// is spelled out as running out of GPU memory.
void checkGlError(const std::string& what);

}  // namespace passtrace
