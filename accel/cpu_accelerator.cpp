#include "accel/cpu_accelerator.h"

#include <array>
#include <chrono>
#include <stdexcept>

#include "accel/brute_force.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_traversal.h"
#include "accel/bvh/escape_sequence.h"
#include "accel/grid_accelerators.h"
#include "accel/kd/kd_accelerator.h"

namespace passtrace {
namespace {

struct AcceleratorInfo {
  const char* name;
  const char* thesisName;
};

constexpr std::array<AcceleratorInfo, 8> kAccelerators{{
    {"kk-bvh", "K/K BVH, sequential"},
    {"gs-bvh", "G/S BVH, sequential"},
    {"kd-tree", "Kd-tree"},
    {"kd-pbrt", "Kd-tree (pbrt)"},
    {"grid", "Uniform grid"},
    {"kk-bvh-recursive", "K/K BVH, recursive"},
    {"gs-bvh-recursive", "G/S BVH, recursive"},
    {"octree", "Octree"},
}};

const AcceleratorInfo& info(int number) {
  if (number < 0 || number >= static_cast<int>(kAccelerators.size()))
    throw std::invalid_argument("accelerator " + std::to_string(number) + " does not exist (valid: 0-7)");
  return kAccelerators[number];
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Tree shape statistics shared by both K/K forms.
}  // namespace

AccelStats bvhStats(int number, const Bvh& bvh) {
  AccelStats s;
  s.name = acceleratorName(number);
  s.nodes = bvh.nodes.size();
  s.leaves = bvh.leafCount();
  s.references = s.leaves;
  s.depth = bvh.depth();
  s.floatsPerTriangle = s.leaves == 0 ? 0.0 : 8.0 * static_cast<double>(s.nodes - s.leaves) / static_cast<double>(s.leaves);
  return s;
}

namespace {

// A BVH's escape-index sequence, traversed as the GPU does (0 and 1). Keeps
// only the sequence, which carries its own copy of the vertices.
class SequenceAccelerator final : public CpuAccelerator {
public:
  SequenceAccelerator(SequenceBuild build, TriangleTest test)
      : sequence_(std::move(build.sequence)), stats_(std::move(build.stats)), test_(test) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseEscapeSequence(sequence_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  EscapeSequence sequence_;
  AccelStats stats_;
  TriangleTest test_;
};

// The same kind of tree descended recursively (5 and 6); holds the caller's triangles.
class RecursiveBvhAccelerator final : public CpuAccelerator {
public:
  RecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats, TriangleTest test)
      : tris_(tris), bvh_(std::move(bvh)), stats_(std::move(stats)), test_(test) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseBvhRecursive(bvh_, tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  Bvh bvh_;
  AccelStats stats_;
  TriangleTest test_;
};

class BruteForce final : public CpuAccelerator {
public:
  BruteForce(std::span<const Triangle> tris, TriangleTest test) : tris_(tris), test_(test) {
    stats_.name = "brute-force";
    stats_.references = tris.size();
  }
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return intersectBruteForce(tris_, ray, anyHit, stats, test_);
  }
  std::string name() const override { return stats_.name; }
  AccelStats stats() const override { return stats_; }

private:
  std::span<const Triangle> tris_;
  AccelStats stats_;
  TriangleTest test_;
};

}  // namespace

SequenceBuild buildKayKajiyaSequence(std::span<const Triangle> tris, const KayKajiyaConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildKayKajiya(tris, config);
  SequenceBuild build{flattenEscapeSequence(bvh, tris), bvhStats(0, bvh)};
  build.stats.buildMs = millisecondsSince(start);
  build.stats.floatsPerTriangle = build.sequence.floatsPerTriangle();
  return build;
}

std::unique_ptr<CpuAccelerator> makeSequenceAccelerator(SequenceBuild build, TriangleTest test) {
  return std::make_unique<SequenceAccelerator>(std::move(build), test);
}

std::unique_ptr<CpuAccelerator> makeRecursiveBvhAccelerator(std::span<const Triangle> tris, Bvh bvh, AccelStats stats,
                                                            TriangleTest test) {
  return std::make_unique<RecursiveBvhAccelerator>(tris, std::move(bvh), std::move(stats), test);
}

std::unique_ptr<CpuAccelerator> makeCpuAccelerator(int number, std::span<const Triangle> tris,
                                                   const AccelBuildConfig& config) {
  info(number);  // throws for numbers outside Table 4
  if (number == 0) return makeSequenceAccelerator(buildKayKajiyaSequence(tris, config.kayKajiya), config.triangleTest);
  if (number == 1 || number == 4 || number == 6 || number == 7)
    return makeGridFamilyCpuAccelerator(number, tris, config);
  if (number == 2 || number == 3) return makeKdCpuAccelerator(number, tris, config);
  // 5: the K/K tree descended recursively.
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh = buildKayKajiya(tris, config.kayKajiya);
  AccelStats stats = bvhStats(5, bvh);
  stats.buildMs = millisecondsSince(start);
  return makeRecursiveBvhAccelerator(tris, std::move(bvh), std::move(stats), config.triangleTest);
}

std::unique_ptr<CpuAccelerator> makeBruteForceAccelerator(std::span<const Triangle> tris, TriangleTest test) {
  return std::make_unique<BruteForce>(tris, test);
}

std::string acceleratorName(int number) { return info(number).name; }

std::string acceleratorThesisName(int number) { return info(number).thesisName; }

int acceleratorNumber(const std::string& nameOrNumber) {
  for (int i = 0; i < static_cast<int>(kAccelerators.size()); ++i)
    if (nameOrNumber == kAccelerators[i].name || nameOrNumber == std::to_string(i)) return i;
  std::string valid;
  for (int i = 0; i < static_cast<int>(kAccelerators.size()); ++i)
    valid += (i ? ", " : "") + std::to_string(i) + " " + kAccelerators[i].name;
  throw std::invalid_argument("unknown accelerator '" + nameOrNumber + "' (valid: " + valid + ")");
}

}  // namespace passtrace
