#pragma once
// Structural checks shared by the BVH tests (K/K and G/S trees alike).

#include <span>

#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"

namespace passtrace::test {

// Structural invariants of any BVH with one triangle per leaf: every node is
// reached once, every triangle sits in exactly one leaf whose box is its
// bounds, every box encloses its children's boxes, and every internal node
// has at least two children.
void expectValidBvh(const Bvh& bvh, std::span<const Triangle> tris);

}  // namespace passtrace::test
