// Uniform-grid traversal (thesis 7.2-7.4): Amanatides & Woo's 3D-DDA over the
// cells a ray pierces, testing each cell's reference list. One step at a time
// so passes can stop anywhere; accel/grid/grid_stream_traversal.cpp runs the same
// steps on the CPU. Layout: accel/grid/grid_texels.h.
//
// A ray's state: its cell, the t at which it crosses the next cell boundary
// on each axis (tNext), and a mode: VISIT (look up the cell's list) or, >= 0,
// the packed list entry to test next.

const float MODE_VISIT = -1.0;

uniform vec3 uGridMin;
uniform vec3 uCellSize;
uniform vec3 uInvCellSize;
uniform ivec3 uGridResolution;

struct GridRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  ivec3 cell;
  vec3 tNext;
  float mode;
  vec4 hit;
  float steps, tests;
  bool done;
};

uint linearCell(ivec3 c) {
  return uint(c.x) + uint(uGridResolution.x) * (uint(c.y) + uint(uGridResolution.y) * uint(c.z));
}

ivec3 cellOf(uint index) {
  uint nx = uint(uGridResolution.x), ny = uint(uGridResolution.y);
  return ivec3(int(index % nx), int((index / nx) % ny), int(index / (nx * ny)));
}

// Leaves the cell: done if the best hit lies within it, or the ray leaves the grid.
void advance(inout GridRay ray) {
  float exit = min(min(ray.tNext.x, ray.tNext.y), ray.tNext.z);
  if (ray.hit.x <= exit || exit == INF) {
    ray.done = true;
    return;
  }
  int axis = ray.tNext.x <= ray.tNext.y && ray.tNext.x <= ray.tNext.z ? 0 : (ray.tNext.y <= ray.tNext.z ? 1 : 2);
  bool forward = ray.direction[axis] > 0.0;
  ray.cell[axis] += forward ? 1 : -1;
  // Recomputed from the boundary itself, not accumulated, so it never drifts.
  float boundary = uGridMin[axis] + float(ray.cell[axis] + (forward ? 1 : 0)) * uCellSize[axis];
  ray.tNext[axis] = (boundary - ray.origin[axis]) * ray.invDir[axis];
  ray.mode = MODE_VISIT;
  ray.done = ray.cell[axis] < 0 || ray.cell[axis] >= uGridResolution[axis];
}

// Looks up the cell's list: starts it, or moves on if the cell is empty.
void visitCell(inout GridRay ray, ConstStream cells) {
  ray.steps += 1.0;
  float start = fetchScalar(cells, linearCell(ray.cell));
  if (start >= 0.0) ray.mode = start;
  else advance(ray);
}

// Tests the next listed triangle, or moves on at the end of the list.
void testNextEntry(inout GridRay ray, ConstStream lists, ConstStream triangles) {
  ray.steps += 1.0;
  uint entry = unpackIndex(ray.mode);
  float id = fetchScalar(lists, entry);
  if (id < 0.0) {
    advance(ray);
  } else {
    ray.tests += 1.0;
    bool found = testListedTriangle(triangles, id, ray.origin, ray.direction, ray.hit);
    ray.done = found && ray.anyHit;
    ray.mode = packIndex(entry + 1u);
  }
}

// The stream surfaces a grid ray lives in: state (packed cell, steps, tests,
// active) and aux (tNext, mode).
GridRay loadGridRay(vec4 origin, vec4 direction, vec4 state, vec4 aux, vec4 hit) {
  GridRay ray;
  ray.origin = origin.xyz;
  ray.direction = direction.xyz;
  ray.invDir = safeInverse(direction.xyz);
  ray.anyHit = origin.w == RAY_SHADOW;
  ray.cell = cellOf(unpackIndex(state.x));
  ray.steps = state.y;
  ray.tests = state.z;
  ray.tNext = aux.xyz;
  ray.mode = aux.w;
  ray.hit = hit;
  ray.done = false;
  return ray;
}
