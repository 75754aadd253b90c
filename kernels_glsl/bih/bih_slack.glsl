// Plane and box parameters widened by kBihSlack (accel/bih/bih_stream_traversal.h)
// so rounding never loses a child the ray touches at its plane.
const float BIH_SLACK = 9.5367431640625e-07;  // 2^-20, kBihSlack
// One rounded product each, exact for 0 and infinities (no inf - inf), as widenUp/widenDown in C++.
float widenUp(float t) {
  precise float r = t * (t > 0.0 ? 1.0 + BIH_SLACK : 1.0 - BIH_SLACK);
  return r;
}
float widenDown(float t) {
  precise float r = t * (t > 0.0 ? 1.0 - BIH_SLACK : 1.0 + BIH_SLACK);
  return r;
}
