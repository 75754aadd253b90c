// Stack BVH traversal set-up: every ray at the root with an empty stack
// (bvh_stack_record.glsl); rays of an empty tree finish here.
#include "texel_address.glsl"
#include "bvh_stack/bvh_stack_record.glsl"

layout(early_fragment_tests) in;

uniform bool uEmpty;

layout(location = 0) out vec4 outState;  // packed link, steps, tests, hasWork
layout(location = 1) out vec4 outAux;    // count, 0, 0, 0

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  outState = vec4(packIndex(0u), 0.0, 0.0, uEmpty ? 0.0 : 1.0);
  outAux = vec4(0.0);
  bvhRecords[bvhRecordBase()] = packIndex(0u);
}
