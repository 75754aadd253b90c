#include "stream/gl_error.h"

#include "stream/gl.h"

namespace passtrace {

static const char* glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY (out of GPU memory)";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
  }
}

void checkGlError(const std::string& what) {
  std::string errors;
  // glGetError can hold several flags; drain them all so the next check starts clean.
  for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
    if (!errors.empty()) errors += ", ";
    errors += glErrorName(e);
  }
  if (!errors.empty()) throw GlError(what + ": " + errors);
}

}  // namespace passtrace
