#include "accel/kd/kd_traversal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace passtrace {
namespace {

struct Pending {
  uint32_t node;
  float tNear, tFar;
};

// A fixed array, as deep as any tree the builders make; a hand-made deeper
// tree spills into the heap rather than overflowing.
class PendingStack {
public:
  bool empty() const { return size_ == 0; }
  void push(const Pending& p) {
    if (size_ < fixed_.size())
      fixed_[size_] = p;
    else
      spill_.push_back(p);
    ++size_;
  }
  Pending pop() {
    --size_;
    if (size_ < fixed_.size()) return fixed_[size_];
    const Pending p = spill_.back();
    spill_.pop_back();
    return p;
  }

private:
  std::array<Pending, kKdDepthLimit + 1> fixed_;
  std::vector<Pending> spill_;
  size_t size_ = 0;
};

}  // namespace

Hit traverseKdTree(const KdTree& tree, std::span<const Triangle> tris, const Ray& ray, bool anyHit, RayStats* stats,
                   TriangleTest test) {
  Hit best;
  best.t = ray.tMax;
  if (tree.nodes.empty()) return best;
  const glm::vec3 invDir = safeInverse(ray.direction);
  float tNear = 0.0f, tFar = ray.tMax;
  float boxNear, boxFar;
  clipToBox(ray.origin, invDir, tree.nodes[0].box, boxNear, boxFar);
  tNear = std::max(tNear, boxNear);
  tFar = std::min(tFar, boxFar);
  if (!(tNear <= tFar)) return best;

  uint32_t steps = 0, triangleTests = 0;
  PendingStack stack;
  uint32_t index = 0;
  for (;;) {
    const KdNode& node = tree.nodes[index];
    ++steps;
    if (!node.isLeaf()) {
      const uint32_t axis = node.axis;
      const float o = ray.origin[axis];
      const uint32_t left = index + 1, right = node.rightChild;
      if (std::fabs(invDir[axis]) > kParallelInverse) {  // parallel to the plane
        if (o < node.split) {
          index = left;
        } else if (o > node.split) {
          index = right;
        } else {  // in the plane: both sides, same interval
          stack.push({right, tNear, tFar});
          index = left;
        }
        continue;
      }
      const float tSplit = (node.split - o) * invDir[axis];
      const bool leftFirst = o < node.split || (o == node.split && invDir[axis] < 0.0f);
      const uint32_t nearChild = leftFirst ? left : right, farChild = leftFirst ? right : left;
      if (tSplit > tFar || tSplit <= 0.0f) {
        index = nearChild;
      } else if (tSplit < tNear) {
        index = farChild;
      } else {
        stack.push({farChild, tSplit, tFar});
        index = nearChild;
        tFar = tSplit;
      }
      continue;
    }

    for (uint32_t r = 0; r < node.refCount; ++r) {
      const uint32_t id = tree.references[node.firstRef + r];
      ++triangleTests;
      if (intersectTriangle(ray.origin, ray.direction, tris[id], id, best, test) && anyHit) goto done;
    }
    for (;;) {
      if (stack.empty()) goto done;
      const Pending next = stack.pop();
      if (best.t <= next.tNear) continue;  // nothing closer can be in there
      index = next.node;
      tNear = next.tNear;
      tFar = next.tFar;
      break;
    }
  }
done:
  if (stats) {
    stats->steps += steps;
    stats->triangleTests += triangleTests;
  }
  return best;
}

}  // namespace passtrace
