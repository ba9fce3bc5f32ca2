#include "hirsute/viewer/interaction/live_model.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <utility>

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

// What the live model lends one organ: the clock, the camera, its drawing and the error line.
class LiveModel::OrganHost final : public LiveOrganHost {
 public:
  OrganHost(LiveModel& live, std::string_view name) : live_(live), name_(name) {}

  Clock::time_point now() const override { return live_.now_(); }
  bool realTime() const override { return live_.realTime_; }
  Camera camera(glm::ivec2 viewport) const override { return live_.camera(viewport); }
  void redraw(const Scene& scene) override { live_.view_.updateOrgan(name_, scene); }
  void fail(const std::string& message) override {
    live_.error_ = "hirsute: " + message;
    std::cerr << live_.error_ << '\n';
    live_.changed_ = true;
  }

 private:
  LiveModel& live_;
  std::string_view name_;
};

LiveModel::LiveModel(const LiveModelOptions& options, ModelBuilder builder, LiveModelView& view,
                     std::function<void()> wake, Now now)
    : options_(options),
      view_(view),
      realTime_(!now),
      now_(now ? std::move(now) : Now(&Clock::now)) {
  for (const LiveOrganType* type : liveOrgans()) {
    hosts_.push_back(std::make_unique<OrganHost>(*this, type->name()));
    organs_.push_back(type->make(*hosts_.back()));
  }
  worker_ = std::make_unique<ModelWorker>(std::move(builder), std::move(wake));
  const std::filesystem::path folder = options_.lsystemFile.parent_path();
  const std::string stem = options_.lsystemFile.stem().string();
  palette_ = std::make_unique<PaletteEditor>(folder, stem, options_.colorFiles);
  panels_ = std::make_unique<PanelEditor>(folder, stem);
  reportEditorFiles();
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

LiveModel::~LiveModel() = default;

double LiveModel::secondsSince(Clock::time_point t) const {
  return std::chrono::duration<double>(now_() - t).count();
}

void LiveModel::update() {
  if (auto build = worker_->take()) applyBuild(std::move(*build));
  if (watcher_ && watcher_->poll()) reloadFiles();
  advanceAnimation();
  if (model_) {
    for (const auto& organ : organs_) {
      if (organ->step()) changed_ = true;
    }
  }
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
  // Unsaved palette edits stay on the plant through every build.
  if (palette_->modified()) {
    auto edited = std::make_shared<ViewerModel>(*model_);
    palette_->apply(edited->scene.materials);
    model_ = std::move(edited);
  }
  // Texture images are read by the model without a model file's extension: watched by name.
  if (watcher_) {
    for (const TextureDeclaration& texture : model_->view.textures) watcher_->watch(texture.file);
  }
  view_.upload(*model_);
  shapes_.follow(
      *model_,
      (options_.viewFile.empty() ? options_.lsystemFile : options_.viewFile).parent_path());
  for (const auto& organ : organs_) organ->take(model_->scene, model_->view);
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
  for (const auto& organ : organs_) organ->filesChanged();
  readAnimation();
  readConstants();
  palette_->reload();
  panels_->reload();
  reportEditorFiles();
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

void LiveModel::shapesEdited() {
  const std::vector<std::filesystem::path> written = shapes_.takeWritten();
  if (written.empty()) return;
  // Re-derived now rather than when the watcher sees the files settle.
  if (watcher_) {
    for (const std::filesystem::path& file : written) watcher_->acknowledge(file);
  }
  reloadFiles();
}

void LiveModel::revertDefines() {
  changedDefines_.clear();
  wanted_.defines.clear();
  request();
}

// ---- editors ----

void LiveModel::reportEditorFiles() {
  // A panel the viewer cannot read is shown with its message; the terminal has it too (a
  // colour file's error is the build's).
  for (const PanelEditor::Panel& panel : panels_->panels()) {
    if (!panel.error.empty()) std::cerr << panel.error << '\n';
  }
}

void LiveModel::showPalette() {
  changed_ = true;
  if (!model_) return;
  auto edited = std::make_shared<ViewerModel>(*model_);
  palette_->apply(edited->scene.materials);
  model_ = std::move(edited);
  view_.upload(*model_);
}

void LiveModel::editPalette(std::size_t file, PaletteDocument next, bool continuing) {
  if (!palette_->edit(file, std::move(next), continuing)) return;
  lastEditor_ = "colors";
  showPalette();
}

void LiveModel::editPanel(std::size_t panel, ControlPanel next) {
  changed_ = true;
  if (panels_->edit(panel, std::move(next))) lastEditor_ = "panel";
}

void LiveModel::activatePanelItem(std::size_t panel, std::size_t item, int value) {
  changed_ = true;
  if (auto define = panels_->activate(panel, item, value, constants_)) {
    setDefine(define->first, define->second);
    if (options_.saveDefines) saveDefines();
  }
}

std::string LiveModel::editorFailure(const std::string& message) {
  if (!message.empty()) {
    error_ = "hirsute: error: " + message;
    // A script's failure is reported at its command.
    if (!options_.script) std::cerr << error_ << '\n';
    changed_ = true;
  }
  return message;
}

std::string LiveModel::undoEdit(const std::string& editor, bool redo) {
  const std::string which = editor.empty()          ? lastEditor_
                            : editor == "materials" ? "colors"
                                                    : editor;
  const char* verb = redo ? "redo" : "undo";
  if (which == "colors") {
    const auto file = palette_->lastEdited();
    if (!file || !(redo ? palette_->redo(*file) : palette_->undo(*file)))
      return editorFailure(std::string("nothing to ") + verb + " in the colours");
    showPalette();
  } else if (which == "panel") {
    const auto panel = panels_->lastEdited();
    if (!panel || !(redo ? panels_->redo(*panel) : panels_->undo(*panel)))
      return editorFailure(std::string("nothing to ") + verb + " in the panels");
    changed_ = true;
  } else {
    return editorFailure(std::string("nothing to ") + verb + ": no editor has been used");
  }
  return {};
}

std::string LiveModel::saveEditor(const std::string& editor) {
  changed_ = true;
  if (editor == "colors" || editor == "materials") {
    if (palette_->empty())
      return editorFailure("the model has no colour file to save; 'create colors' makes one");
    for (std::size_t f = 0; f < palette_->files().size(); ++f) {
      if (!palette_->files()[f].history.modified()) continue;
      if (std::string failure = palette_->save(f); !failure.empty()) return editorFailure(failure);
      std::cout << "wrote " << palette_->files()[f].path.string() << '\n';
    }
    return {};
  }
  if (panels_->panels().empty())
    return editorFailure("the model's folder has no panel (.pnl) to save");
  for (std::size_t p = 0; p < panels_->panels().size(); ++p) {
    if (!panels_->panels()[p].history.modified()) continue;
    if (std::string failure = panels_->save(p); !failure.empty()) return editorFailure(failure);
    std::cout << "wrote " << panels_->panels()[p].path.string() << '\n';
  }
  return {};
}

std::string LiveModel::createEditorFile(const std::string& what) {
  changed_ = true;
  if (what == "panel") {
    std::size_t created = 0;
    if (std::string failure = panels_->create(constants_, &created); !failure.empty())
      return editorFailure(failure);
    std::cout << "wrote " << panels_->panels()[created].path.string() << '\n';
    return {};
  }
  const auto kind =
      what == "materials" ? PaletteDocument::Kind::Materials : PaletteDocument::Kind::ColorMap;
  const std::vector<Material> shown = model_ ? model_->scene.materials : defaultPalette();
  if (std::string failure = palette_->create(kind, shown); !failure.empty())
    return editorFailure(failure);
  // The builder takes the one colour file of the model's folder (docs/files.md), so the next
  // build reads it; nothing else needs to name it.
  std::cout << "wrote " << palette_->files().front().path.string()
            << " (the model's folder's one colour file: used without -m or -M)\n";
  return {};
}

std::string LiveModel::runEditorCommand(const ViewCommand& c) {
  const int index = c.numbers.empty() ? 0 : static_cast<int>(c.numbers[0]);
  if (c.kind == Kind::Color || c.kind == Kind::Material) scriptedEntry_ = index;
  auto fileFor = [&](PaletteDocument::Kind kind) -> std::optional<std::size_t> {
    const auto file = palette_->fileOf(index);
    if (!file || palette_->files()[*file].history.current().kind != kind) return std::nullopt;
    if (!palette_->files()[*file].error.empty()) return std::nullopt;
    return file;
  };
  switch (c.kind) {
    case Kind::Color: {
      const auto file = fileFor(PaletteDocument::Kind::ColorMap);
      if (!file) {
        return "no colour map (.map) holds colour " + std::to_string(index) +
               "; 'create colors' makes one for a model without colour files";
      }
      PaletteDocument next = palette_->files()[*file].history.current();
      setColor(next, index % 256, glm::vec3(c.numbers[1], c.numbers[2], c.numbers[3]));
      editPalette(*file, std::move(next));
      return {};
    }
    case Kind::Material: {
      const auto file = fileFor(PaletteDocument::Kind::Materials);
      if (!file) {
        return "no material file (.mat) holds material " + std::to_string(index) +
               "; 'create materials' makes one for a model without colour files";
      }
      PaletteDocument next = palette_->files()[*file].history.current();
      const MaterialField field = *materialFieldNamed(c.words[0]);
      glm::vec3 values(static_cast<float>(c.numbers[1]));
      if (isColorField(field)) values = glm::vec3(c.numbers[1], c.numbers[2], c.numbers[3]);
      setMaterialField(next, index % 256, field, values);
      editPalette(*file, std::move(next));
      return {};
    }
    case Kind::Undo:
    case Kind::Redo:
      return undoEdit(c.words.empty() ? "" : c.words[0], c.kind == Kind::Redo);
    case Kind::Create:
      return createEditorFile(c.words[0]);
    case Kind::Panel: {
      const std::string& what = c.words[0];
      for (std::size_t p = 0; p < panels_->panels().size(); ++p) {
        const ControlPanel& panel = panels_->panels()[p].history.current();
        const auto type = what == "button" ? PanelItem::Type::Button : PanelItem::Type::Slider;
        const auto item = findPanelItem(panel, type, c.words[1]);
        if (!item) continue;
        if (what == "range") {
          ControlPanel next = panel;
          setPanelRange(next, *item, std::stoi(c.words[2]), std::stoi(c.words[3]),
                        panels_->panels()[p].path.string());
          editPanel(p, std::move(next));
        } else {
          const int value = what == "button" ? (c.words[2] == "on" ? 1 : 0) : std::stoi(c.words[2]);
          activatePanelItem(p, *item, value);
        }
        return {};
      }
      return "no " + what + (what == "range" ? " of a slider" : "") + " named '" + c.words[1] +
             "' in the model's panels (.pnl)";
    }
    default:
      return {};
  }
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

// ---- organs ----

LiveOrgan* LiveModel::organ(std::string_view name) {
  const auto types = liveOrgans();
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (types[k]->name() == name) return organs_[k].get();
  }
  return nullptr;
}

void LiveModel::act(std::size_t index, std::size_t action, glm::ivec2 viewport) {
  changed_ = true;
  if (!model_) return;
  LiveActionCall call;
  call.viewport = viewport;
  organs_[index]->act(action, call);
}

void LiveModel::pointAt(glm::vec2 point, glm::ivec2 viewport) {
  if (!model_) return;
  for (const auto& organ : organs_) {
    if (organ->pointAt(point, viewport)) {
      changed_ = true;
      return;
    }
  }
}

bool LiveModel::organsMoving() const {
  return std::any_of(organs_.begin(), organs_.end(),
                     [](const auto& organ) { return organ->moving(); });
}

// ---- script ----

void LiveModel::scriptFailure(const ViewCommand& command, const std::string& message) {
  std::cerr << Diagnostic{Severity::Error, command.where, message, {}}.text() << '\n';
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
      case Kind::Organ:
        if (c.action < 0) {
          shown_.showOrgan(liveOrgans()[c.organ]->name(), c.words[0] == "on");
        } else if (model_) {
          LiveActionCall call;
          call.byKey = false;
          call.numbers = c.numbers;
          call.words = c.words;
          organs_[c.organ]->act(static_cast<std::size_t>(c.action), call);
        }
        break;
      case Kind::Wireframe:
        shown_.wireframe = c.words[0] == "on";
        break;
      case Kind::Help:
        shown_.help = c.words[0] == "on";
        break;
      case Kind::Panel:
        if (c.words[0] == "on" || c.words[0] == "off") {
          shown_.panel = c.words[0] == "on";
          break;
        }
        [[fallthrough]];
      case Kind::Color:
      case Kind::Material:
      case Kind::Undo:
      case Kind::Redo:
      case Kind::Create:
        if (std::string failure = runEditorCommand(c); !failure.empty()) {
          scriptFailure(c, failure);
          return;
        }
        break;
      case Kind::Colors:
        shown_.colors = c.words[0] == "on";
        break;
      case Kind::Controls:
        shown_.controls = c.words[0] == "on";
        break;
      case Kind::Define:
        setDefine(c.words[0], c.words[1]);
        if (options_.saveDefines) saveDefines();
        break;
      case Kind::Save:
        if (c.words.empty() || c.words[0] == "constants") {
          saveDefines();
        } else if (std::string failure = saveEditor(c.words[0]); !failure.empty()) {
          scriptFailure(c, failure);
          return;
        }
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
        if (!view_.screenshot(c.words[0], c.words.size() < 2   ? LiveModelView::Shot::Plant
                                          : c.words[1] == "ui" ? LiveModelView::Shot::WithUi
                                                               : LiveModelView::Shot::Shown)) {
          scriptFailure(c, "cannot write the screenshot " + c.words[0]);
          return;
        }
        break;
      case Kind::Shape:
        if (const std::string refused = shapes_.run(c); !refused.empty()) {
          scriptFailure(c, refused);
          return;
        }
        shapesEdited();
        break;
      case Kind::Quit:
        closed_ = true;
        return;
    }
  }
}

}  // namespace hirsute
