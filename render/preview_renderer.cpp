#include "render/preview_renderer.h"

#include <chrono>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "render/camera.h"
#include "stream/gl_error.h"
#include "stream/gl_program.h"
#include "stream/inout_stream.h"

namespace passtrace {
namespace {

struct Vertex {
  glm::vec3 position, normal, color;
};

std::vector<Vertex> vertices(const Scene& scene) {
  std::vector<Vertex> out;
  out.reserve(3 * scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    const glm::vec3 geometric = t.geometricNormal();
    const glm::vec3 color = scene.materials[scene.materialIds[i]].diffuse;
    const glm::vec3 corners[3] = {t.v0, t.v1, t.v2};
    for (int k = 0; k < 3; ++k)
      out.push_back({corners[k], scene.hasVertexNormals() ? scene.vertexNormals[i][k] : geometric, color});
  }
  return out;
}

}  // namespace

FrameResult renderPreview(const Scene& scene, const CameraSpec& camera, int width, int height) {
  const CameraBasis basis = makeCameraBasis(camera, width, height);
  // The preview draws into one RGBA32F surface of an InOutStream.
  InOutStream target(width, height, 1);
  const GLuint program = linkProgram("preview", "preview.vert", "preview.frag");

  const std::vector<Vertex> data = vertices(scene);
  GLuint buffer = 0, vertexArray = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(data.size() * sizeof(Vertex)), data.data(), 0);
  glCreateVertexArrays(1, &vertexArray);
  glVertexArrayVertexBuffer(vertexArray, 0, buffer, 0, sizeof(Vertex));
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vertexArray, a);
    glVertexArrayAttribFormat(vertexArray, a, 3, GL_FLOAT, GL_FALSE, GLuint(a * sizeof(glm::vec3)));
    glVertexArrayAttribBinding(vertexArray, a, 0);
  }

  const Aabb box = scene.bounds();
  const float size = box.empty() ? 1.0f : glm::length(box.extent());
  const float farPlane = glm::length(basis.eye - box.center()) + size;
  const glm::mat4 projection = glm::perspective(2.0f * std::atan(basis.tanHalfFov), float(width) / float(height),
                                                farPlane * 1e-4f, farPlane);
  const glm::mat4 view = glm::lookAt(basis.eye, basis.eye + basis.forward, basis.up);
  const glm::mat4 viewProjection = projection * view;
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "uViewProjection"), 1, GL_FALSE,
                            glm::value_ptr(viewProjection));
  glProgramUniform3fv(program, glGetUniformLocation(program, "uEye"), 1, glm::value_ptr(basis.eye));
  glProgramUniform3fv(program, glGetUniformLocation(program, "uLightPosition"), 1,
                      glm::value_ptr(scene.light.position));
  glProgramUniform3fv(program, glGetUniformLocation(program, "uLightColor"), 1, glm::value_ptr(scene.light.color));
  glProgramUniform1f(program, glGetUniformLocation(program, "uAmbient"), scene.ambient);

  FrameResult result;
  result.width = width;
  result.height = height;
  target.enable();
  target.clearSurface(0, glm::vec4(scene.background, 1.0f));
  target.clearDepth(1.0f);
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  glUseProgram(program);
  glBindVertexArray(vertexArray);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(data.size()));
  glFinish();
  result.stats.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  checkGlError("drawing the preview");

  // GL rows run bottom-up; images run top-down.
  const std::vector<glm::vec4> pixels = target.read(0);
  result.rgb.resize(size_t(3) * pixels.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec4& c = pixels[size_t(height - 1 - y) * width + x];
      float* out = &result.rgb[3 * (size_t(y) * width + x)];
      out[0] = c.r, out[1] = c.g, out[2] = c.b;
    }
  target.disable();
  glDeleteVertexArrays(1, &vertexArray);
  glDeleteBuffers(1, &buffer);
  glDeleteProgram(program);
  return result;
}

}  // namespace passtrace
