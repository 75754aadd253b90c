#include "accel/kd/kd_build_driver.h"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace passtrace {
namespace {

Aabb intersection(const Aabb& a, const Aabb& b) { return Aabb{glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) && glm::all(glm::lessThanEqual(inner.max, outer.max));
}

// Sutherland–Hodgman: the part of `tri` inside the closed box, as a
// polygon of n vertices v[0..n) (none when it misses; at most 3 + 6).
struct ClippedPolygon {
  glm::vec3 bufA[12], bufB[12];
  glm::vec3* v = bufA;
  int n = 3;

  ClippedPolygon(const Triangle& tri, const Aabb& box) {
    bufA[0] = tri.v0, bufA[1] = tri.v1, bufA[2] = tri.v2;
    glm::vec3* out = bufB;
    const Aabb triBounds = tri.bounds();
    for (int axis = 0; axis < 3 && n > 0; ++axis) {
      for (int side = 0; side < 2 && n > 0; ++side) {
        const float plane = side == 0 ? box.min[axis] : box.max[axis];
        // Most straddlers cross only the newest plane: skip the planes the
        // whole triangle lies inside of (clipping by them changes nothing).
        if (side == 0 ? triBounds.min[axis] >= plane : triBounds.max[axis] <= plane) continue;
        auto inside = [&](const glm::vec3& p) { return side == 0 ? p[axis] - plane : plane - p[axis]; };
        int m = 0;
        for (int i = 0; i < n; ++i) {
          const glm::vec3& cur = v[i];
          const glm::vec3& next = v[(i + 1) % n];
          const float dc = inside(cur), dn = inside(next);
          if (dc >= 0.0f) out[m++] = cur;
          if ((dc > 0.0f && dn < 0.0f) || (dc < 0.0f && dn > 0.0f)) {
            glm::vec3 p = cur + (dc / (dc - dn)) * (next - cur);
            p[axis] = plane;  // exactly on the plane, whatever the rounding
            out[m++] = p;
          }
        }
        n = m;
        std::swap(v, out);
      }
    }
  }
};

// A triangle straddling the plane `p` on `axis`: its bounds on each side
// from one clip to the parent voxel, the polygon's vertices on that side
// and its crossings of the plane (seed 003 Algorithm 8 makes both boxes at
// once). Either may be empty where rounding clipped everything away.
void splitClip(const Triangle& tri, const Aabb& voxel, int axis, float p, Aabb& left, Aabb& right) {
  const ClippedPolygon poly(tri, voxel);
  for (int i = 0; i < poly.n; ++i) {
    const glm::vec3& cur = poly.v[i];
    const glm::vec3& next = poly.v[(i + 1) % poly.n];
    if (cur[axis] <= p) left.extend(cur);
    if (cur[axis] >= p) right.extend(cur);
    if ((cur[axis] < p && next[axis] > p) || (cur[axis] > p && next[axis] < p)) {
      glm::vec3 x = cur + ((p - cur[axis]) / (next[axis] - cur[axis])) * (next - cur);
      x[axis] = p;
      left.extend(x);
      right.extend(x);
    }
  }
}

// A clipped box made safe: inside the child voxel and the old bounds, and
// when rounding emptied it, the old bounds cut to the child (the triangle
// does touch the child's closed voxel, by classification).
Aabb settle(const Aabb& clipped, const Aabb& old, const Aabb& child) {
  const Aabb b = intersection(intersection(clipped, child), old);
  return b.empty() ? intersection(old, child) : b;
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

// One node still to build.
struct Item {
  std::vector<KdRef> refs;
  Aabb voxel;
  int depth = 0;  // splits above this node
};

// A subtree as a task built it: either a split node whose children were built
// as tasks of their own, or a whole subtree built on one thread with node and
// reference indices local to it (its root's parent is kNoHit).
struct Piece {
  KdNode node;
  std::unique_ptr<Piece> left, right;
  std::vector<KdNode> nodes;
  std::vector<uint32_t> refs;
  bool isSplit() const { return left != nullptr; }
};

class Driver {
 public:
  Driver(std::span<const Triangle> tris, const KdBuildConfig& config, KdSplitFinder findSplit, float minThickness)
      : tris_(tris), config_(config), findSplit_(findSplit), minThickness_(minThickness),
        maxDepth_(kdEffectiveMaxDepth(config, tris.size())),
        minElements_(static_cast<size_t>(std::max(config.minElements, 0))) {}

  std::unique_ptr<Piece> buildPiece(Item item) const {
    auto piece = std::make_unique<Piece>();
    if (item.refs.size() < kKdParallelNodeRefs) {
      buildSerial(std::move(item), piece->nodes, piece->refs);
      return piece;
    }
    const KdSplit split = choose(item);
    if (split.axis < 0) {
      appendLeaf(item, piece->nodes, piece->refs);
      return piece;
    }
    piece->node = splitNode(item.voxel, split);
    std::pair<Item, Item> children = partition(std::move(item), split);
    tbb::parallel_invoke([&] { piece->left = buildPiece(std::move(children.first)); },
                         [&] { piece->right = buildPiece(std::move(children.second)); });
    return piece;
  }

  // Copies the pieces into the depth-first layout, in tree order.
  void assemble(Piece& piece, uint32_t parent, KdTree& tree) const {
    if (piece.isSplit()) {
      const auto index = static_cast<uint32_t>(tree.nodes.size());
      piece.node.parent = parent;
      tree.nodes.push_back(piece.node);
      assemble(*piece.left, index, tree);
      tree.nodes[index].rightChild = static_cast<uint32_t>(tree.nodes.size());
      assemble(*piece.right, index, tree);
      piece = Piece{};
      return;
    }
    const auto base = static_cast<uint32_t>(tree.nodes.size());
    const auto refBase = static_cast<uint32_t>(tree.references.size());
    for (KdNode node : piece.nodes) {
      node.parent = node.parent == kNoHit ? parent : node.parent + base;
      if (node.isLeaf()) node.firstRef += refBase;
      else node.rightChild += base;
      tree.nodes.push_back(node);
    }
    tree.references.insert(tree.references.end(), piece.refs.begin(), piece.refs.end());
    piece = Piece{};  // free as we go
  }

 private:
  // The node's plane, or axis -1 for a leaf.
  KdSplit choose(const Item& item) const {
    const size_t n = item.refs.size();
    KdSplit split;
    if (n > minElements_ && item.depth < maxDepth_) split = findSplit_(item.refs, item.voxel, config_, minThickness_);
    if (!(split.cost < config_.intersectionCost * static_cast<float>(n))) split.axis = -1;  // a leaf is cheaper
    return split;
  }

  static KdNode splitNode(const Aabb& voxel, const KdSplit& split) {
    KdNode node;
    node.axis = static_cast<uint32_t>(split.axis);
    node.split = split.position;
    node.box = voxel;
    return node;
  }

  static void appendLeaf(const Item& item, std::vector<KdNode>& nodes, std::vector<uint32_t>& refs) {
    KdNode leaf;
    leaf.box = item.voxel;
    leaf.firstRef = static_cast<uint32_t>(refs.size());
    leaf.refCount = static_cast<uint32_t>(item.refs.size());
    for (const KdRef& r : item.refs) refs.push_back(r.tri);
    nodes.push_back(leaf);
  }

  // Each reference goes to every child whose closed voxel its bounds touch:
  // triangles in or touching the plane go to both.
  void sendToChildren(std::span<const KdRef> refs, const Aabb& parent, int axis, float p, const Item& left,
                      const Item& right,
                      std::vector<KdRef>& leftRefs, std::vector<KdRef>& rightRefs) const {
    size_t toLeft = 0, toRight = 0;  // counted first: one allocation per list
    for (const KdRef& r : refs) toLeft += r.bounds.min[axis] <= p, toRight += r.bounds.max[axis] >= p;
    leftRefs.reserve(leftRefs.size() + toLeft);
    rightRefs.reserve(rightRefs.size() + toRight);
    for (const KdRef& r : refs) {
      if (config_.splitClipping && r.bounds.min[axis] < p && r.bounds.max[axis] > p) {
        Aabb l, rr;
        splitClip(tris_[r.tri], parent, axis, p, l, rr);
        leftRefs.push_back({r.tri, settle(l, r.bounds, left.voxel)});
        rightRefs.push_back({r.tri, settle(rr, r.bounds, right.voxel)});
        continue;
      }
      if (r.bounds.min[axis] <= p)
        leftRefs.push_back({r.tri, childBounds(tris_[r.tri], r.bounds, left.voxel, config_.splitClipping)});
      if (r.bounds.max[axis] >= p)
        rightRefs.push_back({r.tri, childBounds(tris_[r.tri], r.bounds, right.voxel, config_.splitClipping)});
    }
  }

  std::pair<Item, Item> partition(Item item, const KdSplit& split) const {
    Item left, right;
    left.voxel = right.voxel = item.voxel;
    left.voxel.max[split.axis] = right.voxel.min[split.axis] = split.position;
    left.depth = right.depth = item.depth + 1;
    const std::span<const KdRef> refs = item.refs;
    if (refs.size() < kKdParallelSweepRefs) {
      sendToChildren(refs, item.voxel, split.axis, split.position, left, right, left.refs, right.refs);
    } else {
      // Fixed chunks, concatenated in order: the same lists for any thread count.
      std::vector<std::vector<KdRef>> lefts(kKdSweepChunks), rights(kKdSweepChunks);
      const size_t chunk = (refs.size() + kKdSweepChunks - 1) / kKdSweepChunks;
      tbb::parallel_for(size_t(0), kKdSweepChunks, [&](size_t c) {
        const size_t begin = std::min(refs.size(), c * chunk), end = std::min(refs.size(), begin + chunk);
        sendToChildren(refs.subspan(begin, end - begin), item.voxel, split.axis, split.position, left, right, lefts[c],
                       rights[c]);
      });
      for (size_t c = 0; c < kKdSweepChunks; ++c) {
        left.refs.insert(left.refs.end(), lefts[c].begin(), lefts[c].end());
        right.refs.insert(right.refs.end(), rights[c].begin(), rights[c].end());
        lefts[c] = {}, rights[c] = {};
      }
    }
    return {std::move(left), std::move(right)};
  }

  // A subtree on this thread, right children waiting on an explicit stack
  // while the left subtree is built (so the left child is index + 1).
  void buildSerial(Item root, std::vector<KdNode>& nodes, std::vector<uint32_t>& refs) const {
    struct Pending {
      Item item;
      uint32_t parent = kNoHit;
      bool isRight = false;
    };
    std::vector<Pending> stack;
    stack.push_back({std::move(root)});
    while (!stack.empty()) {
      Pending work = std::move(stack.back());
      stack.pop_back();
      const auto index = static_cast<uint32_t>(nodes.size());
      if (work.isRight) nodes[work.parent].rightChild = index;
      const KdSplit split = choose(work.item);
      if (split.axis < 0) {
        appendLeaf(work.item, nodes, refs);
      } else {
        nodes.push_back(splitNode(work.item.voxel, split));
        auto [left, right] = partition(std::move(work.item), split);
        stack.push_back({std::move(right), index, true});
        stack.push_back({std::move(left), index, false});  // popped next: index + 1
      }
      nodes[index].parent = work.parent;
    }
  }

  std::span<const Triangle> tris_;
  const KdBuildConfig& config_;
  KdSplitFinder findSplit_;
  float minThickness_;
  int maxDepth_;
  size_t minElements_;
};

}  // namespace

Aabb clipTriangleToBox(const Triangle& tri, const Aabb& box) {
  const ClippedPolygon poly(tri, box);
  Aabb bounds;
  for (int i = 0; i < poly.n; ++i) bounds.extend(poly.v[i]);
  return poly.n == 0 ? bounds : intersection(bounds, box);
}

KdTree buildKdTreeWith(std::span<const Triangle> tris, const KdBuildConfig& config, KdSplitFinder findSplit) {
  KdTree tree;
  if (tris.empty()) return tree;
  Item root;
  root.refs.reserve(tris.size());
  for (uint32_t t = 0; t < tris.size(); ++t) {
    root.refs.push_back({t, tris[t].bounds()});
    tree.bounds.extend(root.refs.back().bounds);
  }
  root.voxel = tree.bounds;
  const float minThickness = config.minVoxelFraction * glm::length(tree.bounds.extent());
  const Driver driver(tris, config, findSplit, minThickness);
  std::unique_ptr<Piece> pieces = driver.buildPiece(std::move(root));
  driver.assemble(*pieces, kNoHit, tree);
  return tree;
}

}  // namespace passtrace
