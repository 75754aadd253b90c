// Octree traversal set-up: every ray starts at the root with no frames; the
// first step finds whether it enters the root at all.
#include "texel_address.glsl"
#include "octree/octree_ray_record.glsl"

layout(early_fragment_tests) in;

uniform int uEmpty;  // 1: no triangles, every ray misses

layout(location = 0) out vec4 outState;  // packed node, steps, tests, hasWork
layout(location = 1) out vec4 outAux;    // mode, leafExit, 0, 0

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  outState = vec4(packIndex(0u), 0.0, 0.0, uEmpty != 0 ? 0.0 : 1.0);
  outAux = vec4(-1.0, 0.0, 0.0, 0.0);
  octreeRecords[octreeRecordBase()] = packIndex(0u);
}
