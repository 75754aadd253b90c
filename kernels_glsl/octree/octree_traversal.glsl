// Revelles' octree traversal, one step at a time so a pass can stop anywhere
// and the next resume; accel/octree/octree_stream_traversal.cpp runs the same
// steps on the CPU (its header says why each rule is so). Node layout:
// accel/octree/octree_texels.h; frames: octree_ray_record.glsl.

const float MODE_DOWN = -1.0;
const uint NODE_STRIDE = 3u;

struct OctreeRay {
  vec3 origin, direction;
  bool anyHit;
  int a;           // mirrored axes
  vec3 rootT0, rootT1;
  uint node;
  float mode, leafExit;
  vec4 hit;
  float steps, tests;
  bool done;
  uint count, record;
};

uint frameAt(OctreeRay ray, uint i) { return ray.record + 1u + 8u * i; }

float childOf(ConstStream nodes, uint node, int octant) {
  return fetchTexel(nodes, NODE_STRIDE * node + 1u + uint(octant >> 2))[octant & 3];
}

void advance(inout OctreeRay ray, ConstStream nodes) {
  ray.mode = MODE_DOWN;
  while (ray.count > 0u) {
    uint at = frameAt(ray, ray.count - 1u);
    vec3 t0 = vec3(octreeRecords[at + 1u], octreeRecords[at + 2u], octreeRecords[at + 3u]);
    vec3 t1 = vec3(octreeRecords[at + 4u], octreeRecords[at + 5u], octreeRecords[at + 6u]);
    int current = int(octreeRecords[at + 7u]);
    vec3 c0, c1;
    revellesChild(current, t0, t1, revellesMiddle(t0, t1), c0, c1);
    int next = revellesNextChild(current, c1);
    if (next == REVELLES_EXIT) {
      ray.count -= 1u;
      continue;
    }
    octreeRecords[at + 7u] = float(next);
    float child = childOf(nodes, unpackIndex(octreeRecords[at]), next ^ ray.a);
    if (child >= 0.0) {
      ray.node = unpackIndex(child);
      return;
    }
  }
  ray.done = true;
}

void octreeStep(inout OctreeRay ray, ConstStream nodes, ConstStream lists, ConstStream triangles) {
  ray.steps += 1.0;
  if (ray.mode >= 0.0) {
    uint entry = unpackIndex(ray.mode);
    float id = fetchScalar(lists, entry);
    if (id < 0.0) {  // the leaf is searched: a hit inside it ends the ray
      if (ray.hit.x <= ray.leafExit) ray.done = true;
      else advance(ray, nodes);
    } else {
      ray.tests += 1.0;
      bool found = testListedTriangle(triangles, id, ray.origin, ray.direction, ray.hit);
      ray.done = found && ray.anyHit;
      ray.mode = packIndex(entry + 1u);
    }
    return;
  }
  vec3 t0 = ray.rootT0;
  vec3 t1 = ray.rootT1;
  if (ray.count > 0u) {
    uint at = frameAt(ray, ray.count - 1u);
    vec3 p0 = vec3(octreeRecords[at + 1u], octreeRecords[at + 2u], octreeRecords[at + 3u]);
    vec3 p1 = vec3(octreeRecords[at + 4u], octreeRecords[at + 5u], octreeRecords[at + 6u]);
    revellesChild(int(octreeRecords[at + 7u]), p0, p1, revellesMiddle(p0, p1), t0, t1);
  }
  float entryT = max(max(t0.x, t0.y), t0.z);
  float exitT = min(min(t1.x, t1.y), t1.z);
  if (entryT >= ray.hit.x) {  // every node after this one is entered later still
    ray.done = true;
    return;
  }
  if (entryT > exitT || exitT < 0.0) {  // missed, or behind the origin
    advance(ray, nodes);
    return;
  }
  float tag = fetchTexel(nodes, NODE_STRIDE * ray.node).x;
  if (tag >= 0.0) {  // leaf with triangles: tag is its packed list start
    ray.mode = tag;
    ray.leafExit = exitT;
  } else if (tag > -1.5) {  // empty leaf
    advance(ray, nodes);
  } else {
    int first = revellesFirstChild(t0, revellesMiddle(t0, t1));
    uint at = frameAt(ray, ray.count);
    octreeRecords[at] = packIndex(ray.node);
    octreeRecords[at + 1u] = t0.x;
    octreeRecords[at + 2u] = t0.y;
    octreeRecords[at + 3u] = t0.z;
    octreeRecords[at + 4u] = t1.x;
    octreeRecords[at + 5u] = t1.y;
    octreeRecords[at + 6u] = t1.z;
    octreeRecords[at + 7u] = float(first);
    ray.count += 1u;
    float child = childOf(nodes, ray.node, first ^ ray.a);
    if (child >= 0.0) ray.node = unpackIndex(child);
    else advance(ray, nodes);
  }
}
