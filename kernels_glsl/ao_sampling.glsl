// Ambient-occlusion directions from a per-pixel integer hash, the same
// computation as render/ao_sampling.h (both renderers trace the same rays).

uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

vec2 aoRandom(uint pixel, uint sampleIndex) {
  uint h1 = pcgHash(pixel ^ pcgHash(sampleIndex));
  uint h2 = pcgHash(h1);
  return vec2(float(h1 >> 8u), float(h2 >> 8u)) * (1.0 / 16777216.0);
}

vec3 aoDirection(vec3 n, vec2 u) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
  float r = sqrt(u.x);
  float phi = 6.28318530718 * u.y;
  return t * (r * cos(phi)) + bt * (r * sin(phi)) + n * sqrt(max(0.0, 1.0 - u.x));
}
