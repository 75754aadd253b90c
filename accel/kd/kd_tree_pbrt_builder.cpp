#include "accel/kd/kd_tree_pbrt_builder.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace passtrace {
namespace {

// pbrt's BoundEdge: at equal positions starts sort before ends.
struct BoundEdge {
  float t;
  uint32_t prim;
  bool start;
};

bool edgeLess(const BoundEdge& a, const BoundEdge& b) {
  if (a.t == b.t) return a.start && !b.start;
  return a.t < b.t;
}

struct WorkItem {
  std::vector<uint32_t> prims;
  Aabb voxel;
  int depthLeft = 0;      // pbrt counts depth down to 0
  int badRefines = 0;     // pbrt passes its count down by value
  uint32_t parent = kNoHit;
  bool isRight = false;
};

int maximumExtent(const Aabb& b) {
  const glm::vec3 d = b.extent();
  if (d.x > d.y && d.x > d.z) return 0;
  return d.y > d.z ? 1 : 2;
}

}  // namespace

KdTree buildKdTreePbrt(std::span<const Triangle> tris, const KdBuildConfig& config) {
  KdTree tree;
  if (tris.empty()) return tree;
  const size_t maxPrims = static_cast<size_t>(std::max(config.minElements, 0));
  const float isectCost = config.intersectionCost, traversalCost = config.traversalCost;
  const float emptyBonus = config.emptyBonus;

  std::vector<Aabb> primBounds(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    primBounds[i] = tris[i].bounds();
    tree.bounds.extend(primBounds[i]);
  }

  WorkItem root;
  root.prims.resize(tris.size());
  for (uint32_t i = 0; i < tris.size(); ++i) root.prims[i] = i;
  root.voxel = tree.bounds;
  root.depthLeft = kdEffectiveMaxDepth(config, tris.size());

  std::vector<BoundEdge> edges;
  std::vector<WorkItem> stack;
  stack.push_back(std::move(root));
  while (!stack.empty()) {
    WorkItem item = std::move(stack.back());
    stack.pop_back();
    const auto index = static_cast<uint32_t>(tree.nodes.size());
    KdNode node;
    node.parent = item.parent;
    node.box = item.voxel;
    if (item.isRight) tree.nodes[item.parent].rightChild = index;

    auto makeLeaf = [&] {
      std::sort(item.prims.begin(), item.prims.end());
      node.firstRef = static_cast<uint32_t>(tree.references.size());
      node.refCount = static_cast<uint32_t>(item.prims.size());
      tree.references.insert(tree.references.end(), item.prims.begin(), item.prims.end());
      tree.nodes.push_back(node);
    };
    const size_t n = item.prims.size();
    const float totalArea = item.voxel.surfaceArea();
    // pbrt divides by the area; a point or segment voxel has nothing to split.
    if (n <= maxPrims || item.depthLeft <= 0 || !(totalArea > 0.0f)) {
      makeLeaf();
      continue;
    }

    int bestAxis = -1;
    size_t bestOffset = 0;
    float bestCost = kInfinity;
    const float oldCost = isectCost * static_cast<float>(n);
    const float invTotalArea = 1.0f / totalArea;
    const glm::vec3 d = item.voxel.extent();
    int axis = maximumExtent(item.voxel);
    for (int retries = 0;; ++retries) {
      edges.resize(2 * n);
      for (size_t i = 0; i < n; ++i) {
        const Aabb& b = primBounds[item.prims[i]];
        edges[2 * i] = {b.min[axis], item.prims[i], true};
        edges[2 * i + 1] = {b.max[axis], item.prims[i], false};
      }
      std::sort(edges.begin(), edges.end(), edgeLess);
      size_t nBelow = 0, nAbove = n;
      const float lo = item.voxel.min[axis], hi = item.voxel.max[axis];
      const int other0 = (axis + 1) % 3, other1 = (axis + 2) % 3;
      for (size_t i = 0; i < 2 * n; ++i) {
        if (!edges[i].start) --nAbove;
        const float edgeT = edges[i].t;
        if (edgeT > lo && edgeT < hi) {
          const float belowArea = 2 * (d[other0] * d[other1] + (edgeT - lo) * (d[other0] + d[other1]));
          const float aboveArea = 2 * (d[other0] * d[other1] + (hi - edgeT) * (d[other0] + d[other1]));
          const float pBelow = belowArea * invTotalArea, pAbove = aboveArea * invTotalArea;
          const float eb = (nAbove == 0 || nBelow == 0) ? emptyBonus : 0.0f;
          const float cost = traversalCost + isectCost * (1 - eb) * (pBelow * float(nBelow) + pAbove * float(nAbove));
          if (cost < bestCost) {
            bestCost = cost;
            bestAxis = axis;
            bestOffset = i;
          }
        }
        if (edges[i].start) ++nBelow;
      }
      if (bestAxis != -1 || retries == 2) break;
      axis = (axis + 1) % 3;
    }
    if (bestCost > oldCost) ++item.badRefines;
    if ((bestCost > 4 * oldCost && n < 16) || bestAxis == -1 || item.badRefines == 3) {
      makeLeaf();
      continue;
    }

    // Retries stop at the first axis with a candidate, so `edges` holds bestAxis.
    const float tSplit = edges[bestOffset].t;
    node.axis = static_cast<uint32_t>(bestAxis);
    node.split = tSplit;
    tree.nodes.push_back(node);

    WorkItem below, above;
    // pbrt's classification, except that a triangle whose bounds touch the
    // plane (a vertex on it) goes to both sides: a ray through that vertex
    // may be rounded into either child, and with the triangle on one side
    // only it slipped through closed meshes (tests/gl/watertight_test.cpp).
    for (size_t i = 0; i < 2 * n; ++i)
      if (edges[i].start && (i < bestOffset || edges[i].t == tSplit)) below.prims.push_back(edges[i].prim);
    for (size_t i = 0; i < 2 * n; ++i)
      if (!edges[i].start && (i > bestOffset || edges[i].t == tSplit)) above.prims.push_back(edges[i].prim);
    below.voxel = above.voxel = item.voxel;
    below.voxel.max[bestAxis] = above.voxel.min[bestAxis] = tSplit;
    below.depthLeft = above.depthLeft = item.depthLeft - 1;
    below.badRefines = above.badRefines = item.badRefines;
    below.parent = above.parent = index;
    above.isRight = true;
    item.prims = {};
    stack.push_back(std::move(above));
    stack.push_back(std::move(below));
  }
  return tree;
}

}  // namespace passtrace
