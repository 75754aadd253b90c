// The quad every kernel is drawn with: a triangle strip covering the viewport
// at depth 0.5 (NDC z = 0), so the depth test keeps elements whose stored
// depth is 1 (active) and rejects those at 0 (finished).
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  gl_Position = vec4(corner, 0.0, 1.0);
}
