// Foley & Sugerman's stackless kd-tree traversals (thesis 8.2-8.5) and Horn et
// al.'s push-down and short-stack ones (seed 003 ch. 6), one step at a time so
// a pass can stop anywhere and the next resume. The layouts are
// accel/kd/kd_texels.h; accel/kd/kd_stream_traversal.cpp runs the same steps on
// the CPU. Defines: KD_BACKTRACK for kd-backtrack; else kd-restart, with
// KD_PUSHDOWN restarting from the push-down root and KD_STACK keeping a
// circular stack of uStackSize entries (kd_ray_record.glsl; the full stack is
// one as deep as the tree).
//
// A ray's state: the node it is at, a mode, and its search interval
// [tMin, tMax] inside [., sceneMax]:
//   mode DOWN: descending from `node`, narrowing tMax at each split;
//   mode UP (backtrack): climbing until a node's box reaches past tMin;
//   mode >= 0: testing the leaf's list, at packed list entry `mode`.
// When a leaf yields no hit before its exit tMax, the interval moves on to
// [tMax, sceneMax]: restart descends from the root (or the push-down root)
// again, backtrack climbs; the stack variants first pop a stacked far child.

const float MODE_DOWN = -1.0;
const float MODE_UP = -2.0;

#ifdef KD_BACKTRACK
const uint NODE_STRIDE = 3u;
#else
const uint NODE_STRIDE = 1u;
#endif

// A node's (first) texel in the restart layout's form. KD_COMPACT: 8-byte
// nodes, two per texel, decoded (accel/kd/kd_compact_node.h; parent -1).
vec4 kdNodeTexel(ConstStream nodes, uint node) {
#ifdef KD_COMPACT
  vec4 pair = fetchTexel(nodes, node >> 1u);
  vec2 n = (node & 1u) != 0u ? pair.zw : pair.xy;
  uint word = unpackIndex(n.y);
  uint code = word & 3u;
  uint payload = word >> 2u;
  if (code == 3u) return vec4(0.0, 0.0, -1.0, payload == 0u ? -1.0 : packIndex(payload - 1u));
  return vec4(packIndex(payload), n.x, -1.0, -(float(code) + 2.0));
#else
  return fetchTexel(nodes, NODE_STRIDE * node);
#endif
}

struct KdRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  uint node;
  float mode, tMin, tMax, sceneMax;
  vec4 hit;
  float steps, tests;
  bool done;
  uint root;      // where a restart descends from: 0, or the push-down root
  bool pushDown;  // the descent has met no node with both children to visit
  uint top, count, record;  // the stack in kd_ray_record.glsl
};

#ifdef KD_STACK
// The far child of a node whose children are both visited: (node, tMin, tMax).
void pushEntry(inout KdRay ray, uint node, float tMin, float tMax) {
  kdStorePush(ray.record, ray.top, node, tMin, tMax);
  ray.top = (ray.top + 1u) % uStackSize;
  ray.count = min(ray.count + 1u, uStackSize);
}

void popEntry(inout KdRay ray) {
  ray.top = (ray.top + uStackSize - 1u) % uStackSize;
  ray.count -= 1u;
  uint at = ray.record + 4u + 3u * ray.top;
  ray.node = unpackIndex(kdRecords[at]);
  ray.tMin = kdRecords[at + 1u];
  ray.tMax = kdRecords[at + 2u];
}
#endif

// The leaf at ray.node has been searched.
void leafFinished(inout KdRay ray, vec4 leaf) {
  if (ray.hit.x <= ray.tMax || ray.tMax >= ray.sceneMax) {
    ray.done = true;
    return;
  }
#ifdef KD_BACKTRACK
  ray.tMin = ray.tMax;
  ray.tMax = ray.sceneMax;
  if (leaf.z < 0.0) {
    ray.done = true;
  } else {
    ray.node = unpackIndex(leaf.z);
    ray.mode = MODE_UP;
  }
#else
  ray.mode = MODE_DOWN;
#ifdef KD_STACK
  if (ray.count > 0u) {
    popEntry(ray);
    return;
  }
#endif
  // Restart: descend again over what is left of the ray.
  ray.tMin = ray.tMax;
  ray.tMax = ray.sceneMax;
  ray.node = ray.root;
  ray.pushDown = true;
#endif
}

void kdStep(inout KdRay ray, ConstStream nodes, ConstStream lists, ConstStream triangles) {
  ray.steps += 1.0;
  if (ray.mode >= 0.0) {
    uint entry = unpackIndex(ray.mode);
    float id = fetchScalar(lists, entry);
    if (id < 0.0) {
      leafFinished(ray, kdNodeTexel(nodes, ray.node));
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
  vec4 node = kdNodeTexel(nodes, ray.node);
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
    } else {  // both children: the near one now, the far one later
#ifdef KD_STACK
      pushEntry(ray, second, tSplit, ray.tMax);  // the far child's interval ends at the old tMax
#endif
      ray.pushDown = false;
      ray.node = first;
      ray.tMax = tSplit;
    }
#ifdef KD_PUSHDOWN
    // The ray's rest lies in this child's voxel: later restarts can begin here.
    if (ray.pushDown) ray.root = ray.node;
#endif
  } else if (node.w >= 0.0) {  // leaf with triangles: w is its packed list start
    ray.mode = node.w;
  } else {  // empty leaf
    leafFinished(ray, node);
  }
}
