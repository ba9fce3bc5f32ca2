#include "hirsute/viewer/window/viewer_window.h"

// GLFW declares no GL itself (the renderer resolves GL through GlFunctions).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/fur/fur_motion.h"
#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/hairs/fur/wetness_mask.h"
#include "hirsute/viewer/gl/camera.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/png_image.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/file_watcher.h"
#include "hirsute/viewer/interaction/mouse_camera.h"
#include "hirsute/viewer/window/define_panel.h"
#include "hirsute/viewer/window/multisample_target.h"

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

const std::vector<std::pair<std::string, std::string>>& viewerKeyMap() {
  static const std::vector<std::pair<std::string, std::string>> keys = {
      {"left drag", "rotate (horizontal: about the vertical axis; vertical: about the horizontal)"},
      {"middle drag, wheel", "zoom (drag up or wheel forward zooms in)"},
      {"right drag, shift + left drag", "pan"},
      {"shift + middle drag", "roll"},
      {"Right, N", "next derivation step"},
      {"Left, P", "previous derivation step"},
      {"Home", "first frame of the animation"},
      {"End", "last frame of the animation (the derivation length)"},
      {"F", "animation step: the next frame of the .a file"},
      {"Space, A", "run / stop the animation"},
      {"R", "reset the view (and fit the plant again)"},
      {"H", "show / hide hairs"},
      {"E", "show / hide feathers"},
      {"U", "show / hide fur"},
      {"ctrl + left click", "a droplet of water on the fur where the mouse points"},
      {"J", "spray 20 droplets at random on the fur"},
      {"Y", "let the fur dry (wetness fades over 10 s: curls return, clumps open) / stop"},
      {"G", "a gust of wind through the fur"},
      {"D", "start / pause the feathers' dynamics (wind, gravity, collisions; docs/dynamics.md)"},
      {"W", "wireframe on / off"},
      {"S", "save a PNG screenshot (MODEL-N.png in the current folder)"},
      {"C", "show / hide the constants panel"},
      {"F1, ?", "show / hide this help"},
      {"Q, Escape", "quit"},
  };
  return keys;
}

namespace {

using Clock = std::chrono::steady_clock;
using Kind = ViewCommand::Kind;

// The camera counts as moving this long after the last motion: hairs are thinned out meanwhile.
constexpr std::chrono::milliseconds kStillAfter{150};

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class Viewer {
 public:
  Viewer(const ViewerOptions& options, ModelBuilder builder) : options_(options) {
    builder_ = std::move(builder);
    hairs_ = true;
    panel_ = options.showPanel;
  }
  ~Viewer() { shutdown(); }

  int run();

 private:
  bool open();
  void shutdown();
  void installCallbacks();

  // Models
  void request();
  void applyBuild(ModelBuild build);
  void reloadFiles();
  void readAnimation();
  void readConstants();
  int currentStep() const;
  void stepBy(int steps);
  void goTo(int step);
  void setDefine(const std::string& name, const std::string& value);
  void saveDefines();

  // Animation
  void startAnimation(bool run);
  void advanceAnimation();

  // Drawing
  Camera camera() const;
  bool moving() const;
  void drawScene(bool moving);
  void drawUi();
  void frame();
  RgbaImage readPixels();
  bool screenshot(const std::filesystem::path& file, bool withUi);
  void measure(int frames);

  // Script
  void runScript();
  // A build that has finished but is not yet shown counts as under way.
  bool idle() const { return worker_->settled() && !animating_; }
  void scriptFailure(const ViewCommand& command, const std::string& message);

  // Input
  void onKey(int key, int mods);
  void onButton(int button, int action, int mods);
  void onCursor(double x, double y);
  void onScroll(double dy);

  // Fur (docs/fur.md): the shown fur, stepped and wetted here; the renderer uploads it again.
  void takeFur();
  bool stepFur();
  void dropletAtCursor();

  // Feather dynamics (docs/dynamics.md): the model's feathers simulated while shown, their roots
  // carried by the body as the animation moves it.
  void toggleDynamics();
  bool stepDynamics();
  void stopDynamics(const std::string& why);

  const ViewerOptions& options_;
  ModelBuilder builder_;
  GLFWwindow* window_ = nullptr;
  bool imgui_ = false;
  std::unique_ptr<GlFunctions> gl_;
  std::unique_ptr<GlRenderer> renderer_;
  std::unique_ptr<MultisampleTarget> multisample_;
  std::unique_ptr<ModelWorker> worker_;
  std::optional<FileWatcher> watcher_;

  // What is shown
  std::shared_ptr<const ViewerModel> model_;
  Bounds fitBounds_;
  bool fitted_ = false;
  std::string error_;
  std::string animationError_;
  ModelRequest wanted_;
  int derivationLength_ = 0;
  MouseCamera mouse_;
  bool hairs_ = true, feathers_ = true, wireframe_ = false, help_ = false, panel_ = true;

  // Fur: a copy of the model's fur surfaces that moves, dries and takes droplets.
  Scene fur_;
  fur::FurMotion furMotion_;
  bool furVisible_ = true, drying_ = false, furMoving_ = false;
  glm::vec3 gust_{0.0f};
  float gustLeft_ = 0;  // seconds
  std::uint32_t spraySeed_ = 1;
  Clock::time_point lastFurStep_ = Clock::now();

  // Feather dynamics: the simulation, the feathers it bends (drawn over the model's), whether it
  // runs, whether a new build moved the body, and the rate it keeps.
  std::optional<dynamics::CoatMotion> coat_;
  Scene coatScene_;
  bool simulating_ = false, bodyMoved_ = false;
  Clock::time_point lastCoatStep_ = Clock::now();
  double simulatedFps_ = 0;

  // Animation (cpfg-manual §1.3.3, §8.2)
  AnimationSettings animation_;
  std::vector<AnimationFrame> frames_;
  std::size_t frameIndex_ = 0;
  bool animating_ = false;
  Clock::time_point lastFrameStart_;

  // Constants of the .l (the panel)
  std::vector<DefineConstant> constants_;
  std::map<std::string, std::string> changedDefines_;

  // Input state
  int dragButton_ = -1;
  bool dragShift_ = false;
  double cursorX_ = 0, cursorY_ = 0;
  Clock::time_point lastMotion_ = Clock::now() - std::chrono::seconds(10);
  bool drawnMoving_ = false;
  bool dirty_ = true;
  int uiFrames_ = 2;  // ImGui needs a frame or two after input to settle
  double frameMs_ = 0;
  Clock::time_point lastFrameEnd_;
  int screenshots_ = 0;

  // Script state
  std::size_t scriptIndex_ = 0;
  std::optional<Clock::time_point> waitUntil_;
  std::uint64_t reloadSerial_ = 0;    // the request made for the last file change
  std::uint64_t reloadsApplied_ = 0;  // builds of such requests shown
  std::optional<std::uint64_t> waitingForReloadsAbove_;
  int exitCode_ = 0;
};

bool Viewer::open() {
  glfwSetErrorCallback(
      [](int, const char* description) { std::cerr << "hirsute: glfw: " << description << '\n'; });
  if (!glfwInit()) {
    std::cerr << "hirsute: error: cannot open a window (is there a display? without one, run "
                 "under xvfb-run)\n";
    return false;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);  // multisampling is MultisampleTarget's
  std::string title = "hirsute view: " + options_.lsystemFile.filename().string();
  window_ = glfwCreateWindow(options_.width, options_.height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    std::cerr << "hirsute: error: cannot open a window with a GL 3.3 core-profile context\n";
    return false;
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options_.script ? 0 : 1);
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

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
  ImGui::StyleColorsDark();
  // Installs its callbacks over ours; it calls ours first.
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ = true;
  return true;
}

void Viewer::shutdown() {
  worker_.reset();  // joins the builder's thread before the window goes
  if (imgui_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    imgui_ = false;
  }
  renderer_.reset();
  multisample_.reset();
  gl_.reset();
  if (window_) glfwDestroyWindow(window_);
  window_ = nullptr;
  keepLibrariesLoaded();
  glfwTerminate();
}

void Viewer::installCallbacks() {
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    Viewer* v = static_cast<Viewer*>(glfwGetWindowUserPointer(w));
    v->dirty_ = true;
    v->uiFrames_ = 2;
    if (action == GLFW_PRESS || action == GLFW_REPEAT) v->onKey(key, mods);
  });
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned) {
    Viewer* v = static_cast<Viewer*>(glfwGetWindowUserPointer(w));
    v->dirty_ = true;
    v->uiFrames_ = 2;
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int mods) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->onButton(button, action, mods);
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->onCursor(x, y);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->onScroll(dy);
  });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->dirty_ = true;
  });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) {
    static_cast<Viewer*>(glfwGetWindowUserPointer(w))->dirty_ = true;
  });
}

// ---- models ----

void Viewer::request() {
  worker_->request(wanted_);
  dirty_ = true;
}

void Viewer::applyBuild(ModelBuild build) {
  dirty_ = true;
  if (reloadSerial_ != 0 && build.serial >= reloadSerial_) {
    reloadsApplied_ = build.serial;
    reloadSerial_ = 0;
  }
  if (!build.model) {
    // The last good plant stays on screen.
    error_ = build.error;
    std::cerr << error_ << '\n';
    if (animating_) animating_ = false;
    return;
  }
  error_ = animationError_;  // a broken .a stays reported until it is fixed
  model_ = build.model;
  // Texture images are read by the model without a model file's extension: watched by name.
  if (watcher_) {
    for (const TextureDeclaration& texture : model_->view.textures) watcher_->watch(texture.file);
  }
  renderer_->upload(model_->scene, model_->view, model_->materialMode);
  takeFur();
  if (coat_) {
    bodyMoved_ = true;
    coatScene_.featherTypes = model_->scene.featherTypes;
    coatScene_.materials = model_->scene.materials;
    renderer_->updateFeathers(coatScene_);
  }
  bool newLength = derivationLength_ != model_->derivationLength;
  derivationLength_ = model_->derivationLength;
  if (newLength || frames_.empty()) frames_ = animationFrames(animation_, derivationLength_);
  bool refit = !fitted_ || (animating_ && animation_.scaleBetweenFrames);
  if (refit) {
    fitBounds_ = model_->bounds;
    fitted_ = true;
  }
  if (animating_ && animation_.newViewBetweenFrames) mouse_.reset();
}

void Viewer::readAnimation() {
  animation_ = AnimationSettings();
  animationError_.clear();
  if (options_.animationFile.empty()) return;
  Diagnostics diagnostics(&std::cerr);
  try {
    animation_ = readAnimationFile(options_.animationFile, diagnostics);
  } catch (const DiagnosticError& e) {
    error_ = animationError_ = e.diagnostic().text();
    std::cerr << error_ << '\n';
  }
  frames_ = animationFrames(animation_, derivationLength_);
}

void Viewer::readConstants() {
  constants_ = findDefineConstants(readText(options_.lsystemFile));
}

void Viewer::reloadFiles() {
  // Edited files may bring other feathers: the dynamics starts again from the new model.
  coat_.reset();
  simulating_ = false;
  readAnimation();
  readConstants();
  reloadSerial_ = worker_->request(wanted_);
  dirty_ = true;
}

int Viewer::currentStep() const {
  if (wanted_.steps) return *wanted_.steps;
  if (model_) return model_->steps;
  return derivationLength_;
}

void Viewer::stepBy(int steps) {
  int target = std::clamp(currentStep() + steps, 0, std::max(derivationLength_, 0));
  goTo(target);
}

void Viewer::goTo(int step) {
  wanted_.steps = std::max(step, 0);
  request();
}

void Viewer::setDefine(const std::string& name, const std::string& value) {
  // Applied to a hidden copy of the .l first; with --save the file itself follows once the
  // change is complete (a slider let go, a scripted define), not at every step of a drag.
  auto found = changedDefines_.find(name);
  if (found != changedDefines_.end() && found->second == value) return;  // a slider let go
  changedDefines_[name] = value;
  wanted_.defines = changedDefines_;
  request();
}

void Viewer::saveDefines() {
  if (changedDefines_.empty()) return;
  try {
    saveDefineValues(options_.lsystemFile, changedDefines_);
  } catch (const std::exception& e) {
    error_ = std::string("hirsute: error: ") + e.what();
    std::cerr << error_ << '\n';
    return;
  }
  std::cout << "wrote " << changedDefines_.size() << " constant"
            << (changedDefines_.size() == 1 ? "" : "s") << " into " << options_.lsystemFile.string()
            << '\n';
  changedDefines_.clear();
  wanted_.defines.clear();
  readConstants();
  reloadSerial_ = worker_->request(wanted_);
}

// ---- animation ----

void Viewer::startAnimation(bool run) {
  if (frames_.empty()) frames_ = animationFrames(animation_, derivationLength_);
  if (frames_.empty()) return;
  if (!run) {
    // One frame on (cpfg's Step): after the last comes the first.
    int step = currentStep();
    auto next = std::find_if(frames_.begin(), frames_.end(),
                             [&](const AnimationFrame& f) { return f.step > step; });
    goTo(next == frames_.end() ? frames_.front().step : next->step);
    return;
  }
  animating_ = true;
  frameIndex_ = 0;
  lastFrameStart_ = Clock::now() - std::chrono::hours(1);
}

void Viewer::advanceAnimation() {
  // The frame asked for is built and shown before the next is asked for.
  if (!animating_ || !worker_->settled()) return;
  if (secondsSince(lastFrameStart_) < animation_.swapIntervalSeconds) return;
  if (frameIndex_ >= frames_.size()) {
    animating_ = false;  // cpfg's Run stops at the last frame
    dirty_ = true;
    return;
  }
  if (frameIndex_ > 0) {
    // frame intervals: turn or scale after each frame of the range.
    const AnimationFrame& previous = frames_[frameIndex_ - 1];
    if (previous.rotateAfter) {
      mouse_.rotate(previous.rotateAfter->y, previous.rotateAfter->x);
      mouse_.roll(-previous.rotateAfter->z);
    }
    if (previous.scaleAfter) mouse_.zoom(previous.scaleAfter->x);
  }
  lastFrameStart_ = Clock::now();
  goTo(frames_[frameIndex_++].step);
}

// ---- feather dynamics ----

void Viewer::toggleDynamics() {
  if (simulating_) {
    simulating_ = false;
    return;
  }
  if (!model_ || model_->scene.feathers.empty()) return;
  if (!coat_) {
    try {
      coat_.emplace(model_->scene, dynamics::simulationParametersOf(model_->view.dynamics));
    } catch (const std::exception& e) {
      stopDynamics(std::string("cannot simulate the feathers: ") + e.what());
      return;
    }
    if (coat_->penetrations() > 0) {
      stopDynamics("the feathers' stems already meet before the first step (docs/dynamics.md)");
      return;
    }
    coatScene_ = Scene{};
    coatScene_.featherTypes = model_->scene.featherTypes;
    coatScene_.materials = model_->scene.materials;
    bodyMoved_ = false;
  }
  simulating_ = true;
  lastCoatStep_ = Clock::now();
}

void Viewer::stopDynamics(const std::string& why) {
  simulating_ = false;
  coat_.reset();
  error_ = "hirsute: " + why;
  std::cerr << error_ << '\n';
  if (model_) renderer_->updateFeathers(model_->scene);
}

bool Viewer::stepDynamics() {
  if (!simulating_ || !coat_ || !model_) return false;
  const auto now = Clock::now();
  // Real time, but no more than a 30th of a second a frame: a slow frame slows the motion down
  // rather than taking a step the collisions would have to halve.
  const double seconds =
      std::min(std::chrono::duration<double>(now - lastCoatStep_).count(), 1.0 / 30);
  lastCoatStep_ = now;
  if (!(seconds > 0)) return false;
  try {
    coat_->advance(seconds, model_->view.dynamics.substeps,
                   bodyMoved_ ? &model_->scene : nullptr);
  } catch (const std::exception& e) {
    stopDynamics(std::string("the feathers' dynamics stopped: ") + e.what());
    return true;
  }
  bodyMoved_ = false;
  coat_->pose(coatScene_);
  renderer_->updateFeathers(coatScene_);
  const double took = secondsSince(now);
  simulatedFps_ = took > 0 ? 1 / took : 0;
  return true;
}

// ---- fur ----

void Viewer::takeFur() {
  Scene previous = std::move(fur_);
  fur_ = Scene{};
  fur_.furAttributes = model_->scene.furAttributes;
  fur_.furSurfaces = model_->scene.furSurfaces;
  fur_.furTextures = model_->scene.furTextures;
  // The frame before's particles and wetness carry over (an animation keeps its wet patches
  // and drags its fur); the renderer gets them at once.
  furMotion_.reset(fur_, previous.furSurfaces.empty() ? nullptr : &previous);
  if (!previous.furSurfaces.empty()) renderer_->updateFur(fur_);
  lastFurStep_ = Clock::now();
}

bool Viewer::stepFur() {
  if (fur_.furSurfaces.empty()) return false;
  const auto now = Clock::now();
  const float seconds = static_cast<float>(std::chrono::duration<double>(now - lastFurStep_).count());
  lastFurStep_ = now;
  const glm::vec3 force = model_->view.furForce + (gustLeft_ > 0 ? gust_ : glm::vec3(0.0f));
  const bool wasMoving = furMoving_;
  bool changed = false;
  if (furMoving_ || gustLeft_ > 0) {
    furMoving_ = furMotion_.step(fur_, seconds, force) || gustLeft_ > 0;
    gustLeft_ = std::max(0.0f, gustLeft_ - seconds);
    changed = true;
  }
  if (drying_) {
    drying_ = fur::dryFur(fur_, 0.1f, seconds);
    changed = true;
  }
  if (changed || wasMoving != furMoving_) renderer_->updateFur(fur_);
  return changed;
}

void Viewer::dropletAtCursor() {
  if (!model_ || fur_.furSurfaces.empty()) return;
  int w = 1, h = 1;
  glfwGetWindowSize(window_, &w, &h);
  const Camera c = camera();
  const float x = 2.0f * static_cast<float>(cursorX_) / static_cast<float>(std::max(w, 1)) - 1;
  const float y = 1 - 2.0f * static_cast<float>(cursorY_) / static_cast<float>(std::max(h, 1));
  glm::vec3 origin, direction;
  if (c.projection == Projection::Perspective) {
    const float t = std::tan(glm::radians(c.fieldOfViewY) * 0.5f);
    const float aspect = static_cast<float>(c.viewport.x) / static_cast<float>(std::max(c.viewport.y, 1));
    origin = c.eye;
    direction = glm::normalize(c.forward + x * t * aspect * c.right + y * t * c.up);
  } else {
    direction = c.forward;
    origin = c.eye + x * c.halfWidth * c.right + y * c.halfHeight * c.up;
  }
  if (const auto hit = fur::pickFur(fur_, origin, direction)) {
    fur::blendDroplet(fur_.furSurfaces[hit->surface], hit->uv, 0.05f, 1.0f);
    renderer_->updateFur(fur_);
    dirty_ = true;
  }
}

// ---- drawing ----

Camera Viewer::camera() const {
  int w = 1, h = 1;
  glfwGetFramebufferSize(window_, &w, &h);
  glm::ivec2 size{std::max(w, 1), std::max(h, 1)};
  Camera fitted = fitCamera(model_->view, fitBounds_, size);
  return mouse_.apply(fitted, model_->bounds);
}

bool Viewer::moving() const {
  return Clock::now() - lastMotion_ < kStillAfter;
}

void Viewer::drawScene(bool moving) {
  int w = 1, h = 1;
  glfwGetFramebufferSize(window_, &w, &h);
  // While the camera moves, the frame is drawn without multisampling too (with llvmpipe that
  // halves its time); the still frame that follows has both back.
  bool multisampled = !moving && options_.samples > 1 && multisample_->bind(w, h, options_.samples);
  if (!multisampled) gl_->BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!model_) {
    gl_->Viewport(0, 0, w, h);
    gl_->ClearColor(0.1f, 0.1f, 0.1f, 1);
    gl_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (multisampled) multisample_->resolve();
    return;
  }
  renderer_->setHairsVisible(hairs_);
  renderer_->setFeathersVisible(feathers_);
  renderer_->setFurVisible(furVisible_);
  renderer_->setWireframe(wireframe_);
  float fraction = 1;
  std::size_t hairCount = renderer_->hairCount();
  if (moving && hairCount > options_.movingHairBudget) {
    fraction = static_cast<float>(options_.movingHairBudget) / static_cast<float>(hairCount);
  }
  renderer_->setHairFraction(fraction);
  renderer_->draw(camera());
  drawnMoving_ = moving;
  if (multisampled) multisample_->resolve();
}

void Viewer::drawUi() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImVec2 size = viewport->WorkSize;
  ImGuiWindowFlags overlay = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                             ImGuiWindowFlags_NoSavedSettings |
                             ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                             ImGuiWindowFlags_NoMove;

  // Status line, bottom left.
  ImGui::SetNextWindowPos(ImVec2(8, size.y - 8), ImGuiCond_Always, ImVec2(0, 1));
  ImGui::SetNextWindowBgAlpha(0.55f);
  if (ImGui::Begin("##status", nullptr, overlay)) {
    std::string name = options_.lsystemFile.filename().string();
    ImGui::Text("%s  step %d / %d%s   %.1f ms   F1: help", name.c_str(), model_ ? model_->steps : 0,
                derivationLength_, animating_ ? "  (animating)" : "", frameMs_);
    if (model_ && renderer_->hairCount() > 0) {
      ImGui::Text("hairs %zu%s%s", renderer_->hairCount(), hairs_ ? "" : " (hidden)",
                  drawnMoving_ && renderer_->hairFraction() < 1 ? "  (fewer while moving)" : "");
    }
    if (model_ && renderer_->featherCount() > 0) {
      ImGui::Text("feathers %zu%s", renderer_->featherCount(), feathers_ ? "" : " (hidden)");
      if (coat_) {
        ImGui::Text("dynamics %s: %.1f s simulated, %.0f frames/s, %llu steps retried",
                    simulating_ ? "running" : "paused (D)", coat_->simulation().time(),
                    simulatedFps_,
                    static_cast<unsigned long long>(coat_->simulation().counters().retries));
      }
    }
    if (model_ && !fur_.furSurfaces.empty()) {
      ImGui::Text("fur: %zu surfaces, %d layers%s%s%s", fur_.furSurfaces.size(),
                  fur_.furSurfaces.front().layers, furVisible_ ? "" : " (hidden)",
                  drying_ ? "  drying" : "", furMoving_ ? "  moving" : "");
    }
    // Builds that end within a quarter of a second show no progress (no flicker).
    if (worker_->busy() && worker_->runningSeconds() > 0.25) {
      const BuildProgress& p = worker_->progress();
      static const char* kPhases[] = {"reading", "deriving", "interpreting", "placing hairs",
                                      "growing feathers"};
      int phase = std::clamp(p.phase.load(), 0, 4);
      if (p.totalSteps > 0 && phase == 1) {
        ImGui::Text("%s: step %d of %d  %.1f s", kPhases[phase], p.stepsDone.load(),
                    p.totalSteps.load(), worker_->runningSeconds());
        ImGui::ProgressBar(static_cast<float>(p.stepsDone) / static_cast<float>(p.totalSteps),
                           ImVec2(240, 0));
      } else {
        ImGui::Text("%s...  %.1f s", kPhases[phase], worker_->runningSeconds());
      }
    }
  }
  ImGui::End();

  // The error of the last build, top right, over the last good plant.
  if (!error_.empty()) {
    ImGui::SetNextWindowPos(ImVec2(size.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
    ImGui::SetNextWindowBgAlpha(0.8f);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(size.x * 0.7f, size.y * 0.5f));
    if (ImGui::Begin("##error", nullptr, overlay)) {
      ImGui::PushTextWrapPos(size.x * 0.65f);
      ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error_.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::End();
  }

  if (help_) {
    ImGui::SetNextWindowPos(ImVec2(size.x / 2, size.y / 2), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("Keys and mouse", &help_,
                     ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                         ImGuiWindowFlags_NoCollapse)) {
      if (ImGui::BeginTable("keys", 2)) {
        for (const auto& [key, action] : viewerKeyMap()) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(key.c_str());
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(action.c_str());
        }
        ImGui::EndTable();
      }
    }
    ImGui::End();
  }

  if (panel_ && !constants_.empty()) {
    DefinePanel panel = drawDefinePanel(constants_, changedDefines_, options_.saveDefines, &panel_);
    for (const DefinePanel::Edit& edit : panel.edits) {
      setDefine(edit.name, edit.value);
      if (options_.saveDefines && edit.finished) saveDefines();
    }
    if (panel.save) saveDefines();
    if (panel.revert) {
      changedDefines_.clear();
      wanted_.defines.clear();
      request();
    }
  }

  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Viewer::frame() {
  auto start = Clock::now();
  drawScene(moving());
  drawUi();
  glfwSwapBuffers(window_);
  lastFrameEnd_ = Clock::now();
  frameMs_ = secondsSince(start) * 1000.0;
}

RgbaImage Viewer::readPixels() {
  int w = 1, h = 1;
  glfwGetFramebufferSize(window_, &w, &h);
  RgbaImage upsideDown(w, h);
  gl_->BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl_->ReadBuffer(GL_BACK);
  gl_->PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, upsideDown.rgba.data());
  RgbaImage image(w, h);
  std::size_t row = static_cast<std::size_t>(w) * 4;
  for (int y = 0; y < h; ++y) {
    std::copy_n(&upsideDown.rgba[static_cast<std::size_t>(h - 1 - y) * row], row,
                &image.rgba[static_cast<std::size_t>(y) * row]);
  }
  return image;
}

bool Viewer::screenshot(const std::filesystem::path& file, bool withUi) {
  // ImGui sizes a window that has just appeared over its first frames.
  for (int i = 0; withUi && i < 2; ++i) frame();
  drawScene(false);
  if (withUi) drawUi();
  RgbaImage image = readPixels();
  if (!withUi) drawUi();
  glfwSwapBuffers(window_);
  if (watcher_) watcher_->ignore(file);
  try {
    writePng(file, image);
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return false;
  }
  if (watcher_) watcher_->ignore(file);
  std::cout << "wrote " << file.string() << '\n';
  return true;
}

void Viewer::measure(int frames) {
  if (!model_ || frames < 1) return;
  auto timeFrames = [&](bool move) {
    MouseCamera saved = mouse_;
    gl_->Finish();
    auto start = Clock::now();
    for (int i = 0; i < frames; ++i) {
      if (move) mouse_.rotate(2.0f, 0.0f);
      drawScene(move);
      glfwSwapBuffers(window_);
    }
    gl_->Finish();
    double ms = secondsSince(start) * 1000.0 / frames;
    mouse_ = saved;
    return ms;
  };
  double still = timeFrames(false);
  std::size_t hairs = renderer_->hairCount();
  double movingMs = timeFrames(true);
  float fraction = renderer_->hairFraction();
  std::cout << "frame time: still " << still << " ms, moving " << movingMs << " ms (" << frames
            << " frames each, " << renderer_->triangleCount() << " triangles, "
            << renderer_->lineCount() << " lines, " << hairs << " hairs, "
            << static_cast<std::size_t>(std::lround(fraction * static_cast<double>(hairs)))
            << " drawn while moving)\n";
  dirty_ = true;
}

// ---- script ----

void Viewer::scriptFailure(const ViewCommand& command, const std::string& message) {
  std::cerr << Diagnostic{Severity::Error, command.where, message}.text() << '\n';
  exitCode_ = 1;
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

void Viewer::runScript() {
  const std::vector<ViewCommand>& script = *options_.script;
  for (;;) {
    if (glfwWindowShouldClose(window_)) return;
    // The command in progress, if it waits.
    if (waitUntil_) {
      if (Clock::now() < *waitUntil_) {
        if (waitingForReloadsAbove_ && reloadsApplied_ > *waitingForReloadsAbove_ && idle()) {
          waitingForReloadsAbove_.reset();
          waitUntil_.reset();
        } else {
          return;
        }
      } else if (waitingForReloadsAbove_) {
        scriptFailure(script[scriptIndex_ - 1], "no model file changed within the time given");
        return;
      } else {
        waitUntil_.reset();
      }
    }
    if (!idle()) return;
    if (scriptIndex_ >= script.size()) {
      glfwSetWindowShouldClose(window_, GLFW_TRUE);
      return;
    }
    const ViewCommand& c = script[scriptIndex_++];
    auto number = [&](std::size_t i, double otherwise) {
      return i < c.numbers.size() ? c.numbers[i] : otherwise;
    };
    dirty_ = true;
    switch (c.kind) {
      case Kind::Rotate:
        mouse_.rotate(static_cast<float>(c.numbers[0]), static_cast<float>(number(1, 0)));
        break;
      case Kind::Roll:
        mouse_.roll(static_cast<float>(c.numbers[0]));
        break;
      case Kind::Zoom:
        mouse_.zoom(static_cast<float>(c.numbers[0]));
        break;
      case Kind::Pan:
        mouse_.pan(static_cast<float>(c.numbers[0]), static_cast<float>(c.numbers[1]));
        break;
      case Kind::Reset:
        mouse_.reset();
        if (model_) fitBounds_ = model_->bounds;
        break;
      case Kind::Step:
        stepBy(static_cast<int>(number(0, 1)));
        break;
      case Kind::Back:
        stepBy(-static_cast<int>(number(0, 1)));
        break;
      case Kind::Goto:
        goTo(static_cast<int>(c.numbers[0]));
        break;
      case Kind::Animate:
        startAnimation(true);
        break;
      case Kind::Hairs:
        hairs_ = c.words[0] == "on";
        break;
      case Kind::Feathers:
        feathers_ = c.words[0] == "on";
        break;
      case Kind::Fur:
        furVisible_ = c.words[0] == "on";
        break;
      case Kind::Droplets:
        if (sprayDroplets(fur_, static_cast<std::size_t>(std::max(0.0, c.numbers[0])), 0.05f, 1.0f,
                          spraySeed_++) > 0)
          renderer_->updateFur(fur_);
        break;
      case Kind::Dynamics:
        if ((c.words[0] == "on") != simulating_) toggleDynamics();
        break;
      case Kind::Wireframe:
        wireframe_ = c.words[0] == "on";
        break;
      case Kind::Help:
        help_ = c.words[0] == "on";
        break;
      case Kind::Panel:
        panel_ = c.words[0] == "on";
        break;
      case Kind::Define:
        setDefine(c.words[0], c.words[1]);
        if (options_.saveDefines) saveDefines();
        break;
      case Kind::Save:
        saveDefines();
        break;
      case Kind::WaitReload:
        waitingForReloadsAbove_ = reloadsApplied_;
        waitUntil_ = Clock::now() +
                     std::chrono::milliseconds(static_cast<long long>(number(0, 10) * 1000.0));
        return;
      case Kind::Sleep:
        waitUntil_ =
            Clock::now() + std::chrono::milliseconds(static_cast<long long>(c.numbers[0] * 1000.0));
        return;
      case Kind::Measure:
        measure(static_cast<int>(number(0, 30)));
        break;
      case Kind::Screenshot:
        if (!screenshot(c.words[0], c.words.size() > 1)) {
          scriptFailure(c, "cannot write the screenshot " + c.words[0]);
          return;
        }
        break;
      case Kind::Quit:
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
        return;
    }
  }
}

// ---- input ----

void Viewer::onKey(int key, int mods) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  switch (key) {
    case GLFW_KEY_RIGHT:
    case GLFW_KEY_N:
      stepBy(1);
      break;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_P:
      stepBy(-1);
      break;
    case GLFW_KEY_HOME:
      animating_ = false;
      goTo(frames_.empty() ? 0 : frames_.front().step);
      break;
    case GLFW_KEY_END:
      animating_ = false;
      goTo(frames_.empty() ? derivationLength_ : frames_.back().step);
      break;
    case GLFW_KEY_F:
      startAnimation(false);
      break;
    case GLFW_KEY_SPACE:
    case GLFW_KEY_A:
      if (animating_) {
        animating_ = false;
      } else {
        startAnimation(true);
      }
      break;
    case GLFW_KEY_R:
      mouse_.reset();
      if (model_) fitBounds_ = model_->bounds;
      break;
    case GLFW_KEY_H:
      hairs_ = !hairs_;
      break;
    case GLFW_KEY_E:
      feathers_ = !feathers_;
      break;
    case GLFW_KEY_U:
      furVisible_ = !furVisible_;
      break;
    case GLFW_KEY_J:
      if (sprayDroplets(fur_, 20, 0.05f, 1.0f, spraySeed_++) > 0) renderer_->updateFur(fur_);
      break;
    case GLFW_KEY_Y:
      drying_ = !drying_;
      lastFurStep_ = Clock::now();
      break;
    case GLFW_KEY_G: {
      // A gust across the line of sight, from alternating sides, as strong as a strand's spring.
      const Camera c = camera();
      gust_ = (spraySeed_++ % 2 == 0 ? 1.0f : -1.0f) * 60.0f * c.right;
      gustLeft_ = 0.6f;
      lastFurStep_ = Clock::now();
      break;
    }
    case GLFW_KEY_D:
      toggleDynamics();
      break;
    case GLFW_KEY_W:
      wireframe_ = !wireframe_;
      break;
    case GLFW_KEY_S: {
      std::filesystem::path file =
          options_.lsystemFile.stem().string() + "-" + std::to_string(++screenshots_) + ".png";
      screenshot(file, false);
      break;
    }
    case GLFW_KEY_C:
      panel_ = !panel_;
      break;
    case GLFW_KEY_F1:
      help_ = !help_;
      break;
    case GLFW_KEY_SLASH:
      if (mods & GLFW_MOD_SHIFT) help_ = !help_;
      break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      glfwSetWindowShouldClose(window_, GLFW_TRUE);
      break;
    default:
      break;
  }
  dirty_ = true;
}

void Viewer::onButton(int button, int action, int mods) {
  dirty_ = true;
  uiFrames_ = 2;
  if (action == GLFW_PRESS) {
    if (ImGui::GetIO().WantCaptureMouse || dragButton_ >= 0) return;
    if (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_CONTROL) != 0) {
      glfwGetCursorPos(window_, &cursorX_, &cursorY_);
      dropletAtCursor();
      return;
    }
    dragButton_ = button;
    dragShift_ = (mods & GLFW_MOD_SHIFT) != 0;
    glfwGetCursorPos(window_, &cursorX_, &cursorY_);
  } else if (action == GLFW_RELEASE && button == dragButton_) {
    dragButton_ = -1;
  }
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
  // cpfg-manual §1.3.1: left rotates, shift+left pans, middle zooms, shift+middle rolls; the
  // right button, which opens cpfg's menu, pans here.
  switch (dragButton_) {
    case GLFW_MOUSE_BUTTON_LEFT:
      if (shift)
        mouse_.dragPan(delta, h);
      else
        mouse_.dragRotate(delta);
      break;
    case GLFW_MOUSE_BUTTON_MIDDLE:
      if (shift)
        mouse_.dragRoll(delta);
      else
        mouse_.dragZoom(delta);
      break;
    case GLFW_MOUSE_BUTTON_RIGHT:
      mouse_.dragPan(delta, h);
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
  mouse_.wheel(static_cast<float>(dy));
  lastMotion_ = Clock::now();
}

int Viewer::run() {
  if (!open()) return 1;
  worker_ = std::make_unique<ModelWorker>(builder_, [] { glfwPostEmptyEvent(); });
  readAnimation();
  readConstants();
  if (options_.watch) {
    std::vector<std::filesystem::path> files = {options_.lsystemFile}, folders;
    if (!options_.viewFile.empty()) files.push_back(options_.viewFile);
    if (!options_.animationFile.empty()) files.push_back(options_.animationFile);
    for (const auto& f : options_.extraFiles) files.push_back(f);
    for (const auto& f : files) folders.push_back(f.parent_path());
    watcher_.emplace(files, folders);
  }
  wanted_.steps = options_.steps;
  request();

  while (!glfwWindowShouldClose(window_)) {
    if (auto build = worker_->take()) applyBuild(std::move(*build));
    if (watcher_ && watcher_->poll()) reloadFiles();
    advanceAnimation();
    if (stepFur()) dirty_ = true;
    if (stepDynamics()) dirty_ = true;
    if (options_.script) runScript();
    if (glfwWindowShouldClose(window_)) break;

    bool isMoving = moving();
    if (isMoving != drawnMoving_) dirty_ = true;  // full detail once the camera stops
    bool busy = worker_->busy();
    // While a build runs, the progress line is redrawn a few times a second, no more: the
    // builder needs the processor more.
    bool progressDue = busy && secondsSince(lastFrameEnd_) > 0.2;
    if (dirty_ || uiFrames_ > 0 || progressDue) {
      frame();
      dirty_ = false;
      if (uiFrames_ > 0) --uiFrames_;
    }
    // Wakes for input, for a finished build (glfwPostEmptyEvent), and to poll the files.
    glfwWaitEventsTimeout(options_.script || animating_ || furMoving_ ? 0.005
                          : isMoving                    ? 0.03
                          : busy                        ? 0.1
                                                        : 0.2);
  }
  int code = exitCode_;
  if (code == 0 && !error_.empty()) code = 2;
  shutdown();
  return code;
}

}  // namespace

int runViewer(const ViewerOptions& options, ModelBuilder builder) {
  Viewer viewer(options, std::move(builder));
  return viewer.run();
}

}  // namespace hirsute
