#pragma once
// glTF 2.0 (.gltf with external or embedded buffers, and binary .glb) into a
// Scene, read with tinygltf. glTF has no lines, so errors name the file and
// the object: "FILE: mesh 2 primitive 0: index 99 out of range (12
// vertices)"; tinygltf's own parse errors are passed on after the file name.
// Only regular files are read, the scene and its external buffers alike (a
// FIFO, a directory or /dev/zero is an error), and JSON nested deeper than
// 256 levels is refused (tinygltf would recurse off the stack).
//
// Geometry: the default scene's node trees (every root node when the file
// has no scenes), depth first in node order, each node's mesh in world space
// (matrix, or translation * rotation * scale; normals by the inverse
// transpose, winding reversed where the determinant is negative, as the spec
// says). TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives, indexed or
// not, make n/3, n - 2 and n - 2 triangles (degenerate ones kept). POINTS and
// LINES primitives are skipped with one warning line on stderr counting them.
// Vertex normals (NORMAL) are kept; if some primitives lack them, their
// triangles get the geometric normal. Morph targets add their weighted
// POSITION and NORMAL deltas (weights: animated, else the node's, else the
// mesh's).
//
// Materials: baseColorFactor's rgb is the diffuse colour. The mirror rule: a
// material is a perfect mirror when metallicFactor >= 0.9 and roughnessFactor
// <= 0.1, with reflectance baseColorFactor's rgb. Primitives without a
// material get Material{}.
//
// View and light: the first node (in the order above) with a perspective
// camera gives the view: eye at the node's world origin, looking down its
// -z, up its +y, yfov (vertical, radians) in degrees. The first node with a
// KHR_lights_punctual point light places the light, with the light's colour
// (intensity is photometric, candela, and has no counterpart in our unitless
// light, so it is ignored); without such a light, or without a camera, they
// are framed on the bounds as for OBJ. The background is OBJ's.

#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

// The scene's name is the file's stem. Animations (scenes/gltf_animation.h)
// are evaluated at `time` (seconds, the file's key times): node transforms and
// morph-target weights; Scene::animation is their key range and
// Scene::moving marks the triangles of animated nodes and the nodes below.
Scene loadGltf(const std::filesystem::path& path, float time = 0.0f);

}  // namespace passtrace
