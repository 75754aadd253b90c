// render/image_output.h for a build without OpenImageIO (-DPASSTRACE_IMAGE_OUTPUT=OFF,
// e.g. a benchmark binary carried to a GPU server whose image lacks OpenImageIO's
// dependencies): every image or hit-buffer file is a one-line error, which
// session.cpp raises before anything is built.
#include <stdexcept>

#include "render/image_output.h"

namespace passtrace {
namespace {

[[noreturn]] void unavailable(const std::filesystem::path& path) {
  throw std::runtime_error(path.string() +
                           ": this passtrace was built without OpenImageIO (PASSTRACE_IMAGE_OUTPUT=OFF): no image files");
}

}  // namespace

void checkImageFormat(const std::filesystem::path& path) { unavailable(path); }
std::string encodeImage(const std::filesystem::path& path, int, int, const std::vector<float>&) { unavailable(path); }
std::vector<float> readImage(const std::filesystem::path& path, int&, int&) { unavailable(path); }
std::string encodeHitBuffer(const std::filesystem::path& path, int, int, const std::vector<HitRecord>&) {
  unavailable(path);
}
std::vector<HitRecord> readHitBuffer(const std::filesystem::path& path, int&, int&) { unavailable(path); }
std::string encodeConeHitBuffer(const std::filesystem::path& path, int, int, const std::vector<ConeHitRecord>&) {
  unavailable(path);
}
std::vector<ConeHitRecord> readConeHitBuffer(const std::filesystem::path& path, int&, int&) { unavailable(path); }

}  // namespace passtrace
