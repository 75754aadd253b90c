#pragma once
// Goldsmith/Salmon bottom-up BVH construction (thesis 9.3.2): triangles are
// inserted one at a time, in a shuffled order, each at the place in the tree
// where it increases the estimated traversal cost least. Nodes get any number
// of children; one triangle per leaf. The construction is repeated `tries`
// times with different shuffles and the cheapest tree is kept.
//
// Cost model (Goldsmith & Salmon 1987): a ray that hits a node tests all its
// children, and hits a node with probability SA(node) / SA(root), so
//
//   cost(tree) = sum over internal nodes n of SA(n) / SA(root) * children(n)
//
// (when the root's surface area is 0 every node counts with probability 1).
// Inserting triangle O below node n costs, per level on the way down,
// (SA(n + O) - SA(n)) * children(n) for the enlarged box, and at the bottom
// either SA(n + O) (O becomes one more child of n) or 2 * SA(leaf + O) (a
// leaf child of n is replaced by a new internal node holding the leaf and O).
//
// Where to insert: the 1987 article descends greedily, following at each
// node the child whose enlargement plus own cheapest option is least and
// remembering the cheapest option seen on the path (Greedy below). On 100k
// triangle meshes that gave trees 2.5x the cost of our Kay/Kajiya tree and
// 2.5x its traversal steps (sphere, soup), where the thesis found G/S
// slightly faster than K/K (Table 1). The default therefore finds the
// cheapest position in the whole tree under the same cost (BranchAndBound:
// best-first over inherited cost, pruned because any insertion below a node
// costs at least its inherited cost plus SA(O)), as in Bittner et al.'s
// insertion-based BVH optimisation (2013). It gives trees of about K/K's cost
// with 4.5 floats per triangle on a sphere (Table 3: 4.1-5.0) at roughly
// twice the greedy build time.

#include <cstdint>
#include <span>

#include "accel/bvh/bvh.h"
#include "accel/bvh/bvh_structures.h"
#include "accel/geometry/geometry.h"

namespace passtrace {

enum class GoldsmithSalmonSearch {
  Greedy,          // follow the cheapest child down one path (the 1987 article)
  BranchAndBound,  // the cheapest position in the whole tree (see above)
};

struct GoldsmithSalmonConfig {
  // tracy's -t: constructions with different shuffles; the cheapest is kept.
  // Values below 1 count as 1.
  int tries = 10;
  // Seeds the shuffles. Try k uses the (k+1)-th shuffle of one
  // std::mt19937_64(seed) stream, so the first try of any `tries` is the same
  // tree, and more tries are never worse.
  uint64_t seed = 0x65;
  // Most children per node (not in the thesis): bounds the per-level scan and
  // keeps coincident or heavily overlapping geometry, where the cost model
  // prefers one flat node, from making construction quadratic. A full node
  // takes new triangles only below its children. At least 2.
  int maxChildren = 16;
  GoldsmithSalmonSearch search = GoldsmithSalmonSearch::BranchAndBound;
  // Tries run on this many threads (0: std::thread::hardware_concurrency());
  // the result is the same for any count.
  int threads = 0;
};

// Builds the cheapest of config.tries trees; an empty span gives an empty
// Bvh. Children are stored in insertion order (the old leaf before the new
// triangle when a leaf is split). estimatedCost, when given, receives the
// kept tree's cost as defined above (0 for an empty or single-leaf tree).
// Deterministic for given triangles and config, whatever the thread count and
// standard library: own Fisher-Yates over std::mt19937_64, a total order on
// search candidates (cost, then fewest leaves below, then node index), ties
// between tries to the earlier one. Ties between options go to the first
// seen (a node's new-child option before its children's); with maxChildren
// and the fewest-leaves rule, coincident geometry (all areas 0) becomes a
// balanced tree of depth about log16 N.
Bvh buildGoldsmithSalmon(std::span<const Triangle> tris, const GoldsmithSalmonConfig& config = {},
                         double* estimatedCost = nullptr);

// The cost above of any BVH (n-ary, one triangle per leaf).
double goldsmithSalmonCost(const Bvh& bvh);

// The G/S tree flattened to its escape-index sequence (the same layout and
// kernel as Kay/Kajiya), with statistics named acceleratorName(1); buildMs
// covers all tries and the flattening. floatsPerTriangle = 8 * boxes / N.
SequenceBuild buildGoldsmithSalmonSequence(std::span<const Triangle> tris, const GoldsmithSalmonConfig& config = {});

}  // namespace passtrace
