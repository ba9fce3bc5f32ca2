// What the rendering benchmarks share: the raw baseline they compare the renderer with (a
// trivial shader: transform and a constant colour) and frame timing.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute::bench {

inline GLuint compileShader(const GlFunctions& gl, GLenum stage, const char* source) {
  GLuint shader = gl.CreateShader(stage);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) throw std::runtime_error("the trivial shader does not compile");
  return shader;
}

// The trivial program: transform, constant colour.
inline GLuint trivialProgram(const GlFunctions& gl) {
  GLuint program = gl.CreateProgram();
  gl.AttachShader(program, compileShader(gl, GL_VERTEX_SHADER, R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
void main() { gl_Position = uViewProjection * vec4(aPosition, 1.0); })"));
  gl.AttachShader(program, compileShader(gl, GL_FRAGMENT_SHADER, R"(#version 330 core
out vec4 fragColor;
void main() { fragColor = vec4(0.3, 0.7, 0.2, 1.0); })"));
  gl.LinkProgram(program);
  return program;
}

// Seconds a frame of each drawing: the medians of `frames` frames each, timed in turn (A, B, …,
// A, B, …) so that a change in the machine's load falls on all alike. One frame of each is drawn
// first and left out.
inline std::vector<double> frameSeconds(const GlFunctions& gl, int frames,
                                        const std::vector<std::function<void()>>& draws) {
  auto time = [&](const std::function<void()>& draw) {
    auto start = std::chrono::steady_clock::now();
    draw();
    gl.Finish();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  for (const auto& draw : draws) time(draw);
  std::vector<std::vector<double>> times(draws.size());
  for (int i = 0; i < frames; ++i) {
    for (std::size_t d = 0; d < draws.size(); ++d) times[d].push_back(time(draws[d]));
  }
  std::vector<double> medians;
  for (auto& t : times) {
    std::sort(t.begin(), t.end());
    medians.push_back(t[t.size() / 2]);
  }
  return medians;
}

}  // namespace hirsute::bench
