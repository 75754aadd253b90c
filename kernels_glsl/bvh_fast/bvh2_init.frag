// bvh-fast traversal set-up: every ray starts at the root with an empty stack
// (aux.x) and fresh counts; an empty scene finishes every ray here.
#include "texel_address.glsl"

layout(early_fragment_tests) in;

uniform int uEmpty;  // 1: no nodes

layout(location = 0) out vec4 outState;  // packed node, steps, tests, hasWork
layout(location = 1) out vec4 outAux;    // packed stack entries

void main() {
  outState = vec4(packIndex(0u), 0.0, 0.0, uEmpty != 0 ? 0.0 : 1.0);
  outAux = vec4(packIndex(0u), 0.0, 0.0, 0.0);
}
