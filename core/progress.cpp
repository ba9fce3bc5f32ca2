#include "hirsute/core/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace hirsute {
namespace {

// The line is redrawn at most this often.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

// Progress::lastStage(): names are string literals, so the pointer is all there is to keep.
std::atomic<const char*> lastStageBegun{""};

// The line without its note.
std::string countLine(const char* stage, Progress::Unit unit, double done, double total) {
  switch (unit) {
    case Progress::Unit::Steps:
      return fmt::format("{}: step {}/{}", stage, static_cast<long long>(done),
                         static_cast<long long>(total));
    case Progress::Unit::Percent: {
      const double share = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
      // 100% only when it is done: a stage at 99.7% still has work to do.
      return fmt::format("{}: {}%", stage, static_cast<int>(std::floor(share * 100)));
    }
    case Progress::Unit::None:
      return stage;
    case Progress::Unit::Count:
      break;
  }
  if (done >= 1e9) return fmt::format("{}: {:.1f} G", stage, done / 1e9);
  if (done >= 1e6) return fmt::format("{}: {:.1f} M", stage, done / 1e6);
  if (done >= 1e4) return fmt::format("{}: {:.0f} k", stage, done / 1e3);
  return fmt::format("{}: {}", stage, static_cast<long long>(done));
}

}  // namespace

std::string progressLine(const char* stage, Progress::Unit unit, double done, double total,
                         const std::string& note) {
  return countLine(stage, unit, done, total) + note;
}

Progress::Progress(std::FILE* terminal, std::chrono::milliseconds quietStart)
    : terminal_(terminal), quietStart_(quietStart), started_(Clock::now()) {}

Progress Progress::onTerminal(std::FILE* stream) {
  return Progress(stream != nullptr && isatty(fileno(stream)) ? stream : nullptr);
}

Progress::~Progress() {
  clear();
}

const char* Progress::lastStage() {
  return lastStageBegun.load(std::memory_order_relaxed);
}

void Progress::begin(const char* name, Unit unit, double total) {
  stage_ = name;
  lastStageBegun.store(name, std::memory_order_relaxed);
  unit_ = unit;
  total_ = total;
  countdown_ = kTicksPerPoll;
  lastDrawn_ = {};  // a new stage is shown at its first update
  note_.clear();
}

void Progress::poll(double done) {
  const Clock::time_point now = Clock::now();
  if (now - started_ < quietStart_ || now - lastDrawn_ < kRedrawInterval) return;
  lastDrawn_ = now;
  line_ = progressLine(stage_, unit_, done, total_, note_);
  // Spaces cover what is left of a longer line drawn before.
  const std::size_t width = line_.size();
  if (width < shownWidth_) line_.append(shownWidth_ - width, ' ');
  std::fputc('\r', terminal_);
  std::fwrite(line_.data(), 1, line_.size(), terminal_);
  std::fflush(terminal_);
  shownWidth_ = std::max(width, shownWidth_);
}

void Progress::clear() {
  if (terminal_ == nullptr || shownWidth_ == 0) return;
  std::fputc('\r', terminal_);
  for (std::size_t i = 0; i < shownWidth_; ++i) std::fputc(' ', terminal_);
  std::fputc('\r', terminal_);
  std::fflush(terminal_);
  shownWidth_ = 0;
  lastDrawn_ = {};
}

}  // namespace hirsute
