// Compaction, pass 1: every live element (it passed the early depth test)
// takes the next slot. Lanes of one SIMD block take consecutive slots, so
// rays that were neighbours stay neighbours; the order of blocks is the
// driver's (results are per ray and do not depend on it).
#include "compact/compact_layout.glsl"

layout(early_fragment_tests) in;

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  uint home = homeIndex(ivec2(gl_FragCoord.xy));
  uint slot = atomicAdd(liveCount, 1u);
  homes[slot] = home;
  slotOf[home] = slot;
}
