// Making the GL objects the renderer's drawings share.
#include "hirsute/viewer/gl/gl_objects.h"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace hirsute::gl {

GLuint compileShader(const GlFunctions& gl, GLenum stage,
                     std::initializer_list<const char*> pieces) {
  GLuint shader = gl.CreateShader(stage);
  std::vector<const char*> sources(pieces);
  gl.ShaderSource(shader, static_cast<GLsizei>(sources.size()), sources.data(), nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string("GL shader does not compile: ") + log);
  }
  return shader;
}

GLuint linkProgram(const GlFunctions& gl, std::initializer_list<const char*> vertex,
                   std::initializer_list<const char*> fragment,
                   std::initializer_list<const char*> geometry) {
  std::vector<GLuint> stages;
  try {
    stages.push_back(compileShader(gl, GL_VERTEX_SHADER, vertex));
    stages.push_back(compileShader(gl, GL_FRAGMENT_SHADER, fragment));
    if (geometry.size() > 0) stages.push_back(compileShader(gl, GL_GEOMETRY_SHADER, geometry));
  } catch (...) {
    for (GLuint shader : stages) gl.DeleteShader(shader);
    throw;
  }
  GLuint program = gl.CreateProgram();
  for (GLuint shader : stages) gl.AttachShader(program, shader);
  gl.LinkProgram(program);
  for (GLuint shader : stages) gl.DeleteShader(shader);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    gl.DeleteProgram(program);
    throw std::runtime_error(std::string("GL program does not link: ") + log);
  }
  return program;
}

void checkErrors(const GlFunctions& gl, const char* where) {
  GLenum error = gl.GetError();
  if (error != GL_NO_ERROR) {
    char text[64];
    std::snprintf(text, sizeof text, "GL error 0x%04x in ", error);
    throw std::runtime_error(text + std::string(where));
  }
}

void floatAttribute(const GlFunctions& gl, GLuint location, GLint size, GLsizei stride,
                    std::size_t offset, bool perInstance) {
  gl.EnableVertexAttribArray(location);
  gl.VertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, stride,
                         reinterpret_cast<const void*>(offset));
  if (perInstance) gl.VertexAttribDivisor(location, 1);
}

void intAttribute(const GlFunctions& gl, GLuint location, GLsizei stride, std::size_t offset) {
  gl.EnableVertexAttribArray(location);
  gl.VertexAttribIPointer(location, 1, GL_INT, stride, reinterpret_cast<const void*>(offset));
  gl.VertexAttribDivisor(location, 1);
}

}  // namespace hirsute::gl
