// Shading (thesis 4.2), one bounce: resolves the ray just traced and writes
// the element's next ray. render/shading.cpp applies the same rules on the CPU.
//   shadow ray:  adds its pending light unless something occluded it;
//   miss:        adds the background;
//   mirror:      spawns the reflection ray (nothing if this is the last bounce);
//   diffuse:     adds ambient*C, and (N.L)C times the light through a shadow
//                ray, or directly on the last bounce (-b 1: primary rays only).
#include "texel_address.glsl"
#include "ray_kinds.glsl"

layout(early_fragment_tests) in;

uniform sampler2D uOrigin;
uniform sampler2D uDirection;
uniform sampler2D uState;
uniform sampler2D uHit;
uniform sampler2D uColor;
uniform sampler2D uThroughput;
uniform sampler2D uPending;
uniform ConstStream uTriangles;  // 4 texels per triangle: (n0, material) n1 n2 (geometric normal)
uniform ConstStream uMaterials;  // 2 texels per material: diffuse, mirror reflectance
uniform vec3 uLightPosition;
uniform vec3 uLightColor;
uniform vec3 uBackground;
uniform float uAmbient;
uniform float uEpsilon;        // offset of secondary ray origins along the normal
uniform int uLastBounce;       // 1 when no further rays may be traced

layout(location = 0) out vec4 outOrigin;
layout(location = 1) out vec4 outDirection;
layout(location = 2) out vec4 outState;
layout(location = 3) out vec4 outHit;
layout(location = 4) out vec4 outColor;
layout(location = 5) out vec4 outThroughput;
layout(location = 6) out vec4 outPending;

void main() {
  vec4 origin = readElement(uOrigin);
  vec4 direction = readElement(uDirection);
  vec4 state = readElement(uState);
  vec4 hit = readElement(uHit);
  vec4 color = readElement(uColor);
  vec4 throughput = readElement(uThroughput);
  vec4 pending = readElement(uPending);
  // The traversal counters of the ray just traced join the element's totals.
  throughput.w += state.y;
  pending.w += state.z;

  float kind = RAY_NONE;
  vec3 newOrigin = origin.xyz, newDirection = direction.xyz;
  float tMax = INF;
  bool found = hit.x < direction.w;

  if (origin.w == RAY_SHADOW) {
    if (!found) color.rgb += pending.rgb;
  } else if (origin.w == RAY_NEAREST) {
    if (!found) {
      color.rgb += throughput.rgb * uBackground;
    } else {
      uint triangle = unpackIndex(hit.w);
      vec4 n0 = fetchTexel(uTriangles, 4u * triangle);
      vec3 n1 = fetchTexel(uTriangles, 4u * triangle + 1u).xyz;
      vec3 n2 = fetchTexel(uTriangles, 4u * triangle + 2u).xyz;
      vec3 geometric = fetchTexel(uTriangles, 4u * triangle + 3u).xyz;
      uint material = unpackIndex(n0.w);
      vec3 diffuse = fetchTexel(uMaterials, 2u * material).rgb;
      vec3 mirror = fetchTexel(uMaterials, 2u * material + 1u).rgb;

      vec3 position = origin.xyz + hit.x * direction.xyz;
      // Both normals face the incoming ray: triangles are two-sided.
      vec3 ng = dot(geometric, direction.xyz) > 0.0 ? -geometric : geometric;
      vec3 n = normalize(n0.xyz * (1.0 - hit.y - hit.z) + n1 * hit.y + n2 * hit.z);
      n = dot(n, ng) < 0.0 ? -n : n;
      newOrigin = position + uEpsilon * ng;

      if (any(greaterThan(mirror, vec3(0.0)))) {
        if (uLastBounce == 0) {
          kind = RAY_NEAREST;
          newDirection = reflect(direction.xyz, n);
          throughput.rgb *= mirror;
        }
      } else {
        color.rgb += throughput.rgb * uAmbient * diffuse;
        vec3 toLight = uLightPosition - newOrigin;
        float distance = length(toLight);
        vec3 l = toLight / distance;
        float nDotL = dot(ng, l) > 0.0 ? max(dot(n, l), 0.0) : 0.0;
        vec3 direct = throughput.rgb * diffuse * uLightColor * nDotL;
        if (uLastBounce != 0) {
          color.rgb += direct;
        } else if (nDotL > 0.0) {
          kind = RAY_SHADOW;
          newDirection = l;
          tMax = distance;
          pending.rgb = direct;
        }
      }
    }
  }
  outOrigin = vec4(newOrigin, kind);
  outDirection = vec4(newDirection, tMax);
  outState = vec4(packIndex(0u), 0.0, 0.0, kind != RAY_NONE ? 1.0 : 0.0);
  outHit = vec4(tMax, 0.0, 0.0, packIndex(0u));
  outColor = color;
  outThroughput = throughput;
  outPending = pending;
}
