#include "hirsute/viewer/interaction/live_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <utility>

#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/hairs/fur/wetness_mask.h"
#include "hirsute/interpreter/feather_part.h"
#include "hirsute/interpreter/fur_part.h"
#include "hirsute/interpreter/fur_settings.h"

namespace hirsute {
namespace {

// The animation's frames, at most kMaxAnimationFrames of them: the viewer plays the first million.
std::vector<AnimationFrame> playedFrames(const AnimationSettings& settings, int derivationLength) {
  std::vector<AnimationFrame> frames = animationFrames(settings, derivationLength);
  if (frames.size() > kMaxAnimationFrames) frames.resize(kMaxAnimationFrames);
  return frames;
}

using Kind = ViewCommand::Kind;

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

LiveModel::LiveModel(const LiveModelOptions& options, ModelBuilder builder, LiveModelView& view,
                     std::function<void()> wake, Now now)
    : options_(options), view_(view), now_(std::move(now)) {
  lastFurStep_ = lastCoatStep_ = now_();
  worker_ = std::make_unique<ModelWorker>(std::move(builder), std::move(wake));
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
}

double LiveModel::secondsSince(Clock::time_point t) const {
  return std::chrono::duration<double>(now_() - t).count();
}

void LiveModel::update() {
  if (auto build = worker_->take()) applyBuild(std::move(*build));
  if (watcher_ && watcher_->poll()) reloadFiles();
  advanceAnimation();
  if (stepFur()) changed_ = true;
  if (stepDynamics()) changed_ = true;
  if (options_.script) runScript();
}

bool LiveModel::takeChanged() {
  return std::exchange(changed_, false);
}

int LiveModel::exitCode() const {
  if (scriptFailed_) return 1;
  return error_.empty() ? 0 : 2;
}

void LiveModel::ignoreWrite(const std::filesystem::path& file) {
  if (watcher_) watcher_->ignore(file);
}

// ---- models ----

void LiveModel::request() {
  worker_->request(wanted_);
  changed_ = true;
}

void LiveModel::applyBuild(ModelBuild build) {
  changed_ = true;
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
  view_.upload(*model_);
  takeFur();
  if (coat_) {
    bodyMoved_ = true;
    coatScene_.organ<FeatherPart>().types = model_->scene.organ<FeatherPart>().types;
    coatScene_.materials = model_->scene.materials;
    view_.updateFeathers(coatScene_);
  }
  bool newLength = derivationLength_ != model_->derivationLength;
  derivationLength_ = model_->derivationLength;
  if (newLength || frames_.empty()) frames_ = playedFrames(animation_, derivationLength_);
  bool refit = !fitted_ || (animating_ && animation_.scaleBetweenFrames);
  if (refit) {
    fitBounds_ = model_->bounds;
    fitted_ = true;
  }
  if (animating_ && animation_.newViewBetweenFrames) mouse_.reset();
}

void LiveModel::readAnimation() {
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
  frames_ = playedFrames(animation_, derivationLength_);
}

void LiveModel::readConstants() {
  constants_ = findDefineConstants(readText(options_.lsystemFile));
}

void LiveModel::reloadFiles() {
  // Edited files may bring other feathers: the dynamics starts again from the new model.
  coat_.reset();
  simulating_ = false;
  readAnimation();
  readConstants();
  reloadSerial_ = worker_->request(wanted_);
  changed_ = true;
}

int LiveModel::currentStep() const {
  if (wanted_.steps) return *wanted_.steps;
  if (model_) return model_->steps;
  return derivationLength_;
}

void LiveModel::stepBy(int steps) {
  int target = std::clamp(currentStep() + steps, 0, std::max(derivationLength_, 0));
  goTo(target);
}

void LiveModel::goTo(int step) {
  wanted_.steps = std::max(step, 0);
  request();
}

void LiveModel::setDefine(const std::string& name, const std::string& value) {
  // Applied to the .l's text in memory first; with --save the file itself follows once the
  // change is complete (a slider let go, a scripted define), not at every step of a drag.
  auto found = changedDefines_.find(name);
  if (found != changedDefines_.end() && found->second == value) return;  // a slider let go
  changedDefines_[name] = value;
  wanted_.defines = changedDefines_;
  request();
}

void LiveModel::saveDefines() {
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

void LiveModel::revertDefines() {
  changedDefines_.clear();
  wanted_.defines.clear();
  request();
}

// ---- animation ----

void LiveModel::runAnimation() {
  if (frames_.empty()) frames_ = playedFrames(animation_, derivationLength_);
  if (frames_.empty()) return;
  animating_ = true;
  frameIndex_ = 0;
  lastFrameStart_ = now_() - std::chrono::hours(1);
}

void LiveModel::stepAnimation() {
  if (frames_.empty()) frames_ = playedFrames(animation_, derivationLength_);
  if (frames_.empty()) return;
  // One frame on (cpfg's Step): after the last comes the first.
  int step = currentStep();
  auto next = std::find_if(frames_.begin(), frames_.end(),
                           [&](const AnimationFrame& f) { return f.step > step; });
  goTo(next == frames_.end() ? frames_.front().step : next->step);
}

void LiveModel::firstFrame() {
  animating_ = false;
  goTo(frames_.empty() ? 0 : frames_.front().step);
}

void LiveModel::lastFrame() {
  animating_ = false;
  goTo(frames_.empty() ? derivationLength_ : frames_.back().step);
}

void LiveModel::advanceAnimation() {
  // The frame asked for is built and shown before the next is asked for.
  if (!animating_ || !worker_->settled()) return;
  if (secondsSince(lastFrameStart_) < animation_.swapIntervalSeconds) return;
  if (frameIndex_ >= frames_.size()) {
    animating_ = false;  // cpfg's Run stops at the last frame
    changed_ = true;
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
  lastFrameStart_ = now_();
  goTo(frames_[frameIndex_++].step);
}

// ---- camera ----

Camera LiveModel::camera(glm::ivec2 viewport) const {
  glm::ivec2 size{std::max(viewport.x, 1), std::max(viewport.y, 1)};
  Camera fitted = fitCamera(model_->view, fitBounds_, size);
  return mouse_.apply(fitted, model_->bounds);
}

void LiveModel::resetView() {
  mouse_.reset();
  if (model_) fitBounds_ = model_->bounds;
  changed_ = true;
}

// ---- feather dynamics ----

void LiveModel::toggleDynamics() {
  changed_ = true;
  if (simulating_) {
    simulating_ = false;
    return;
  }
  if (!model_ || model_->scene.organ<FeatherPart>().feathers.empty()) return;
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
    coatScene_.organ<FeatherPart>().types = model_->scene.organ<FeatherPart>().types;
    coatScene_.materials = model_->scene.materials;
    bodyMoved_ = false;
  }
  simulating_ = true;
  lastCoatStep_ = now_();
}

void LiveModel::stopDynamics(const std::string& why) {
  simulating_ = false;
  coat_.reset();
  error_ = "hirsute: " + why;
  std::cerr << error_ << '\n';
  if (model_) view_.updateFeathers(model_->scene);
}

bool LiveModel::stepDynamics() {
  if (!simulating_ || !coat_ || !model_) return false;
  const auto now = now_();
  // Real time, but no more than a 30th of a second a frame: a slow frame slows the motion down
  // rather than taking a step the collisions would have to halve.
  const double seconds =
      std::min(std::chrono::duration<double>(now - lastCoatStep_).count(), 1.0 / 30);
  lastCoatStep_ = now;
  if (!(seconds > 0)) return false;
  try {
    coat_->advance(seconds, model_->view.dynamics.substeps, bodyMoved_ ? &model_->scene : nullptr);
  } catch (const std::exception& e) {
    stopDynamics(std::string("the feathers' dynamics stopped: ") + e.what());
    return true;
  }
  bodyMoved_ = false;
  coat_->pose(coatScene_);
  view_.updateFeathers(coatScene_);
  const double took = secondsSince(now);
  simulatedFps_ = took > 0 ? 1 / took : 0;
  return true;
}

// ---- fur ----

void LiveModel::takeFur() {
  Scene previous = std::move(fur_);
  fur_ = Scene{};
  fur_.organ<FurPart>() = std::as_const(model_->scene).organ<FurPart>();
  // The frame before's particles and wetness carry over (an animation keeps its wet patches
  // and drags its fur); the view gets them at once.
  furMotion_.reset(fur_, previous.organ<FurPart>().surfaces.empty() ? nullptr : &previous);
  if (!previous.organ<FurPart>().surfaces.empty()) view_.updateFur(fur_);
  lastFurStep_ = now_();
}

bool LiveModel::stepFur() {
  if (fur_.organ<FurPart>().surfaces.empty()) return false;
  const auto now = now_();
  const float seconds =
      static_cast<float>(std::chrono::duration<double>(now - lastFurStep_).count());
  lastFurStep_ = now;
  const glm::vec3 force =
      model_->view.organ<FurSettings>().force + (gustLeft_ > 0 ? gust_ : glm::vec3(0.0f));
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
  if (changed || wasMoving != furMoving_) view_.updateFur(fur_);
  return changed;
}

void LiveModel::toggleDrying() {
  drying_ = !drying_;
  lastFurStep_ = now_();
  changed_ = true;
}

void LiveModel::sprayDroplets(std::size_t count) {
  changed_ = true;
  if (hirsute::sprayDroplets(fur_, count, 0.05f, 1.0f, spraySeed_++) > 0) view_.updateFur(fur_);
}

void LiveModel::dropletAt(glm::vec2 point, glm::ivec2 viewport) {
  if (!model_ || fur_.organ<FurPart>().surfaces.empty()) return;
  const Camera c = camera(viewport);
  glm::vec3 origin, direction;
  if (c.projection == Projection::Perspective) {
    const float t = std::tan(glm::radians(c.fieldOfViewY) * 0.5f);
    const float aspect =
        static_cast<float>(c.viewport.x) / static_cast<float>(std::max(c.viewport.y, 1));
    origin = c.eye;
    direction = glm::normalize(c.forward + point.x * t * aspect * c.right + point.y * t * c.up);
  } else {
    direction = c.forward;
    origin = c.eye + point.x * c.halfWidth * c.right + point.y * c.halfHeight * c.up;
  }
  if (const auto hit = fur::pickFur(fur_, origin, direction)) {
    fur::blendDroplet(fur_.organ<FurPart>().surfaces[hit->surface], hit->uv, 0.05f, 1.0f);
    view_.updateFur(fur_);
    changed_ = true;
  }
}

void LiveModel::gust(glm::ivec2 viewport) {
  if (!model_) return;
  // A gust across the line of sight, from alternating sides, as strong as a strand's spring.
  gust_ = (spraySeed_++ % 2 == 0 ? 1.0f : -1.0f) * 60.0f * camera(viewport).right;
  gustLeft_ = 0.6f;
  lastFurStep_ = now_();
  changed_ = true;
}

// ---- script ----

void LiveModel::scriptFailure(const ViewCommand& command, const std::string& message) {
  std::cerr << Diagnostic{Severity::Error, command.where, message}.text() << '\n';
  scriptFailed_ = true;
  closed_ = true;
}

void LiveModel::runScript() {
  const std::vector<ViewCommand>& script = *options_.script;
  for (;;) {
    if (closed_) return;
    // The command in progress, if it waits.
    if (waitUntil_) {
      if (now_() < *waitUntil_) {
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
      closed_ = true;
      return;
    }
    const ViewCommand& c = script[scriptIndex_++];
    auto number = [&](std::size_t i, double otherwise) {
      return i < c.numbers.size() ? c.numbers[i] : otherwise;
    };
    changed_ = true;
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
        resetView();
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
        runAnimation();
        break;
      case Kind::Hairs:
        shown_.hairs = c.words[0] == "on";
        break;
      case Kind::Feathers:
        shown_.feathers = c.words[0] == "on";
        break;
      case Kind::Fur:
        shown_.fur = c.words[0] == "on";
        break;
      case Kind::Droplets:
        sprayDroplets(static_cast<std::size_t>(std::max(0.0, c.numbers[0])));
        break;
      case Kind::Dynamics:
        if ((c.words[0] == "on") != simulating_) toggleDynamics();
        break;
      case Kind::Wireframe:
        shown_.wireframe = c.words[0] == "on";
        break;
      case Kind::Help:
        shown_.help = c.words[0] == "on";
        break;
      case Kind::Panel:
        shown_.panel = c.words[0] == "on";
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
        waitUntil_ =
            now_() + std::chrono::milliseconds(static_cast<long long>(number(0, 10) * 1000.0));
        return;
      case Kind::Sleep:
        waitUntil_ =
            now_() + std::chrono::milliseconds(static_cast<long long>(c.numbers[0] * 1000.0));
        return;
      case Kind::Measure:
        view_.measure(static_cast<int>(number(0, 30)));
        break;
      case Kind::Screenshot:
        if (!view_.screenshot(c.words[0], c.words.size() > 1)) {
          scriptFailure(c, "cannot write the screenshot " + c.words[0]);
          return;
        }
        break;
      case Kind::Quit:
        closed_ = true;
        return;
    }
  }
}

}  // namespace hirsute
