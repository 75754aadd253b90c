// The BIH traversal (Wächter & Keller 2006), one step at a time so a pass can
// stop anywhere and the next resume; accel/bih/bih_stream_traversal.cpp runs
// the same steps on the CPU (the comments there say why each rule is so).
// Node layout: accel/bih/bih_texels.h. A ray's state: the node it is at, a
// mode (DOWN, or the packed list entry of the leaf it is testing), its
// interval [tMin, tMax] at that node, and the stack in bih_ray_record.glsl.

const float MODE_DOWN = -1.0;
const float PARALLEL_INVERSE = 1e19;  // kParallelInverse
struct BihRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  uint node;
  float mode, tMin, tMax;
  vec4 hit;
  float steps, tests;
  bool done;
  uint count, record;  // the stack in bih_ray_record.glsl
};

void popOrDone(inout BihRay ray) {
  ray.mode = MODE_DOWN;
  if (ray.count == 0u) {
    ray.done = true;
    return;
  }
  ray.count -= 1u;
  uint at = ray.record + 1u + 3u * ray.count;
  ray.node = unpackIndex(bihRecords[at]);
  ray.tMin = bihRecords[at + 1u];
  ray.tMax = bihRecords[at + 2u];
}

void pushEntry(inout BihRay ray, uint node, float tMin, float tMax) {
  uint at = ray.record + 1u + 3u * ray.count;
  bihRecords[at] = packIndex(node);
  bihRecords[at + 1u] = tMin;
  bihRecords[at + 2u] = tMax;
  ray.count += 1u;
}

void bihStep(inout BihRay ray, ConstStream nodes, ConstStream lists, ConstStream triangles) {
  ray.steps += 1.0;
  if (ray.mode >= 0.0) {
    uint entry = unpackIndex(ray.mode);
    float id = fetchScalar(lists, entry);
    if (id < 0.0) {
      popOrDone(ray);
    } else {
      ray.tests += 1.0;
      bool found = testListedTriangle(triangles, id, ray.origin, ray.direction, ray.hit);
      ray.done = found && ray.anyHit;
      ray.mode = packIndex(entry + 1u);
    }
    return;
  }
  // Children beyond the current hit are skipped.
  float tEnd = min(ray.tMax, ray.hit.x);
  if (ray.tMin > tEnd) {
    popOrDone(ray);
    return;
  }
  vec4 node = fetchTexel(nodes, ray.node);
  if (node.w >= 0.0) {  // leaf with triangles: w is its packed list start
    ray.mode = node.w;
    return;
  }
  if (node.w > -1.5) {  // empty leaf
    popOrDone(ray);
    return;
  }
  int axis = int(-node.w) - 2;
  float o = ray.origin[axis];
  float inv = ray.invDir[axis];
  // Each child's part of [tMin, tEnd]: x left, y right.
  vec2 lo = vec2(ray.tMin);
  vec2 hi = vec2(tEnd);
  if (abs(inv) > PARALLEL_INVERSE) {  // parallel to the planes: in a child's slab for all t or none
    if (!(o <= node.y)) hi.x = -INF;
    if (!(o >= node.z)) hi.y = -INF;
  } else {
    precise float tLeft = (node.y - o) * inv;
    precise float tRight = (node.z - o) * inv;
    if (inv > 0.0) {
      hi.x = min(hi.x, widenUp(tLeft));
      lo.y = max(lo.y, widenDown(tRight));
    } else {
      lo.x = max(lo.x, widenDown(tLeft));
      hi.y = min(hi.y, widenUp(tRight));
    }
  }
  bool leftNear = inv > 0.0;
  uint nearChild = leftNear ? ray.node + 1u : unpackIndex(node.x);
  uint farChild = leftNear ? unpackIndex(node.x) : ray.node + 1u;
  vec2 nearT = leftNear ? vec2(lo.x, hi.x) : vec2(lo.y, hi.y);
  vec2 farT = leftNear ? vec2(lo.y, hi.y) : vec2(lo.x, hi.x);
  bool visitNear = nearT.x <= nearT.y;
  bool visitFar = farT.x <= farT.y;
  if (visitNear && visitFar) pushEntry(ray, farChild, farT.x, farT.y);
  if (visitNear) {
    ray.node = nearChild;
    ray.tMin = nearT.x;
    ray.tMax = nearT.y;
  } else if (visitFar) {
    ray.node = farChild;
    ray.tMin = farT.x;
    ray.tMax = farT.y;
  } else {
    popOrDone(ray);  // the ray passes through the gap between the planes
  }
}
