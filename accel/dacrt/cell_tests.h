#pragma once
// The three tests DACRT filters with (seed 001, §3.2-3.3): a ray against a
// cell, a triangle against a cell, and a cone of rays against a cell. All
// three are conservative: rounding may keep an element that misses the cell,
// never drop one that touches it, since a dropped element is a lost hit.

#include <cmath>

#include "accel/geometry/geometry.h"

namespace passtrace::dacrt {

// Does the ray enter `cell` before tBest (its best hit so far, or tMax)? The
// BVHs' robust slab test (geometry.h), with the entry compared as loosely as
// the exit: a hit exactly on the cell's face must not be lost.
inline bool rayEntersCell(const glm::vec3& origin, const glm::vec3& invDir, const Aabb& cell, float tBest) {
  float tNear, tFar;
  clipToBox(origin, invDir, cell, tNear, tFar);
  const float tExit = tFar * kRobustExitScale;
  return tNear <= tExit && tExit >= 0.0f && tNear <= tBest * kRobustExitScale;
}

// The cell grown by a margin that covers the rounding of the tests below
// (about 1e-5 of its size and position; far more than their float error).
inline Aabb loosened(const Aabb& cell) {
  const glm::vec3 scale = glm::max(glm::abs(cell.min), glm::abs(cell.max));
  const float size = std::max({cell.max.x - cell.min.x, cell.max.y - cell.min.y, cell.max.z - cell.min.z});
  const glm::vec3 margin = 1e-5f * (glm::vec3(size) + scale) + glm::vec3(1e-30f);
  return Aabb{cell.min - margin, cell.max + margin};
}

// Separating-axis test of Akenine-Möller ("Fast 3D triangle-box overlap
// testing", 2001) against the loosened cell: the box's three axes, the
// triangle's plane, and the nine cross products of their edges.
bool triangleTouchesCell(const Triangle& tri, const Aabb& cell);

// A cone of rays: every ray of the packet starts at `apex` (or, for shadow
// rays, ends there) and its direction, seen from the apex, makes an angle of
// at most acos(cosAngle) with `axis` (unit). Half-angles must stay below 90°.
struct Cone {
  glm::vec3 apex{0.0f};
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  float cosAngle = 1.0f;
};

// Exact cone/box test (the seed's Appendix, after Eberly's line/cone
// intersection), on the loosened cell: the cone touches the box when the
// apex is inside it, when its axis ray enters it, or when one of its twelve
// edges enters the cone. (If neither, the cone's section with a face lies
// inside the face and is bounded, so it holds the axis's point: a
// contradiction.) The seed tests only the silhouette edges (0, 4 or 6); this
// tests all twelve, which is the same answer for more work.
bool coneTouchesCell(const Cone& cone, const Aabb& cell);

}  // namespace passtrace::dacrt
