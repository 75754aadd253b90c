// A triangle's shading data (render/scene_streams.h): with SHADING_TEXELS 4,
// (n0, packed material) (n1, 0) (n2, 0) (unit geometric normal, 0); with
// SHADING_TEXELS 1, for scenes without vertex normals, (unit geometric
// normal, packed material), the vertex normals being the geometric one.
// Needs texel_address.glsl.
#ifndef SHADING_TEXELS
#error "SHADING_TEXELS: the renderer defines it (render/scene_streams.h, shadingTexelsDefine)"
#endif

uniform ConstStream uTriangles;

struct TriangleShading {
  vec3 n0, n1, n2, geometric;
  uint material;
};

TriangleShading fetchTriangleShading(uint triangle) {
#if SHADING_TEXELS == 1
  vec4 only = fetchTexel(uTriangles, triangle);
  return TriangleShading(only.xyz, only.xyz, only.xyz, only.xyz, unpackIndex(only.w));
#else
  vec4 n0 = fetchTexel(uTriangles, 4u * triangle);
  return TriangleShading(n0.xyz, fetchTexel(uTriangles, 4u * triangle + 1u).xyz,
                         fetchTexel(uTriangles, 4u * triangle + 2u).xyz,
                         fetchTexel(uTriangles, 4u * triangle + 3u).xyz, unpackIndex(n0.w));
#endif
}
