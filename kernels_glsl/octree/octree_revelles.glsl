// Revelles et al. 2000's parametric octree traversal, operation for operation
// as accel/octree/octree_revelles.cpp: the mirrored ray's slab parameters, the
// first child from the entry plane, the next child from Revelles' table.
const float REVELLES_LIMIT = 1e30;  // kRevellesLimit
const int REVELLES_EXIT = 8;

// Sets a (mirrored axes) and the root's t0, t1.
void revellesStart(vec3 rootMin, vec3 rootMax, vec3 origin, vec3 direction, out int a, out vec3 t0, out vec3 t1) {
  a = 0;
  precise vec3 o = origin;
  vec3 d = direction;
  for (int k = 0; k < 3; ++k) {
    // Parallel rays in the upper half are mirrored too (never on the exit face).
    bool parallel = abs(d[k]) < 1e-20;
    precise float twice = rootMin[k] + rootMax[k];
    precise float doubled = o[k] + o[k];
    if (parallel ? doubled > twice : d[k] < 0.0) {
      o[k] = twice - o[k];
      a |= 1 << k;
    }
    d[k] = abs(d[k]);
  }
  vec3 inv = safeInverse(d);
  precise vec3 lo = (rootMin - o) * inv;
  precise vec3 hi = (rootMax - o) * inv;
  t0 = clamp(lo, vec3(-REVELLES_LIMIT), vec3(REVELLES_LIMIT));
  t1 = clamp(hi, vec3(-REVELLES_LIMIT), vec3(REVELLES_LIMIT));
}

vec3 revellesMiddle(vec3 t0, vec3 t1) {
  precise vec3 tm = 0.5 * (t0 + t1);
  return tm;
}

int revellesFirstChild(vec3 t0, vec3 tm) {
  int entry = 0;
  if (t0.y > t0[entry]) entry = 1;
  if (t0.z > t0[entry]) entry = 2;
  int child = 0;
  for (int k = 0; k < 3; ++k)
    if (k != entry && tm[k] < t0[entry]) child |= 1 << k;
  return child;
}

// Revelles' table: next[current][exit axis], 8 = out of the parent.
int revellesNextChild(int current, vec3 t1) {
  int exitAxis = 0;
  if (t1.y < t1[exitAxis]) exitAxis = 1;
  if (t1.z < t1[exitAxis]) exitAxis = 2;
  int bit = 1 << exitAxis;
  return (current & bit) != 0 ? REVELLES_EXIT : current | bit;
}

void revellesChild(int octant, vec3 t0, vec3 t1, vec3 tm, out vec3 c0, out vec3 c1) {
  bvec3 upper = bvec3((octant & 1) != 0, (octant & 2) != 0, (octant & 4) != 0);
  c0 = mix(t0, tm, upper);
  c1 = mix(tm, t1, upper);
}
