// The octree traversal's frames, which do not fit the ray's surfaces: one
// record per stream element in a shader storage buffer, indexed by the
// element, so it outlives a pass. accel/octree/gpu_octree_traversal.cpp sizes
// and binds it. Record of element e, at float e * (1 + 8 uStackSize):
//   [0] count: frames on the stack (packed)
//   then uStackSize frames (packed node, t0.xyz, t1.xyz, current child), root first.
layout(std430, binding = 0) buffer OctreeRayRecords { float octreeRecords[]; };
uniform uint uStackSize;
uniform uint uStreamWidth;

uint octreeRecordBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * (1u + 8u * uStackSize);
}
