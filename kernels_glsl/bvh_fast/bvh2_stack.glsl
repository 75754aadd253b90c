// bvh-fast's per-ray stack (accel/bvh_fast/gpu_bvh2_traversal.cpp sizes and
// binds it): one record per stream element in a shader storage buffer, so it
// outlives a pass. Record of element e, at float e * 2 uStackDepth: up to
// uStackDepth entries (packed node, entry distance), the nearest last. The
// entry count lives in the aux surface.
layout(std430, binding = 0) buffer Bvh2Stacks { float bvh2Stack[]; };
uniform uint uStackDepth;
uniform uint uStreamWidth;

uint bvh2StackBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * 2u * uStackDepth;
}
