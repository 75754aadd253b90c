#include "accel/bvh_stack/sbvh_builder.h"

#include <algorithm>
#include <cmath>

#include "accel/bvh_stack/bvh_object_split.h"

namespace passtrace {
namespace {

struct SpatialSplit {
  float cost = kInfinity;
  int axis = -1;
  float plane = 0;
};

Aabb intersect(const Aabb& a, const Aabb& b) { return {glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

float area(const Aabb& box) { return box.empty() ? 0.0f : box.surfaceArea(); }

Aabb unite(Aabb a, const Aabb& b) {
  a.extend(b);
  return a;
}

// The best spatial split of refs over `box`: bins of equal width, each
// reference clipped into every bin it overlaps.
SpatialSplit findSpatialSplit(std::span<const Triangle> tris, std::span<const BvhBuildRef> refs, const Aabb& box,
                              const BvhStackConfig& config) {
  SpatialSplit best;
  const uint32_t bins = std::max(2u, config.bins);
  const float nodeArea = box.surfaceArea();
  std::vector<Aabb> binBox(bins), rightBox(bins);
  std::vector<uint32_t> entries(bins), exits(bins);
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = box.min[axis], extent = box.max[axis] - lo;
    if (!(extent > 0.0f)) continue;
    const float width = extent / float(bins);
    const auto binAt = [&](float x) { return std::min(bins - 1, uint32_t(std::max(0.0f, (x - lo) / width))); };
    std::fill(binBox.begin(), binBox.end(), Aabb{});
    std::fill(entries.begin(), entries.end(), 0u);
    std::fill(exits.begin(), exits.end(), 0u);
    for (const BvhBuildRef& r : refs) {
      const uint32_t first = binAt(r.box.min[axis]), last = binAt(r.box.max[axis]);
      ++entries[first];
      ++exits[last];
      BvhBuildRef rest = r;
      for (uint32_t b = first; b < last; ++b) {
        Aabb below, above;
        splitReference(tris[r.triangle], rest, axis, lo + width * float(b + 1), below, above);
        binBox[b].extend(below);
        rest.box = above;
        if (above.empty()) break;
      }
      if (!rest.box.empty()) binBox[last].extend(rest.box);
    }
    Aabb acc;
    for (uint32_t b = bins; b-- > 0;) {
      acc.extend(binBox[b]);
      rightBox[b] = acc;
    }
    Aabb leftBox;
    uint32_t nLeft = 0, nRight = uint32_t(refs.size());
    for (uint32_t b = 0; b + 1 < bins; ++b) {
      leftBox.extend(binBox[b]);
      nLeft += entries[b];
      nRight -= exits[b];
      if (nLeft == 0 || nRight == 0) continue;
      const float weighted = area(leftBox) * float(nLeft) + area(rightBox[b + 1]) * float(nRight);
      const float cost =
          config.traversalCost + config.intersectionCost * (nodeArea > 0.0f ? weighted / nodeArea : 0.0f);
      if (cost < best.cost) best = {cost, axis, lo + width * float(b + 1)};
    }
  }
  return best;
}

// Distributes refs at the plane; a straddling reference is split into both
// halves or kept whole in one, whichever the SAH prefers (unsplitting).
void applySpatialSplit(std::span<const Triangle> tris, const SpatialSplit& split, std::span<const BvhBuildRef> refs,
                       std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right) {
  const int axis = split.axis;
  std::vector<BvhBuildRef> straddling;
  Aabb leftBox, rightBox;
  for (const BvhBuildRef& r : refs) {
    if (r.box.max[axis] <= split.plane) {
      left.push_back(r);
      leftBox.extend(r.box);
    } else if (r.box.min[axis] >= split.plane) {
      right.push_back(r);
      rightBox.extend(r.box);
    } else {
      straddling.push_back(r);
    }
  }
  for (const BvhBuildRef& r : straddling) {
    Aabb below, above;
    splitReference(tris[r.triangle], r, axis, split.plane, below, above);
    const float nl = float(left.size()), nr = float(right.size());
    const float both = below.empty() || above.empty()
                           ? kInfinity
                           : area(unite(leftBox, below)) * (nl + 1) + area(unite(rightBox, above)) * (nr + 1);
    const float leftOnly = area(unite(leftBox, r.box)) * (nl + 1) + area(rightBox) * nr;
    const float rightOnly = area(leftBox) * nl + area(unite(rightBox, r.box)) * (nr + 1);
    if (both < leftOnly && both < rightOnly) {
      left.push_back({below, r.triangle});
      right.push_back({above, r.triangle});
      leftBox.extend(below);
      rightBox.extend(above);
    } else if (leftOnly <= rightOnly) {
      left.push_back(r);
      leftBox.extend(r.box);
    } else {
      right.push_back(r);
      rightBox.extend(r.box);
    }
  }
}

}  // namespace

void splitReference(const Triangle& tri, const BvhBuildRef& ref, int axis, float plane, Aabb& below, Aabb& above) {
  below = above = Aabb{};
  const glm::vec3 v[3] = {tri.v0, tri.v1, tri.v2};
  for (int i = 0; i < 3; ++i) {
    const glm::vec3& a = v[i];
    const glm::vec3& b = v[(i + 1) % 3];
    if (a[axis] <= plane) below.extend(a);
    if (a[axis] >= plane) above.extend(a);
    if ((a[axis] < plane && b[axis] > plane) || (a[axis] > plane && b[axis] < plane)) {
      const float t = (plane - a[axis]) / (b[axis] - a[axis]);
      glm::vec3 x = a + t * (b - a);
      x[axis] = plane;
      // The crossing point is rounded: pad it outward so the parts' boxes
      // still contain the true edge point (the reference box clamps the pad).
      const glm::vec3 pad = (glm::abs(a) + glm::abs(b)) * 0x1p-20f;
      below.extend(x - pad), below.extend(x + pad);
      above.extend(x - pad), above.extend(x + pad);
    }
  }
  below = intersect(below, ref.box);
  above = intersect(above, ref.box);
  below.max[axis] = std::min(below.max[axis], plane);
  above.min[axis] = std::max(above.min[axis], plane);
  if (below.empty()) below = Aabb{};
  if (above.empty()) above = Aabb{};
}

BinaryBvh buildSbvh(std::span<const Triangle> tris, const BvhStackConfig& config) {
  const Aabb scene = [&] {
    Aabb box;
    for (const BvhBuildRef& r : bvhBuildRefs(tris)) box.extend(r.box);
    return box;
  }();
  const float minOverlap = config.sbvhAlpha * area(scene);
  size_t budget = size_t(double(config.sbvhSplitBudget) * double(tris.size()));  // references spatial splits may add
  return buildBinaryBvh(tris, config,
                        [&](std::vector<BvhBuildRef>& refs, const Aabb& box, uint32_t,
                            std::vector<BvhBuildRef>& left, std::vector<BvhBuildRef>& right) {
                          const BvhObjectSplit object = findObjectSplit(refs, box, config);
                          SpatialSplit spatial;
                          const float overlap = object.valid() ? area(intersect(object.left, object.right)) : kInfinity;
                          if (budget > 0 && overlap > minOverlap) spatial = findSpatialSplit(tris, refs, box, config);
                          const bool leafAllowed = refs.size() <= config.maxLeafSize;
                          if (spatial.axis >= 0 && spatial.cost < object.cost) {
                            if (leafAllowed && leafCost(refs.size(), config) <= spatial.cost) return false;
                            applySpatialSplit(tris, spatial, refs, left, right);
                            const size_t added = left.size() + right.size() - refs.size();
                            if (!left.empty() && !right.empty() && added <= budget) {
                              budget -= added;
                              return true;
                            }
                            left.clear(), right.clear();  // all on one side, or over budget: split by objects
                          }
                          if (leafAllowed && leafCost(refs.size(), config) <= object.cost) return false;
                          if (object.valid()) applyObjectSplit(object, refs, config, left, right);
                          else bvhMedianSplit(refs, left, right);
                          return true;
                        });
}

}  // namespace passtrace
