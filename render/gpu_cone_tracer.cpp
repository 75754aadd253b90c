#include "render/gpu_cone_tracer.h"

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

namespace passtrace {
namespace {

// Floats before a record's stack (kernels_glsl/cone/cone_record.glsl: CONE_HEADER).
constexpr uint64_t kConeRecordHeader = 12;

float bits(uint32_t u) { return std::bit_cast<float>(u); }

void pushDouble(std::vector<float>& out, double d) {
  const uint64_t b = std::bit_cast<uint64_t>(d);
  out.push_back(bits(uint32_t(b)));  // packDouble2x32: x the low word
  out.push_back(bits(uint32_t(b >> 32)));
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
  const uint32_t tableSize = std::bit_ceil(2 * uint64_t(gpu.capacity)) > (uint64_t(1) << 31)
                                 ? 0u
                                 : uint32_t(std::bit_ceil(2 * uint64_t(gpu.capacity)));
  if (config.maxHits == 0 && tableSize == 0)
    throw std::runtime_error("--cone-capacity " + std::to_string(gpu.capacity) + " is too large");
  const uint64_t hitFloats = config.maxHits > 0 ? 2 * uint64_t(config.maxHits) : tableSize;
  const uint32_t stackSize = tree.stackSize;
  const uint64_t stride = kConeRecordHeader + 3 * uint64_t(stackSize) + hitFloats;
  constexpr uint64_t kMaxRecordFloats = uint64_t(1) << 30;  // 4 GiB
  if (elements * stride > kMaxRecordFloats)
    throw std::runtime_error("--cone on the stream path: " + std::to_string(width) + "x" + std::to_string(height) +
                             " cones with lists of " + std::to_string(capacity) + " need " +
                             std::to_string((elements * stride * 4) >> 20) +
                             " MiB of records (at most 4096): use a smaller -s or --cone-max");
  // A pass must have room for one triangle and its insertion into the list
  // (cone_record.glsl: insertWork), or the kernel could not progress.
  const auto* glRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const uint32_t workBudget = shaderLoopBudget(glRenderer ? glRenderer : "");
  const uint64_t maxHitsLimit = workBudget > 200 ? workBudget - 200 : 0;
  if (config.maxHits > maxHitsLimit)
    throw std::runtime_error("--cone-max " + std::to_string(config.maxHits) + ": the stream path on this driver keeps at most " +
                             std::to_string(maxHitsLimit) +
                             " sorted triangles per cone (its shader loops are capped); use -r 1 or --cone-max 0");

  // The cones: the CPU's primary rays and Eq. 2's spread, as KdConeTraversal has them.
  std::vector<float> cones;
  cones.reserve(4 + 16 * elements);
  pushDouble(cones, std::cos(double(halfAngle)));
  pushDouble(cones, std::sin(double(halfAngle)));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = primaryRay(camera, x, y);
      const Cone cone{ray.origin, ray.direction, halfAngle};
      const glm::vec3 k = coneSpread(cone);
      const glm::dvec3 v = glm::normalize(glm::dvec3(cone.axis));
      cones.insert(cones.end(), {cone.apex.x, cone.apex.y, cone.apex.z, cone.axis.x, cone.axis.y, cone.axis.z, k.x,
                                 k.y, k.z, 0.0f});
      for (int a = 0; a < 3; ++a) pushDouble(cones, v[a]);
    }
  StorageBuffer treeData("cone tree"), coneData("cones"), records("cone records (stacks and hit lists)");
  treeData.upload(tree.data);
  coneData.upload(cones);
  records.reserve(elements * stride);

  InOutStream stream(width, height, 1);
  StreamKernel kernel("cone", tree.kernel);
  kernel.bindStorage(0, records);
  kernel.bindStorage(1, treeData);
  kernel.bindStorage(2, coneData);
  kernel.set("uStreamWidth", uint32_t(width));
  kernel.set("uRecordFloats", uint32_t(stride));
  kernel.set("uStackSize", stackSize);
  kernel.set("uCapacity", gpu.capacity);
  kernel.set("uTableSize", tableSize);
  kernel.set("uWorkBudget", workBudget);
  kernel.set("uMaxHits", config.maxHits);
  kernel.set("uNodeCount", tree.nodeCount);
  kernel.set("uNodeBase", tree.nodeBase);
  kernel.set("uRefBase", tree.refBase);
  kernel.set("uTriBase", tree.triBase);
  stream.enable();
  stream.setWriteSurfaces({0});
  stream.clearDepth(1.0f);
  // Untimed: llvmpipe compiles a kernel on its first draw. With no steps the
  // pass only starts each cone (root box), a state the next pass resumes.
  kernel.set("uLoopLimit", 0);
  kernel.execute();
  kernel.set("uLoopLimit", gpu.loopLimit);
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  while (kernel.execute(true) > 0) {
  }
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stream.disable();

  const std::vector<float> data = records.read(elements * stride);
  ConeFrame frame;
  frame.width = width, frame.height = height, frame.ms = ms;
  frame.hits.resize(elements);
  frame.nodes.resize(elements);
  frame.triangles.resize(elements);
  for (uint64_t e = 0; e < elements; ++e) {
    const float* r = data.data() + e * stride;
    if (r[0] == 3.0f)
      throw std::runtime_error("--cone-max 0 on the stream path: the cone of pixel (" + std::to_string(e % width) +
                               ", " + std::to_string(e / width) + ") meets more than " + std::to_string(capacity) +
                               " triangles, its list's capacity: raise --cone-capacity, or use --cone-max N or -r 1");
    const uint32_t count = std::bit_cast<uint32_t>(r[5]);
    // The nearest: the sorted list's first entry, or the set's record of it.
    const float* nearest = config.maxHits > 0 ? r + kConeRecordHeader + 3 * stackSize : r + 9;
    frame.hits[e] = count == 0 ? ConeHitRecord{0, kNoHit, kInfinity}
                               : ConeHitRecord{count, std::bit_cast<uint32_t>(nearest[1]), nearest[0]};
    frame.nodes[e] = std::bit_cast<uint32_t>(r[6]);
    frame.triangles[e] = std::bit_cast<uint32_t>(r[7]);
  }
  return frame;
}

}  // namespace passtrace
