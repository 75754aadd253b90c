#pragma once
// Revelles, Ureña & Lastra 2000, "An Efficient Parametric Algorithm for Octree
// Traversal": a node's slab parameters t0 (entry) and t1 (exit) per axis; its
// children's come from tm = ½(t0 + t1) by selection alone (only adds and
// halvings). The ray is mirrored to positive directions around the root's
// center (and parallel rays in the upper half); the a-mask (bit k: mirrored) maps a mirrored octant to
// the stored one (octant ^ a). Octant bit k: upper half along axis k, as
// buildOctree numbers them. kernels_glsl/octree/octree_revelles.glsl computes
// the same, operation for operation.

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"

namespace passtrace {

// Slab parameters are clamped to ±kRevellesLimit so sums of them stay finite
// (a parallel ray's 1e20 inverse over a 1e20-wide scene would overflow).
inline constexpr float kRevellesLimit = 1e30f;
inline constexpr int kRevellesExit = 8;  // "no next child": the ray leaves the parent

struct RevellesRay {
  int a = 0;  // mirrored axes
  glm::vec3 t0{0.0f}, t1{0.0f};  // the root's parameters
};

// The mirrored ray's parameters over the root box.
RevellesRay revellesStart(const Aabb& root, const glm::vec3& origin, const glm::vec3& direction);

// The first child the ray enters: the entry plane is the axis of the largest
// t0 (lowest axis on ties); along each other axis the upper half when the
// ray has crossed its middle (tm) before entering.
int revellesFirstChild(const glm::vec3& t0, const glm::vec3& tm);
// The child after `current`, whose exit parameters are t1: leaving through
// the exit plane's axis (smallest t1, lowest axis on ties) into the upper
// half, or out of the parent when `current` is there already. Revelles'
// table: next[current][exit axis].
int revellesNextChild(int current, const glm::vec3& t1);
// The parameters of mirrored child `octant` of a node with t0, t1, tm.
void revellesChild(int octant, const glm::vec3& t0, const glm::vec3& t1, const glm::vec3& tm, glm::vec3& c0,
                   glm::vec3& c1);

// The stored octants (octant ^ a) of a node with box `box` that the ray
// passes, in the order Revelles visits them (children behind the origin
// included), for tests.
std::vector<int> revellesChildOrder(const Aabb& box, const Ray& ray);

}  // namespace passtrace
