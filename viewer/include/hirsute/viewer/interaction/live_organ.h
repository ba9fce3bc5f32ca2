// An organ in the interactive viewer (docs/design.md, "Organs"): the name it is shown,
// hidden and counted by (its drawing's, organ_drawing.h), the key that shows and hides it, what
// moves between frames (strands, a simulation), its actions (keys of the
// window and commands of the view script) and its words on the status line. The live model
// (live_model.h) makes one LiveOrgan of every type of liveOrgans() for the model it shows and
// names none; the window maps keys and the view script parses commands from the same list.
//
// Adding an organ's part in the viewer: a class derived from LiveOrgan and a LiveOrganType that
// makes it (LiveOrganTypeOf), in the organ's `live/` folder (hairs/NAME/live/), returned by its
// nameLive() (hairs/organs/organ_list.h). No GL: what must be drawn again goes through the host.
#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

// What the live model lends one of its organs.
class LiveOrganHost {
 public:
  using Clock = std::chrono::steady_clock;

  virtual ~LiveOrganHost() = default;
  // The clock of the animation and the script (tests move it by hand).
  virtual Clock::time_point now() const = 0;
  // Whether that clock is the wall clock (Clock::now): an organ may then step on a thread of its
  // own in real time and hand step() its latest state. False when tests move the clock by hand:
  // everything then steps in step(), on that clock.
  virtual bool realTime() const = 0;
  // The camera of a picture `viewport` pixels large, as the view file and the mouse set it.
  virtual Camera camera(glm::ivec2 viewport) const = 0;
  // The organ's drawing takes again from `scene` what moves (organ_drawing.h's update).
  virtual void redraw(const Scene& scene) = 0;
  // Reports an error on the status line and the terminal; the picture shown stays.
  virtual void fail(const std::string& message) = 0;
};

// An action an organ offers: a key of the window, a command of the view script, or both.
struct LiveAction {
  // The script's command ("droplets"; empty: a key only) and its arguments as view_script.h
  // writes them: 'n' a number, 'w' a word, 'o' on or off; lower case required, upper optional.
  std::string_view command;
  std::string_view arguments;
  // The key, an upper-case letter (0: the script only), and its line in the key map.
  char key = 0;
  std::string_view help;
};

// How an action was asked for: its key (no arguments) or its script command with the
// arguments, for a picture `viewport` pixels large (actions aimed along the camera).
struct LiveActionCall {
  bool byKey = true;
  std::span<const double> numbers;
  std::span<const std::string> words;
  glm::ivec2 viewport{1, 1};
};

class LiveOrgan {
 public:
  virtual ~LiveOrgan() = default;

  // A new build is shown: its scene and view settings (they outlive the next take()).
  virtual void take(const Scene& scene, const ViewSettings& view) = 0;
  // One turn of the window's loop, after take(): moves what moves by the time passed since the
  // turn before. Returns whether what is drawn changed.
  virtual bool step() { return false; }
  // The model's files were edited: what the organ made from the model shown (a simulation) starts
  // again from the next build, which may bring other organs.
  virtual void filesChanged() {}
  // Something moves on its own: the window keeps drawing frames.
  virtual bool moving() const { return false; }
  // Action `index` of its type's actions().
  virtual void act(std::size_t /*index*/, const LiveActionCall& /*call*/) {}
  // A ctrl + click at `point` of the picture (-1 to 1 from left to right and bottom to top):
  // returns whether the organ took it.
  virtual bool pointAt(glm::vec2 /*point*/, glm::ivec2 /*viewport*/) { return false; }
  // Its words on the status line after its name and count ("drying"); empty: none.
  virtual std::string status() const { return {}; }
};

class LiveOrganType {
 public:
  virtual ~LiveOrganType() = default;
  // Its name: its drawing's, and the view script's `NAME on|off`.
  virtual const char* name() const = 0;
  // The key that shows and hides it, an upper-case letter.
  virtual char showKey() const = 0;
  virtual std::span<const LiveAction> actions() const { return {}; }
  // The key map's line for a ctrl + click (empty: the organ takes none).
  virtual std::string_view pointHelp() const { return {}; }
  virtual std::unique_ptr<LiveOrgan> make(LiveOrganHost& host) const = 0;
};

// The type of an organ class constructed from its host alone: its name, show key, actions and
// ctrl + click line given as values.
template <class Organ>
class LiveOrganTypeOf final : public LiveOrganType {
 public:
  LiveOrganTypeOf(const char* name, char showKey, std::span<const LiveAction> actions = {},
                  std::string_view pointHelp = {})
      : name_(name), showKey_(showKey), actions_(actions), pointHelp_(pointHelp) {}
  const char* name() const override { return name_; }
  char showKey() const override { return showKey_; }
  std::span<const LiveAction> actions() const override { return actions_; }
  std::string_view pointHelp() const override { return pointHelp_; }
  std::unique_ptr<LiveOrgan> make(LiveOrganHost& host) const override {
    return std::make_unique<Organ>(host);
  }

 private:
  const char* name_;
  char showKey_;
  std::span<const LiveAction> actions_;
  std::string_view pointHelp_;
};

// Every organ's type in the viewer, in the order of organDrawings() (hairs/organs/organ_list.h).
std::span<const LiveOrganType* const> liveOrgans();

}  // namespace hirsute
