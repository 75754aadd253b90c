// --shading whitted, one pass: resolves the ray just traced and writes the
// element's next ray; render/whitted_shading.cpp is the same computation in
// the same order. Per nearest hit: ambient (1 - T) C; the reflection and
// refraction rays (Schlick's Fresnel, total internal reflection) pushed on
// the element's stack while depth < -b; then per light a shadow ray carrying
// the diffuse + Phong light (the first light's traced next, the others
// pushed). An element with no ray pops its stack's top.
// Stack of element e in whittedStack at float e * 12 * STACK_SIZE, entries of
// (origin, depth) (direction, tMax) (throughput or a shadow ray's light, kind);
// color.a holds count * 128 + depth - 1 (raygen's 0: empty stack, depth 1).
#include "texel_address.glsl"
#include "ray_kinds.glsl"
#include "triangle_shading.glsl"

layout(early_fragment_tests) in;
layout(std430, binding = 1) buffer WhittedStacks { float whittedStack[]; };

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uColor;
uniform sampler2D uThroughput;
uniform sampler2D uPending;
uniform ConstStream uMaterials;  // 4 texels per material: diffuse, mirror, (Ks, shine), (T, ior)
uniform vec3 uLightPositions[MAX_LIGHTS];
uniform vec3 uLightColors[MAX_LIGHTS];
uniform int uLightCount;
uniform vec3 uBackground;
uniform float uAmbient;
uniform float uEpsilon;
uniform int uMaxDepth;         // -b
uniform uint uStreamWidth;
uniform float uMinThroughput;  // kWhittedMinThroughput

layout(location = 0) out vec4 outOrigin;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outState;
layout(location = 3) out vec4 outHit;
layout(location = 4) out vec4 outColor;
layout(location = 5) out vec4 outThroughput;
layout(location = 6) out vec4 outPending;

uint stackBase() {
  uvec2 at = uvec2(gl_FragCoord.xy);
  return (at.y * uStreamWidth + at.x) * uint(12 * STACK_SIZE);
}

void store(inout int count, vec3 origin, vec3 direction, vec3 throughput, int depth, float tMax, float kind) {
  if (count == STACK_SIZE) return;  // full: the new ray is dropped
  uint at = stackBase() + uint(12 * count);
  whittedStack[at] = origin.x;
  whittedStack[at + 1u] = origin.y;
  whittedStack[at + 2u] = origin.z;
  whittedStack[at + 3u] = float(depth);
  whittedStack[at + 4u] = direction.x;
  whittedStack[at + 5u] = direction.y;
  whittedStack[at + 6u] = direction.z;
  whittedStack[at + 7u] = tMax;
  whittedStack[at + 8u] = throughput.r;
  whittedStack[at + 9u] = throughput.g;
  whittedStack[at + 10u] = throughput.b;
  whittedStack[at + 11u] = kind;
  count += 1;
}

void push(inout int count, vec3 origin, vec3 direction, vec3 throughput, int depth) {
  if (max(throughput.r, max(throughput.g, throughput.b)) < uMinThroughput) return;
  store(count, origin, direction, throughput, depth, INF, RAY_NEAREST);
}

float schlick(float ior, float cosine) {
  float r0 = ((ior - 1.0) / (ior + 1.0)) * ((ior - 1.0) / (ior + 1.0));
  float c = 1.0 - cosine;
  return r0 + (1.0 - r0) * (c * c * c * c * c);
}

void main() {
  if (gl_HelperInvocation) return;  // its storage reads may lie past the buffer (docs/design.md)
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  vec4 color = readElement(uColor);
  vec4 throughput = readElement(uThroughput);
  vec4 pending = readElement(uPending);
  throughput.w += state.y;
  pending.w += state.z;
  int count = int(color.a) / 128;
  int depth = int(color.a) - 128 * count + 1;

  float kind = RAY_NONE;
  vec3 newOrigin = origin.xyz, newDirection = direction.xyz;
  float tMax = INF;
  bool found = hit.x < direction.w;
  vec3 d = direction.xyz;

  if (origin.w == RAY_SHADOW) {
    if (!found) color.rgb += pending.rgb;
  } else if (origin.w == RAY_NEAREST && !found) {
    color.rgb += throughput.rgb * uBackground;
  } else if (origin.w == RAY_NEAREST) {
    uint triangle = unpackIndex(hit.w);
    TriangleShading shading = fetchTriangleShading(triangle);
    vec3 geometric = shading.geometric;
    uint material = shading.material;
    vec3 diffuse = fetchTexel(uMaterials, 4u * material).rgb;
    vec3 mirrorColor = fetchTexel(uMaterials, 4u * material + 1u).rgb;
    vec4 specular = fetchTexel(uMaterials, 4u * material + 2u);
    vec4 transmissive = fetchTexel(uMaterials, 4u * material + 3u);
    float ior = transmissive.y;

    vec3 position = origin.xyz + hit.x * d;
    bool entering = dot(geometric, d) <= 0.0;
    vec3 ng = entering ? geometric : -geometric;
    vec3 n = normalize(shading.n0 * (1.0 - hit.y - hit.z) + shading.n1 * hit.y + shading.n2 * hit.z);
    n = dot(n, ng) < 0.0 ? -n : n;
    vec3 front = position + uEpsilon * ng, back = position - uEpsilon * ng;
    vec3 thr = throughput.rgb;
    bool mirror = any(greaterThan(mirrorColor, vec3(0.0)));
    float t = mirror ? 0.0 : transmissive.x;
    if (!mirror) color.rgb += thr * uAmbient * diffuse * (1.0 - t);

    if (depth < uMaxDepth) {
      int childDepth = depth + 1;
      if (mirror) {
        push(count, front, reflect(d, n), thr * mirrorColor, childDepth);
      } else if (t > 0.0) {
        float eta = entering ? 1.0 / ior : ior;
        float cosi = clamp(-dot(d, n), 0.0, 1.0);
        float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
        float fresnel = 1.0;
        if (k >= 0.0) {
          float cost = sqrt(k);
          fresnel = schlick(ior, eta > 1.0 ? cost : cosi);
          vec3 refracted = eta * d + (eta * cosi - cost) * n;
          push(count, back, refracted, thr * (t * (1.0 - fresnel)), childDepth);
        }
        push(count, front, reflect(d, n), thr * (t * fresnel), childDepth);
      }
    }

    if (!mirror) {
      for (int k = uLightCount - 1; k >= 0; --k) {  // the first light's ray ends up traced next
        vec3 toLight = uLightPositions[k] - front;
        float distance = length(toLight);
        vec3 l = toLight / distance;
        float nDotL = dot(ng, l) > 0.0 ? max(dot(n, l), 0.0) : 0.0;
        if (nDotL <= 0.0) continue;
        float highlight = 0.0;
        if (any(greaterThan(specular.rgb, vec3(0.0))))
          highlight = pow(max(dot(reflect(-l, n), -d), 0.0), specular.w);
        vec3 direct = thr * uLightColors[k] * (diffuse * (nDotL * (1.0 - t)) + specular.rgb * highlight);
        if (!any(greaterThan(direct, vec3(0.0)))) continue;
        if (kind == RAY_SHADOW) store(count, newOrigin, newDirection, pending.rgb, 0, tMax, RAY_SHADOW);
        kind = RAY_SHADOW;
        newOrigin = front;
        newDirection = l;
        tMax = distance;
        pending.rgb = direct;
      }
    }
  }
  if (kind == RAY_NONE && count > 0) {
    count -= 1;
    uint at = stackBase() + uint(12 * count);
    newOrigin = vec3(whittedStack[at], whittedStack[at + 1u], whittedStack[at + 2u]);
    newDirection = vec3(whittedStack[at + 4u], whittedStack[at + 5u], whittedStack[at + 6u]);
    tMax = whittedStack[at + 7u];
    vec3 weight = vec3(whittedStack[at + 8u], whittedStack[at + 9u], whittedStack[at + 10u]);
    kind = whittedStack[at + 11u];
    if (kind == RAY_SHADOW) {
      pending.rgb = weight;
    } else {
      throughput.rgb = weight;
      depth = int(whittedStack[at + 3u]);
    }
  }
  color.a = float(128 * count + depth - 1);
  outOrigin = vec4(newOrigin, kind);
  outDirection = vec4(newDirection, tMax);
  outState = vec4(packIndex(0u), 0.0, 0.0, kind != RAY_NONE ? 1.0 : 0.0);
  outHit = vec4(tMax, 0.0, 0.0, packIndex(0u));
  outColor = color;
  outThroughput = throughput;
  outPending = pending;
}
