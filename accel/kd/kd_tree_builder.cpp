#include "accel/kd/kd_tree_builder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>
#include <vector>

namespace passtrace {

int kdDefaultMaxDepth(size_t triangleCount) {
  if (triangleCount <= 1) return 8;
  return static_cast<int>(std::lround(8.0 + 1.3 * std::log2(static_cast<double>(triangleCount))));
}

int kdEffectiveMaxDepth(const KdBuildConfig& config, size_t triangleCount) {
  const int depth = config.maxDepth > 0 ? config.maxDepth : kdDefaultMaxDepth(triangleCount);
  return std::clamp(depth, 0, kKdDepthLimit);
}

namespace {

// A triangle as one node sees it: its bounds clipped to the node's voxel.
struct Ref {
  uint32_t tri;
  Aabb bounds;
};

// One node still to build. Right children wait on the stack while the left
// subtree is built, which gives the depth-first layout.
struct WorkItem {
  std::vector<Ref> refs;
  Aabb voxel;
  int depth = 0;              // splits above this node
  uint32_t parent = kNoHit;
  bool isRight = false;       // tell the parent where its right child went
};

Aabb intersection(const Aabb& a, const Aabb& b) { return Aabb{glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::lessThanEqual(inner.max, outer.max));
}

// Sutherland–Hodgman: the bounds of the part of `tri` inside the closed box,
// cut to the box (rounding may put an intersection point a hair outside).
// Empty when the triangle misses the box. At most 3 + 6 vertices survive.
Aabb clipTriangleToBox(const Triangle& tri, const Aabb& box) {
  glm::vec3 bufA[12] = {tri.v0, tri.v1, tri.v2}, bufB[12];
  glm::vec3* in = bufA;
  glm::vec3* out = bufB;
  int n = 3;
  for (int axis = 0; axis < 3 && n > 0; ++axis) {
    for (int side = 0; side < 2 && n > 0; ++side) {
      const float plane = side == 0 ? box.min[axis] : box.max[axis];
      auto inside = [&](const glm::vec3& p) { return side == 0 ? p[axis] - plane : plane - p[axis]; };
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const glm::vec3& cur = in[i];
        const glm::vec3& next = in[(i + 1) % n];
        const float dc = inside(cur), dn = inside(next);
        if (dc >= 0.0f) out[m++] = cur;
        if ((dc > 0.0f && dn < 0.0f) || (dc < 0.0f && dn > 0.0f)) {
          glm::vec3 p = cur + (dc / (dc - dn)) * (next - cur);
          p[axis] = plane;  // exactly on the plane, whatever the rounding
          out[m++] = p;
        }
      }
      n = m;
      std::swap(in, out);
    }
  }
  Aabb bounds;
  for (int i = 0; i < n; ++i) bounds.extend(in[i]);
  return n == 0 ? bounds : intersection(bounds, box);
}

struct Split {
  int axis = -1;
  float position = 0.0f;
  float cost = kInfinity;
};

// Floats as unsigned keys that sort in the same order (negative floats have
// all bits flipped, positive ones their sign bit set). -0 is made +0 first
// so equal floats get equal keys.
uint32_t sortKey(float f) {
  const auto bits = std::bit_cast<uint32_t>(f + 0.0f);
  return (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;
}
float keyFloat(uint32_t key) { return std::bit_cast<float>((key & 0x80000000u) ? key & 0x7FFFFFFFu : ~key); }

// LSD radix sort (11-bit digits, three passes) for large arrays: the
// candidate sort is most of the build time, and this makes it linear.
void sortKeys(std::vector<uint32_t>& keys, std::vector<uint32_t>& scratch) {
  const size_t n = keys.size();
  if (n < 512) {
    std::sort(keys.begin(), keys.end());
    return;
  }
  constexpr int kBits = 11, kBuckets = 1 << kBits;
  std::vector<uint32_t> counts(3 * kBuckets, 0);
  for (const uint32_t k : keys)
    for (int d = 0; d < 3; ++d) ++counts[d * kBuckets + ((k >> (d * kBits)) & (kBuckets - 1))];
  scratch.resize(n);
  for (int d = 0; d < 3; ++d) {
    uint32_t* c = counts.data() + d * kBuckets;
    uint32_t sum = 0;
    for (int b = 0; b < kBuckets; ++b) sum += std::exchange(c[b], sum);
    for (const uint32_t k : keys) scratch[c[(k >> (d * kBits)) & (kBuckets - 1)]++] = k;
    keys.swap(scratch);
  }
}

struct Scratch {
  std::vector<uint32_t> mins, maxs, tmp;
};

// Finds the cheapest plane over all three axes. Candidates are the clipped
// bounds' faces strictly inside the voxel (a plane on the voxel's face
// leaves one child with everything). With the closed-voxel rule,
// N_L(p) = #{min <= p} and N_R(p) = #{max >= p}: one merged walk over the
// sorted mins and maxes.
Split findSplit(const std::vector<Ref>& refs, const Aabb& voxel, const KdBuildConfig& config, float minThickness,
                Scratch& s) {
  Split best;
  const glm::vec3 e = voxel.extent();
  const float area = voxel.surfaceArea();
  if (!(area > 0.0f)) return best;  // a point or segment voxel: nothing to weigh
  const float invArea = 1.0f / area;
  const size_t n = refs.size();
  s.mins.resize(n);
  s.maxs.resize(n);
  for (int axis = 0; axis < 3; ++axis) {
    if (!(e[axis] > 0.0f)) continue;
    for (size_t i = 0; i < n; ++i) {
      s.mins[i] = sortKey(refs[i].bounds.min[axis]);
      s.maxs[i] = sortKey(refs[i].bounds.max[axis]);
    }
    sortKeys(s.mins, s.tmp);
    sortKeys(s.maxs, s.tmp);
    const uint32_t* mins = s.mins.data();
    const uint32_t* maxs = s.maxs.data();
    const uint32_t lo = sortKey(voxel.min[axis]), hi = sortKey(voxel.max[axis]);
    const float loF = voxel.min[axis], hiF = voxel.max[axis];
    const float a1 = e[(axis + 1) % 3], a2 = e[(axis + 2) % 3];
    const float cross = a1 * a2, perimeter = a1 + a2;
    size_t i = 0, j = 0;  // mins consumed (<= p), maxs consumed (< p)
    while (i < n || j < n) {
      const uint32_t p = (i < n && (j >= n || mins[i] <= maxs[j])) ? mins[i] : maxs[j];
      while (i < n && mins[i] <= p) ++i;
      const float pF = keyFloat(p);
      if (p > lo && p < hi && pF - loF >= minThickness && hiF - pF >= minThickness) {
        const size_t nLeft = i, nRight = n - j;
        const float areaLeft = 2.0f * (cross + (pF - loF) * perimeter);
        const float areaRight = 2.0f * (cross + (hiF - pF) * perimeter);
        const float bonus = (nLeft == 0 || nRight == 0) ? config.emptyBonus : 0.0f;
        const float cost = config.traversalCost + config.intersectionCost * (1.0f - bonus) * invArea *
                                                      (areaLeft * float(nLeft) + areaRight * float(nRight));
        if (cost < best.cost) best = Split{axis, pF, cost};
      }
      while (j < n && maxs[j] <= p) ++j;
    }
  }
  return best;
}

// The bounds of a triangle in a child voxel, given its bounds in the parent.
// Only a triangle reaching past the new plane changes; its clipped region
// can only shrink, so the old bounds cap the new ones, and when rounding
// clips everything away the old bounds cut to the child stand in (the
// triangle does touch the child's closed voxel, by classification).
Aabb childBounds(const Triangle& tri, const Aabb& old, const Aabb& child, bool splitClipping) {
  if (contains(child, old)) return old;
  const Aabb cut = intersection(old, child);
  if (!splitClipping) return cut;
  const Aabb clipped = intersection(clipTriangleToBox(tri, child), old);
  return clipped.empty() ? cut : clipped;
}

}  // namespace

KdTree buildKdTree(std::span<const Triangle> tris, const KdBuildConfig& config) {
  KdTree tree;
  if (tris.empty()) return tree;
  const int maxDepth = kdEffectiveMaxDepth(config, tris.size());
  const size_t minElements = static_cast<size_t>(std::max(config.minElements, 0));

  WorkItem root;
  root.refs.reserve(tris.size());
  for (uint32_t t = 0; t < tris.size(); ++t) {
    root.refs.push_back({t, tris[t].bounds()});
    tree.bounds.extend(root.refs.back().bounds);
  }
  root.voxel = tree.bounds;
  const float minThickness = config.minVoxelFraction * glm::length(tree.bounds.extent());

  Scratch scratch;  // reused by every findSplit
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

    const size_t n = item.refs.size();
    Split split;
    if (n > minElements && item.depth < maxDepth) split = findSplit(item.refs, item.voxel, config, minThickness, scratch);
    const float leafCost = config.intersectionCost * static_cast<float>(n);
    if (split.axis < 0 || !(split.cost < leafCost)) {
      node.firstRef = static_cast<uint32_t>(tree.references.size());
      node.refCount = static_cast<uint32_t>(n);
      for (const Ref& r : item.refs) tree.references.push_back(r.tri);
      tree.nodes.push_back(node);
      continue;
    }

    const int axis = split.axis;
    const float p = split.position;
    node.axis = static_cast<uint32_t>(axis);
    node.split = p;
    tree.nodes.push_back(node);

    WorkItem left, right;
    left.voxel = right.voxel = item.voxel;
    left.voxel.max[axis] = right.voxel.min[axis] = p;
    left.depth = right.depth = item.depth + 1;
    left.parent = right.parent = index;
    right.isRight = true;
    for (const Ref& r : item.refs) {
      if (r.bounds.min[axis] <= p)
        left.refs.push_back({r.tri, childBounds(tris[r.tri], r.bounds, left.voxel, config.splitClipping)});
      if (r.bounds.max[axis] >= p)
        right.refs.push_back({r.tri, childBounds(tris[r.tri], r.bounds, right.voxel, config.splitClipping)});
    }
    item.refs = {};  // free before the subtrees grow
    stack.push_back(std::move(right));
    stack.push_back(std::move(left));  // popped next: index + 1
  }
  return tree;
}

}  // namespace passtrace
