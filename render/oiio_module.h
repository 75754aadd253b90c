#pragma once
// The image formats other than OpenEXR (.png, .jpg, .tif, .hdr, ...) are
// written by OpenImageIO in a module of their own, libpasstrace_oiio.so
// (render/oiio_module.cpp), loaded the first time such a file is named: see
// render/exr_io.h for why OpenImageIO is not linked into passtrace.

#include <filesystem>
#include <string>
#include <vector>

namespace passtrace {

struct OiioModule {
  // Throws unless OpenImageIO can write the format to memory.
  void (*checkFormat)(const std::filesystem::path& path);
  // encodeImage's contract (render/image_output.h) for these formats.
  std::string (*encodeImage)(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb);
};

// The module, loaded on first use from $PASSTRACE_OIIO_MODULE, else beside the
// running program, else the installed or the build tree's copy. Throws
// std::runtime_error("PATH: reason") naming `forFile` when none loads.
const OiioModule& oiioModule(const std::filesystem::path& forFile);

}  // namespace passtrace

// The module's one exported symbol.
extern "C" const passtrace::OiioModule* passtrace_oiio_module();
