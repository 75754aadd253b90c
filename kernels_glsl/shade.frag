// The shading pass (thesis 4.2): shade_thesis.glsl over every active element.
#include "texel_address.glsl"
#include "ray_kinds.glsl"
#include "shade_thesis.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uColor;
uniform sampler2D uThroughput;
uniform sampler2D uPending;

layout(location = 0) out vec4 outOrigin;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outState;
layout(location = 3) out vec4 outHit;
layout(location = 4) out vec4 outColor;
layout(location = 5) out vec4 outThroughput;
layout(location = 6) out vec4 outPending;

void main() {
  StreamElement e = StreamElement(readElement(uOrigin), readElement(uDirection), readElement(uState),
                                  readElement(uHit), readElement(uColor), readElement(uThroughput),
                                  readElement(uPending));
  shadeElement(e);
  outOrigin = e.origin;
  outDirection = e.direction;
  outState = e.state;
  outHit = e.hit;
  outColor = e.color;
  outThroughput = e.throughput;
  outPending = e.pending;
}
