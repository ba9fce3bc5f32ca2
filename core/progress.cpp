#include "hirsute/core/progress.h"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace hirsute {
namespace {

// The line is redrawn at most this often.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
// The heartbeat's redrawing, often enough that the elapsed seconds move one by one.
constexpr auto kHeartbeatInterval = std::chrono::milliseconds(500);
// Between the parts of the line.
constexpr const char* kSeparator = " \u00b7 ";

// Progress::lastStage(): names are string literals, so the pointer is all there is to keep.
std::atomic<const char*> lastStageBegun{""};

// The count of the line, after the stage's name.
std::string countText(Progress::Unit unit, double done, double total, const char* counted) {
  const std::string after = counted != nullptr ? std::string(" ") + counted : std::string();
  switch (unit) {
    case Progress::Unit::Steps:
      if (counted != nullptr) {
        return fmt::format("{}/{}{}", static_cast<long long>(done), static_cast<long long>(total),
                           after);
      }
      return fmt::format("step {}/{}", static_cast<long long>(done), static_cast<long long>(total));
    case Progress::Unit::Percent: {
      const double share = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
      // 100% only when it is done: a stage at 99.7% still has work to do.
      return fmt::format("{}%{}", static_cast<int>(std::floor(share * 100)), after);
    }
    case Progress::Unit::None:
      return "";
    case Progress::Unit::Count:
      break;
  }
  if (done >= 1e9) return fmt::format("{:.1f} G{}", done / 1e9, after);
  if (done >= 1e6) return fmt::format("{:.1f} M{}", done / 1e6, after);
  if (done >= 1e4) return fmt::format("{:.0f} k{}", done / 1e3, after);
  return fmt::format("{}{}", static_cast<long long>(done), after);
}

// The columns `text` takes: its UTF-8 characters (every one here is one column wide).
std::size_t columns(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xc0) != 0x80;
  }));
}

// `text` cut to its first `width` columns, never inside a character.
void cutToColumns(std::string& text, std::size_t width) {
  std::size_t seen = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xc0) == 0x80) continue;
    if (seen++ == width) {
      text.resize(i);
      return;
    }
  }
}

// The terminal's width in columns; 0 when it does not say.
std::size_t terminalWidth(std::FILE* terminal) {
  winsize size{};
  if (ioctl(fileno(terminal), TIOCGWINSZ, &size) != 0) return 0;
  return size.ws_col;
}

}  // namespace

std::string clockText(double seconds) {
  const long long whole = static_cast<long long>(std::max(0.0, std::floor(seconds)));
  if (whole >= 3600)
    return fmt::format("{}:{:02d}:{:02d}", whole / 3600, (whole / 60) % 60, whole % 60);
  return fmt::format("{}:{:02d}", whole / 60, whole % 60);
}

std::string timeLeftText(double seconds) {
  if (seconds < 5) return "a few seconds left";
  const double step = seconds < 60 ? 5 : seconds < 600 ? 10 : 60;
  return "about " + clockText(std::ceil(seconds / step) * step) + " left";
}

std::string durationText(double seconds) {
  if (seconds < 10) return fmt::format("{:.1f} s", std::max(0.0, seconds));
  if (seconds < 60) return fmt::format("{:.0f} s", seconds);
  return clockText(std::round(seconds));
}

std::string progressLine(const ProgressReading& r) {
  std::string line = r.stage;
  const std::string count = countText(r.unit, r.done, r.total, r.counted);
  if (!count.empty()) line += ": " + count;
  line += r.note;
  if (r.elapsed) line += kSeparator + clockText(*r.elapsed) + " elapsed";
  if (r.secondsLeft) line += kSeparator + timeLeftText(*r.secondsLeft);
  return line;
}

Progress::Progress(std::FILE* terminal, std::chrono::milliseconds quietStart)
    : terminal_(terminal),
      quietStart_(quietStart),
      started_(Clock::now()),
      stageStarted_(started_) {}

Progress Progress::onTerminal(std::FILE* stream) {
  return Progress(stream != nullptr && isatty(fileno(stream)) ? stream : nullptr);
}

Progress::~Progress() {
  clear();
}

const char* Progress::lastStage() {
  return lastStageBegun.load(std::memory_order_relaxed);
}

void Progress::begin(const char* name, Unit unit, double total, const char* counted) {
  lastStageBegun.store(name, std::memory_order_relaxed);
  countdown_ = kTicksPerPoll;
  const std::lock_guard lock(mutex_);
  stage_ = name;
  unit_ = unit;
  total_ = total;
  done_ = 0;
  counted_ = counted;
  showsTimeLeft_ = unit == Unit::Steps || unit == Unit::Percent;
  timeLeft_ = TimeLeft();
  stageStarted_ = Clock::now();
  lastDrawn_ = {};  // a new stage is shown at its first update
  note_.clear();
}

void Progress::withoutTimeLeft() {
  const std::lock_guard lock(mutex_);
  showsTimeLeft_ = false;
}

void Progress::note(std::string text) {
  const std::lock_guard lock(mutex_);
  note_ = std::move(text);
}

void Progress::poll(double done, double share) {
  const Clock::time_point now = Clock::now();
  const std::lock_guard lock(mutex_);
  done_ = done;
  if (showsTimeLeft_) {
    if (share < 0) share = total_ > 0 ? done / total_ : 0;
    timeLeft_.add(std::chrono::duration<double>(now - stageStarted_).count(), share);
  }
  if (now - started_ < quietStart_ || now - lastDrawn_ < kRedrawInterval) return;
  draw(now);
}

void Progress::redraw() {
  if (terminal_ == nullptr) return;
  const Clock::time_point now = Clock::now();
  const std::lock_guard lock(mutex_);
  if (now - started_ < quietStart_) return;
  draw(now);
}

void Progress::draw(Clock::time_point now) {
  lastDrawn_ = now;
  ProgressReading reading{stage_,   unit_, done_,        total_,
                          counted_, note_, std::nullopt, std::nullopt};
  reading.elapsed = std::chrono::duration<double>(now - started_).count();
  if (showsTimeLeft_)
    reading.secondsLeft =
        timeLeft_.secondsLeft(std::chrono::duration<double>(now - stageStarted_).count());
  line_ = progressLine(reading);
  // A line longer than the terminal is wide would wrap, and \r would rewrite its last row only.
  if (const std::size_t width = terminalWidth(terminal_); width > 1) cutToColumns(line_, width - 1);
  // Spaces cover what is left of a longer line drawn before.
  const std::size_t width = columns(line_);
  if (width < shownWidth_) line_.append(shownWidth_ - width, ' ');
  std::fputc('\r', terminal_);
  std::fwrite(line_.data(), 1, line_.size(), terminal_);
  std::fflush(terminal_);
  shownWidth_ = std::max(width, shownWidth_);
}

void Progress::clear() {
  if (terminal_ == nullptr) return;
  const std::lock_guard lock(mutex_);
  if (shownWidth_ == 0) return;
  std::fputc('\r', terminal_);
  for (std::size_t i = 0; i < shownWidth_; ++i) std::fputc(' ', terminal_);
  std::fputc('\r', terminal_);
  std::fflush(terminal_);
  shownWidth_ = 0;
  lastDrawn_ = {};
}

ProgressHeartbeat::ProgressHeartbeat(Progress& progress) : progress_(progress) {
  if (!progress_.enabled()) return;
  thread_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, kHeartbeatInterval, [this] { return stopping_; }))
      progress_.redraw();
  });
}

ProgressHeartbeat::~ProgressHeartbeat() {
  if (!thread_.joinable()) return;
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

}  // namespace hirsute
