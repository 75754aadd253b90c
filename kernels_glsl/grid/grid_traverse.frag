// Uniform-grid traversal and intersection merged into one kernel (the
// thesis's choice, 7.4.1): up to uLoopLimit steps per pass, each a cell visit
// or one triangle test.
#include "texel_address.glsl"
#include "intersect.glsl"
#include "ray_kinds.glsl"
#include "reference_lists.glsl"
#include "grid/grid_traversal.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uAux;
uniform ConstStream uCells;
uniform ConstStream uLists;
uniform ConstStream uTriangles;
uniform int uLoopLimit;

layout(location = 0) out vec4 outState;
layout(location = 1) out vec4 outHit;
layout(location = 2) out vec4 outAux;

void main() {
  GridRay ray = loadGridRay(readElement(uOrigin), readElement(uDirection), readElement(uState), readElement(uAux),
                            readElement(uHit));
  for (int i = 0; i < uLoopLimit && !ray.done; ++i) {
    if (ray.mode < 0.0) visitCell(ray, uCells);
    else testNextEntry(ray, uLists, uTriangles);
  }
  outState = vec4(packIndex(ray.done ? 0u : linearCell(ray.cell)), ray.steps, ray.tests, ray.done ? 0.0 : 1.0);
  outHit = ray.hit;
  outAux = vec4(ray.tNext, ray.mode);
}
