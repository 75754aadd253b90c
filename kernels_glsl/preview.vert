// Rasterized preview (-r 0): positions and normals in world space.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec3 inColor;

uniform mat4 uViewProjection;

out vec3 vPosition;
out vec3 vNormal;
out vec3 vColor;

void main() {
  vPosition = inPosition;
  vNormal = inNormal;
  vColor = inColor;
  gl_Position = uViewProjection * vec4(inPosition, 1.0);
}
