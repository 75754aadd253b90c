// Compaction, pass 2 (drawn into the compact stream): each slot below
// uLive copies every surface of its home element; the slots after them in
// the last blocks get zeros (state w = 0, retired by the next cull).
#include "texel_address.glsl"
#include "compact/compact_layout.glsl"

layout(early_fragment_tests) in;

uniform uint uLive;

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
  uint slot = compactSlot(ivec2(gl_FragCoord.xy));
  bool live = slot < uLive;
  ivec2 from = live ? homeTexel(homes[slot]) : ivec2(0);
  out0 = live ? readElementAt(uSurface0, from, uHomeWidth) : vec4(0.0);
#if SURFACES > 1
  out1 = live ? readElementAt(uSurface1, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 2
  out2 = live ? readElementAt(uSurface2, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 3
  out3 = live ? readElementAt(uSurface3, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 4
  out4 = live ? readElementAt(uSurface4, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 5
  out5 = live ? readElementAt(uSurface5, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 6
  out6 = live ? readElementAt(uSurface6, from, uHomeWidth) : vec4(0.0);
#endif
#if SURFACES > 7
  out7 = live ? readElementAt(uSurface7, from, uHomeWidth) : vec4(0.0);
#endif
}
