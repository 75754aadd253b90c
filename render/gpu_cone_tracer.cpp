#include "render/gpu_cone_tracer.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "accel/cone/cone_tests.h"
#include "stream/gl.h"
#include "stream/inout_stream.h"
#include "stream/storage_buffer.h"
#include "stream/stream_kernel.h"

namespace passtrace {
namespace {

float bits(uint32_t u) { return std::bit_cast<float>(u); }

void pushDouble(std::vector<float>& out, double d) {
  const uint64_t b = std::bit_cast<uint64_t>(d);
  out.push_back(bits(uint32_t(b)));  // packDouble2x32: x the low word
  out.push_back(bits(uint32_t(b >> 32)));
}

// The tree buffer of kd_cone.frag: root box, nodes, references, triangles.
std::vector<float> treeBuffer(const KdTree& tree, std::span<const Triangle> tris, uint32_t& nodeBase,
                              uint32_t& refBase, uint32_t& triBase) {
  std::vector<float> out;
  for (int a = 0; a < 3; ++a) out.push_back(tree.bounds.min[a]);
  for (int a = 0; a < 3; ++a) out.push_back(tree.bounds.max[a]);
  nodeBase = uint32_t(out.size());
  for (const KdNode& n : tree.nodes) {
    out.push_back(n.split);
    out.push_back(bits(n.axis));
    out.push_back(bits(n.rightChild));
    out.push_back(bits(n.firstRef));
    out.push_back(bits(n.refCount));
  }
  refBase = uint32_t(out.size());
  for (uint32_t r : tree.references) out.push_back(bits(r));
  triBase = uint32_t(out.size());
  for (const Triangle& t : tris)
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) out.insert(out.end(), {p.x, p.y, p.z});
  return out;
}

}  // namespace

ConeFrame traceConesGpu(const KdTree& tree, std::span<const Triangle> tris, const CameraBasis& camera,
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
  const uint32_t stackSize = tree.depth() + 1;  // at most one push per level
  const uint64_t stride = 8 + 3 * uint64_t(stackSize) + 2 * uint64_t(capacity);
  constexpr uint64_t kMaxRecordFloats = uint64_t(1) << 30;  // 4 GiB
  if (elements * stride > kMaxRecordFloats)
    throw std::runtime_error("--cone on the stream path: " + std::to_string(width) + "x" + std::to_string(height) +
                             " cones with lists of " + std::to_string(capacity) + " need " +
                             std::to_string((elements * stride * 4) >> 20) +
                             " MiB of records (at most 4096): use a smaller -s or --cone-max");

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
  uint32_t nodeBase = 0, refBase = 0, triBase = 0;
  StorageBuffer treeData("cone kd-tree"), coneData("cones"), records("cone records (stacks and hit lists)");
  treeData.upload(treeBuffer(tree, tris, nodeBase, refBase, triBase));
  coneData.upload(cones);
  records.reserve(elements * stride);

  InOutStream stream(width, height, 1);
  StreamKernel kernel("kd-cone", "cone/kd_cone.frag");
  kernel.bindStorage(0, records);
  kernel.bindStorage(1, treeData);
  kernel.bindStorage(2, coneData);
  kernel.set("uStreamWidth", uint32_t(width));
  kernel.set("uStackSize", stackSize);
  kernel.set("uCapacity", capacity);
  kernel.set("uMaxHits", config.maxHits);
  kernel.set("uNodeCount", uint32_t(tree.nodes.size()));
  kernel.set("uNodeBase", nodeBase);
  kernel.set("uRefBase", refBase);
  kernel.set("uTriBase", triBase);
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
    const float* hits = r + 8 + 3 * stackSize;
    frame.hits[e] = count == 0 ? ConeHitRecord{0, kNoHit, kInfinity}
                               : ConeHitRecord{count, std::bit_cast<uint32_t>(hits[1]), hits[0]};
    frame.nodes[e] = std::bit_cast<uint32_t>(r[6]);
    frame.triangles[e] = std::bit_cast<uint32_t>(r[7]);
  }
  return frame;
}

}  // namespace passtrace
