#pragma once
// Compiling and linking a vertex + fragment program from kernels_glsl/ files,
// or a fragment kernel's compute variant, with failures reported by kernel
// name, GLSL file and line.

#include <string>
#include <vector>

#include "stream/gl.h"

namespace passtrace {

// Returns the linked program. Throws GlError("kernel NAME (FILE): compile
// failed: FILE:LINE ...") with the driver's log translated to file lines.
GLuint linkProgram(const std::string& name, const std::string& vertexFile, const std::string& fragmentFile,
                   const std::vector<std::string>& defines = {});
// The compute variant of fragment kernel `fragmentFile` (compute_variant.h),
// with errors reported as above.
GLuint linkComputeProgram(const std::string& name, const std::string& fragmentFile,
                          const std::vector<std::string>& defines = {});
// A compute shader written as one (kernels_glsl/*.comp), reported as above.
GLuint linkComputeShader(const std::string& name, const std::string& computeFile);

}  // namespace passtrace
