// The cone tests of accel/cone/cone_tests.{h,cpp} in GLSL, operation for
// operation, so the stream path finds the same triangles, t and node counts
// as the CPU: the exact test in double (GLSL 4.5 fp64) with glm's evaluation
// order for dot and cross; the float interval clips divide in double and
// round once, which gives the correctly rounded float quotient as C++ does.
// `precise` keeps the compiler from fusing multiply-adds the CPU does not.

const float CONE_SLACK = 1e-4;
const float CONE_INF = uintBitsToFloat(0x7f800000u);

double coneDot(dvec3 a, dvec3 b) {
  precise double r = a.x * b.x + a.y * b.y;
  r = r + a.z * b.z;
  return r;
}

dvec3 coneCross(dvec3 a, dvec3 b) {
  precise dvec3 r = dvec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
  return r;
}

// coneClip: restricts [t0, t1] to { t : c + m t <= 0 }.
void coneClip(float c, float m, inout float t0, inout float t1) {
  if (m > 0.0) t1 = min(t1, float(double(-c) / double(m)));
  else if (m < 0.0) t0 = max(t0, float(double(-c) / double(m)));
  else if (c > 0.0) t0 = CONE_INF;
}

bool coneIntervalOpen(float t0, float t1) {
  precise float bound = t1 + CONE_SLACK * abs(t1);
  bound = bound + 1e-30;
  return t0 <= bound;
}

bool coneSide(vec3 apex, vec3 axis, vec3 k, uint a, float d, uint side, inout float t0, inout float t1) {
  precise float c = apex[a] - d;
  if (side == 0u) {
    precise float m = axis[a] - k[a];
    coneClip(c, m, t0, t1);
  } else {
    precise float m = -(axis[a] + k[a]);
    coneClip(-c, m, t0, t1);
  }
  return coneIntervalOpen(t0, t1);
}

bool coneBox(vec3 apex, vec3 axis, vec3 k, vec3 lo, vec3 hi, inout float t0, inout float t1) {
  for (int a = 0; a < 3; ++a) {
    precise float c0 = apex[a] - hi[a];
    precise float m0 = axis[a] - k[a];
    coneClip(c0, m0, t0, t1);
    precise float c1 = lo[a] - apex[a];
    precise float m1 = -(axis[a] + k[a]);
    coneClip(c1, m1, t0, t1);
  }
  return coneIntervalOpen(t0, t1);
}

double coneAxisCrossing(dvec3 s, dvec3 v, dvec3 p0, dvec3 p1, dvec3 p2) {
  precise dvec3 e1 = p1 - p0;
  precise dvec3 e2 = p2 - p0;
  dvec3 p = coneCross(v, e2);
  double det = coneDot(p, e1);
  if (det == 0.0LF) return -1.0LF;
  precise dvec3 tv = s - p0;
  precise double u = coneDot(p, tv) / det;
  dvec3 q = coneCross(tv, e1);
  precise double w = coneDot(q, v) / det;
  precise double t = coneDot(q, e2) / det;
  return u >= 0.0LF && w >= 0.0LF && u + w <= 1.0LF && t >= 0.0LF ? t : -1.0LF;
}

struct ConeEdge {
  dvec3 d0, e;
  double g0, g1, qa, qh, qc, s0, s1, best;
};

double coneEdgeF(ConeEdge E, double x) {
  precise double r = E.qa * x + 2.0LF * E.qh;
  r = r * x + E.qc;
  return r;
}

void coneConsider(inout ConeEdge E, double x, bool onBoundary) {
  if (x < E.s0 || x > E.s1) return;
  precise dvec3 p = E.d0 + x * E.e;
  precise double limit = onBoundary ? -1e-13LF * coneDot(p, p) : 0.0LF;
  if (coneEdgeF(E, x) < limit) return;
  precise double g = max(0.0LF, E.g0 + x * E.g1);
  if (E.best < 0.0LF || g < E.best) E.best = g;
}

double coneEdgeNearest(dvec3 s, dvec3 v, double cos2, dvec3 a, dvec3 b) {
  ConeEdge E;
  E.d0 = a - s;
  E.e = b - a;
  E.g0 = coneDot(E.d0, v);
  E.g1 = coneDot(E.e, v);
  E.s0 = 0.0LF;
  E.s1 = 1.0LF;
  E.best = -1.0LF;
  if (E.g1 > 0.0LF) E.s0 = max(E.s0, -E.g0 / E.g1);
  else if (E.g1 < 0.0LF) E.s1 = min(E.s1, -E.g0 / E.g1);
  else if (E.g0 < 0.0LF) return -1.0LF;
  if (E.s0 > E.s1) return -1.0LF;
  precise double qa = E.g1 * E.g1 - cos2 * coneDot(E.e, E.e);
  precise double qh = E.g0 * E.g1 - cos2 * coneDot(E.d0, E.e);
  precise double qc = E.g0 * E.g0 - cos2 * coneDot(E.d0, E.d0);
  E.qa = qa, E.qh = qh, E.qc = qc;
  coneConsider(E, E.s0, false);
  coneConsider(E, E.s1, false);
  if (qa != 0.0LF) {
    precise double disc = qh * qh - qa * qc;
    if (disc >= 0.0LF) {
      precise double r = sqrt(disc);
      precise double x0 = (-qh - r) / qa;
      precise double x1 = (-qh + r) / qa;
      coneConsider(E, x0, true);
      coneConsider(E, x1, true);
    }
  } else if (qh != 0.0LF) {
    precise double x = -qc / (2.0LF * qh);
    coneConsider(E, x, true);
  }
  return E.best;
}

// coneMeetsTriangle: s the apex, v the unit axis in double, c/sinA the cosine
// and sine of the half-angle (computed by the CPU).
bool coneMeetsTriangle(dvec3 s, dvec3 v, double c, double sinA, dvec3 p0, dvec3 p1, dvec3 p2, out float t) {
  precise double cos2 = c * c;
  double best = coneAxisCrossing(s, v, p0, p1, p2);
  for (int k = 0; k < 3; ++k) {
    dvec3 a = k == 0 ? p0 : (k == 1 ? p1 : p2);
    dvec3 b = k == 0 ? p1 : (k == 1 ? p2 : p0);
    double g = coneEdgeNearest(s, v, cos2, a, b);
    if (g >= 0.0LF && (best < 0.0LF || g < best)) best = g;
  }
  t = 0.0;
  if (best < 0.0LF) return false;
  precise dvec3 n = coneCross(p1 - p0, p2 - p0);
  precise dvec3 w = n - coneDot(n, v) * v;
  precise double wl = sqrt(coneDot(w, w));
  if (wl > 0.0LF) {
    for (int k = 0; k < 2; ++k) {
      precise double side = k == 0 ? -1.0LF : 1.0LF;
      precise dvec3 dir = c * v + side * sinA * (w / wl);
      double lambda = coneAxisCrossing(s, dir, p0, p1, p2);
      precise double lc = lambda * c;
      if (lambda >= 0.0LF) best = min(best, lc);
    }
  }
  t = float(best);
  return true;
}
