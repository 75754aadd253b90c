#include "stream/gl_program.h"

#include <initializer_list>
#include <utility>

#include "stream/compute_variant.h"
#include "stream/gl_error.h"
#include "stream/glsl_sources.h"

namespace passtrace {
namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  isProgram ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::max(length, 1), '\0');
  isProgram ? glGetProgramInfoLog(object, length, nullptr, log.data())
            : glGetShaderInfoLog(object, length, nullptr, log.data());
  log.resize(std::min(log.size(), log.find('\0')));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log;
}

// `transform` rewrites the assembled source (the compute variant), or is null.
GLuint compile(GLenum type, const std::string& kernel, const std::string& file,
               const std::vector<std::string>& defines, std::string (*transform)(std::string) = nullptr) {
  AssembledGlsl glsl;
  try {
    glsl = assembleGlsl(file, defines);
    if (transform) glsl.source = transform(std::move(glsl.source));
  } catch (const std::exception& e) {
    throw GlError("kernel " + kernel + " (" + file + "): " + e.what());
  }
  const GLuint shader = glCreateShader(type);
  const char* text = glsl.source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  const std::string log = glsl.translateLog(infoLog(shader, false));
  glDeleteShader(shader);
  throw GlError("kernel " + kernel + " (" + file + "): compile failed: " + log);
}

// Links the compiled shaders (deleting them) into a program.
GLuint link(const std::string& name, const std::string& file, std::initializer_list<GLuint> shaders) {
  const GLuint program = glCreateProgram();
  for (const GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  for (const GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(program, true);
    glDeleteProgram(program);
    throw GlError("kernel " + name + " (" + file + "): link failed: " + log);
  }
  checkGlError("linking kernel " + name);
  return program;
}

}  // namespace

GLuint linkProgram(const std::string& name, const std::string& vertexFile, const std::string& fragmentFile,
                   const std::vector<std::string>& defines) {
  const GLuint vs = compile(GL_VERTEX_SHADER, name, vertexFile, defines);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, name, fragmentFile, defines);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  return link(name, fragmentFile, {vs, fs});
}

GLuint linkComputeProgram(const std::string& name, const std::string& fragmentFile,
                          const std::vector<std::string>& defines) {
  return link(name, fragmentFile, {compile(GL_COMPUTE_SHADER, name, fragmentFile, defines, computeVariant)});
}

GLuint linkComputeShader(const std::string& name, const std::string& computeFile) {
  return link(name, computeFile, {compile(GL_COMPUTE_SHADER, name, computeFile, {})});
}

}  // namespace passtrace
