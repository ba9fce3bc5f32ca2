#include "label_overlay.h"

#include <cstring>
#include <stdexcept>

#include "hirsute/viewer/gl/gl_objects.h"

#define STB_EASY_FONT_IMPLEMENTATION  // a header of static functions; this is its one user
#include <stb/stb_easy_font.h>

namespace hirsute {
namespace {

// Positions arrive in pixels from the top left corner, as stb_easy_font lays them out.
constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 aPixel;
uniform vec2 uViewport;
void main() {
  gl_Position = vec4(aPixel.x / uViewport.x * 2.0 - 1.0, 1.0 - aPixel.y / uViewport.y * 2.0, 0.0, 1.0);
}
)";
constexpr const char* kFragmentShader = R"(#version 330 core
uniform vec3 uColor;
out vec4 fragColor;
void main() { fragColor = vec4(uColor, 1.0); }
)";

}  // namespace

LabelOverlay::LabelOverlay(const GlFunctions& gl) : gl_(gl) {
  program_ = gl::linkProgram(gl_, {kVertexShader}, {kFragmentShader});
  viewportUniform_ = gl_.GetUniformLocation(program_, "uViewport");
  colorUniform_ = gl_.GetUniformLocation(program_, "uColor");
  gl_.GenVertexArrays(1, &vertexArray_);
  gl_.GenBuffers(1, &buffer_);
  gl_.BindVertexArray(vertexArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, buffer_);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(glm::vec2), nullptr);
  gl_.BindVertexArray(0);
}

LabelOverlay::~LabelOverlay() {
  gl_.DeleteBuffers(1, &buffer_);
  gl_.DeleteVertexArrays(1, &vertexArray_);
  gl_.DeleteProgram(program_);
}

void LabelOverlay::upload(const Scene& scene) {
  labels_.clear();
  for (const Label& label : scene.labels) {
    const bool known =
        label.material >= 0 && static_cast<std::size_t>(label.material) < scene.materials.size();
    const Material material =
        known ? scene.materials[static_cast<std::size_t>(label.material)] : Material{};
    labels_.push_back(Text{label.position, label.text, material.diffuse});
  }
}

void LabelOverlay::draw(const Camera& camera) {
  if (labels_.empty()) return;
  const glm::mat4 viewProjection = camera.viewProjection();
  const glm::vec2 viewport(camera.viewport);
  gl_.UseProgram(program_);
  gl_.Uniform2f(viewportUniform_, viewport.x, viewport.y);
  gl_.BindVertexArray(vertexArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, buffer_);
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_BLEND);
  gl_.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  // stb_easy_font writes quads of four 16-byte vertices (x, y, z, rgba); about 270 bytes a
  // character at most.
  std::vector<char> quads;
  std::vector<glm::vec2> triangles;
  for (const Text& label : labels_) {
    const glm::vec4 clip = viewProjection * glm::vec4(label.position, 1.0f);
    if (clip.w <= 0 || label.text.empty()) continue;
    const glm::vec2 anchor((clip.x / clip.w * 0.5f + 0.5f) * viewport.x,
                           (0.5f - clip.y / clip.w * 0.5f) * viewport.y);
    std::string text = label.text;  // stb_easy_font takes a mutable pointer
    quads.assign(300 * (text.size() + 1), 0);
    const int count = stb_easy_font_print(0, 0, text.data(), nullptr, quads.data(),
                                          static_cast<int>(quads.size()));
    triangles.clear();
    for (int q = 0; q < count; ++q) {
      glm::vec2 corner[4];
      for (int v = 0; v < 4; ++v) {
        float xy[2];
        std::memcpy(xy, quads.data() + 16 * (4 * q + v), sizeof xy);
        corner[v] = anchor + kPixelScale * glm::vec2(xy[0], xy[1]);
      }
      for (int v : {0, 1, 2, 0, 2, 3}) triangles.push_back(corner[v]);
    }
    if (triangles.empty()) continue;
    gl_.Uniform3fv(colorUniform_, 1, &label.color.x);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(glm::vec2)),
                   triangles.data(), GL_STREAM_DRAW);
    gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size()));
  }
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
}

}  // namespace hirsute
