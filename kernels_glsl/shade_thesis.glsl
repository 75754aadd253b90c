// Shading (thesis 4.2), one bounce, as a function over one stream element:
// resolves the ray just traced and makes the element's next ray. shade.frag
// runs it as its own pass; fused kernels (bvh/bvh_octant_fused.frag) run it
// after their traversal. render/shading.cpp applies the same rules on the CPU.
//   shadow ray:  adds its pending light unless something occluded it;
//   miss:        adds the background;
//   mirror:      spawns the reflection ray (nothing if this is the last bounce);
//   diffuse:     adds ambient*C, and (N.L)C times the light through a shadow
//                ray, or directly on the last bounce (-b 1: primary rays only).
// Needs texel_address.glsl and ray_kinds.glsl.
#include "triangle_shading.glsl"

uniform ConstStream uMaterials;  // 2 texels per material: diffuse, mirror reflectance
uniform vec3 uLightPosition;
uniform vec3 uLightColor;
uniform vec3 uBackground;
uniform float uAmbient;
uniform float uEpsilon;        // offset of secondary ray origins along the normal
uniform int uLastBounce;       // 1 when no further rays may be traced

// The seven surfaces of a stream element (accel/ray_stream_layout.h).
struct StreamElement {
  vec4 origin, direction, state, hit, color, throughput, pending;
};

void shadeElement(inout StreamElement e) {
  // The traversal counters of the ray just traced join the element's totals.
  e.throughput.w += e.state.y;
  e.pending.w += e.state.z;

  float kind = RAY_NONE;
  vec3 newOrigin = e.origin.xyz, newDirection = e.direction.xyz;
  float tMax = INF;
  bool found = e.hit.x < e.direction.w;

  if (e.origin.w == RAY_SHADOW) {
    if (!found) e.color.rgb += e.pending.rgb;
  } else if (e.origin.w == RAY_NEAREST) {
    if (!found) {
      e.color.rgb += e.throughput.rgb * uBackground;
    } else {
      uint triangle = unpackIndex(e.hit.w);
      TriangleShading shading = fetchTriangleShading(triangle);
      vec3 geometric = shading.geometric;
      uint material = shading.material;
      vec3 diffuse = fetchTexel(uMaterials, 2u * material).rgb;
      vec3 mirror = fetchTexel(uMaterials, 2u * material + 1u).rgb;

      vec3 position = e.origin.xyz + e.hit.x * e.direction.xyz;
      // Both normals face the incoming ray: triangles are two-sided.
      vec3 ng = dot(geometric, e.direction.xyz) > 0.0 ? -geometric : geometric;
      vec3 n = normalize(shading.n0 * (1.0 - e.hit.y - e.hit.z) + shading.n1 * e.hit.y + shading.n2 * e.hit.z);
      n = dot(n, ng) < 0.0 ? -n : n;
      newOrigin = position + uEpsilon * ng;

      if (any(greaterThan(mirror, vec3(0.0)))) {
        if (uLastBounce == 0) {
          kind = RAY_NEAREST;
          newDirection = reflect(e.direction.xyz, n);
          e.throughput.rgb *= mirror;
        }
      } else {
        e.color.rgb += e.throughput.rgb * uAmbient * diffuse;
        vec3 toLight = uLightPosition - newOrigin;
        float distance = length(toLight);
        vec3 l = toLight / distance;
        float nDotL = dot(ng, l) > 0.0 ? max(dot(n, l), 0.0) : 0.0;
        vec3 direct = e.throughput.rgb * diffuse * uLightColor * nDotL;
        if (uLastBounce != 0) {
          e.color.rgb += direct;
        } else if (nDotL > 0.0) {
          kind = RAY_SHADOW;
          newDirection = l;
          tMax = distance;
          e.pending.rgb = direct;
        }
      }
    }
  }
  e.origin = vec4(newOrigin, kind);
  e.direction = vec4(newDirection, tMax);
  e.state = vec4(packIndex(0u), 0.0, 0.0, kind != RAY_NONE ? 1.0 : 0.0);
  e.hit = vec4(tMax, 0.0, 0.0, packIndex(0u));
}
