#pragma once
// The one way passtrace code includes OpenGL: glad's GL 4.5 core table, filled
// from whichever backend created the context (stream/gl_context.h).
#include <glad/gl.h>
