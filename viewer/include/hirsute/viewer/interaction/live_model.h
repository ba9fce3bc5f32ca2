// What `hirsute view` shows, without the window: the model built in the background and the step
// asked for, the animation's clock (cpfg-manual §1.3.3, §8.2), what the organs do between builds
// (live_organ.h: what moves, their keys and commands), the `#define` values of the panel, the
// files watched, the camera the mouse has moved, and the view script's commands (view_script.h). No
// GL: what must be drawn or read back goes to a LiveModelView, which the window implements. Time
// comes from a clock given to it, so that tests can move it by hand.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/viewer/interaction/animation_file.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/file_watcher.h"
#include "hirsute/viewer/interaction/live_organ.h"
#include "hirsute/viewer/interaction/model_worker.h"
#include "hirsute/viewer/interaction/mouse_camera.h"
#include "hirsute/viewer/interaction/palette_editor.h"
#include "hirsute/viewer/interaction/panel_editor.h"
#include "hirsute/viewer/interaction/shape_workbench.h"
#include "hirsute/viewer/interaction/view_script.h"
#include "hirsute/viewer/view/camera.h"

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
  // The model's colour files, as the builder finds them (-m, -M or the folder's one), for the
  // palette and material editors.
  ColorFiles colorFiles;
};

// What is drawn, as the keys and the script switch it.
struct ShownParts {
  bool wireframe = false;
  bool help = false, panel = true;       // the key map overlay and the constants panel
  bool colors = false, controls = true;  // the palette editor and the .pnl panels
  // The organs hidden, by name (live_organ.h); every other one is shown.
  std::set<std::string, std::less<>> hiddenOrgans;

  bool organShown(std::string_view organ) const { return !hiddenOrgans.contains(organ); }
  void showOrgan(std::string_view organ, bool shown) {
    if (shown) {
      if (auto found = hiddenOrgans.find(organ); found != hiddenOrgans.end())
        hiddenOrgans.erase(found);
    } else {
      hiddenOrgans.emplace(organ);
    }
  }
};

// What shows the live model: the window, in the program. Each call is made when the live model
// changes what it shows, before the next frame is drawn.
class LiveModelView {
 public:
  virtual ~LiveModelView() = default;
  // A new build to draw (its scene, view settings and material mode).
  virtual void upload(const ViewerModel& model) = 0;
  // The organ named `organ` moved (live_organ.h): its drawing takes what moves from `scene`.
  virtual void updateOrgan(std::string_view organ, const Scene& scene) = 0;
  // What the script's `screenshot FILE [ui|shown]` takes: the plant alone, drawn anew; the plant
  // with the overlays, drawn anew; or the picture the window shows now, as it was last drawn.
  enum class Shot { Plant, WithUi, Shown };
  // The script's screenshot: false when the file cannot be written.
  virtual bool screenshot(const std::filesystem::path& file, Shot shot) = 0;
  // The script's `measure N`: frame times printed over N frames.
  virtual void measure(int frames) = 0;
};

class LiveModel {
 public:
  using Clock = std::chrono::steady_clock;
  using Now = std::function<Clock::time_point()>;

  // Starts the first build at once. `wake` is called from the builder's thread when a build has
  // finished; `now` is the clock of the animation, the organs and the script's waits (none: the
  // wall clock, Clock::now, and the organs may run in real time on threads of their own; a clock
  // given, as tests move it by hand, steps everything in update()).
  LiveModel(const LiveModelOptions& options, ModelBuilder builder, LiveModelView& view,
            std::function<void()> wake = {}, Now now = {});
  ~LiveModel();
  LiveModel(const LiveModel&) = delete;
  LiveModel& operator=(const LiveModel&) = delete;

  // One turn of the window's loop, in this order: a finished build is shown, changed files are
  // read again, the animation and the organs step, and the script goes on.
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
  // The window could not draw the build (an organ's geometry at this camera's detail passed
  // --max-vertices): the message shows on the error line until the next build.
  void drawingFailed(const std::string& message) {
    if (error_.empty()) error_ = message;
  }
  // The screenshot being written is not an edit of the model's files.
  void ignoreWrite(const std::filesystem::path& file);

  // Constants of the .l (the panel)
  const std::vector<DefineConstant>& constants() const { return constants_; }
  const std::map<std::string, std::string>& changedDefines() const { return changedDefines_; }
  void setDefine(const std::string& name, const std::string& value);
  void saveDefines();
  void revertDefines();

  // The editors (docs/viewer.md, "Editors"): the palette and material editor, whose edits show
  // on the plant at once without a build, and the model's control panels (.pnl).
  PaletteEditor& palette() { return *palette_; }
  const PaletteEditor& palette() const { return *palette_; }
  PanelEditor& panels() { return *panels_; }
  const PanelEditor& panels() const { return *panels_; }
  // A palette file edited (palette_editor.h): the plant is drawn with its present state.
  void editPalette(std::size_t file, PaletteDocument next, bool continuing = false);
  // A panel file edited (panel_editor.h).
  void editPanel(std::size_t panel, ControlPanel next);
  // Control `item` of panel `panel` set to `value`: the #define it is bound to changes.
  void activatePanelItem(std::size_t panel, std::size_t item, int value);
  // Editor actions, by the view script's names ("colors" or "materials", "panel"): each returns
  // its failure's message (empty on success), which also shows on the error line.
  std::string undoEdit(const std::string& editor, bool redo = false);
  std::string saveEditor(const std::string& editor);
  std::string createEditorFile(const std::string& what);
  // The colour index the script's last `color` or `material` command edited (-1: none), which
  // the editor's window selects.
  int scriptedEntry() const { return scriptedEntry_; }
  // The shape editors' files (shape_workbench.h); after an edit, shapesEdited() re-derives from
  // the files written.
  ShapeWorkbench& shapes() { return shapes_; }
  void shapesEdited();

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

  // The organs (live_organ.h): one of each type of liveOrgans(), in its order.
  LiveOrgan& organ(std::size_t index) { return *organs_[index]; }
  const LiveOrgan& organ(std::size_t index) const { return *organs_[index]; }
  // The organ of the type named `name`, or null.
  LiveOrgan* organ(std::string_view name);
  // Action `action` of organ `index` (its type's actions()), as its key asks for it, for a
  // picture `viewport` pixels large.
  void act(std::size_t index, std::size_t action, glm::ivec2 viewport);
  // A ctrl + click at `point` of the picture of `viewport`'s camera (-1 to 1 from left to right
  // and from bottom to top), handed to the organs in order until one takes it.
  void pointAt(glm::vec2 point, glm::ivec2 viewport);
  // Some organ moves on its own: the window keeps drawing.
  bool organsMoving() const;

 private:
  void request();
  void applyBuild(ModelBuild build);
  void reloadFiles();
  void readAnimation();
  void readConstants();
  void advanceAnimation();
  void showPalette();
  void reportEditorFiles();
  std::string editorFailure(const std::string& message);
  std::string runEditorCommand(const ViewCommand& command);
  class OrganHost;
  void runScript();
  void scriptFailure(const ViewCommand& command, const std::string& message);
  double secondsSince(Clock::time_point t) const;

  const LiveModelOptions& options_;
  LiveModelView& view_;
  bool realTime_;  // now_ is the wall clock (made before now_, which takes the clock given)
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

  // The organs, each with the host that lends it the clock, the camera and the view.
  std::vector<std::unique_ptr<OrganHost>> hosts_;
  std::vector<std::unique_ptr<LiveOrgan>> organs_;

  // Animation (cpfg-manual §1.3.3, §8.2)
  AnimationSettings animation_;
  std::vector<AnimationFrame> frames_;
  std::size_t frameIndex_ = 0;
  bool animating_ = false;
  Clock::time_point lastFrameStart_;

  // Constants of the .l (the panel)
  std::vector<DefineConstant> constants_;
  std::map<std::string, std::string> changedDefines_;

  // The editors
  std::unique_ptr<PaletteEditor> palette_;
  std::unique_ptr<PanelEditor> panels_;
  std::string lastEditor_;  // "colors" or "panel": what undo and redo act on
  int scriptedEntry_ = -1;
  ShapeWorkbench shapes_;

  // Script state
  std::size_t scriptIndex_ = 0;
  std::optional<Clock::time_point> waitUntil_;
  std::uint64_t reloadSerial_ = 0;    // the request made for the last file change
  std::uint64_t reloadsApplied_ = 0;  // builds of such requests shown
  std::optional<std::uint64_t> waitingForReloadsAbove_;
  bool closed_ = false, scriptFailed_ = false;
};

}  // namespace hirsute
