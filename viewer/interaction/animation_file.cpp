#include "hirsute/viewer/interaction/animation_file.h"

#include <cctype>
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>

namespace hirsute {
namespace {

struct LineReader {
  const std::string& text;  // the value, after the colon
  std::size_t at;
  SourceLocation where;  // of the line; the column is set for each error
  int valueColumn;       // column of text[0]

  [[noreturn]] void fail(const std::string& message) const {
    SourceLocation here = where;
    here.column = valueColumn + static_cast<int>(at);
    throw DiagnosticError(here, message);
  }
  void skipSpaces() {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  }
  bool atEnd() {
    skipSpaces();
    return at >= text.size();
  }
  bool accept(char c) {
    skipSpaces();
    if (at < text.size() && text[at] == c) {
      ++at;
      return true;
    }
    return false;
  }
  bool acceptWord(const std::string& word) {
    skipSpaces();
    if (text.compare(at, word.size(), word) == 0) {
      at += word.size();
      return true;
    }
    return false;
  }
  int integer(const char* what) {
    skipSpaces();
    int value = 0;
    auto [end, error] = std::from_chars(text.data() + at, text.data() + text.size(), value);
    if (error != std::errc()) fail(std::string("expected ") + what + ", an integer");
    at = static_cast<std::size_t>(end - text.data());
    return value;
  }
  float number(const char* what) {
    skipSpaces();
    const char* begin = text.c_str() + at;
    char* end = nullptr;
    float value = std::strtof(begin, &end);
    if (end == begin) fail(std::string("expected ") + what + ", a number");
    at += static_cast<std::size_t>(end - begin);
    return value;
  }
  bool flag() {
    if (acceptWord("on")) return true;
    if (acceptWord("off")) return false;
    fail("expected on or off");
  }
  void end() {
    if (!atEnd()) fail("unexpected text after the value");
  }
};

// `1, 3-5, 10-16 step 2, 11-100 rotate 1.5 0 0, 1-100 scale 0.9 0.9 0.9`
std::vector<FrameInterval> frameIntervals(LineReader& r) {
  std::vector<FrameInterval> intervals;
  do {
    FrameInterval interval;
    interval.first = interval.last = r.integer("a frame number");
    if (r.accept('-')) interval.last = r.integer("the last frame of the range");
    if (interval.last < interval.first) r.fail("a range must not end before it starts");
    if (r.acceptWord("step")) {
      interval.step = r.integer("the step");
      if (interval.step < 1) r.fail("the step must be at least 1");
    } else if (r.acceptWord("rotate")) {
      glm::vec3 angles;
      for (int i = 0; i < 3; ++i) angles[i] = r.number("an angle");
      interval.rotate = angles;
    } else if (r.acceptWord("scale")) {
      glm::vec3 factors;
      for (int i = 0; i < 3; ++i) factors[i] = r.number("a scale factor");
      interval.scale = factors;
    }
    intervals.push_back(interval);
  } while (r.accept(','));
  r.end();
  return intervals;
}

}  // namespace

AnimationSettings parseAnimationText(const std::string& text, const std::string& fileName,
                                     Diagnostics& diagnostics) {
  AnimationSettings settings;
  auto name = std::make_shared<const std::string>(fileName);
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos) continue;
    std::size_t colon = line.find(':');
    SourceLocation where{name, lineNumber, static_cast<int>(start) + 1};
    if (colon == std::string::npos) {
      diagnostics.warn(where, "a line without a label: ignored");
      continue;
    }
    std::string label = line.substr(start, colon - start);
    while (!label.empty() && std::isspace(static_cast<unsigned char>(label.back())))
      label.pop_back();
    std::string value = line.substr(colon + 1);
    LineReader r{value, 0, where, static_cast<int>(colon) + 2};
    if (label == "first frame") {
      settings.firstFrame = r.integer("the first frame");
      r.end();
    } else if (label == "last frame") {
      int last = r.integer("the last frame");
      r.end();
      // cpfg's own files write -1 for "the derivation length".
      if (last >= 0)
        settings.lastFrame = last;
      else
        settings.lastFrame.reset();
    } else if (label == "step") {
      settings.step = r.integer("the step");
      if (settings.step < 1) {
        r.at = 0;
        r.fail("the step must be at least 1");
      }
      r.end();
    } else if (label == "swap interval") {
      float tenths = r.number("the swap interval in tenths of a second");
      r.end();
      settings.swapIntervalSeconds = tenths > 0 ? tenths / 10.0 : 0;
    } else if (label == "clear between frames") {
      settings.clearBetweenFrames = r.flag();
      r.end();
    } else if (label == "scale between frames") {
      settings.scaleBetweenFrames = r.flag();
      r.end();
    } else if (label == "new view between frames") {
      settings.newViewBetweenFrames = r.flag();
      r.end();
    } else if (label == "double buffer") {
      settings.doubleBuffer = r.flag();
      r.end();
    } else if (label == "frame intervals") {
      settings.frameIntervals = frameIntervals(r);
    } else if (label == "center between frames" || label == "hcenter between frames" ||
               label == "display on request" || label == "frame numbers") {
      // cpfg's and lpfg's labels that change nothing in this viewer.
    } else {
      diagnostics.warn(where, "unknown animation label '" + label + "': ignored");
    }
  }
  return settings;
}

AnimationSettings readAnimationFile(const std::filesystem::path& file, Diagnostics& diagnostics) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
                          "cannot open the animation file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parseAnimationText(text.str(), file.string(), diagnostics);
}

std::vector<AnimationFrame> animationFrames(const AnimationSettings& settings,
                                            int derivationLength) {
  std::vector<AnimationFrame> frames;
  // The frames first, first + step, … up to last and the derivation length. Counted in 64 bits:
  // a step near INT_MAX past the last frame must not wrap, and a range that starts far below 0
  // starts at its first frame from 0 instead of walking up to it.
  const auto addRange = [&](int first, int last, int step, const FrameInterval* interval) {
    const std::int64_t by = std::max(step, 1);
    const std::int64_t end = std::min(last, derivationLength);
    std::int64_t f = first;
    if (f < 0) f += (-f + by - 1) / by * by;
    for (; f <= end && frames.size() <= kMaxAnimationFrames; f += by) {
      AnimationFrame frame;
      frame.step = static_cast<int>(f);
      if (interval) {
        frame.rotateAfter = interval->rotate;
        frame.scaleAfter = interval->scale;
      }
      frames.push_back(frame);
    }
  };
  if (!settings.frameIntervals.empty()) {
    for (const FrameInterval& interval : settings.frameIntervals)
      addRange(interval.first, interval.last, interval.step, &interval);
    return frames;
  }
  addRange(std::max(settings.firstFrame, 0), settings.lastFrame.value_or(derivationLength),
           settings.step, nullptr);
  return frames;
}

}  // namespace hirsute
