// Compaction, pass 3 (drawn into the ray stream, live elements only): each
// element copies every surface back from the slot it was gathered to.
#include "texel_address.glsl"
#include "compact/compact_layout.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uSurface0;
layout(location = 0) out vec4 out0;
#if SURFACES > 1
uniform sampler2D uSurface1;
layout(location = 1) out vec4 out1;
#endif
#if SURFACES > 2
uniform sampler2D uSurface2;
layout(location = 2) out vec4 out2;
#endif
#if SURFACES > 3
uniform sampler2D uSurface3;
layout(location = 3) out vec4 out3;
#endif
#if SURFACES > 4
uniform sampler2D uSurface4;
layout(location = 4) out vec4 out4;
#endif
#if SURFACES > 5
uniform sampler2D uSurface5;
layout(location = 5) out vec4 out5;
#endif
#if SURFACES > 6
uniform sampler2D uSurface6;
layout(location = 6) out vec4 out6;
#endif
#if SURFACES > 7
uniform sampler2D uSurface7;
layout(location = 7) out vec4 out7;
#endif

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  ivec2 from = compactTexel(slotOf[homeIndex(ivec2(gl_FragCoord.xy))]);
  out0 = readElementAt(uSurface0, from, 4u * uBlocksPerRow);
#if SURFACES > 1
  out1 = readElementAt(uSurface1, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 2
  out2 = readElementAt(uSurface2, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 3
  out3 = readElementAt(uSurface3, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 4
  out4 = readElementAt(uSurface4, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 5
  out5 = readElementAt(uSurface5, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 6
  out6 = readElementAt(uSurface6, from, 4u * uBlocksPerRow);
#endif
#if SURFACES > 7
  out7 = readElementAt(uSurface7, from, 4u * uBlocksPerRow);
#endif
}
