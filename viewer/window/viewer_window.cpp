#include "hirsute/viewer/window/viewer_window.h"

// GLFW declares no GL itself (the renderer resolves GL through GlFunctions).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/interaction/live_organ.h"
#include "hirsute/viewer/window/control_panel_window.h"
#include "hirsute/viewer/window/define_panel.h"
#include "hirsute/viewer/window/shape_panels.h"
#include "hirsute/viewer/window/glfw_window.h"
#include "hirsute/viewer/window/multisample_target.h"
#include "hirsute/viewer/window/overlays.h"
#include "hirsute/viewer/window/palette_panel.h"

namespace hirsute {

namespace {

using Clock = std::chrono::steady_clock;

// The camera counts as moving this long after the last motion: hairs are thinned out meanwhile.
constexpr std::chrono::milliseconds kStillAfter{150};

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

class Viewer;
Viewer* viewerOf(GLFWwindow* window) {
  return static_cast<Viewer*>(glfwGetWindowUserPointer(window));
}

class Viewer final : public LiveModelView {
 public:
  Viewer(const ViewerOptions& options, ModelBuilder builder)
      : options_(options), builder_(std::move(builder)) {}
  ~Viewer() override { shutdown(); }

  int run();

  // What the live model asks of the window.
  void upload(const ViewerModel& model) override {
    renderer_->upload(model.scene, model.view, model.materialMode);
  }
  void updateOrgan(std::string_view organ, const Scene& scene) override {
    renderer_->updateOrgan(organ, scene);
  }
  bool screenshot(const std::filesystem::path& file, Shot shot) override;
  void measure(int frames) override;

 private:
  // The frame drawn (with the panel for WithUi) and read back, or for Shown the picture on the
  // screen as it is, handed to `write`, which writes `file`; false, with the message printed,
  // when it fails.
  bool capture(const std::filesystem::path& file, Shot shot,
               const std::function<void(const RgbaImage&)>& write);
  // The key S's screenshot, "MODEL-N.png" in the current folder (which may be the model's own):
  // a name the viewer makes up, so it is created there without following a link planted at it.
  void screenshotHere(const std::string& name);
  bool open();
  void shutdown();
  void installCallbacks();

  // Drawing
  glm::ivec2 framebufferSize() const;
  bool moving() const { return Clock::now() - lastMotion_ < kStillAfter; }
  void drawScene(bool moving);
  void drawUi();
  void frame();

  // Input
  void onKey(int key, int mods);
  void onButton(int button, int action, int mods);
  void onCursor(double x, double y);
  void onScroll(double dy);
  void organKey(int key);
  void pointAtCursor();

  const ViewerOptions& options_;
  ModelBuilder builder_;
  std::unique_ptr<GlfwWindow> glfw_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<GlFunctions> gl_;
  std::unique_ptr<GlRenderer> renderer_;
  std::unique_ptr<MultisampleTarget> multisample_;
  std::unique_ptr<LiveModel> live_;

  // Input and frame state
  int dragButton_ = -1;
  bool dragShift_ = false;
  double cursorX_ = 0, cursorY_ = 0;
  Clock::time_point lastMotion_ = Clock::now() - std::chrono::seconds(10);
  bool drawnMoving_ = false;
  bool dirty_ = true;
  int uiFrames_ = 2;  // ImGui needs a frame or two after input to settle
  double frameMs_ = 0;
  Clock::time_point lastFrameEnd_;
  // The picture the last frame put on the screen, kept for a script that asks for it
  // (`screenshot FILE shown`): a window's front buffer cannot be read back everywhere.
  bool keepShown_ = false;
  RgbaImage shown_;
  int screenshots_ = 0;
  PaletteUiState paletteUi_;
  ShapePanels shapePanels_;
};

bool Viewer::open() {
  std::string title = "hirsute view: " + options_.lsystemFile.filename().string();
  glfw_ = GlfwWindow::open(title, options_.width, options_.height, !options_.script);
  if (!glfw_) return false;
  window_ = glfw_->handle();
  if (options_.script) {
    keepShown_ =
        std::any_of(options_.script->begin(), options_.script->end(), [](const ViewCommand& c) {
          return c.kind == ViewCommand::Kind::Screenshot && c.words.size() > 1 &&
                 c.words[1] == "shown";
        });
  }
  try {
    gl_ = std::make_unique<GlFunctions>(
        [](const char* name) { return reinterpret_cast<GlProc>(glfwGetProcAddress(name)); });
    renderer_ = std::make_unique<GlRenderer>(*gl_);
    multisample_ = std::make_unique<MultisampleTarget>(*gl_);
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return false;
  }
  glfwSetWindowUserPointer(window_, this);
  installCallbacks();
  glfw_->startUi();
  return true;
}

void Viewer::shutdown() {
  live_.reset();  // joins the builder's thread before the window goes
  renderer_.reset();
  multisample_.reset();
  gl_.reset();
  glfw_.reset();
  window_ = nullptr;
}

void Viewer::installCallbacks() {
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    Viewer* v = viewerOf(w);
    v->dirty_ = true;
    v->uiFrames_ = 2;
    if (action == GLFW_PRESS || action == GLFW_REPEAT) v->onKey(key, mods);
  });
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned) {
    viewerOf(w)->dirty_ = true;
    viewerOf(w)->uiFrames_ = 2;
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    viewerOf(w)->onButton(button, action, mods);
  });
  glfwSetCursorPosCallback(window_,
                           [](GLFWwindow* w, double x, double y) { viewerOf(w)->onCursor(x, y); });
  glfwSetScrollCallback(window_,
                        [](GLFWwindow* w, double, double dy) { viewerOf(w)->onScroll(dy); });
  glfwSetFramebufferSizeCallback(window_,
                                 [](GLFWwindow* w, int, int) { viewerOf(w)->dirty_ = true; });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { viewerOf(w)->dirty_ = true; });
}

// ---- drawing ----

glm::ivec2 Viewer::framebufferSize() const {
  int w = 1, h = 1;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

void Viewer::drawScene(bool moving) {
  const glm::ivec2 size = framebufferSize();
  // While the camera moves, the frame is drawn without multisampling too (with llvmpipe that
  // halves its time); the still frame that follows has both back.
  bool multisampled =
      !moving && options_.samples > 1 && multisample_->bind(size.x, size.y, options_.samples);
  if (!multisampled) gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!live_->model()) {
    gl_->Viewport(0, 0, size.x, size.y);
    gl_->ClearColor(0.1f, 0.1f, 0.1f, 1);
    gl_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (multisampled) multisample_->resolve();
    return;
  }
  const ShownParts& shown = live_->shown();
  for (const LiveOrganType* organ : liveOrgans())
    renderer_->setOrganVisible(organ->name(), shown.organShown(organ->name()));
  renderer_->setWireframe(shown.wireframe);
  // While moving, the organs that can draw a part of their instances (hairs) draw the budget.
  float fraction = 1;
  const std::size_t thinned = renderer_->thinnedInstances();
  if (moving && thinned > options_.movingHairBudget) {
    fraction = static_cast<float>(options_.movingHairBudget) / static_cast<float>(thinned);
  }
  renderer_->setDetail(fraction);
  try {
    renderer_->draw(live_->camera(size));
  } catch (const GeometryLimitError& e) {
    live_->drawingFailed(e.what());
  }
  drawnMoving_ = moving;
  if (multisampled) multisample_->resolve();
}

void Viewer::drawUi() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  drawStatusOverlay(*live_, *renderer_, options_.lsystemFile.filename().string(), frameMs_,
                    drawnMoving_ && renderer_->detail() < 1);
  drawErrorOverlay(live_->error());
  drawHelpOverlay(&live_->shown().help);
  if (live_->shown().panel && !live_->constants().empty()) {
    DefinePanel panel = drawDefinePanel(live_->constants(), live_->changedDefines(),
                                        options_.saveDefines, &live_->shown().panel);
    for (const DefinePanel::Edit& edit : panel.edits) {
      live_->setDefine(edit.name, edit.value);
      if (options_.saveDefines && edit.finished) live_->saveDefines();
    }
    if (panel.save) live_->saveDefines();
    if (panel.revert) live_->revertDefines();
    if (panel.makePanel) live_->createEditorFile("panel");
  }
  if (live_->shown().colors) drawPalettePanel(*live_, paletteUi_, &live_->shown().colors);
  if (live_->shown().controls) drawControlPanels(*live_);
  drawFunctionPanel(live_->shapes(), shapePanels_.function);
  drawContourPanel(live_->shapes(), shapePanels_.contour);
  drawSurfacePanel(live_->shapes(), shapePanels_.surface);
  live_->shapesEdited();
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Viewer::frame() {
  auto start = Clock::now();
  drawScene(moving());
  drawUi();
  if (keepShown_) shown_ = glfw_->readPixels(*gl_);
  glfwSwapBuffers(window_);
  lastFrameEnd_ = Clock::now();
  frameMs_ = secondsSince(start) * 1000.0;
}

bool Viewer::screenshot(const std::filesystem::path& file, Shot shot) {
  return capture(file, shot, [&](const RgbaImage& image) {
    writeImage(file, image, imageFormatOf(file).value_or(ImageFormat::Png));
  });
}

void Viewer::screenshotHere(const std::string& name) {
  capture(name, Shot::Plant,
          [&](const RgbaImage& image) { writePng(OutputFolder("."), name, image); });
}

bool Viewer::capture(const std::filesystem::path& file, Shot shot,
                     const std::function<void(const RgbaImage&)>& write) {
  RgbaImage image;
  if (shot == Shot::Shown) {
    image = shown_;
  } else {
    const bool withUi = shot == Shot::WithUi;
    // ImGui sizes a window that has just appeared over its first frames.
    for (int i = 0; withUi && i < 2; ++i) frame();
    drawScene(false);
    if (withUi) drawUi();
    image = glfw_->readPixels(*gl_);
    if (!withUi) drawUi();
    glfwSwapBuffers(window_);
  }
  live_->ignoreWrite(file);
  try {
    write(image);
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return false;
  }
  live_->ignoreWrite(file);
  std::cout << "wrote " << file.string() << '\n';
  return true;
}

void Viewer::measure(int frames) {
  if (!live_->model() || frames < 1) return;
  auto timeFrames = [&](bool move) {
    MouseCamera saved = live_->mouse();
    gl_->Finish();
    auto start = Clock::now();
    for (int i = 0; i < frames; ++i) {
      if (move) live_->mouse().rotate(2.0f, 0.0f);
      drawScene(move);
      glfwSwapBuffers(window_);
    }
    gl_->Finish();
    double ms = secondsSince(start) * 1000.0 / frames;
    live_->mouse() = saved;
    return ms;
  };
  double still = timeFrames(false);
  const std::size_t thinned = renderer_->thinnedInstances();
  double movingMs = timeFrames(true);
  float fraction = renderer_->detail();
  std::cout << "frame time: still " << still << " ms, moving " << movingMs << " ms (" << frames
            << " frames each, " << renderer_->triangleCount() << " triangles, "
            << renderer_->lineCount() << " lines";
  for (const LiveOrganType* organ : liveOrgans()) {
    const std::size_t n = renderer_->organInstances(organ->name());
    if (n > 0) std::cout << ", " << n << ' ' << organ->name();
  }
  if (thinned > 0) {
    std::cout << "; "
              << static_cast<std::size_t>(std::lround(fraction * static_cast<double>(thinned)))
              << " of " << thinned << " drawn while moving";
  }
  std::cout << ")\n";
  // What moves on its own says how it keeps up (the feathers' dynamics: simulated seconds per
  // wall-clock second).
  const std::span<const LiveOrganType* const> organs = liveOrgans();
  for (std::size_t k = 0; k < organs.size(); ++k) {
    const std::string status = live_->organ(k).status();
    if (live_->organ(k).moving() && !status.empty())
      std::cout << organs[k]->name() << ": " << status << '\n';
  }
  dirty_ = true;
}

// ---- input ----

void Viewer::onKey(int key, int mods) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  ShownParts& shown = live_->shown();
  std::string screenshotFile =
      options_.lsystemFile.stem().string() + "-" + std::to_string(screenshots_ + 1) + ".png";
  const auto toggle = [](bool& open) { open = !open; };
  // One line a key, in the order of the key map (key_map.cpp).
  // clang-format off
  switch (key) {
    case GLFW_KEY_RIGHT: case GLFW_KEY_N: live_->stepBy(1); break;
    case GLFW_KEY_LEFT: case GLFW_KEY_P: live_->stepBy(-1); break;
    case GLFW_KEY_HOME: live_->firstFrame(); break;
    case GLFW_KEY_END: live_->lastFrame(); break;
    case GLFW_KEY_F: live_->stepAnimation(); break;
    case GLFW_KEY_SPACE: case GLFW_KEY_A:
      live_->animating() ? live_->stopAnimation() : live_->runAnimation(); break;
    case GLFW_KEY_R: live_->resetView(); break;
    case GLFW_KEY_W: shown.wireframe = !shown.wireframe; break;
    case GLFW_KEY_S: ++screenshots_; screenshotHere(screenshotFile); break;
    case GLFW_KEY_C: shown.panel = !shown.panel; break;
    case GLFW_KEY_M: shown.colors = !shown.colors; break;
    case GLFW_KEY_K: shown.controls = !shown.controls; break;
    case GLFW_KEY_F1: shown.help = !shown.help; break;
    case GLFW_KEY_F6: toggle(live_->shapes().functionView.open); break;
    case GLFW_KEY_F7: toggle(live_->shapes().contourView.open); break;
    case GLFW_KEY_F8: toggle(live_->shapes().surfaceView.open); break;
    case GLFW_KEY_SLASH: if (mods & GLFW_MOD_SHIFT) shown.help = !shown.help; break;
    case GLFW_KEY_Q: case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_, GLFW_TRUE); break;
    default: organKey(key); break;
  }
  // clang-format on
  dirty_ = true;
}

void Viewer::onButton(int button, int action, int mods) {
  dirty_ = true;
  uiFrames_ = 2;
  if (action == GLFW_PRESS) {
    if (ImGui::GetIO().WantCaptureMouse || dragButton_ >= 0) return;
    glfwGetCursorPos(window_, &cursorX_, &cursorY_);
    if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_CONTROL) != 0) {
      pointAtCursor();
      return;
    }
    dragButton_ = button;
    dragShift_ = (mods & GLFW_MOD_SHIFT) != 0;
  } else if (action == GLFW_RELEASE && button == dragButton_) {
    dragButton_ = -1;
  }
}

// The organs' keys (live_organ.h; letters, whose GLFW codes are their ASCII codes): the one that
// shows and hides each, and those of its actions.
void Viewer::organKey(int key) {
  const std::span<const LiveOrganType* const> organs = liveOrgans();
  for (std::size_t k = 0; k < organs.size(); ++k) {
    if (key == organs[k]->showKey()) {
      ShownParts& shown = live_->shown();
      shown.showOrgan(organs[k]->name(), !shown.organShown(organs[k]->name()));
      return;
    }
    const std::span<const LiveAction> actions = organs[k]->actions();
    for (std::size_t a = 0; a < actions.size(); ++a) {
      if (actions[a].key != 0 && key == actions[a].key) {
        live_->act(k, a, framebufferSize());
        return;
      }
    }
  }
}

void Viewer::pointAtCursor() {
  int w = 1, h = 1;
  glfwGetWindowSize(window_, &w, &h);
  const float x = 2.0f * static_cast<float>(cursorX_) / static_cast<float>(std::max(w, 1)) - 1;
  const float y = 1 - 2.0f * static_cast<float>(cursorY_) / static_cast<float>(std::max(h, 1));
  live_->pointAt({x, y}, framebufferSize());
}

void Viewer::onCursor(double x, double y) {
  uiFrames_ = std::max(uiFrames_, 1);
  if (dragButton_ < 0) {
    cursorX_ = x;
    cursorY_ = y;
    return;
  }
  glm::vec2 delta(static_cast<float>(x - cursorX_), static_cast<float>(y - cursorY_));
  cursorX_ = x;
  cursorY_ = y;
  int w = 1, h = 1;
  glfwGetWindowSize(window_, &w, &h);
  bool shift = dragShift_ || glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
               glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  MouseCamera& mouse = live_->mouse();
  // cpfg-manual §1.3.1: left rotates, shift+left pans, middle zooms, shift+middle rolls; the
  // right button, which opens cpfg's menu, pans here.
  switch (dragButton_) {
    case GLFW_MOUSE_BUTTON_LEFT:
      if (shift)
        mouse.dragPan(delta, h);
      else
        mouse.dragRotate(delta);
      break;
    case GLFW_MOUSE_BUTTON_MIDDLE:
      if (shift)
        mouse.dragRoll(delta);
      else
        mouse.dragZoom(delta);
      break;
    case GLFW_MOUSE_BUTTON_RIGHT:
      mouse.dragPan(delta, h);
      break;
    default:
      return;
  }
  lastMotion_ = Clock::now();
  dirty_ = true;
}

void Viewer::onScroll(double dy) {
  dirty_ = true;
  uiFrames_ = 2;
  if (ImGui::GetIO().WantCaptureMouse) return;
  live_->mouse().wheel(static_cast<float>(dy));
  lastMotion_ = Clock::now();
}

int Viewer::run() {
  if (!open()) return 1;
  live_ = std::make_unique<LiveModel>(options_, builder_, *this, [] { glfwPostEmptyEvent(); });
  live_->shown().panel = options_.showPanel;

  while (!glfwWindowShouldClose(window_)) {
    live_->update();
    if (live_->takeChanged()) {
      dirty_ = true;
      // A message that has just appeared (a broken save's error) is laid out by ImGui over its
      // first frames: draw them now, not when the next input event arrives.
      uiFrames_ = std::max(uiFrames_, 2);
    }
    if (live_->closed()) glfwSetWindowShouldClose(window_, GLFW_TRUE);
    if (glfwWindowShouldClose(window_)) break;

    bool isMoving = moving();
    if (isMoving != drawnMoving_) dirty_ = true;  // full detail once the camera stops
    bool busy = live_->worker().busy();
    // While a build runs, the progress line is redrawn a few times a second, no more: the
    // builder needs the processor more.
    bool progressDue = busy && secondsSince(lastFrameEnd_) > 0.2;
    if (dirty_ || uiFrames_ > 0 || progressDue) {
      frame();
      dirty_ = false;
      if (uiFrames_ > 0) --uiFrames_;
    }
    // Wakes for input, for a finished build (glfwPostEmptyEvent), and to poll the files.
    glfwWaitEventsTimeout(options_.script || live_->animating() || live_->organsMoving() ? 0.005
                          : isMoving                                                     ? 0.03
                          : busy                                                         ? 0.1
                                                                                         : 0.2);
  }
  int code = live_->exitCode();
  shutdown();
  return code;
}

}  // namespace

int runViewer(const ViewerOptions& options, ModelBuilder builder) {
  Viewer viewer(options, std::move(builder));
  return viewer.run();
}

}  // namespace hirsute
