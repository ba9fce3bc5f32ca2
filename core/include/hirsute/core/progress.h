// Progress of a long run on the user's terminal: one line on stderr, rewritten in place, that
// names the stage, how far it has got in the unit the user knows, the time since the run began
// and, where the stage knows its total, the time it has left:
//
//   tracing: 17/48 samples a pixel · 0:42 elapsed · about 1:10 left
//   simulating: 12/120 frames · 0:05 elapsed · about 0:40 left
//   rendering with POV-Ray: 45% of the pixels · 1:02 elapsed · about 1:20 left
//
// Nothing is shown before the run has taken a second, nothing at all when the stream is not a
// terminal (pipes and files get the same bytes as without it), and the line is cleared when the
// run ends or a message is printed. The command line makes one and hands it down to every
// stage; a stage that was given none reports nothing. Inner loops call tick(), which counts
// down and reads the clock only every few thousand calls.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "hirsute/core/time_left.h"

namespace hirsute {

class Progress {
 public:
  // How a stage counts what it has done.
  enum class Unit {
    Steps,    // "step 37/216", or "17/48 samples a pixel" with what it counts
    Percent,  // "45%" of the total, or "45% of the pixels"
    Count,    // "1.2 M": a count that has no known total
    None,     // the stage's name alone ("rendering"), for work that cannot count itself
  };

  // A run shorter than this shows nothing.
  static constexpr std::chrono::milliseconds kQuietStart{1000};

  // Reports on `terminal`, or nowhere when it is null; nothing before `quietStart` has passed.
  explicit Progress(std::FILE* terminal = nullptr,
                    std::chrono::milliseconds quietStart = kQuietStart);
  // Reports on `stream` only when it is a terminal (isatty).
  static Progress onTerminal(std::FILE* stream);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  // Stays where it was made (the command's own); onTerminal's result is built in place.
  Progress(Progress&&) = delete;
  Progress& operator=(Progress&&) = delete;

  bool enabled() const { return terminal_ != nullptr; }

  // A new stage: `name` as the line starts, what it counts and, for Steps and Percent, the
  // total; `counted` names what the count counts ("samples a pixel": "17/48 samples a pixel";
  // "of the pixels": "45% of the pixels"), without it Steps reads "step 17/48". A stage with a
  // total shows the time it has left once enough of it is done (time_left.h).
  void begin(const char* name, Unit unit, double total = 0, const char* counted = nullptr);
  // The stage shows no time left: for steps that grow dearer as they go (a derivation's string
  // grows with each step), where the rate so far would promise too little.
  void withoutTimeLeft();
  // Where the stage is: shown at once if the second has passed (and the last update is a tenth
  // of a second old). For calls made a few times a second or less (a derivation step).
  void update(double done) {
    if (terminal_ != nullptr) poll(done, -1);
  }
  // The same, with the share of the stage's work done (0 to 1) where it is not done / total
  // (the tracer's passes grow cheaper as pixels stop): the time left is estimated from it.
  void update(double done, double share) {
    if (terminal_ != nullptr) poll(done, share);
  }
  // The same for inner loops: only every kTicksPerPoll calls looks at the clock.
  void tick(double done) {
    if (--countdown_ == 0) {
      countdown_ = kTicksPerPoll;
      if (terminal_ != nullptr) poll(done, -1);
    }
  }
  // Draws the line again as it last was, its elapsed time moved on (ProgressHeartbeat's thread,
  // while a call that reports nothing runs).
  void redraw();
  // Clears the line (if anything is shown); the next update draws it again. Called before other
  // text goes to the same stream, and when the run ends.
  void clear();
  // Words shown after the count until the next begin() (", 31% of pixels active"): what a stage
  // knows beside its steps.
  void note(std::string text);

  static constexpr std::uint32_t kTicksPerPoll = 4096;

  // The stage any Progress of the process began last ("" before the first): where an
  // out-of-memory error happened.
  static const char* lastStage();

 private:
  using Clock = std::chrono::steady_clock;
  void poll(double done, double share);
  // Draws the line as it is now; the lock is held.
  void draw(Clock::time_point now);

  std::FILE* terminal_;
  std::chrono::milliseconds quietStart_;
  std::uint32_t countdown_ = kTicksPerPoll;
  // Everything below is shared with the heartbeat's thread, under this lock.
  std::mutex mutex_;
  Clock::time_point started_;
  Clock::time_point stageStarted_;
  Clock::time_point lastDrawn_{};
  const char* stage_ = "";
  Unit unit_ = Unit::Count;
  double total_ = 0;
  double done_ = 0;
  const char* counted_ = nullptr;
  bool showsTimeLeft_ = true;
  TimeLeft timeLeft_;
  std::size_t shownWidth_ = 0;  // columns on the line now; 0: nothing shown
  std::string line_;
  std::string note_;
};

// Keeps the line's elapsed time moving while one long call runs that reports nothing itself
// (the GL render, building the ray tracer's scene, the denoiser): from a thread of its own it
// redraws the line twice a second until it is destroyed. Nothing runs when `progress` is off.
class ProgressHeartbeat {
 public:
  explicit ProgressHeartbeat(Progress& progress);
  ~ProgressHeartbeat();
  ProgressHeartbeat(const ProgressHeartbeat&) = delete;
  ProgressHeartbeat& operator=(const ProgressHeartbeat&) = delete;

 private:
  Progress& progress_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

// What the line says of a stage at one moment.
struct ProgressReading {
  const char* stage = "";
  Progress::Unit unit = Progress::Unit::None;
  double done = 0;
  double total = 0;
  const char* counted = nullptr;      // Progress::begin's `counted`
  std::string note;                   // Progress::note
  std::optional<double> elapsed;      // seconds since the run began
  std::optional<double> secondsLeft;  // the stage's (TimeLeft)
};

// The text of the line: "tracing: 17/48 samples a pixel, 31% of pixels active · 0:42 elapsed ·
// about 1:10 left".
std::string progressLine(const ProgressReading& reading);

// A time on the clock's face, in whole seconds: "0:42", "12:05", "1:02:03".
std::string clockText(double seconds);

// The time left as the line says it, rounded as far as an estimate deserves: "a few seconds
// left" under five seconds, then "about 0:45 left" (up to the next 5 s under a minute, 10 s
// under ten minutes, the next minute beyond).
std::string timeLeftText(double seconds);

// A run's length in a closing summary: "0.4 s", "12 s", "2:03", "1:02:03".
std::string durationText(double seconds);

}  // namespace hirsute
