#pragma once
// OSMesa, the second backend. Kept in its own translation unit because
// GL/osmesa.h pulls in GL/gl.h, which must not meet glad's header.

#include <string>

#include "stream/gl_context.h"

namespace passtrace {

bool createOsMesaContext(PlatformContext& out, std::string& error);

}  // namespace passtrace
