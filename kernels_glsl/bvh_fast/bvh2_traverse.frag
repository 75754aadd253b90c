// bvh-fast: a binary BVH walked near child first with a per-ray stack
// (accel/bvh_fast/bvh2_texels.h has the layout, bvh2_traversal.cpp the same
// steps on the CPU). One step visits one node and tests both its children: a
// box, or a single triangle in place of its box. Up to uLoopLimit steps per
// pass; with a large -l a ray's whole traversal is one pass. The stack lives
// in a local array during a pass (BVH2_STACK_DEPTH entries, the tree's depth)
// and in the storage buffer between passes, so a ray that finishes in its
// pass never touches the buffer (llvmpipe's buffer accesses are slow).
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "bvh_fast/bvh2_stack.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uAux;
uniform ConstStream uNodes;
uniform ConstStream uTriangles;
uniform int uLoopLimit;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;
layout(location = 2) out vec4 outAux;

const float KIND_NODE = 1.0, KIND_TRIANGLE = 2.0;

vec3 gOrigin, gDirection, gInvDir;
vec4 gHit;
float gTests;

// Child `first` (texel 4 node + first) of a node: tests its triangle, or its
// box. Returns true when an any-hit ray found its hit.
bool visitChild(uint at, bool anyHit, out bool enter, out float entry, out uint child) {
  vec4 lo = fetchTexel(uNodes, at);
  vec4 hi = fetchTexel(uNodes, at + 1u);
  enter = false;
  entry = 0.0;
  child = 0u;
  if (hi.w == KIND_TRIANGLE) {
    gTests += 1.0;
    uint id = unpackIndex(lo.w);
    vec3 a = fetchTexel(uTriangles, 3u * id).xyz;
    vec3 b = fetchTexel(uTriangles, 3u * id + 1u).xyz;
    vec3 c = fetchTexel(uTriangles, 3u * id + 2u).xyz;
    return intersectTriangle(gOrigin, gDirection, a, b, c, lo.w, gHit) && anyHit;
  }
  if (hi.w == KIND_NODE) {
    float tNear, tFar;
    clipToBox(gOrigin, gInvDir, lo.xyz, hi.xyz, tNear, tFar);
    precise float tExit = tFar * 1.00000035762786865234375;
    enter = tNear <= tExit && tExit >= 0.0 && tNear < gHit.x;
    entry = tNear;
    child = unpackIndex(lo.w);
  }
  return false;
}

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  gHit = readElement(uHit);
  uint count = unpackIndex(readElement(uAux).x);
  bool anyHit = origin.w == RAY_SHADOW;
  gOrigin = origin.xyz;
  gDirection = direction.xyz;
  gInvDir = safeInverse(direction.xyz);
  uint base = bvh2StackBase();

  uint stackNode[BVH2_STACK_DEPTH];
  float stackEntry[BVH2_STACK_DEPTH];
  for (uint s = 0u; s < count; ++s) {
    stackNode[s] = unpackIndex(bvh2Stack[base + 2u * s]);
    stackEntry[s] = bvh2Stack[base + 2u * s + 1u];
  }

  uint node = unpackIndex(state.x);
  float steps = state.y;
  gTests = state.z;
  bool done = false;
  for (int i = 0; i < uLoopLimit && !done; ++i) {
    steps += 1.0;
    bool enter0, enter1;
    float entry0, entry1;
    uint child0, child1;
    done = visitChild(4u * node, anyHit, enter0, entry0, child0);
    if (done) break;
    done = visitChild(4u * node + 2u, anyHit, enter1, entry1, child1);
    if (done) break;
    if (enter0 && enter1) {
      bool nearIsOne = entry1 < entry0;
      stackNode[count] = nearIsOne ? child0 : child1;
      stackEntry[count] = nearIsOne ? entry0 : entry1;
      count += 1u;
      node = nearIsOne ? child1 : child0;
    } else if (enter0 || enter1) {
      node = enter0 ? child0 : child1;
    } else {
      done = true;
      while (count > 0u) {
        count -= 1u;
        if (stackEntry[count] < gHit.x) {
          node = stackNode[count];
          done = false;
          break;
        }
      }
    }
  }
  if (!done) {
    for (uint s = 0u; s < count; ++s) {
      bvh2Stack[base + 2u * s] = packIndex(stackNode[s]);
      bvh2Stack[base + 2u * s + 1u] = stackEntry[s];
    }
  }
  outState = vec4(packIndex(node), steps, gTests, done ? 0.0 : 1.0);
  outHit = gHit;
  outAux = vec4(packIndex(count), 0.0, 0.0, 0.0);
}
