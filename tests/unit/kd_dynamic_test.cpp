// Dynamic scenes with kd-trees (accel/kd/kd_dynamic.h, kd_merge.h): the
// merged tree is a valid kd-tree whose traversal equals brute force on the
// frame's triangles, the static tree is the same node for node after every
// merge, and the two-trees composite equals brute force too; for the stack
// traversal and both stream kernels' CPU mirrors, on the kd meshes with a
// third of their triangles moving (in place, and moved partly out of the
// static bounds) and on the built-in dynamic scene over its animation.

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <random>
#include <string>
#include <vector>

#include "accel/brute_force.h"
#include "accel/kd/kd_dynamic.h"
#include "accel/kd/kd_merge.h"
#include "accel/kd/kd_traversal.h"
#include "tests/kd_checks.h"
#include "tests/test_meshes.h"
#include "scenes/scene_registry.h"

namespace passtrace {
namespace {

using test::kd::compare;
using test::kd::expectAgreement;
using test::kd::expectValidKdTree;
using testmesh::NamedMesh;

const std::optional<KdStreamVariant> kVariants[] = {std::nullopt, KdStreamVariant::Restart, KdStreamVariant::Backtrack};

std::string variantName(std::optional<KdStreamVariant> v) {
  if (!v) return "stack";
  return *v == KdStreamVariant::Restart ? "restart" : "backtrack";
}

// Every third triangle moves.
std::vector<uint8_t> everyThird(size_t count) {
  std::vector<uint8_t> moving(count, 0);
  for (size_t i = 0; i < count; i += 3) moving[i] = 1;
  return moving;
}

// The moving triangles shifted by `offset`.
std::vector<Triangle> moved(std::vector<Triangle> tris, const std::vector<uint8_t>& moving, const glm::vec3& offset) {
  for (size_t i = 0; i < tris.size(); ++i)
    if (moving[i]) tris[i] = Triangle{tris[i].v0 + offset, tris[i].v1 + offset, tris[i].v2 + offset};
  return tris;
}

// Rays starting exactly on the tree's split planes, where kd-trees go wrong most easily.
std::vector<Ray> planeRays(const KdTree& tree, size_t count, uint64_t seed) {
  std::vector<Ray> rays;
  std::vector<const KdNode*> internal;
  for (const KdNode& n : tree.nodes)
    if (!n.isLeaf()) internal.push_back(&n);
  if (internal.empty()) return rays;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (size_t r = 0; r < count; ++r) {
    const KdNode& n = *internal[rng() % internal.size()];
    Ray ray;
    for (int k = 0; k < 3; ++k) ray.origin[k] = n.box.min[k] + (n.box.max[k] - n.box.min[k]) * unit(rng);
    ray.origin[n.axis] = n.split;
    glm::vec3 d{unit(rng) * 2 - 1, unit(rng) * 2 - 1, unit(rng) * 2 - 1};
    if (r % 4 == 0) d[n.axis] = 0.0f;  // in the plane
    if (glm::dot(d, d) < 1e-4f) d = glm::vec3(0.3f, -0.5f, 0.8f);
    ray.direction = glm::normalize(d);
    rays.push_back(ray);
  }
  return rays;
}

void expectSameTree(const KdTree& a, const KdTree& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const KdNode &x = a.nodes[i], &y = b.nodes[i];
    ASSERT_TRUE(x.axis == y.axis && x.split == y.split && x.rightChild == y.rightChild && x.parent == y.parent &&
                x.firstRef == y.firstRef && x.refCount == y.refCount && x.box.min == y.box.min &&
                x.box.max == y.box.max)
        << "node " << i;
  }
  EXPECT_EQ(a.references, b.references);
  EXPECT_EQ(a.bounds.min, b.bounds.min);
  EXPECT_EQ(a.bounds.max, b.bounds.max);
}

// One frame of each strategy against brute force on `frame`.
void expectFrameAgrees(KdDynamicTrees& trees, const std::vector<Triangle>& frame, const std::string& what) {
  trees.update(frame);
  if (trees.strategy() == DynamicStrategy::Merge) {
    expectValidKdTree(trees.mergedTree(), frame, what + " merged");
    EXPECT_LE(trees.mergedTree().depth(), uint32_t(kKdDepthLimit)) << what;
  }
  const Aabb bounds = testmesh::boundsOf(frame);
  std::vector<Ray> rays = testmesh::rayMix(bounds, 150, 7);
  if (trees.strategy() == DynamicStrategy::Merge) {
    const std::vector<Ray> planes = planeRays(trees.mergedTree(), 600, 11);
    rays.insert(rays.end(), planes.begin(), planes.end());
  }
  for (const auto variant : kVariants) {
    const auto accel = makeKdDynamicCpu(trees, variant, frame, TriangleTest::MollerTrumbore, "kd", 0.0);
    expectAgreement(compare(*accel, frame, rays), what + " " + variantName(variant));
  }
}

class KdDynamicMeshTest : public ::testing::TestWithParam<NamedMesh> {};

TEST_P(KdDynamicMeshTest, MergeAndTwoTreesAgreeWithBruteForce) {
  const std::vector<Triangle>& tris = GetParam().tris;
  const std::vector<uint8_t> moving = everyThird(tris.size());
  const Aabb bounds = testmesh::boundsOf(tris);
  for (const DynamicStrategy strategy : {DynamicStrategy::Merge, DynamicStrategy::TwoTrees}) {
    KdDynamicTrees trees(strategy, tris, moving, AccelBuildConfig{});
    const KdTree before = trees.staticTree();
    const std::string what = GetParam().name + " " + std::string(dynamicStrategyName(strategy));
    expectFrameAgrees(trees, tris, what + " in place");
    // Partly out of the static bounds: the merged root grows.
    expectFrameAgrees(trees, moved(tris, moving, 0.3f * bounds.extent() + glm::vec3(0.05f)), what + " moved");
    expectSameTree(trees.staticTree(), before);
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, KdDynamicMeshTest, ::testing::ValuesIn(test::kd::kdMeshes()),
                         [](const auto& info) { return info.param.name; });

TEST(KdMerge, StaticTreeIsTheSameNodeForNodeAfterMerging) {
  const std::vector<Triangle> tris = testmesh::standardMeshes().front().tris;
  const std::vector<uint8_t> moving = everyThird(tris.size());
  KdDynamicTrees trees(DynamicStrategy::Merge, tris, moving, AccelBuildConfig{});
  const KdTree before = trees.staticTree();
  ASSERT_FALSE(before.empty());
  for (int f = 0; f < 3; ++f) {
    trees.update(moved(tris, moving, glm::vec3(0.1f * float(f), 0.0f, 0.0f)));
    ASSERT_GT(trees.mergedTree().nodes.size(), before.nodes.size());  // something was merged
    expectSameTree(trees.staticTree(), before);
  }
}

// A chain along `axis`: triangle first + k lies in [k, k + 0.5]; node k
// splits at k + 0.75, triangle k's leaf below, the rest above.
KdTree chainTree(std::span<const Triangle> tris, uint32_t first, uint32_t count, uint32_t axis) {
  KdTree tree;
  for (uint32_t k = 0; k < count; ++k) tree.bounds.extend(testmesh::boundsOf(tris.subspan(first + k, 1)));
  Aabb box = tree.bounds;
  uint32_t parent = kNoHit;
  for (uint32_t k = 0; k < count; ++k) {
    tree.references.push_back(first + k);
    KdNode leaf;
    leaf.firstRef = k, leaf.refCount = 1;
    if (k + 1 == count) {
      leaf.parent = parent, leaf.box = box;
      tree.nodes.push_back(leaf);
      break;
    }
    const uint32_t index = uint32_t(tree.nodes.size());
    KdNode node;
    node.axis = axis, node.split = float(k) + 0.75f, node.parent = parent, node.box = box, node.rightChild = index + 2;
    tree.nodes.push_back(node);
    leaf.parent = index, leaf.box = box;
    leaf.box.max[axis] = node.split;
    tree.nodes.push_back(leaf);
    box.min[axis] = node.split;
    parent = index;
  }
  return tree;
}

class TreeAccelerator final : public CpuAccelerator {
 public:
  TreeAccelerator(const KdTree& tree, std::span<const Triangle> tris) : tree_(tree), tris_(tris) {}
  Hit intersect(const Ray& ray, bool anyHit, RayStats* stats) const override {
    return traverseKdTree(tree_, tris_, ray, anyHit, stats);
  }
  std::string name() const override { return "merged"; }
  AccelStats stats() const override { return {}; }

 private:
  const KdTree& tree_;
  std::span<const Triangle> tris_;
};

TEST(KdMerge, DeepTreesStopAtTheDepthLimit) {
  // Two chains 40 levels deep, one along x, one along y, crossing: merged
  // naively they would reach 80 levels.
  const uint32_t n = 40;
  std::vector<Triangle> tris;
  for (uint32_t k = 0; k < n; ++k)
    tris.push_back({glm::vec3(k, 0, 0), glm::vec3(k + 0.5f, 0, 0), glm::vec3(k, n, 1)});
  for (uint32_t k = 0; k < n; ++k)
    tris.push_back({glm::vec3(0, k, 0), glm::vec3(n, k, 0), glm::vec3(0, k + 0.5f, 1)});
  const KdTree xs = chainTree(tris, 0, n, 0), ys = chainTree(tris, n, n, 1);
  expectValidKdTree(xs, std::span(tris).first(n), "x chain");  // (y's references are n and above)
  ASSERT_EQ(ys.depth(), n);
  const KdTree merged = mergeKdTrees(xs, ys, tris);
  expectValidKdTree(merged, tris, "merged chains");
  EXPECT_EQ(merged.depth(), uint32_t(kKdDepthLimit));
  const TreeAccelerator accel(merged, tris);
  std::vector<Ray> rays = testmesh::rayMix(merged.bounds, 300, 5);
  const std::vector<Ray> planes = planeRays(merged, 1000, 3);
  rays.insert(rays.end(), planes.begin(), planes.end());
  expectAgreement(compare(accel, tris, rays), "merged chains");
}

TEST(KdMerge, EitherTreeMayBeEmpty) {
  const std::vector<Triangle> tris = testmesh::standardMeshes().front().tris;
  for (const uint8_t flag : {uint8_t(0), uint8_t(1)}) {
    KdDynamicTrees trees(DynamicStrategy::Merge, tris, std::vector<uint8_t>(tris.size(), flag), AccelBuildConfig{});
    expectFrameAgrees(trees, tris, flag ? "all moving" : "all static");
  }
  const KdTree empty;
  EXPECT_TRUE(mergeKdTrees(empty, empty, tris).empty());
}

// The built-in dynamic scene (tests/data/gltf/dynamic.gltf) over its animation.
TEST(KdDynamicScene, EveryFrameAgreesWithBruteForce) {
  const std::string file = std::string(PASSTRACE_TEST_DATA) + "/gltf/dynamic.gltf";
  SceneOptions options;
  const Scene first = loadScene(file, options);
  ASSERT_TRUE(first.animation);
  ASSERT_EQ(first.moving.size(), first.triangles.size());
  for (const DynamicStrategy strategy : {DynamicStrategy::Merge, DynamicStrategy::TwoTrees}) {
    KdDynamicTrees trees(strategy, first.triangles, first.moving, AccelBuildConfig{});
    for (const float time : {0.0f, 0.3f, 0.9f, 1.4f, 2.0f}) {
      options.time = time;
      const Scene frame = loadScene(file, options);
      expectFrameAgrees(trees, frame.triangles,
                        std::string(dynamicStrategyName(strategy)) + " at t=" + std::to_string(time));
    }
  }
}

TEST(KdDynamic, StrategyNamesAndRows) {
  for (const DynamicStrategy s : {DynamicStrategy::Rebuild, DynamicStrategy::TwoTrees, DynamicStrategy::Merge})
    EXPECT_EQ(dynamicStrategyByName(dynamicStrategyName(s)), s);
  EXPECT_FALSE(dynamicStrategyByName("merged"));
  EXPECT_FALSE(kdDynamicVariant("kd-tree"));
  EXPECT_EQ(kdDynamicVariant("kd-backtrack"), KdStreamVariant::Backtrack);
  EXPECT_THROW(kdDynamicVariant("grid"), std::invalid_argument);
}

}  // namespace
}  // namespace passtrace
