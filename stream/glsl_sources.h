#pragma once
// The GLSL files of kernels_glsl/, embedded in the binary at build time
// (cmake/embed_glsl.cmake), and the #include resolution that assembles one
// kernel's source from them.

#include <string>
#include <string_view>
#include <vector>

namespace passtrace {

struct GlslFile {
  const char* name;  // path inside kernels_glsl/, e.g. "intersect.glsl" or "kd/kd_traverse.frag"
  const char* text;
};

const std::vector<GlslFile>& embeddedGlslFiles();

// A kernel's source with every `#include "file"` expanded. GLSL #line
// directives number each file's lines; `files[k]` is the file whose text
// carries source-string number k, so driver logs can be translated back.
struct AssembledGlsl {
  std::string source;
  std::vector<std::string> files;

  // Rewrites "S:L(C)" / "S:L:" locations in a driver log as "file:L".
  std::string translateLog(std::string_view log) const;
};

// Assembles `name` (a file of kernels_glsl/) with "#version 450" first and the
// `defines` lines after it. Throws std::runtime_error for a missing file or
// an include cycle.
AssembledGlsl assembleGlsl(const std::string& name, const std::vector<std::string>& defines = {});

}  // namespace passtrace
