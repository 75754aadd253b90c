#include "apps/memory_check.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace passtrace {
namespace {

// Peak resident bytes per triangle, the slope between 1 M and 2 M triangles
// of the procedural "spheres" scene measured on llvmpipe (2-core Debian 12):
//   /usr/bin/time -f %M passtrace -s spheres --triangles N -r R -a A -w 64 -b 1 -t 1
// with N = 1,000,000 and 2,000,000. GPU runs include llvmpipe's texture
// copies (on a real GPU part of this lives in GPU memory instead).
const std::map<std::string, double> kGpuBytesPerTriangle = {
    {"kk-bvh", 255}, {"gs-bvh", 233}, {"kd-restart", 358}, {"kd-backtrack", 536}, {"grid", 1265}};
const std::map<std::string, double> kCpuBytesPerTriangle = {
    {"kk-bvh", 230},           {"gs-bvh", 232},           {"kd-tree", 282},     {"kd-pbrt", 947},
    {"grid", 1148},            {"kk-bvh-recursive", 164}, {"gs-bvh-recursive", 232}, {"octree", 70},
    {"kd-restart", 394}, {"kd-backtrack", 498}, {"grid-stream", 1243},
    {"embree", 202}};
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

const char* rendererName(int renderer) {
  switch (renderer) {
    case 0: return "preview";
    case 1: return "CPU";
    case 2: return "GPU stream";
    default: return "Embree";
  }
}

}  // namespace

uint64_t estimatedRunBytes(int renderer, const std::string& structure, uint64_t triangles, uint64_t pixels) {
  double perTriangle = kPreviewBytesPerTriangle;
  if (renderer == 1 || renderer == 2 || renderer == 3) {
    const auto& table = renderer == 2 ? kGpuBytesPerTriangle : kCpuBytesPerTriangle;
    const auto it = table.find(renderer == 3 ? "embree" : structure);
    // An unlisted structure (a new one): the most any listed one needs.
    perTriangle = 0;
    if (it != table.end()) perTriangle = it->second;
    else
      for (const auto& [name, bytes] : table) perTriangle = std::max(perTriangle, bytes);
  }
  const double perPixel = renderer == 2 || renderer == 0 ? kGpuBytesPerPixel : kCpuBytesPerPixel;
  return uint64_t(kMargin * (kBaseBytes + perTriangle * double(triangles) + perPixel * double(pixels)));
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

void checkRunFitsInMemory(const std::string& scene, int renderer, const std::string& structure, uint64_t triangles,
                          uint64_t pixels) {
  const auto available = availableMemoryBytes();
  if (!available) return;  // nothing to compare with: try
  const uint64_t needed = estimatedRunBytes(renderer, structure, triangles, pixels);
  if (needed <= *available) return;
  throw std::runtime_error(scene + ": " + std::to_string(triangles) + " triangles with " + structure + " on the " +
                           rendererName(renderer) + " renderer need about " + gib(double(needed)) + "; " +
                           gib(double(*available)) + " available (nothing was built)");
}

}  // namespace passtrace
