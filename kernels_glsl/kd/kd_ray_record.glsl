// The push-down, short-stack and stack traversals' per-ray state that does not
// fit the ray's surfaces (state and aux are full): one record per stream
// element in a shader storage buffer, indexed by the element, so it outlives a
// pass. accel/kd/gpu_kd_traversal.cpp sizes and binds it. Record of element e,
// at float e * (4 + 3 uStackSize):
//   [0] restart root (packed node): 0, or with push-down the push-down root
//   [1] top: the slot the next push writes (packed)
//   [2] count: entries on the stack, <= uStackSize (packed)
//   [3] 1 while the current descent has met no node with both children to visit
//   then uStackSize entries (packed node, tMin, tMax), a circular stack: a
//   push onto a full stack overwrites the oldest entry.
layout(std430, binding = 0) buffer KdRayRecords { float kdRecords[]; };
uniform uint uStackSize;
uniform uint uStreamWidth;

uint kdRecordBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * (4u + 3u * uStackSize);
}

void kdStorePush(uint base, uint top, uint node, float tMin, float tMax) {
  uint at = base + 4u + 3u * top;
  kdRecords[at] = packIndex(node);
  kdRecords[at + 1u] = tMin;
  kdRecords[at + 2u] = tMax;
}
