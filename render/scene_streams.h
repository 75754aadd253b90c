#pragma once
// The scene data the shading kernels read, laid out as texels
// (kernels_glsl/triangle_shading.glsl): per triangle in scene order 4 texels
//   (n0, packed material id) (n1, 0) (n2, 0) (unit geometric normal, 0)
// or, where the scene has no vertex normals, 1 texel
//   (unit geometric normal, packed material id)
// (48 bytes per triangle less: procedural spheres at 50M triangles); per
// material 2 texels (diffuse, 0) (mirror reflectance, 0).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"
#include "stream/const_input_stream.h"

namespace passtrace {

uint32_t shadingTexelsPerTriangle(const Scene& scene);
// "SHADING_TEXELS n", which every kernel reading the stream is compiled with.
std::string shadingTexelsDefine(const Scene& scene);
std::vector<glm::vec4> triangleShadingTexels(const Scene& scene);
// The same as a stream, written in pieces of 65,536 triangles: the whole
// array never exists beside its texture (its size per triangle less at the peak).
std::unique_ptr<ConstInputStream> triangleShadingStream(const Scene& scene, uint64_t maxPageTexels);
std::vector<glm::vec4> materialTexels(const Scene& scene);
// --shading whitted (kernels_glsl/shade_whitted.frag): 4 texels per material
//   (diffuse, 0) (mirror reflectance, 0) (Phong Ks, shininess) (transmission, ior, 0, 0)
std::vector<glm::vec4> whittedMaterialTexels(const Scene& scene);

}  // namespace passtrace
