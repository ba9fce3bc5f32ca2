// The viewer's window: GLFW with a GL 3.3 core-profile context, made current, and Dear ImGui
// over it with its GLFW and OpenGL 3 backends, and its pictures read back. Closing it ends ImGui,
// the window and GLFW.
#pragma once

#include <memory>
#include <string>

#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/view/png_image.h"

struct GLFWwindow;

namespace hirsute {

class GlfwWindow {
 public:
  // Null, after a message on stderr, when there is no display or no GL 3.3 context.
  static std::unique_ptr<GlfwWindow> open(const std::string& title, int width, int height,
                                          bool vsync);
  ~GlfwWindow();
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  // ImGui installs its callbacks over the window's own, which it calls first: after those.
  void startUi();
  // The back buffer's pixels, top row first (as a PNG has them).
  RgbaImage readPixels(const GlFunctions& gl) const;

 private:
  explicit GlfwWindow(GLFWwindow* window) : window_(window) {}
  GLFWwindow* window_;
  bool ui_ = false;
};

}  // namespace hirsute
