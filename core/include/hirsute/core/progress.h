// Progress of a long run on the user's terminal: one line on stderr, rewritten in place, that
// names the stage and how far it has got (`deriving: step 37/216`, `interpreting: 45%`,
// `placing hairs: 1.2 M`, `writing POV-Ray: 60%`).
//
// Nothing is shown before the run has taken a second, nothing at all when the stream is not a
// terminal (pipes and files get the same bytes as without it), and the line is cleared when the
// run ends or a message is printed. The command line makes one and hands it down to every
// stage; a stage that was given none reports nothing. Inner loops call tick(), which counts
// down and reads the clock only every few thousand calls.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

namespace hirsute {

class Progress {
 public:
  // How a stage counts what it has done.
  enum class Unit {
    Steps,    // "step 37/216"
    Percent,  // "45%" of the total
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

  // A new stage: `name` as the line starts, what it counts and, for Steps and Percent, the total.
  void begin(const char* name, Unit unit, double total = 0);
  // Where the stage is: shown at once if the second has passed (and the last update is a tenth
  // of a second old). For calls made a few times a second or less (a derivation step).
  void update(double done) {
    if (terminal_ != nullptr) poll(done);
  }
  // The same for inner loops: only every kTicksPerPoll calls looks at the clock.
  void tick(double done) {
    if (--countdown_ == 0) {
      countdown_ = kTicksPerPoll;
      if (terminal_ != nullptr) poll(done);
    }
  }
  // Clears the line (if anything is shown); the next update draws it again. Called before other
  // text goes to the same stream, and when the run ends.
  void clear();
  // Words shown after the count until the next begin() (", 31% of pixels active"): what a stage
  // knows beside its steps.
  void note(std::string text) { note_ = std::move(text); }

  static constexpr std::uint32_t kTicksPerPoll = 4096;

  // The stage any Progress of the process began last ("" before the first): where an
  // out-of-memory error happened.
  static const char* lastStage();

 private:
  using Clock = std::chrono::steady_clock;
  void poll(double done);

  std::FILE* terminal_;
  std::chrono::milliseconds quietStart_;
  std::uint32_t countdown_ = kTicksPerPoll;
  Clock::time_point started_;
  Clock::time_point lastDrawn_{};
  const char* stage_ = "";
  Unit unit_ = Unit::Count;
  double total_ = 0;
  std::size_t shownWidth_ = 0;  // characters on the line now; 0: nothing shown
  std::string line_;
  std::string note_;
};

// The text of the line for a stage at `done` (of `total`): "deriving: step 37/216", followed by
// `note` (Progress::note).
std::string progressLine(const char* stage, Progress::Unit unit, double done, double total,
                         const std::string& note = "");

}  // namespace hirsute
