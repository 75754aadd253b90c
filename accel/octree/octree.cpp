#include "accel/octree/octree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "accel/grid/grid_traversal.h"
#include "accel/grid/uniform_grid_builder.h"

namespace passtrace {
namespace {

struct Work {
  uint32_t node;
  uint32_t level;  // root 0
  std::vector<uint32_t> tris;
};

Aabb octantBox(const Aabb& box, int octant) {
  const glm::vec3 c = box.center();
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    const bool upper = (octant >> k) & 1;
    b.min[k] = upper ? c[k] : box.min[k];
    b.max[k] = upper ? box.max[k] : c[k];
  }
  return b;
}

bool overlapsPadded(const Triangle& tri, const Aabb& triBounds, bool degenerate, Aabb box, float pad) {
  box.min -= glm::vec3(pad);
  box.max += glm::vec3(pad);
  if (degenerate)
    return glm::all(glm::lessThanEqual(box.min, triBounds.max)) && glm::all(glm::greaterThanEqual(box.max, triBounds.min));
  return triangleOverlapsBox(tri, box);
}

}  // namespace

Octree buildOctree(std::span<const Triangle> tris, const OctreeConfig& config) {
  Octree tree;
  if (tris.empty()) return tree;
  Aabb bounds;
  for (const Triangle& t : tris) bounds.extend(t.bounds());
  const glm::vec3 e = bounds.extent();
  const float edge = std::max(std::max(e.x, e.y), e.z);
  const glm::vec3 center = bounds.center();
  Aabb rootBox{glm::min(center - glm::vec3(0.5f * edge), bounds.min), glm::max(center + glm::vec3(0.5f * edge), bounds.max)};
  const glm::vec3 magnitude = glm::max(glm::abs(bounds.min), glm::abs(bounds.max));
  const float scale = std::max(std::max(magnitude.x, magnitude.y), magnitude.z);

  int maxDepth = config.maxDepth;
  if (maxDepth <= 0) maxDepth = int(std::ceil(std::log(double(tris.size())) / std::log(8.0) - 1e-9)) + 3;
  maxDepth = std::clamp(maxDepth, 1, 16);
  const size_t maxLeaf = size_t(std::max(0, config.maxLeafTriangles));

  std::vector<Aabb> triBounds(tris.size());
  std::vector<char> degenerate(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    triBounds[i] = tris[i].bounds();
    degenerate[i] = glm::cross(tris[i].v1 - tris[i].v0, tris[i].v2 - tris[i].v0) == glm::vec3(0.0f);
  }

  tree.nodes.push_back(OctreeNode{rootBox});
  std::vector<Work> stack;
  stack.push_back({0, 0, std::vector<uint32_t>(tris.size())});
  for (uint32_t i = 0; i < tris.size(); ++i) stack.back().tris[i] = i;
  while (!stack.empty()) {
    Work work = std::move(stack.back());
    stack.pop_back();
    tree.depth = std::max(tree.depth, work.level + 1);
    const Aabb box = tree.nodes[work.node].box;
    const float nodeEdge = box.max.x - box.min.x;
    std::array<std::vector<uint32_t>, 8> octants;
    bool split = work.tris.size() > maxLeaf && int(work.level) < maxDepth && nodeEdge > 0.0f;
    if (split) {
      const float pad = 1e-4f * nodeEdge + 1e-6f * scale;
      std::array<Aabb, 8> boxes;
      for (int o = 0; o < 8; ++o) boxes[o] = octantBox(box, o);
      const glm::vec3 c = box.center();
      for (const uint32_t t : work.tris) {
        const Aabb& b = triBounds[t];
        // Octants the padded bounds reach on each axis: bit k may be 0 and/or 1.
        int lowMask = 0, highMask = 0;
        for (int k = 0; k < 3; ++k) {
          if (b.min[k] <= c[k] + 2.0f * pad) lowMask |= 1 << k;
          if (b.max[k] >= c[k] - 2.0f * pad) highMask |= 1 << k;
        }
        for (int o = 0; o < 8; ++o) {
          bool reach = true;
          for (int k = 0; k < 3; ++k) reach = reach && (((o >> k) & 1) ? (highMask >> k) & 1 : (lowMask >> k) & 1);
          if (reach && overlapsPadded(tris[t], b, degenerate[t], boxes[o], pad)) octants[o].push_back(t);
        }
      }
      // No progress when every non-empty octant holds everything.
      bool separates = false;
      for (const auto& list : octants) separates = separates || (!list.empty() && list.size() < work.tris.size());
      split = separates;
      if (split) {
        const auto first = static_cast<uint32_t>(tree.nodes.size());
        uint32_t count = 0;
        for (int o = 0; o < 8; ++o) {
          if (octants[o].empty()) continue;
          tree.nodes.push_back(OctreeNode{boxes[o]});
          stack.push_back({first + count, work.level + 1, std::move(octants[o])});
          ++count;
        }
        tree.nodes[work.node].firstChild = first;
        tree.nodes[work.node].childCount = count;
      }
    }
    if (!split) {
      OctreeNode& node = tree.nodes[work.node];
      node.firstRef = static_cast<uint32_t>(tree.references.size());
      node.refCount = static_cast<uint32_t>(work.tris.size());
      tree.references.insert(tree.references.end(), work.tris.begin(), work.tris.end());
    }
  }
  return tree;
}

Hit traverseOctree(const Octree& octree, std::span<const Triangle> tris, const Ray& ray, bool anyHit,
                   RayStats* stats, TriangleTest test) {
  Hit best{ray.tMax};
  if (octree.nodes.empty()) return best;
  const glm::vec3 invDir = safeInverse(ray.direction);
  struct Entry {
    uint32_t node;
    float tNear, tFar;
  };
  // Depth <= 17 levels, at most 8 pushes per level.
  std::array<Entry, 8 * 18> stack;
  size_t top = 0;
  float tNear, tFar;
  if (clipRayToBox(ray.origin, invDir, octree.nodes[0].box, best.t, tNear, tFar)) stack[top++] = {0, tNear, tFar};
  uint32_t steps = 0, tests = 0;
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.tNear >= best.t) continue;  // nothing in it can be closer
    ++steps;
    const OctreeNode& node = octree.nodes[entry.node];
    if (node.isLeaf()) {
      bool found = false;
      for (uint32_t r = node.firstRef; r < node.firstRef + node.refCount; ++r) {
        const uint32_t id = octree.references[r];
        ++tests;
        found = intersectTriangle(ray.origin, ray.direction, tris[id], id, best, test) || found;
        if (found && anyHit) break;
      }
      if ((found && anyHit) || best.t <= entry.tFar) break;
      continue;
    }
    // Children that the ray enters before best.t, pushed farthest first.
    std::array<Entry, 8> hits;
    int n = 0;
    for (uint32_t c = 0; c < node.childCount; ++c) {
      const uint32_t child = node.firstChild + c;
      if (clipRayToBox(ray.origin, invDir, octree.nodes[child].box, best.t, tNear, tFar)) {
        // Insertion sort by tNear, descending.
        int i = n++;
        while (i > 0 && hits[i - 1].tNear < tNear) {
          hits[i] = hits[i - 1];
          --i;
        }
        hits[i] = {child, tNear, tFar};
      }
    }
    for (int i = 0; i < n; ++i) stack[top++] = hits[i];
  }
  if (stats) {
    stats->steps += steps;
    stats->triangleTests += tests;
  }
  return best;
}

}  // namespace passtrace
