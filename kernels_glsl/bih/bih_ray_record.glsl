// The BIH traversal's stack, which does not fit the ray's surfaces: one record
// per stream element in a shader storage buffer, indexed by the element, so it
// outlives a pass. accel/bih/gpu_bih_traversal.cpp sizes and binds it. Record
// of element e, at float e * (1 + 3 uStackSize):
//   [0] count: entries on the stack (packed)
//   then uStackSize entries (packed node, tMin, tMax), bottom first.
layout(std430, binding = 0) buffer BihRayRecords { float bihRecords[]; };
uniform uint uStackSize;
uniform uint uStreamWidth;

uint bihRecordBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * (1u + 3u * uStackSize);
}
