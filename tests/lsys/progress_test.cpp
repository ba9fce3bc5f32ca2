// The terminal's progress line (hirsute/core/progress.h): what it says, that it stays silent for
// its first second and off a terminal, and that it leaves the line blank when it is cleared.
#include "hirsute/core/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace hirsute {
namespace {

using namespace std::chrono_literals;

// What has been written to `file` so far.
std::string contents(std::FILE* file) {
  std::fflush(file);
  std::string text;
  const long end = std::ftell(file);
  std::rewind(file);
  text.resize(static_cast<std::size_t>(end));
  if (end > 0) {
    EXPECT_EQ(std::fread(text.data(), 1, text.size(), file), text.size());
  }
  std::fseek(file, 0, SEEK_END);
  return text;
}

class ProgressTest : public testing::Test {
 protected:
  void SetUp() override {
    file_ = std::tmpfile();
    ASSERT_NE(file_, nullptr);
  }
  void TearDown() override { std::fclose(file_); }
  std::FILE* file_ = nullptr;
};

// The line's text for a stage at `done` of `total`, without its clock.
std::string line(const char* stage, Progress::Unit unit, double done, double total,
                 const char* counted = nullptr, std::string note = "") {
  return progressLine(
      {stage, unit, done, total, counted, std::move(note), std::nullopt, std::nullopt});
}

TEST(ProgressLine, NamesTheStageAndHowFarItHasGot) {
  EXPECT_EQ(line("deriving", Progress::Unit::Steps, 37, 216), "deriving: step 37/216");
  EXPECT_EQ(line("interpreting", Progress::Unit::Percent, 45, 100), "interpreting: 45%");
  // Not 100% until it is done, and never past it.
  EXPECT_EQ(line("interpreting", Progress::Unit::Percent, 999, 1000), "interpreting: 99%");
  EXPECT_EQ(line("interpreting", Progress::Unit::Percent, 1500, 1000), "interpreting: 100%");
  EXPECT_EQ(line("writing POV-Ray", Progress::Unit::Percent, 3, 5), "writing POV-Ray: 60%");
  EXPECT_EQ(line("placing hairs", Progress::Unit::Count, 1.23e6, 0), "placing hairs: 1.2 M");
  EXPECT_EQ(line("placing hairs", Progress::Unit::Count, 45'600, 0), "placing hairs: 46 k");
  EXPECT_EQ(line("placing hairs", Progress::Unit::Count, 812, 0), "placing hairs: 812");
  EXPECT_EQ(line("rendering", Progress::Unit::None, 0, 0), "rendering");
  EXPECT_EQ(line("tracing", Progress::Unit::Steps, 40, 256, nullptr, ", 31% of pixels active"),
            "tracing: step 40/256, 31% of pixels active");
}

TEST(ProgressLine, CountsInTheUnitTheUserKnows) {
  EXPECT_EQ(line("tracing", Progress::Unit::Steps, 17, 48, "samples a pixel"),
            "tracing: 17/48 samples a pixel");
  EXPECT_EQ(line("simulating", Progress::Unit::Steps, 12, 120, "frames"),
            "simulating: 12/120 frames");
  EXPECT_EQ(line("rendering with POV-Ray", Progress::Unit::Percent, 45, 100, "of the pixels"),
            "rendering with POV-Ray: 45% of the pixels");
  EXPECT_EQ(line("rendering frames", Progress::Unit::Steps, 3, 10, "frames", ", 1 failed"),
            "rendering frames: 3/10 frames, 1 failed");
}

TEST(ProgressLine, GivesTheTimeElapsedAndTheTimeLeft) {
  ProgressReading reading{"tracing", Progress::Unit::Steps, 17, 48, "samples a pixel", "", 42.7,
                          70};
  EXPECT_EQ(progressLine(reading),
            "tracing: 17/48 samples a pixel \u00b7 0:42 elapsed \u00b7 about 1:10 left");
  // Before enough is known, the time elapsed alone.
  reading.secondsLeft.reset();
  EXPECT_EQ(progressLine(reading), "tracing: 17/48 samples a pixel \u00b7 0:42 elapsed");
  EXPECT_EQ(progressLine({"rendering with OpenGL", Progress::Unit::None, 0, 0, nullptr, "", 3725,
                          std::nullopt}),
            "rendering with OpenGL \u00b7 1:02:05 elapsed");
}

TEST(ProgressLine, ClockTextInSecondsMinutesAndHours) {
  EXPECT_EQ(clockText(0), "0:00");
  EXPECT_EQ(clockText(42.9), "0:42");
  EXPECT_EQ(clockText(70), "1:10");
  EXPECT_EQ(clockText(12 * 60 + 5), "12:05");
  EXPECT_EQ(clockText(3600 + 2 * 60 + 3), "1:02:03");
  EXPECT_EQ(clockText(-3), "0:00");
}

TEST(ProgressLine, TheTimeLeftIsRoundedAsAnEstimateDeserves) {
  EXPECT_EQ(timeLeftText(3), "a few seconds left");
  EXPECT_EQ(timeLeftText(4.9), "a few seconds left");
  EXPECT_EQ(timeLeftText(9), "about 0:10 left");
  EXPECT_EQ(timeLeftText(41), "about 0:45 left");  // to 5 s under a minute
  EXPECT_EQ(timeLeftText(45), "about 0:45 left");
  EXPECT_EQ(timeLeftText(63), "about 1:10 left");    // to 10 s under ten minutes
  EXPECT_EQ(timeLeftText(754), "about 13:00 left");  // to the minute beyond
  EXPECT_EQ(timeLeftText(3725), "about 1:03:00 left");
}

TEST(ProgressLine, ARunsLengthForItsSummary) {
  EXPECT_EQ(durationText(0.42), "0.4 s");
  EXPECT_EQ(durationText(12.3), "12 s");
  EXPECT_EQ(durationText(123.4), "2:03");
  EXPECT_EQ(durationText(3723), "1:02:03");
}

TEST_F(ProgressTest, NothingIsShownInTheFirstSecond) {
  Progress progress(file_);
  progress.begin("deriving", Progress::Unit::Steps, 10);
  for (int step = 1; step <= 10; ++step) progress.update(step);
  for (int i = 0; i < 100'000; ++i) progress.tick(i);
  progress.clear();
  EXPECT_EQ(contents(file_), "");
}

TEST_F(ProgressTest, WithoutATerminalNothingIsShownAtAll) {
  Progress progress(nullptr, 0ms);
  EXPECT_FALSE(progress.enabled());
  progress.begin("deriving", Progress::Unit::Steps, 10);
  progress.update(3);
  // A file is no terminal: onTerminal reports nowhere.
  Progress onFile = Progress::onTerminal(file_);
  EXPECT_FALSE(onFile.enabled());
  onFile.begin("deriving", Progress::Unit::Steps, 10);
  onFile.update(3);
  onFile.clear();
  EXPECT_EQ(contents(file_), "");
}

// What follows each line drawn within the run's first second.
const std::string kNoTime = " \u00b7 0:00 elapsed";

TEST_F(ProgressTest, AfterTheQuietStartTheLineIsRewrittenInPlaceAndCleared) {
  const std::string first = "\rderiving: step 37/216" + kNoTime;
  const std::string second = "\rderiving: step 38/216" + kNoTime;
  {
    Progress progress(file_, 0ms);
    progress.begin("deriving", Progress::Unit::Steps, 216);
    progress.withoutTimeLeft();
    progress.update(37);
    EXPECT_EQ(contents(file_), first);
    // A tenth of a second between two drawings.
    progress.update(38);
    EXPECT_EQ(contents(file_), first);
    std::this_thread::sleep_for(110ms);
    progress.update(38);
    EXPECT_EQ(contents(file_), first + second);
    // A new stage is drawn at once, a shorter line padded over the longer one (in columns:
    // the separator is two bytes of UTF-8 and one column).
    progress.begin("writing", Progress::Unit::None);
    progress.update(0);
    EXPECT_EQ(contents(file_), first + second + "\rwriting" + kNoTime + std::string(14, ' '));
  }
  // Destroyed: the line is blanked and the cursor back at its start.
  const std::string text = contents(file_);
  EXPECT_EQ(text.substr(text.size() - 38), "\r" + std::string(36, ' ') + "\r");
}

TEST_F(ProgressTest, ANoteFollowsTheCountUntilTheNextStage) {
  Progress progress(file_, 0ms);
  progress.begin("tracing", Progress::Unit::Steps, 64, "samples a pixel");
  progress.note(", 31% of pixels active");
  progress.update(2);
  const std::string first = "\rtracing: 2/64 samples a pixel, 31% of pixels active" + kNoTime;
  EXPECT_EQ(contents(file_), first);
  progress.begin("writing", Progress::Unit::None);
  progress.update(0);
  EXPECT_EQ(contents(file_).substr(first.size()), "\rwriting" + kNoTime + std::string(44, ' '));
}

TEST_F(ProgressTest, TheTimeLeftShowsOnceEnoughOfTheStageIsDone) {
  Progress progress(file_, 0ms);
  progress.begin("simulating", Progress::Unit::Steps, 1000, "frames");
  progress.update(1);  // 0.1%: nothing to go by
  EXPECT_EQ(contents(file_), "\rsimulating: 1/1000 frames" + kNoTime);
  std::this_thread::sleep_for(110ms);
  // Half done in a tenth of a second: as much again is left, a few seconds.
  progress.update(500);
  std::string text = contents(file_);
  EXPECT_EQ(text.substr(text.rfind('\r')),
            "\rsimulating: 500/1000 frames" + kNoTime + " \u00b7 a few seconds left");
  // A derivation's steps give none.
  progress.begin("deriving", Progress::Unit::Steps, 10);
  progress.withoutTimeLeft();
  progress.update(5);
  text = contents(file_);
  const std::string last = text.substr(text.rfind('\r'));
  EXPECT_EQ(last.substr(0, last.find_last_not_of(' ') + 1), "\rderiving: step 5/10" + kNoTime);
}

TEST_F(ProgressTest, TickLooksAtTheClockOnlyEveryFewThousandCalls) {
  Progress progress(file_, 0ms);
  progress.begin("placing hairs", Progress::Unit::Count);
  for (std::uint32_t i = 1; i < Progress::kTicksPerPoll; ++i) progress.tick(i);
  EXPECT_EQ(contents(file_), "");
  progress.tick(Progress::kTicksPerPoll);
  EXPECT_EQ(contents(file_), "\rplacing hairs: 4096" + kNoTime);
}

TEST_F(ProgressTest, AHeartbeatKeepsTheClockMovingThroughACallThatSaysNothing) {
  Progress progress(file_, 0ms);
  progress.begin("rendering with OpenGL", Progress::Unit::None);
  {
    ProgressHeartbeat heartbeat(progress);
    std::this_thread::sleep_for(1200ms);  // a call that reports nothing
  }
  const std::string text = contents(file_);
  EXPECT_NE(text.find("\rrendering with OpenGL \u00b7 0:00 elapsed"), std::string::npos) << text;
  EXPECT_NE(text.find("\rrendering with OpenGL \u00b7 0:01 elapsed"), std::string::npos) << text;
  // Gone with the call: nothing more is drawn.
  std::this_thread::sleep_for(600ms);
  EXPECT_EQ(contents(file_), text);
}

TEST_F(ProgressTest, AHeartbeatOffATerminalStartsNothing) {
  Progress progress(nullptr, 0ms);
  ProgressHeartbeat heartbeat(progress);
  progress.begin("rendering with OpenGL", Progress::Unit::None);
  progress.redraw();
  EXPECT_EQ(contents(file_), "");
}

}  // namespace
}  // namespace hirsute
