// Foley & Sugerman's stackless kd-tree traversals (thesis 8.2-8.5), one step
// at a time so a pass can stop anywhere and the next resume. The layouts are
// accel/kd/kd_texels.h; accel/kd/kd_stream_traversal.cpp runs the same steps on
// the CPU. Define KD_BACKTRACK for kd-backtrack, else kd-restart.
//
// A ray's state: the node it is at, a mode, and its search interval
// [tMin, tMax] inside [., sceneMax]:
//   mode DOWN: descending from `node`, narrowing tMax at each split;
//   mode UP (backtrack): climbing until a node's box reaches past tMin;
//   mode >= 0: testing the leaf's list, at packed list entry `mode`.
// When a leaf yields no hit before its exit tMax, the interval moves on to
// [tMax, sceneMax]: restart descends from the root again, backtrack climbs.

const float MODE_DOWN = -1.0;
const float MODE_UP = -2.0;

#ifdef KD_BACKTRACK
const uint NODE_STRIDE = 3u;
#else
const uint NODE_STRIDE = 1u;
#endif

struct KdRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  uint node;
  float mode, tMin, tMax, sceneMax;
  vec4 hit;
  float steps, tests;
  bool done;
};

// The leaf at ray.node has been searched.
void leafFinished(inout KdRay ray, vec4 leaf) {
  if (ray.hit.x <= ray.tMax || ray.tMax >= ray.sceneMax) {
    ray.done = true;
    return;
  }
  ray.tMin = ray.tMax;
  ray.tMax = ray.sceneMax;
#ifdef KD_BACKTRACK
  if (leaf.z < 0.0) {
    ray.done = true;
  } else {
    ray.node = unpackIndex(leaf.z);
    ray.mode = MODE_UP;
  }
#else
  ray.node = 0u;
  ray.mode = MODE_DOWN;
#endif
}

void kdStep(inout KdRay ray, ConstStream nodes, ConstStream lists, ConstStream triangles) {
  ray.steps += 1.0;
  if (ray.mode >= 0.0) {
    uint entry = unpackIndex(ray.mode);
    float id = fetchScalar(lists, entry);
    if (id < 0.0) {
      leafFinished(ray, fetchTexel(nodes, NODE_STRIDE * ray.node));
    } else {
      ray.tests += 1.0;
      bool found = testListedTriangle(triangles, id, ray.origin, ray.direction, ray.hit);
      ray.done = found && ray.anyHit;
      ray.mode = packIndex(entry + 1u);
    }
    return;
  }
#ifdef KD_BACKTRACK
  if (ray.mode == MODE_UP) {
    vec3 lo = fetchTexel(nodes, NODE_STRIDE * ray.node + 1u).xyz;
    vec3 hi = fetchTexel(nodes, NODE_STRIDE * ray.node + 2u).xyz;
    float tNear, tFar;
    clipToBox(ray.origin, ray.invDir, lo, hi, tNear, tFar);
    if (tFar > ray.tMin) {
      ray.mode = MODE_DOWN;
      ray.tMax = min(tFar, ray.sceneMax);
    } else {
      float parent = fetchTexel(nodes, NODE_STRIDE * ray.node).z;
      if (parent < 0.0) ray.done = true;
      else ray.node = unpackIndex(parent);
    }
    return;
  }
#endif
  vec4 node = fetchTexel(nodes, NODE_STRIDE * ray.node);
  if (node.w < -1.5) {  // internal: w = -(axis + 2)
    int axis = int(-node.w) - 2;
    float split = node.y;
    float o = ray.origin[axis];
    // An origin on the plane never crosses it: it stays on the side it heads to.
    float tSplit = o == split ? INF : (split - o) * ray.invDir[axis];
    bool belowFirst = o < split || (o == split && ray.direction[axis] <= 0.0);
    uint right = unpackIndex(node.x);
    uint first = belowFirst ? ray.node + 1u : right;
    uint second = belowFirst ? right : ray.node + 1u;
    if (tSplit < 0.0 || tSplit >= ray.tMax) {
      ray.node = first;
    } else if (tSplit <= ray.tMin) {
      ray.node = second;
    } else {
      ray.node = first;
      ray.tMax = tSplit;
    }
  } else if (node.w >= 0.0) {  // leaf with triangles: w is its packed list start
    ray.mode = node.w;
  } else {  // empty leaf
    leafFinished(ray, node);
  }
}
