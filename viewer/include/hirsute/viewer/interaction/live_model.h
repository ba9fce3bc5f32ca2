// What `hirsute view` shows, without the window: the model built in the background and the step
// asked for, the animation's clock (cpfg-manual §1.3.3, §8.2), the fur's motion, drying and
// droplets (docs/fur.md), the feathers' dynamics (docs/dynamics.md), the `#define` values of the
// panel, the files watched, the camera the mouse has moved, and the view script's commands
// (view_script.h). No GL: what must be drawn or read back goes to a LiveModelView, which the
// window implements. Time comes from a clock given to it, so that tests can move it by hand.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/hairs/dynamics/coat_motion.h"
#include "hirsute/hairs/fur/fur_motion.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/interaction/animation_file.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/file_watcher.h"
#include "hirsute/viewer/interaction/model_worker.h"
#include "hirsute/viewer/interaction/mouse_camera.h"
#include "hirsute/viewer/interaction/view_script.h"

namespace hirsute {

// The model's files and how they are followed.
struct LiveModelOptions {
  std::filesystem::path lsystemFile;
  std::filesystem::path viewFile;                 // may be empty
  std::filesystem::path animationFile;            // may be empty: cpfg's defaults
  std::vector<std::filesystem::path> extraFiles;  // colour files and others to watch
  std::optional<int> steps;  // the step shown first; none: the derivation length
  // Scripted mode: the commands run in order; the window closes after the last one.
  std::optional<std::vector<ViewCommand>> script;
  // Constants changed in the panel are written back into the .l at once (`--save`).
  bool saveDefines = false;
  bool watch = true;  // live reloading
};

// What is drawn, as the keys and the script switch it.
struct ShownParts {
  bool hairs = true, feathers = true, fur = true, wireframe = false;
  bool help = false, panel = true;  // the key map overlay and the constants panel
};

// What shows the live model: the window, in the program. Each call is made when the live model
// changes what it shows, before the next frame is drawn.
class LiveModelView {
 public:
  virtual ~LiveModelView() = default;
  // A new build to draw (its scene, view settings and material mode).
  virtual void upload(const ViewerModel& model) = 0;
  // The fur moved, dried or took droplets; the feathers the dynamics bent (or the model's again).
  virtual void updateFur(const Scene& fur) = 0;
  virtual void updateFeathers(const Scene& feathers) = 0;
  // The script's `screenshot FILE [ui]`: false when the file cannot be written.
  virtual bool screenshot(const std::filesystem::path& file, bool withUi) = 0;
  // The script's `measure N`: frame times printed over N frames.
  virtual void measure(int frames) = 0;
};

class LiveModel {
 public:
  using Clock = std::chrono::steady_clock;
  using Now = std::function<Clock::time_point()>;

  // Starts the first build at once. `wake` is called from the builder's thread when a build has
  // finished; `now` is the clock of the animation, the fur, the dynamics and the script's waits.
  LiveModel(const LiveModelOptions& options, ModelBuilder builder, LiveModelView& view,
            std::function<void()> wake = {}, Now now = &Clock::now);
  LiveModel(const LiveModel&) = delete;
  LiveModel& operator=(const LiveModel&) = delete;

  // One turn of the window's loop, in this order: a finished build is shown, changed files are
  // read again, the animation, the fur and the dynamics step, and the script goes on.
  void update();
  // Something shown changed since the last call (the window draws a frame).
  bool takeChanged();
  // The script has ended, failed or quit: the window closes.
  bool closed() const { return closed_; }
  // 0; 1 when a scripted command failed; 2 when the model shown last has an error.
  int exitCode() const;

  // Models
  const ViewerModel* model() const { return model_.get(); }
  int derivationLength() const { return derivationLength_; }
  int currentStep() const;
  void stepBy(int steps);
  void goTo(int step);
  // Nothing is being built or animated: what was asked for is shown.
  bool idle() const { return worker_->settled() && !animating_; }
  const ModelWorker& worker() const { return *worker_; }
  // The last build's error (or the animation file's, or a dynamics failure); empty when none.
  const std::string& error() const { return error_; }
  // The screenshot being written is not an edit of the model's files.
  void ignoreWrite(const std::filesystem::path& file);

  // Constants of the .l (the panel)
  const std::vector<DefineConstant>& constants() const { return constants_; }
  const std::map<std::string, std::string>& changedDefines() const { return changedDefines_; }
  void setDefine(const std::string& name, const std::string& value);
  void saveDefines();
  void revertDefines();

  // Animation: Run plays the frames of the .a to the last one, Step shows the next frame.
  bool animating() const { return animating_; }
  void runAnimation();
  void stopAnimation() { animating_ = false; }
  void stepAnimation();
  void firstFrame();
  void lastFrame();

  // The camera: the view file's, fitted to the plant, as the mouse and the script moved it.
  MouseCamera& mouse() { return mouse_; }
  const MouseCamera& mouse() const { return mouse_; }
  Camera camera(glm::ivec2 viewport) const;
  void resetView();
  ShownParts& shown() { return shown_; }
  const ShownParts& shown() const { return shown_; }

  // Fur (docs/fur.md): a copy of the model's fur surfaces that moves, dries and takes droplets.
  const Scene& fur() const { return fur_; }
  bool furMoving() const { return furMoving_; }
  bool drying() const { return drying_; }
  void toggleDrying();
  // `count` droplets at random, as the J key and the script's `droplets` spray them.
  void sprayDroplets(std::size_t count);
  // A droplet where the fur meets the ray through `point` of the picture of `viewport`'s camera
  // (-1 to 1 from left to right and from bottom to top), as ctrl + click drops it.
  void dropletAt(glm::vec2 point, glm::ivec2 viewport);
  // A gust across the line of sight of `viewport`'s camera, from alternating sides.
  void gust(glm::ivec2 viewport);

  // Feather dynamics (docs/dynamics.md): the model's feathers simulated while shown, their roots
  // carried by the body as the animation moves it.
  void toggleDynamics();
  bool simulating() const { return simulating_; }
  const dynamics::CoatMotion* coat() const { return coat_ ? &*coat_ : nullptr; }
  double simulatedFps() const { return simulatedFps_; }

 private:
  void request();
  void applyBuild(ModelBuild build);
  void reloadFiles();
  void readAnimation();
  void readConstants();
  void advanceAnimation();
  void takeFur();
  bool stepFur();
  bool stepDynamics();
  void stopDynamics(const std::string& why);
  void runScript();
  void scriptFailure(const ViewCommand& command, const std::string& message);
  double secondsSince(Clock::time_point t) const;

  const LiveModelOptions& options_;
  LiveModelView& view_;
  Now now_;
  std::unique_ptr<ModelWorker> worker_;
  std::optional<FileWatcher> watcher_;
  bool changed_ = true;

  // What is shown
  std::shared_ptr<const ViewerModel> model_;
  Bounds fitBounds_;
  bool fitted_ = false;
  std::string error_;
  std::string animationError_;
  ModelRequest wanted_;
  int derivationLength_ = 0;
  MouseCamera mouse_;
  ShownParts shown_;

  // Fur: a copy of the model's fur surfaces that moves, dries and takes droplets.
  Scene fur_;
  fur::FurMotion furMotion_;
  bool drying_ = false, furMoving_ = false;
  glm::vec3 gust_{0.0f};
  float gustLeft_ = 0;  // seconds
  std::uint32_t spraySeed_ = 1;
  Clock::time_point lastFurStep_;

  // Feather dynamics: the simulation, the feathers it bends (drawn over the model's), whether it
  // runs, whether a new build moved the body, and the rate it keeps.
  std::optional<dynamics::CoatMotion> coat_;
  Scene coatScene_;
  bool simulating_ = false, bodyMoved_ = false;
  Clock::time_point lastCoatStep_;
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

  // Script state
  std::size_t scriptIndex_ = 0;
  std::optional<Clock::time_point> waitUntil_;
  std::uint64_t reloadSerial_ = 0;    // the request made for the last file change
  std::uint64_t reloadsApplied_ = 0;  // builds of such requests shown
  std::optional<std::uint64_t> waitingForReloadsAbove_;
  bool closed_ = false, scriptFailed_ = false;
};

}  // namespace hirsute
