// Triangle reference lists (accel/reference_lists.h) are scalars read with
// fetchScalar: a packed triangle index per entry, each list ended by a
// negative entry. The triangles they point to are 3 texels each, in scene order.

// Tests triangle `packedId` (a list entry) against the ray; see intersect.glsl.
bool testListedTriangle(ConstStream triangles, float packedId, vec3 origin, vec3 dir, inout vec4 hit) {
  uint base = 3u * unpackIndex(packedId);
  vec3 a = fetchTexel(triangles, base).xyz;
  vec3 b = fetchTexel(triangles, base + 1u).xyz;
  vec3 c = fetchTexel(triangles, base + 2u).xyz;
  return intersectTriangle(origin, dir, a, b, c, packedId, hit);
}
