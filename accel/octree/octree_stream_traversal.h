#pragma once
// Revelles' octree traversal (octree_revelles.h) on the CPU, step for step as
// kernels_glsl/octree/octree_traversal.glsl runs it on the GPU, over the same
// texels (octree_texels.h): both must find the same hits and count the same
// steps (tests/gl/gpu_traversal_test.cpp). It is also the `octree` row's CPU
// traversal. Why a copy and not one source: see accel/kd/kd_stream_traversal.h.
//
// A ray is at a node (mode DOWN) or testing a leaf's list. Each internal node
// on the current path is a frame (node, t0, t1, current child) on a stack as
// deep as the tree; the node the ray is at gets its parameters from the top
// frame (or the root's). Children come in the order the ray passes them, so
// traversal ends at the first node entered at or beyond the current hit, and
// after a leaf whose exit lies at or beyond it.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/geometry/geometry.h"
#include "accel/geometry/triangle_test.h"
#include "accel/traversal_stats.h"

namespace passtrace {

struct OctreeStreamData {
  Aabb rootBox;
  std::span<const glm::vec4> nodes, lists, triangles;
  TriangleTest triangleTest = TriangleTest::MollerTrumbore;  // as the kernel is compiled
};

struct OctreeStreamCursor {
  static constexpr float kModeDown = -1.0f;
  struct Frame {
    uint32_t node;
    glm::vec3 t0, t1;
    int current;  // the mirrored octant being visited
  };
  uint32_t node = 0;
  float mode = kModeDown;  // kModeDown, or a packed list entry while testing a leaf
  float leafExit = 0;      // the leaf's exit parameter while testing it
  Hit best;
  RayStats stats;
  bool done = false;
  std::vector<Frame> frames;
};

// octree_init.frag: at the root with no frames; done for an empty octree.
OctreeStreamCursor octreeStreamStart(const OctreeStreamData& data, const Ray& ray);
// Up to maxSteps steps of octree_traverse.frag; returns true while work remains.
bool octreeStreamSteps(const OctreeStreamData& data, const Ray& ray, bool anyHit, OctreeStreamCursor& cursor,
                       uint32_t maxSteps);
Hit traverseOctreeStream(const OctreeStreamData& data, const Ray& ray, bool anyHit, RayStats* stats = nullptr);

}  // namespace passtrace
