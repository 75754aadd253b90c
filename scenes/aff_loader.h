#pragma once
// NFF (Haines' Neutral File Format) and AFF (BART's Animated File Format, a
// superset) into a Scene; one parser reads both. Format facts:
// ../shared/docs/aff-nff.md. Every malformed input throws SceneError
// "FILE:LINE: reason" naming the file (an included one where it lies there)
// and line.
//
// Geometry. Triangles come in file order, includes expanded in place (a file
// included twice is two instances). Only `m` meshes, `p` polygons, `pp`
// patches, `s` spheres and `c` cones make triangles; the triangle count is the
// sum of the meshes' `triangles N`, n - 2 per polygon or patch and the
// fixed tessellations of tessellate.h. Polygons and patches are triangulated
// as polygon_triangulation.h says (convex: the fan from the first vertex;
// concave: ear clipping), with one warning line on stderr counting the
// non-planar and self-intersecting ones of the file and its includes. With these rules BART Kitchen has
// 110,561 triangles and Robots 71,708, the counts of the thesis. Texture
// coordinates are read and checked but not kept (textures are not rendered).
//
// Transforms. `xs` is scale, then rotation about an axis (degrees), then
// translation; `x name` is the Kochanek–Bartels interpolation of the keys of
// `k name` at `time` (an `x` without keys is the identity). Keys may come
// after the `x` that uses them, even in another file. Nested blocks compose
// outer * inner. Normals use the inverse transpose.
//
// Materials. `fm` (ambient, diffuse, specular rgb, shine, T, ior) takes its
// diffuse rgb as the diffuse colour; NFF `f r g b Kd Ks shine T ior` gives
// diffuse = Kd * (r, g, b). The mirror rule, for both: a material is a perfect
// mirror when it is opaque (T == 0), its specular coefficient Ks (for fm,
// every channel) is at least kAffMirrorKs = 0.95 and its Phong exponent
// (shine) is at least kAffMirrorShine = 1000 (a highlight lobe a few degrees
// wide: the Phong model's limit towards a mirror); the reflectance is then Ks
// (fm: the specular rgb). Our mirrors reflect everything (thesis 4.2), so only
// near-perfect specular surfaces qualify; glossy ones such as Kitchen's shiny
// metal (Ks 0.9, shine 97) and Robots' Ks 1.0, shine 157 part stay diffuse,
// and neither Kitchen nor Robots has a mirror, as in the thesis. Until the
// first f/fm the material is Material{}.
//
// Light rule. Scene holds one point light: it sits at the first `l` of the
// file (in include order) and its colour is the sum of every `l`'s colour
// (colour 1 1 1 when a light gives none), so the scene keeps its total light.
// Without lights, a light is framed on the scene's bounds.
//
// View. `v` gives eye (from), lookAt (at), up and the field of view `angle`,
// taken as vertical (as gluPerspective, which BART's viewer used); hither and
// resolution are checked and ignored. Where the file has keyframes `k
// camera`, they place the camera at `time` instead (BART's camera looks down
// -z with +y up before its keyed rotation and translation; the `v` angle is
// kept): at t = 0 this is the overview of Kitchen and the street view of
// Robots that Foley & Sugerman rendered, whereas Kitchen's static `v` is a
// close-up of the sink and Robots' is 2,800 units away. The fact sheet allows
// either; this is the one the thesis approximated. Without `v` or camera keys
// the view is framed on the bounds.
//
// Background `b`, and `am r g b`: ambient = clamp(0.3 * mean(am), 0, 0.4)
// (BART's am is 1 in Robots, 2.5 in Kitchen: with one overhead point light
// and no ambient the Robots street is black; without `am` it is 0.1).
//
// Robustness: counts larger than the rest of the file could hold, include
// nesting deeper than 64, more than 10,000 includes or 1 GiB of included
// files in all, an included file that is not a regular file (a directory,
// /dev/zero, a FIFO), block nesting deeper than 256 and scenes over
// kAffMaxTriangles triangles are refused. Numbers after a command's arguments
// on the same line are ignored (stray tokens); a number where a command
// should start on a new line is an error (usually a wrong count).

#include <cstddef>
#include <filesystem>

#include "scenes/scene.h"

namespace passtrace {

inline constexpr float kAffMirrorKs = 0.95f;
inline constexpr float kAffMirrorShine = 1000.0f;
inline constexpr std::size_t kAffMaxTriangles = std::size_t{1} << 25;

// The scene's name is the file's stem.
Scene loadAff(const std::filesystem::path& path, float time = 0.0f);
// The same parser (NFF is a subset of AFF).
inline Scene loadNff(const std::filesystem::path& path) { return loadAff(path); }

}  // namespace passtrace
