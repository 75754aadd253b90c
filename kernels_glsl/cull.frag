// The cull kernel (thesis 3.6): retires finished elements by writing depth 0,
// so later passes skip them in the early depth test. Active elements are
// discarded, so the occlusion query counts the elements retired by this pass.
#include "texel_address.glsl"

uniform sampler2D uState;  // w: 1 while the element has work, 0 when finished

void main() {
  if (readElement(uState).w != 0.0) discard;
  gl_FragDepth = 0.0;
}
