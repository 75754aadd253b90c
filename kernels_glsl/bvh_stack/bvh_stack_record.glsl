// The stack BVH's per-ray stack, which must outlive a pass: one record per
// stream element in a shader storage buffer (accel/bvh_stack/gpu_bvh_stack_traversal.cpp
// sizes and binds it). Record of element e, at float e * (1 + 3 uStackSize):
//   [0] entries on the stack (packed)
//   then uStackSize entries (link, count, tNear) as bvh_stack_texels.h's child links.
layout(std430, binding = 0) buffer BvhStackRecords { float bvhRecords[]; };
uniform uint uStackSize;
uniform uint uStreamWidth;

uint bvhRecordBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * (1u + 3u * uStackSize);
}
