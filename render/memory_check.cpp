#include "render/memory_check.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace passtrace {
namespace {

constexpr double kPreviewBytesPerTriangle = 150;  // the scene plus one vertex buffer
constexpr double kBaseBytes = 200.0 * (1 << 20);  // the process, GL and llvmpipe at start
// Per pixel: the GPU ray stream (8 RGBA32F surfaces + depth, read-backs); the
// CPU renderer's path state and image.
constexpr double kGpuBytesPerPixel = 200, kCpuBytesPerPixel = 100;
constexpr double kMargin = 1.25;

std::optional<uint64_t> readNumber(const char* path) {
  std::ifstream in(path);
  uint64_t v = 0;
  if (in >> v) return v;
  return std::nullopt;
}

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / double(1ull << 30));
  return text;
}

const MemoryCost& costOn(RendererId renderer, const Structure& s) {
  return renderer == RendererId::Gpu ? s.memory.gpu : s.memory.cpu;
}

}  // namespace

uint64_t estimatedRunBytes(RendererId renderer, const Structure* structure, uint64_t triangles, uint64_t pixels,
                           double extraBytesPerPixel) {
  double sceneBytes = kPreviewBytesPerTriangle * double(triangles);
  if (structure) {
    const MemoryCost& cost = costOn(renderer, *structure);
    sceneBytes = cost.bytesFor(triangles);
    // Not measured (a new structure): the most any measured one needs there.
    if (cost.bytesPerTriangle <= 0)
      for (const Structure& s : structures())
        if (s.runsOn(renderer)) sceneBytes = std::max(sceneBytes, costOn(renderer, s).bytesFor(triangles));
  }
  const bool gl = renderer == RendererId::Gpu || renderer == RendererId::OpenGl;
  const double perPixel = (gl ? kGpuBytesPerPixel : kCpuBytesPerPixel) + extraBytesPerPixel;
  return uint64_t(kMargin * (kBaseBytes + sceneBytes + perPixel * double(pixels)));
}

uint64_t residentBytes() {
  // /proc/self/statm: total and resident pages.
  std::ifstream statm("/proc/self/statm");
  uint64_t total = 0, resident = 0;
  if (!(statm >> total >> resident)) return 0;
  return resident * uint64_t(sysconf(_SC_PAGESIZE));
}

std::optional<uint64_t> availableMemoryBytes() {
  std::optional<uint64_t> available;
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key;
    uint64_t kib = 0;
    if (fields >> key >> kib && key == "MemAvailable:") available = kib * 1024;
  }
  // Containers cap memory below what the host has (cgroup v2).
  const auto limit = readNumber("/sys/fs/cgroup/memory.max");  // "max" reads as no number
  const auto used = readNumber("/sys/fs/cgroup/memory.current");
  if (limit && used) {
    const uint64_t left = *limit > *used ? *limit - *used : 0;
    available = available ? std::min(*available, left) : left;
  }
  return available;
}

void checkRunFitsInMemory(const std::string& scene, RendererId renderer, const Structure* structure,
                          uint64_t triangles, uint64_t pixels, double extraBytesPerPixel) {
  auto available = availableMemoryBytes();
  if (!available) return;  // nothing to compare with: try
  // The estimate is the whole process's peak, and what it holds already (the
  // loaded scene: 4 GB of 100M spheres) is no longer counted as available.
  *available += residentBytes();
  const uint64_t needed = estimatedRunBytes(renderer, structure, triangles, pixels, extraBytesPerPixel);
  if (needed <= *available) return;
  throw std::runtime_error(scene + ": " + std::to_string(triangles) + " triangles with " +
                           std::string(structure ? structure->name : "preview") + " on the " +
                           std::string(rendererTitle(renderer)) + " renderer need about " + gib(double(needed)) + "; " +
                           gib(double(*available)) + " available (nothing was built)");
}

}  // namespace passtrace
