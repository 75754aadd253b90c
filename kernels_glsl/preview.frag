// Rasterized preview (-r 0): ambient plus unshadowed (N.L)C, two-sided, as the
// ray tracers shade a diffuse hit without its shadow ray.
in vec3 vPosition;
in vec3 vNormal;
in vec3 vColor;

uniform vec3 uEye;
uniform vec3 uLightPosition;
uniform vec3 uLightColor;
uniform float uAmbient;

layout(location = 0) out vec4 outColor;

void main() {
  vec3 n = normalize(vNormal);
  n = dot(n, vPosition - uEye) > 0.0 ? -n : n;
  vec3 l = normalize(uLightPosition - vPosition);
  outColor = vec4(vColor * (uAmbient + uLightColor * max(dot(n, l), 0.0)), 1.0);
}
