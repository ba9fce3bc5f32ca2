// Making the GL objects the renderer's drawings share (the surfaces, lines and labels of
// gl_renderer.cpp, each organ's drawing): shader programs, buffers, vertex attributes. Every call
// goes through GlFunctions.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <vector>

#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute::gl {

// Compiles a shader stage from its pieces, in order; throws std::runtime_error with the log.
GLuint compileShader(const GlFunctions& gl, GLenum stage,
                     std::initializer_list<const char*> pieces);
// Links a program of a vertex, a fragment and an optional geometry stage; throws
// std::runtime_error with the log.
GLuint linkProgram(const GlFunctions& gl, std::initializer_list<const char*> vertex,
                   std::initializer_list<const char*> fragment,
                   std::initializer_list<const char*> geometry = {});
// Throws std::runtime_error naming `where` when GL has an error.
void checkErrors(const GlFunctions& gl, const char* where);

// A new buffer bound to `target`, holding `data`.
template <typename T>
GLuint makeBuffer(const GlFunctions& gl, GLenum target, const std::vector<T>& data) {
  GLuint buffer = 0;
  gl.GenBuffers(1, &buffer);
  gl.BindBuffer(target, buffer);
  gl.BufferData(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                GL_STATIC_DRAW);
  return buffer;
}

// Vertex attribute `location` of `size` floats (or one int), per vertex or per instance.
void floatAttribute(const GlFunctions& gl, GLuint location, GLint size, GLsizei stride,
                    std::size_t offset, bool perInstance);
void intAttribute(const GlFunctions& gl, GLuint location, GLsizei stride, std::size_t offset);

}  // namespace hirsute::gl
