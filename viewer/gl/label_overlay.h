// Draws the Scene's labels (cpfg's @L, manual §6.10) over the rendered image: screen-aligned
// text of a fixed pixel size at each label's projected position, in the label's colour. The
// glyphs are stb_easy_font's quads (Debian's libstb-dev), drawn without depth test as cpfg draws
// its text over the model.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute {

class LabelOverlay {
 public:
  // stb_easy_font's glyphs are about 7 pixels tall; they are drawn this many times larger.
  static constexpr float kPixelScale = 2.0f;

  explicit LabelOverlay(const GlFunctions& gl);
  ~LabelOverlay();
  LabelOverlay(const LabelOverlay&) = delete;
  LabelOverlay& operator=(const LabelOverlay&) = delete;

  // Keeps the scene's labels with their colours (the material's diffuse colour, which is the
  // colour itself with a colour map).
  void upload(const Scene& scene);
  // Draws them into the bound framebuffer for `camera`; the text's top left corner is at the
  // projected position. Labels behind the eye are not drawn.
  void draw(const Camera& camera);

 private:
  struct Text {
    glm::vec3 position;
    std::string text;
    glm::vec3 color;
  };

  const GlFunctions& gl_;
  std::vector<Text> labels_;
  GLuint program_ = 0, vertexArray_ = 0, buffer_ = 0;
  GLint viewportUniform_ = -1, colorUniform_ = -1;
};

}  // namespace hirsute
