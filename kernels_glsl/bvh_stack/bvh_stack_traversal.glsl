// Aila & Laine's stack BVH traversal, one step at a time so a pass can stop
// anywhere and the next resume; accel/bvh_stack/bvh_stack_traversal.cpp runs
// the same steps on the CPU. Node layout: accel/bvh_stack/bvh_stack_texels.h.
// A ray is at `link`: a node when count == 0, else the next reference of a
// leaf with `count` references left. A step visits a node (the nearer child
// entered, the farther pushed; children entered at or beyond the hit skipped)
// or tests one reference.

struct BvhRay {
  vec3 origin, direction, invDir;
  bool anyHit;
  uint link, count;
  vec4 hit;
  float steps, tests;
  bool done;
  uint depth, record;  // entries on the stack, and its record (bvh_stack_record.glsl)
};

// The next stacked child the ray still reaches before its hit; done when none.
void bvhPop(inout BvhRay ray) {
  while (ray.depth > 0u) {
    ray.depth -= 1u;
    uint at = ray.record + 1u + 3u * ray.depth;
    if (bvhRecords[at + 2u] < ray.hit.x) {
      ray.link = unpackIndex(bvhRecords[at]);
      ray.count = uint(bvhRecords[at + 1u]);
      return;
    }
  }
  ray.done = true;
}

// intersectsBox (intersect.glsl) with the entry t; absent slots (w < 0) are missed.
bool bvhEnters(BvhRay ray, vec4 lo, vec4 hi, out float tNear) {
  tNear = INF;
  if (lo.w < 0.0) return false;
  float tFar;
  clipToBox(ray.origin, ray.invDir, lo.xyz, hi.xyz, tNear, tFar);
  precise float tExit = tFar * 1.00000035762786865234375;
  return tNear <= tExit && tExit >= 0.0 && tNear < ray.hit.x;
}

void bvhStep(inout BvhRay ray, ConstStream nodes, ConstStream references, ConstStream triangles) {
  ray.steps += 1.0;
  if (ray.count > 0u) {
    uint entry = ray.link;
    ray.tests += 1.0;
    bool found = testListedTriangle(triangles, fetchScalar(references, entry), ray.origin, ray.direction, ray.hit);
    if (found && ray.anyHit) {
      ray.done = true;
      return;
    }
    ray.link = entry + 1u;
    ray.count -= 1u;
    if (ray.count == 0u) bvhPop(ray);
    return;
  }
  uint base = 4u * ray.link;
  vec4 lo0 = fetchTexel(nodes, base);
  vec4 hi0 = fetchTexel(nodes, base + 1u);
  vec4 lo1 = fetchTexel(nodes, base + 2u);
  vec4 hi1 = fetchTexel(nodes, base + 3u);
  float t0, t1;
  bool hit0 = bvhEnters(ray, lo0, hi0, t0);
  bool hit1 = bvhEnters(ray, lo1, hi1, t1);
  if (hit0 && hit1) {
    bool nearFirst = t0 <= t1;
    uint at = ray.record + 1u + 3u * ray.depth;
    bvhRecords[at] = nearFirst ? lo1.w : lo0.w;
    bvhRecords[at + 1u] = nearFirst ? hi1.w : hi0.w;
    bvhRecords[at + 2u] = nearFirst ? t1 : t0;
    ray.depth = min(ray.depth + 1u, uStackSize);  // never reached: the stack is as deep as the tree
    ray.link = unpackIndex(nearFirst ? lo0.w : lo1.w);
    ray.count = uint(nearFirst ? hi0.w : hi1.w);
  } else if (hit0 || hit1) {
    ray.link = unpackIndex(hit0 ? lo0.w : lo1.w);
    ray.count = uint(hit0 ? hi0.w : hi1.w);
  } else {
    bvhPop(ray);
  }
}
