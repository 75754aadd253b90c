#pragma once
// Kay/Kajiya top-down BVH construction (thesis 9.3.1, Algorithm 3): binary,
// one triangle per leaf, split at the spatial median along whichever axis
// gives the smallest summed surface area of the two child boxes.

#include <cstdint>
#include <span>

#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"

namespace passtrace {

struct KayKajiyaConfig {
  // Probability that an internal node's two children are swapped (Foley's
  // coin flip, thesis 9.4.3): tracy's -c argument times 0.5, so the default
  // 0.5 is tracy's default -c 1. 0 keeps "left" (centroid < median) first.
  float swapProbability = 0.5f;
  // Seeds the coin flips; the same seed and triangles give the same tree.
  uint64_t seed = 0x5eed;
};

// Builds the tree; an empty span gives an empty Bvh. Each split uses the
// spatial median of the node's *centroid* box (not its triangle box): a
// triangle goes left when its centroid lies below the median. Using centroids
// means any axis along which centroids differ can be split, and the child
// boxes are the bounds of the triangles themselves. Axes that put every
// triangle on one side are skipped; when all three are (coincident
// centroids), the node's triangles are halved in scene order (lower indices
// left), so construction always terminates. The tree depends only on the
// triangles, the config and the seed, not on the standard library.
// O(N log N) for reasonable scenes; an explicit work stack, no recursion.
// Peak extra memory: 40 bytes per triangle besides the tree itself.
Bvh buildKayKajiya(std::span<const Triangle> tris, const KayKajiyaConfig& config = {});

}  // namespace passtrace
