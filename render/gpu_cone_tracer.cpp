#include "render/gpu_cone_tracer.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "accel/cone/cone_tests.h"
#include "stream/gl.h"
#include "stream/inout_stream.h"
#include "stream/shader_loop_budget.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"
#include "stream/texel_address.h"

namespace passtrace {
namespace {

// Floats before a record's stack (kernels_glsl/cone/cone_record.glsl: CONE_HEADER).
constexpr uint64_t kConeRecordHeader = 12;

void pushDouble(std::vector<float>& out, double d) {
  const uint64_t b = std::bit_cast<uint64_t>(d);
  out.push_back(bitsAsFloat(uint32_t(b)));  // packDouble2x32: x the low word
  out.push_back(bitsAsFloat(uint32_t(b >> 32)));
}

}  // namespace

ConeFrame traceConesGpu(const ConeStreamTree& tree, const CameraBasis& camera,
                        float halfAngle, const ConeQueryConfig& config, const GpuConeConfig& gpu) {
  if (config.maxHits > gpu.capacity)
    throw std::runtime_error("--cone-max " + std::to_string(config.maxHits) + ": the stream path keeps at most " +
                             std::to_string(gpu.capacity) + " triangles per cone");
  if (config.tNear != 0.0f || config.tFar != kInfinity)
    throw std::runtime_error("cone queries on the stream path take the whole axis (no t-near/t-far)");
  const int width = camera.width, height = camera.height;
  InOutStream::checkSize(width, height);
  const uint64_t elements = uint64_t(width) * uint64_t(height);
  const uint32_t capacity = config.maxHits > 0 ? config.maxHits : gpu.capacity;
  // --cone-max N keeps a sorted list of N; --cone-max 0 a set (open
  // addressing) at most half full.
  const uint64_t tableSize = std::bit_ceil(2 * uint64_t(gpu.capacity));
  const uint64_t hitFloats = config.maxHits > 0 ? 2 * uint64_t(config.maxHits) : tableSize;
  const uint32_t stackSize = tree.stackSize;
  const uint64_t stride = kConeRecordHeader + 3 * uint64_t(stackSize) + hitFloats;
  // The records of one band of cones must fit one storage buffer binding:
  // the driver's block size and 1 GiB (llvmpipe addresses a buffer with
  // 32-bit signed byte offsets: beyond 2 GiB it crashes).
  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  const uint64_t bandFloats =
      std::min({uint64_t(std::max<GLint64>(maxBlock, 0)), uint64_t(1) << 30, gpu.maxBandBytes}) / 4;
  if (stride > bandFloats)
    throw std::runtime_error("--cone-capacity " + std::to_string(gpu.capacity) + ": one cone's record (" +
                             std::to_string((stride * 4) >> 10) + " KiB) exceeds this driver's storage buffers (" +
                             std::to_string((bandFloats * 4) >> 10) + " KiB): use a smaller --cone-capacity or -r 1");
  const uint64_t band = std::min(elements, bandFloats / stride);
  // A pass must have room for one triangle and its insertion into the list
  // (cone_record.glsl: insertWork), or the kernel could not progress.
  const auto* glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const uint32_t workBudget = shaderLoopBudget(glRenderer ? glRenderer : "");
  const uint64_t maxHitsLimit = workBudget > 200 ? workBudget - 200 : 0;
  if (config.maxHits > maxHitsLimit)
    throw std::runtime_error("--cone-max " + std::to_string(config.maxHits) +
                             ": the stream path on this driver keeps at most " +
                             std::to_string(maxHitsLimit) +
                             " sorted triangles per cone (its shader loops are capped); use -r 1 or --cone-max 0");

  StorageBuffer treeData("cone tree"), coneData("cones"), records("cone records (stacks and hits)");
  treeData.upload(tree.data);
  StreamKernel kernel("cone", tree.kernel);
  kernel.bindStorage(1, treeData);
  kernel.set("uRecordFloats", uint32_t(stride));
  kernel.set("uStackSize", stackSize);
  kernel.set("uCapacity", gpu.capacity);
  kernel.set("uTableSize", uint32_t(tableSize));
  kernel.set("uWorkBudget", workBudget);
  kernel.set("uMaxHits", config.maxHits);
  kernel.set("uNodeCount", tree.nodeCount);
  kernel.set("uNodeBase", tree.nodeBase);
  kernel.set("uRefBase", tree.refBase);
  kernel.set("uTriBase", tree.triBase);

  ConeFrame frame;
  frame.width = width, frame.height = height;
  frame.hits.resize(elements);
  frame.nodes.resize(elements);
  frame.triangles.resize(elements);
  // Bands of `band` cones in pixel order, each a stream of its own.
  for (uint64_t first = 0; first < elements; first += band) {
    const uint64_t count = std::min(band, elements - first);
    const int streamWidth = int(std::min<uint64_t>(count, uint64_t(width)));
    const int streamRows = int((count + streamWidth - 1) / streamWidth);
    // The cones: the CPU's primary rays and Eq. 2's spread, as KdConeTraversal has them.
    std::vector<float> cones;
    cones.reserve(4 + 16 * count);
    pushDouble(cones, std::cos(double(halfAngle)));
    pushDouble(cones, std::sin(double(halfAngle)));
    for (uint64_t p = first; p < first + count; ++p) {
      const Ray ray = primaryRay(camera, int(p % width), int(p / width));
      const Cone cone{ray.origin, ray.direction, halfAngle};
      const glm::vec3 k = coneSpread(cone);
      const glm::dvec3 v = glm::normalize(glm::dvec3(cone.axis));
      cones.insert(cones.end(), {cone.apex.x, cone.apex.y, cone.apex.z, cone.axis.x, cone.axis.y, cone.axis.z, k.x,
                                 k.y, k.z, 0.0f});
      for (int a = 0; a < 3; ++a) pushDouble(cones, v[a]);
    }
    coneData.upload(cones);
    records.reserve(count * stride);
    if (first > 0) records.zero(count * stride);
    kernel.bindStorage(0, records);
    kernel.bindStorage(2, coneData);
    kernel.set("uStreamWidth", uint32_t(streamWidth));
    kernel.set("uElementCount", uint32_t(count));

    InOutStream stream(streamWidth, streamRows, 1);
    stream.enable();
    stream.setWriteSurfaces({0});
    stream.clearDepth(1.0f);
    // Untimed: llvmpipe compiles a kernel on its first draw. With no steps the
    // pass only starts each cone (root box), a state the next pass resumes.
    kernel.set("uLoopLimit", 0);
    kernel.execute();
    kernel.set("uLoopLimit", passStepLimit(gpu.loopLimit));
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    while (kernel.execute(true) > 0) {
    }
    glFinish();
    frame.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stream.disable();

    const std::vector<float> data = records.read(count * stride);
    for (uint64_t e = 0; e < count; ++e) {
      const float* r = data.data() + e * stride;
      const uint64_t p = first + e;
      if (r[0] == 3.0f)
        throw std::runtime_error("--cone-max 0 on the stream path: the cone of pixel (" + std::to_string(p % width) +
                                 ", " + std::to_string(p / width) + ") meets more than " + std::to_string(capacity) +
                                 " triangles, its list's capacity: raise --cone-capacity, or use --cone-max N or -r 1");
      const uint32_t met = std::bit_cast<uint32_t>(r[5]);
      // The nearest: the sorted list's first entry, or the set's record of it.
      const float* nearest = config.maxHits > 0 ? r + kConeRecordHeader + 3 * stackSize : r + 9;
      frame.hits[p] = met == 0 ? ConeHitRecord{0, kNoHit, kInfinity}
                               : ConeHitRecord{met, std::bit_cast<uint32_t>(nearest[1]), nearest[0]};
      frame.nodes[p] = std::bit_cast<uint32_t>(r[6]);
      frame.triangles[p] = std::bit_cast<uint32_t>(r[7]);
    }
  }
  return frame;
}

}  // namespace passtrace
