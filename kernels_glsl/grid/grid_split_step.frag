// Purcell's split grid traversal, first kernel: one cell visit for the rays
// that are walking the grid; rays waiting to test triangles are discarded, so
// the occlusion query counts the rays this kernel served.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#include "grid/grid_traversal.glsl"

// No early_fragment_tests: with them a fragment is counted by the occlusion
// query before the shader runs, so the rays this kernel discards would be
// counted as served and the schedule in accel/grid/gpu_grid_traversal.cpp
// would never switch kernels (it did not on NVIDIA; llvmpipe counts after).
// The depth test still culls finished rays: the shader writes no depth.

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uAux;
uniform ConstStream uCells;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;
layout(location = 2) out vec4 outAux;

void main() {
  vec4 aux = readElement(uAux);
  if (aux.w >= 0.0) discard;
  GridRay ray = loadGridRay(readElement(uOrigin), readElement(uDirection), readElement(uState), aux, readElement(uHit));
  visitCell(ray, uCells);
  outState = vec4(packIndex(ray.done ? 0u : linearCell(ray.cell)), ray.steps, ray.tests, ray.done ? 0.0 : 1.0);
  outHit = ray.hit;
  outAux = vec4(ray.tNext, ray.mode);
}
