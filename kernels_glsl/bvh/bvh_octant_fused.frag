// bvh-octant-fused (issue 17 item 3, fewer passes per bounce): a primary
// bounce in one pass, raygen.frag's ray, bvh_octant_walk.glsl's traversal
// and shade.frag's shading, with nothing between them going through the
// stream's surfaces. It writes what those three passes leave behind. A ray
// the walk could not finish within the pass's budget counts itself in
// uUnfinished; the renderer then runs the bounce again pass by pass.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "camera.glsl"
#include "shade_thesis.glsl"
#include "bvh/bvh_octant_walk.glsl"

layout(early_fragment_tests) in;

uniform int uKeepHit;  // 1: the hit surface keeps the primary hit (--hits on the last bounce)
layout(std430, binding = 0) buffer Unfinished { uint uUnfinished; };

layout(location = 0) out vec4 outOrigin;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outState;
layout(location = 3) out vec4 outHit;
layout(location = 4) out vec4 outColor;
layout(location = 5) out vec4 outThroughput;
layout(location = 6) out vec4 outPending;

void main() {
  vec3 direction = cameraRayDirection();
  StreamElement e = StreamElement(vec4(uEye, RAY_NEAREST), vec4(direction, INF), vec4(0.0),
                                  vec4(INF, 0.0, 0.0, packIndex(0u)), vec4(0.0), vec4(1.0, 1.0, 1.0, 0.0),
                                  vec4(0.0));
  uint index = 0u;
  float steps = 0.0, tests = 0.0;
  octantWalk(e.origin.xyz, direction, false, index, steps, tests, e.hit);
  e.state = vec4(packIndex(index), steps, tests, 0.0);
  if (index < uSequenceSize) {
    atomicAdd(uUnfinished, 1u);
  } else {
    vec4 primaryHit = e.hit;
    shadeElement(e);
    if (uKeepHit != 0) e.hit = primaryHit;
  }
  outOrigin = e.origin;
  outDirection = e.direction;
  outState = e.state;
  outHit = e.hit;
  outColor = e.color;
  outThroughput = e.throughput;
  outPending = e.pending;
}
