#pragma once
// Structural checks shared by the BVH tests (K/K and G/S trees alike, and the
// box predicates of the bvh-stack and bvh8 build tests).

#include <span>

#include "accel/bvh/bvh.h"
#include "accel/geometry/geometry.h"

namespace passtrace::test {

// Structural invariants of any BVH with one triangle per leaf: every node is
// reached once, every triangle sits in exactly one leaf whose box is its
// bounds, every box encloses its children's boxes, and every internal node
// has at least two children.
void expectValidBvh(const Bvh& bvh, std::span<const Triangle> tris);

// Box predicates of the BVH build tests (bvh-stack, bvh8 and its SBVH).
bool contains(const Aabb& outer, const Aabb& inner);
// With 1e-6 of the coordinates' size as slack: sampled points are rounded.
bool containsPoint(const Aabb& box, const glm::vec3& p);
bool finiteTriangle(const Triangle& t);
// Every point of a 45-point grid over triangle `index` lies in one of `boxes`
// (its leaves' boxes; an SBVH clips a triangle into several).
void expectTriangleInBoxes(const Triangle& tri, std::span<const Aabb> boxes, size_t index);

}  // namespace passtrace::test
