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

TEST(ProgressLine, NamesTheStageAndHowFarItHasGot) {
  EXPECT_EQ(progressLine("deriving", Progress::Unit::Steps, 37, 216), "deriving: step 37/216");
  EXPECT_EQ(progressLine("interpreting", Progress::Unit::Percent, 45, 100), "interpreting: 45%");
  // Not 100% until it is done, and never past it.
  EXPECT_EQ(progressLine("interpreting", Progress::Unit::Percent, 999, 1000), "interpreting: 99%");
  EXPECT_EQ(progressLine("interpreting", Progress::Unit::Percent, 1500, 1000),
            "interpreting: 100%");
  EXPECT_EQ(progressLine("writing POV-Ray", Progress::Unit::Percent, 3, 5), "writing POV-Ray: 60%");
  EXPECT_EQ(progressLine("placing hairs", Progress::Unit::Count, 1.23e6, 0),
            "placing hairs: 1.2 M");
  EXPECT_EQ(progressLine("placing hairs", Progress::Unit::Count, 45'600, 0), "placing hairs: 46 k");
  EXPECT_EQ(progressLine("placing hairs", Progress::Unit::Count, 812, 0), "placing hairs: 812");
  EXPECT_EQ(progressLine("rendering", Progress::Unit::None, 0, 0), "rendering");
  EXPECT_EQ(progressLine("tracing", Progress::Unit::Steps, 40, 256, ", 31% of pixels active"),
            "tracing: step 40/256, 31% of pixels active");
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

TEST_F(ProgressTest, AfterTheQuietStartTheLineIsRewrittenInPlaceAndCleared) {
  {
    Progress progress(file_, 0ms);
    progress.begin("deriving", Progress::Unit::Steps, 216);
    progress.update(37);
    EXPECT_EQ(contents(file_), "\rderiving: step 37/216");
    // A tenth of a second between two drawings.
    progress.update(38);
    EXPECT_EQ(contents(file_), "\rderiving: step 37/216");
    std::this_thread::sleep_for(110ms);
    progress.update(38);
    EXPECT_EQ(contents(file_), "\rderiving: step 37/216\rderiving: step 38/216");
    // A new stage is drawn at once, a shorter line padded over the longer one.
    progress.begin("interpreting", Progress::Unit::Percent, 200);
    progress.update(90);
    EXPECT_EQ(contents(file_),
              "\rderiving: step 37/216\rderiving: step 38/216\rinterpreting: 45%    ");
  }
  // Destroyed: the line is blanked and the cursor back at its start.
  const std::string text = contents(file_);
  EXPECT_EQ(text.substr(text.size() - 23), "\r" + std::string(21, ' ') + "\r");
}

TEST_F(ProgressTest, ANoteFollowsTheCountUntilTheNextStage) {
  Progress progress(file_, 0ms);
  progress.begin("tracing", Progress::Unit::Steps, 64);
  progress.note(", 31% of pixels active");
  progress.update(20);
  EXPECT_EQ(contents(file_), "\rtracing: step 20/64, 31% of pixels active");
  progress.begin("writing", Progress::Unit::None);
  progress.update(0);
  EXPECT_EQ(contents(file_).substr(42), "\rwriting" + std::string(34, ' '));
}

TEST_F(ProgressTest, TickLooksAtTheClockOnlyEveryFewThousandCalls) {
  Progress progress(file_, 0ms);
  progress.begin("placing hairs", Progress::Unit::Count);
  for (std::uint32_t i = 1; i < Progress::kTicksPerPoll; ++i) progress.tick(i);
  EXPECT_EQ(contents(file_), "");
  progress.tick(Progress::kTicksPerPoll);
  EXPECT_EQ(contents(file_), "\rplacing hairs: 4096");
}

}  // namespace
}  // namespace hirsute
