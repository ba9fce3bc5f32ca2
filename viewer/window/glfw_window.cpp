#include "hirsute/viewer/window/glfw_window.h"

// GLFW declares no GL itself (the renderer resolves GL through GlFunctions).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <iostream>

// In the sanitizer build, the GL driver's own allocations that it never frees would be reported
// from a library already unloaded at exit (glfwTerminate closes it), where no suppression can
// name it; the libraries are kept loaded, so that offscreen.cpp's suppressions match them.
#if defined(__SANITIZE_ADDRESS__)
#define HIRSUTE_KEEP_GL_LIBRARIES 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HIRSUTE_KEEP_GL_LIBRARIES 1
#endif
#endif
#ifdef HIRSUTE_KEEP_GL_LIBRARIES
#include <dlfcn.h>
#include <link.h>
#endif

namespace hirsute {
namespace {

void keepLibrariesLoaded() {
#ifdef HIRSUTE_KEEP_GL_LIBRARIES
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void*) {
        if (info->dlpi_name && info->dlpi_name[0] != '\0') {
          // RTLD_NOLOAD: only those loaded; the handle is kept on purpose.
          dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        }
        return 0;
      },
      nullptr);
#endif
}

}  // namespace

std::unique_ptr<GlfwWindow> GlfwWindow::open(const std::string& title, int width, int height,
                                             bool vsync) {
  glfwSetErrorCallback(
      [](int, const char* description) { std::cerr << "hirsute: glfw: " << description << '\n'; });
  // GLFW is terminated by the window's destructor, even when no window opens.
  std::unique_ptr<GlfwWindow> window(new GlfwWindow(nullptr));
  if (!glfwInit()) {
    std::cerr << "hirsute: error: cannot open a window (is there a display? without one, run "
                 "under xvfb-run)\n";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);  // multisampling is MultisampleTarget's
  window->window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window->window_) {
    std::cerr << "hirsute: error: cannot open a window with a GL 3.3 core-profile context\n";
    return nullptr;
  }
  glfwMakeContextCurrent(window->window_);
  glfwSwapInterval(vsync ? 1 : 0);
  return window;
}

void GlfwWindow::startUi() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  ui_ = true;
}

RgbaImage GlfwWindow::readPixels(const GlFunctions& gl) const {
  int w = 1, h = 1;
  glfwGetFramebufferSize(window_, &w, &h);
  RgbaImage upsideDown(w, h);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl.ReadBuffer(GL_BACK);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, upsideDown.rgba.data());
  RgbaImage image(w, h);
  std::size_t row = static_cast<std::size_t>(w) * 4;
  for (int y = 0; y < h; ++y) {
    std::copy_n(&upsideDown.rgba[static_cast<std::size_t>(h - 1 - y) * row], row,
                &image.rgba[static_cast<std::size_t>(y) * row]);
  }
  return image;
}

GlfwWindow::~GlfwWindow() {
  if (ui_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (window_) glfwDestroyWindow(window_);
  keepLibrariesLoaded();
  glfwTerminate();
}

}  // namespace hirsute
