// kd-ropes' stackless traversal (Popov et al. 2007), one step at a time so a
// pass can stop anywhere and the next resume. Layout: accel/kd/kd_ropes.h;
// accel/kd/kd_ropes_traversal.cpp runs the same steps on the CPU (its header
// explains the parametric descent).
//
// A ray's state: node (texel offset), mode (DOWN: descending to the leaf that
// holds the entry point; >= 0: testing the leaf's list at that packed entry),
// its entry distance tEntry and where it ends, sceneMax.

const float MODE_DOWN = -1.0;

struct KdRopesRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  uint node;
  float mode, tEntry, sceneMax;
  vec4 hit;
  float steps, tests;
  bool done;
};

// The leaf at ray.node is searched: leave it through its nearest face on the
// side the ray heads to, along that face's rope.
void leaveLeaf(inout KdRopesRay ray, ConstStream nodes) {
  vec3 lo = fetchTexel(nodes, ray.node + 2u).xyz;
  vec3 hi = fetchTexel(nodes, ray.node + 3u).xyz;
  bvec3 ahead = greaterThanEqual(ray.direction, vec3(0.0));
  precise vec3 t = (mix(lo, hi, ahead) - ray.origin) * ray.invDir;
  // A ray parallel to a slab never leaves through it (as clipToBox).
  t = mix(t, vec3(INF), greaterThan(abs(ray.invDir), vec3(1e19)));
  int axis = t.x <= t.y && t.x <= t.z ? 0 : (t.y <= t.z ? 1 : 2);
  float tExit = t[axis];
  if (ray.hit.x <= tExit || tExit >= ray.sceneMax) {
    ray.done = true;
    return;
  }
  float rope = fetchTexel(nodes, ray.node + (ahead[axis] ? 1u : 0u))[axis];
  if (rope < 0.0) {
    ray.done = true;
    return;
  }
  ray.node = unpackIndex(rope);
  ray.tEntry = max(ray.tEntry, tExit);
  ray.mode = MODE_DOWN;
}

void kdRopesStep(inout KdRopesRay ray, ConstStream nodes, ConstStream lists, ConstStream triangles) {
  if (ray.steps >= float(uMaxSteps)) {  // the robustness bound
    ray.done = true;
    return;
  }
  ray.steps += 1.0;
  if (ray.mode >= 0.0) {
    uint entry = unpackIndex(ray.mode);
    float id = fetchScalar(lists, entry);
    if (id < 0.0) {
      leaveLeaf(ray, nodes);
    } else {
      ray.tests += 1.0;
      bool found = testListedTriangle(triangles, id, ray.origin, ray.direction, ray.hit);
      ray.done = found && ray.anyHit;
      ray.mode = packIndex(entry + 1u);
    }
    return;
  }
  vec4 node = fetchTexel(nodes, ray.node);
  if (node.w < -1.5) {  // internal: w = -(axis + 2)
    int axis = int(-node.w) - 2;
    float split = node.y;
    float o = ray.origin[axis];
    // An origin on the plane, or a ray parallel to it, never crosses it.
    bool never = o == split || abs(ray.invDir[axis]) > 1e19;
    precise float tSplit = never ? INF : (split - o) * ray.invDir[axis];
    bool belowFirst = o < split || (o == split && ray.direction[axis] <= 0.0);
    bool crossed = tSplit >= 0.0 && tSplit <= ray.tEntry;
    ray.node = belowFirst != crossed ? ray.node + 1u : unpackIndex(node.x);
  } else if (node.w >= 0.0) {  // leaf with triangles: w is its packed list start
    ray.mode = node.w;
  } else {  // empty leaf
    leaveLeaf(ray, nodes);
  }
}
