#include "accel/bvh/goldsmith_salmon_builder.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <numeric>
#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "accel/bvh/escape_sequence.h"

namespace passtrace {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

inline float unionArea(const Aabb& a, const Aabb& b) {
  const glm::vec3 e = glm::max(a.max, b.max) - glm::min(a.min, b.min);
  return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// The tree while it grows: children as singly linked lists, so inserting a
// child or splitting a leaf in place is O(1).
struct BuildNode {
  Aabb box;
  uint32_t triangle = kNone;  // leaf: scene index
  uint32_t firstChild = kNone, lastChild = kNone, nextSibling = kNone;
  uint32_t childCount = 0;
  uint32_t leaves = 1;  // leaves below (a leaf: 1), for tie-breaking
  uint32_t parent = kNone;
  bool isLeaf() const { return childCount == 0; }
};

class Inserter {
 public:
  Inserter(std::span<const Aabb> boxes, uint32_t maxChildren, bool exhaustive)
      : boxes_(boxes), maxChildren_(maxChildren), exhaustive_(exhaustive) {
    nodes_.reserve(2 * boxes.size());
  }

  void clear() { nodes_.clear(); }

  void insert(uint32_t tri) {
    const Aabb& b = boxes_[tri];
    if (nodes_.empty()) {
      nodes_.push_back(leaf(tri));
      return;
    }
    if (nodes_[0].isLeaf()) {
      split(0, tri);
      return;
    }
    if (!exhaustive_) return insertGreedy(tri);
    // Branch and bound over the same costs: subtrees are expanded cheapest
    // inherited cost first; any insertion below a node costs at least its
    // inherited cost plus SA(O) (a new child's box holds O), which prunes.
    const float own = b.surfaceArea();
    float bestCost = std::numeric_limits<float>::infinity();
    bool bestPair = false;
    uint32_t bestNode = 0;
    heap_.clear();
    // Min-heap on (cost, leaves below, node index), a total order: equal
    // costs (zero-area geometry) go to the lightest subtree first, which
    // keeps such trees balanced and finds a free slot after a few pops.
    auto later = [this](const Candidate& x, const Candidate& y) {
      if (x.cost != y.cost) return x.cost > y.cost;
      const uint32_t lx = nodes_[x.node].leaves, ly = nodes_[y.node].leaves;
      return lx != ly ? lx > ly : x.node > y.node;
    };
    {
      const BuildNode& root = nodes_[0];
      heap_.push_back({(unionArea(root.box, b) - root.box.surfaceArea()) * float(root.childCount), 0});
    }
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const Candidate cand = heap_.back();
      heap_.pop_back();
      if (!(cand.cost + own < bestCost)) break;  // nothing left can beat the best
      const BuildNode& node = nodes_[cand.node];
      if (node.childCount < maxChildren_) {
        const float cost = cand.cost + unionArea(node.box, b);
        if (cost < bestCost) {
          bestCost = cost;
          bestPair = false;
          bestNode = cand.node;
        }
      }
      for (uint32_t c = node.firstChild; c != kNone; c = nodes_[c].nextSibling) {
        const BuildNode& child = nodes_[c];
        const float area = unionArea(child.box, b);
        if (child.isLeaf()) {
          if (cand.cost + 2.0f * area < bestCost) {
            bestCost = cand.cost + 2.0f * area;
            bestPair = true;
            bestNode = c;
          }
          continue;
        }
        const float inherited = cand.cost + (area - child.box.surfaceArea()) * float(child.childCount);
        if (inherited + own < bestCost) {
          heap_.push_back({inherited, c});
          std::push_heap(heap_.begin(), heap_.end(), later);
        }
      }
    }
    place(tri, bestPair, bestNode);
  }

  // Grows the boxes from `at`'s parent (pair) or `at` (new child) up to the
  // root, then links the triangle in.
  void place(uint32_t tri, bool pair, uint32_t at) {
    const Aabb& b = boxes_[tri];
    for (uint32_t n = pair ? nodes_[at].parent : at; n != kNone; n = nodes_[n].parent) {
      nodes_[n].box.extend(b);
      ++nodes_[n].leaves;
    }
    if (pair) {
      split(at, tri);
      return;
    }
    const auto index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back(leaf(tri));
    nodes_[index].parent = at;
    BuildNode& parent = nodes_[at];
    nodes_[parent.lastChild].nextSibling = index;
    parent.lastChild = index;
    ++parent.childCount;
  }

  void insertGreedy(uint32_t tri) {
    const Aabb& b = boxes_[tri];
    // Greedy descent from the root.
    float bestCost = std::numeric_limits<float>::infinity();
    enum { kNewChild, kPair } bestKind = kNewChild;
    uint32_t bestNode = 0;
    float pathCost = 0.0f;
    uint32_t n = 0;
    for (;;) {
      const BuildNode& node = nodes_[n];
      const float grown = unionArea(node.box, b);
      pathCost += (grown - node.box.surfaceArea()) * static_cast<float>(node.childCount);
      if (!(pathCost < bestCost)) break;  // every option below costs at least this
      if (node.childCount < maxChildren_ && pathCost + grown < bestCost) {
        bestCost = pathCost + grown;
        bestKind = kNewChild;
        bestNode = n;
      }
      // Cheapest leaf to pair with, and the most promising internal child.
      float leafCost = std::numeric_limits<float>::infinity();
      uint32_t leafChild = kNone;
      float innerEstimate = std::numeric_limits<float>::infinity(), innerIncrease = 0.0f;
      uint32_t innerChild = kNone;
      for (uint32_t c = node.firstChild; c != kNone; c = nodes_[c].nextSibling) {
        const BuildNode& child = nodes_[c];
        const float area = unionArea(child.box, b);
        if (child.isLeaf()) {
          if (2.0f * area < leafCost) {
            leafCost = 2.0f * area;
            leafChild = c;
          }
          continue;
        }
        // Its enlargement plus its own cheapest immediate option: one more
        // child, or (when full) at best a pair below it.
        const float increase = (area - child.box.surfaceArea()) * static_cast<float>(child.childCount);
        const float estimate = increase + (child.childCount < maxChildren_ ? area : 2.0f * area);
        if (innerChild == kNone || estimate < innerEstimate ||
            (estimate == innerEstimate && child.leaves < nodes_[innerChild].leaves)) {
          innerEstimate = estimate;
          innerIncrease = increase;
          innerChild = c;
        }
      }
      if (leafChild != kNone && pathCost + leafCost < bestCost) {
        bestCost = pathCost + leafCost;
        bestKind = kPair;
        bestNode = leafChild;
      }
      if (innerChild == kNone || !(pathCost + innerIncrease < bestCost)) break;
      n = innerChild;
    }
    place(tri, bestKind == kPair, bestNode);
  }

  // Goldsmith/Salmon cost of the current tree (see the header).
  double cost() const {
    if (nodes_.empty()) return 0.0;
    double sum = 0.0;
    bool any = false;
    for (const BuildNode& node : nodes_)
      if (!node.isLeaf()) {
        sum += double(node.box.surfaceArea()) * node.childCount;
        any = true;
      }
    if (!any) return 0.0;
    const double root = nodes_[0].box.surfaceArea();
    if (root > 0.0) return sum / root;
    double children = 0.0;  // zero-area scene: every node is hit
    for (const BuildNode& node : nodes_) children += node.childCount;
    return children;
  }

  std::vector<BuildNode>& nodes() { return nodes_; }

 private:
  BuildNode leaf(uint32_t tri) const {
    BuildNode node;
    node.box = boxes_[tri];
    node.triangle = tri;
    return node;
  }

  // Leaf `at` becomes an internal node holding its old triangle and `tri`;
  // it keeps its index, so its parent's child list is untouched.
  void split(uint32_t at, uint32_t tri) {
    const auto oldLeaf = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back(leaf(nodes_[at].triangle));
    nodes_.push_back(leaf(tri));
    BuildNode& node = nodes_[at];
    node.triangle = kNone;
    node.box.extend(boxes_[tri]);
    node.firstChild = oldLeaf;
    node.lastChild = oldLeaf + 1;
    node.childCount = 2;
    node.leaves = 2;
    nodes_[oldLeaf].nextSibling = oldLeaf + 1;
    nodes_[oldLeaf].parent = at;
    nodes_[oldLeaf + 1].parent = at;
  }

  std::span<const Aabb> boxes_;
  struct Candidate {
    float cost;
    uint32_t node;
  };
  uint32_t maxChildren_;
  bool exhaustive_;
  std::vector<BuildNode> nodes_;
  std::vector<Candidate> heap_;
};

// Breadth first into the shared Bvh layout, children in list order.
Bvh toBvh(const std::vector<BuildNode>& build) {
  Bvh bvh;
  if (build.empty()) return bvh;
  bvh.nodes.reserve(build.size());
  bvh.children.reserve(build.size() - 1);
  auto convert = [&](const BuildNode& b) {
    BvhNode node;
    node.box = b.box;
    node.triangle = b.isLeaf() ? b.triangle : kNoHit;
    return node;
  };
  bvh.nodes.push_back(convert(build[0]));
  std::vector<std::pair<uint32_t, uint32_t>> queue{{0u, 0u}};  // (build node, bvh node)
  for (size_t head = 0; head < queue.size(); ++head) {
    const auto [src, dst] = queue[head];
    const BuildNode& b = build[src];
    if (b.isLeaf()) continue;
    bvh.nodes[dst].firstChild = static_cast<uint32_t>(bvh.children.size());
    bvh.nodes[dst].childCount = b.childCount;
    for (uint32_t c = b.firstChild; c != kNone; c = build[c].nextSibling) {
      const auto index = static_cast<uint32_t>(bvh.nodes.size());
      bvh.nodes.push_back(convert(build[c]));
      bvh.children.push_back(index);
      queue.emplace_back(c, index);
    }
  }
  return bvh;
}

}  // namespace

Bvh buildGoldsmithSalmon(std::span<const Triangle> tris, const GoldsmithSalmonConfig& config,
                         double* estimatedCost) {
  if (estimatedCost) *estimatedCost = 0.0;
  if (tris.empty()) return {};
  std::vector<Aabb> boxes(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) boxes[i] = tris[i].bounds();

  // The shuffles are drawn one after another from one stream (so the first
  // try is the same whatever `tries` is), then built on worker threads.
  const int tries = std::max(1, config.tries);
  std::vector<std::vector<uint32_t>> orders(static_cast<size_t>(tries));
  std::vector<uint32_t> order(tris.size());
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(config.seed);
  for (auto& o : orders) {
    // Fisher-Yates on the previous order, spelled out so every standard
    // library gives the same sequence (std::shuffle is unspecified).
    for (size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng() % (i + 1)]);
    o = order;
  }
  const uint32_t maxChildren = static_cast<uint32_t>(std::max(2, config.maxChildren));
  const bool exhaustive = config.search == GoldsmithSalmonSearch::BranchAndBound;
  int threads = config.threads > 0 ? config.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, tries);

  // Each worker keeps its cheapest try; ties go to the lower try index, so
  // the result does not depend on the thread count or scheduling.
  struct Best {
    double cost = std::numeric_limits<double>::infinity();
    int attempt = -1;
    std::vector<BuildNode> nodes;
  };
  std::vector<Best> bests(static_cast<size_t>(threads));
  std::atomic<int> next{0};
  auto work = [&](Best& best) {
    Inserter inserter(boxes, maxChildren, exhaustive);
    for (int attempt = next++; attempt < tries; attempt = next++) {
      inserter.clear();
      for (const uint32_t tri : orders[static_cast<size_t>(attempt)]) inserter.insert(tri);
      const double cost = inserter.cost();
      if (best.attempt < 0 || cost < best.cost || (cost == best.cost && attempt < best.attempt)) {
        best.cost = cost;
        best.attempt = attempt;
        std::swap(best.nodes, inserter.nodes());
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, std::ref(bests[static_cast<size_t>(t)]));
  work(bests[0]);
  for (std::thread& t : pool) t.join();
  Best* chosen = &bests[0];
  for (Best& b : bests)
    if (b.attempt >= 0 && (chosen->attempt < 0 || b.cost < chosen->cost ||
                           (b.cost == chosen->cost && b.attempt < chosen->attempt)))
      chosen = &b;
  const double bestCost = chosen->cost;
  std::vector<BuildNode>& best = chosen->nodes;
  if (estimatedCost) *estimatedCost = bestCost;
  return toBvh(best);
}

double goldsmithSalmonCost(const Bvh& bvh) {
  if (bvh.nodes.empty()) return 0.0;
  double sum = 0.0, children = 0.0;
  for (const BvhNode& node : bvh.nodes)
    if (!node.isLeaf()) {
      sum += double(node.box.surfaceArea()) * node.childCount;
      children += node.childCount;
    }
  if (children == 0.0) return 0.0;
  const double root = bvh.nodes[0].box.surfaceArea();
  return root > 0.0 ? sum / root : children;
}

SequenceBuild buildGoldsmithSalmonSequence(std::span<const Triangle> tris, const GoldsmithSalmonConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildGoldsmithSalmon(tris, config);
  SequenceBuild build{flattenEscapeSequence(bvh, tris), bvhStats("gs-bvh", bvh)};
  build.stats.floatsPerTriangle = build.sequence.floatsPerTriangle();
  build.stats.buildMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return build;
}

}  // namespace passtrace
