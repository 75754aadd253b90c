// The stream path's ceiling on this driver: what one texel fetch costs in a
// fragment kernel (kernels_glsl/texel_fetch_probe.frag), the unit every
// stream traversal step is made of (bvh-octant: two texels per box step, three
// per triangle step). The FP32 peak and the memory bandwidth of the roofline
// (measure_machine_peak) say little about llvmpipe, which fetches lane by lane.
//
// One full-screen pass of WIDTH x WIDTH elements, each reading FETCHES texels
// of a TEXELS-texel table, against the same pass reading none: the difference
// over WIDTH^2 x FETCHES is the cost of a fetch, with the pass's fixed cost
// (the quad, the write) taken out. Four ways:
//   chain:       each address comes from the texel before (a walk's next index);
//   independent: the same addresses, computed from the start alone;
//   coherent:    the elements of an 8x8 block read the same texels (primary rays);
//   scattered:   every element reads its own (incoherent rays).
// Checks that every element read the texels its way names. Prints one JSON
// line per way: the minimum of each pass over REPEATS (glFinish and a steady
// clock, after an untimed warm-up), ns per fetch per element and G fetches/s
// over the whole pass (all llvmpipe threads; null where the two passes' times
// were too close to tell apart).
//
//   build/tests/measure/measure_texel_fetch [WIDTH=512] [REPEATS=5] [FETCHES=32] [TEXELS=2097152]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "stream/const_input_stream.h"
#include "stream/gl_context.h"
#include "stream/inout_stream.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"
#include "tests/measure/renderer_rays.h"

namespace {

using namespace passtrace;
using Clock = std::chrono::steady_clock;

struct Way {
  const char* name;
  bool dependent;
  uint32_t tile;  // elements of a tile x tile block share their addresses
};

// texel_fetch_probe.frag's startOf: where the elements of `block` start reading.
uint32_t startOf(uint32_t bx, uint32_t by, uint32_t tableSize, uint32_t fetches) {
  uint32_t h = (bx * 0x9E3779B1u) ^ (by * 0x85EBCA77u);
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return h % (tableSize - fetches);
}

// The probe's pass over every element; milliseconds.
double passMs(StreamKernel& kernel, InOutStream& stream) {
  stream.enable();
  stream.clearDepth(1.0f);
  stream.setWriteSurfaces({0});
  glFinish();
  const auto start = Clock::now();
  kernel.execute();
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  stream.disable();
  return ms;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const int width = argc > 1 ? parsePositiveInt("WIDTH", argv[1]) : 512;
    const int repeats = argc > 2 ? parsePositiveInt("REPEATS", argv[2]) : 5;
    const int fetches = argc > 3 ? parsePositiveInt("FETCHES", argv[3]) : 32;
    const uint32_t texels = argc > 4 ? uint32_t(parsePositiveInt("TEXELS", argv[4])) : 1u << 21;
    if (texels <= uint32_t(fetches))
      throw std::invalid_argument("TEXELS: '" + std::to_string(texels) + "' is not more than FETCHES (" +
                                  std::to_string(fetches) + ")");
    constexpr uint32_t kMostTexels = 1u << 26;  // 1 GiB of RGBA32F, llvmpipe's largest texture
    if (texels > kMostTexels)
      throw std::invalid_argument("TEXELS: '" + std::string(argv[4]) + "' is more than " + std::to_string(kMostTexels));

    const auto context = GlContext::create(GlBackend::Auto);
    std::vector<glm::vec4> table(texels);
    for (uint32_t i = 0; i < texels; ++i)  // texel i names i + 1, as the probe's independent way computes it
      table[i] = glm::vec4(float(i & 1023u), 1.0f, 0.5f, packIndex(i + 1u));
    const ConstInputStream data(table, "the probe's table");
    StreamKernel kernel("texel_fetch_probe", "texel_fetch_probe.frag", StreamKernel::Depth::Test,
                        {streamPagesDefine({&data})});
    kernel.bindInput("uTable", data);
    kernel.set("uTableSize", texels);
    InOutStream stream(width, width, 1);

    const Way ways[] = {{"chain, coherent", true, 8},
                        {"chain, scattered", true, 1},
                        {"independent, coherent", false, 8},
                        {"independent, scattered", false, 1}};
    for (const Way& way : ways) {
      kernel.set("uDependent", int(way.dependent));
      kernel.set("uTile", way.tile);
      double none = std::numeric_limits<double>::infinity(), all = none;
      for (int r = -1; r < repeats; ++r) {  // -1: a warm-up (llvmpipe compiles at the first draw)
        kernel.set("uFetches", 0);
        const double a = passMs(kernel, stream);
        kernel.set("uFetches", fetches);
        const double b = passMs(kernel, stream);
        if (r >= 0) none = std::min(none, a), all = std::min(all, b);
      }
      // Each element sums the texels start .. start + FETCHES - 1 (x = i mod 1024, y = 1, z = 0.5): small
      // integers and halves, exact in float, so any other read shows.
      const std::vector<glm::vec4> sums = stream.read(0);
      for (int y = 0; y < width; ++y)
        for (int x = 0; x < width; ++x) {
          const uint32_t start = startOf(uint32_t(x) / way.tile, uint32_t(y) / way.tile, texels, uint32_t(fetches));
          float expectX = 0.0f;
          for (uint32_t i = start; i < start + uint32_t(fetches); ++i) expectX += float(i & 1023u);
          const glm::vec4& sum = sums[size_t(y) * size_t(width) + size_t(x)];
          if (sum.x != expectX || sum.y != float(fetches) || sum.z != 0.5f * float(fetches))
            throw std::runtime_error(std::string(way.name) + ": element (" + std::to_string(x) + ", " +
                                     std::to_string(y) + ") read other texels than its own");
        }
      const double perFetchNs = (all - none) * 1e6 / (double(width) * width * fetches);
      const std::string ns = perFetchNs > 0 ? std::to_string(perFetchNs) : "null";
      const std::string rate = perFetchNs > 0 ? std::to_string(1.0 / perFetchNs) : "null";
      std::printf("{\"renderer\": \"%s\", \"way\": \"%s\", \"width\": %d, \"fetches\": %d, \"texels\": %u, "
                  "\"pass_ms\": %.3f, \"empty_pass_ms\": %.3f, \"ns_per_fetch\": %s, \"g_fetches_per_s\": %s}\n",
                  reinterpret_cast<const char*>(glGetString(GL_RENDERER)), way.name, width, fetches, texels, all, none,
                  ns.c_str(), rate.c_str());
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "measure_texel_fetch: %s\n", e.what());
    return 1;
  }
}
