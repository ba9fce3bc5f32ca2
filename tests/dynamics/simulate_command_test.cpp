// `hirsute simulate` on the shipped models: numbered POV-Ray frames and the table of what each
// frame's steps did, no intersection left in any frame, the body of an animation carrying its
// feathers, the wind moving awns on a still body, the same frames from the same run, and the
// errors of a model without feathers.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

struct Output {
  std::string text;
  int status = -1;
};

// The command's standard output and error, and its exit status.
Output run(const std::string& command) {
  Output out;
  std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    out.text.append(buffer, n);
  const int status = pclose(pipe);
  out.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

std::string quoted(const fs::path& path) {
  return "'" + path.string() + "'";
}

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The rows of simulation.csv, each split at its commas (the header first).
std::vector<std::vector<std::string>> table(const fs::path& folder) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(readText(folder / "simulation.csv"));
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

class SimulateCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("hirsute_simulate_" + std::to_string(::getpid()) + "_" +
               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  Output simulate(const fs::path& model, const std::string& files, const std::string& options,
                  const fs::path& out) {
    return run("cd " + quoted(kModels / model) + " && " + quoted(HIRSUTE_BINARY) + " simulate " +
               files + " -o " + quoted(out) + " " + options);
  }

  fs::path folder_;
};

TEST_F(SimulateCommand, TheBendingBodyCarriesItsCoatAndNothingIntersects) {
  const Output out =
      simulate("coat-bending", "bending.l bending.v bending.a", "--frames 4", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("4 frames of"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("0 left"), std::string::npos) << out.text;
  for (const char* name : {"frame-0001.pov", "frame-0002.pov", "frame-0003.pov", "frame-0004.pov"})
    EXPECT_TRUE(fs::is_regular_file(folder_ / name)) << name;
  const auto rows = table(folder_);
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0][10], "penetrations");
  for (std::size_t r = 2; r < rows.size(); ++r) {
    // At least the view file's four steps a frame (more for the stiff springs), none halved.
    EXPECT_GE(std::stoi(rows[r][2]), 4) << "frame " << r;
    EXPECT_EQ(rows[r][2], rows[r][3]) << "frame " << r;
    EXPECT_NE(rows[r][5], "0") << "frame " << r;       // candidates: the coat is dense
  }
  // The body bends from frame to frame, and so the scenes differ.
  EXPECT_NE(readText(folder_ / "frame-0001.pov"), readText(folder_ / "frame-0004.pov"));
}

TEST_F(SimulateCommand, WindMovesTheAwnsAndTheSameRunGivesTheSameFrames) {
  const fs::path again = folder_ / "again";
  const std::string files = "feather-grass.l wind.v";
  ASSERT_EQ(simulate("feather-grass", files, "--frames 3 --obj", folder_ / "first").status, 0);
  ASSERT_EQ(simulate("feather-grass", files, "--frames 3 --obj", again).status, 0);
  const std::string frame1 = readText(folder_ / "first" / "frame-0001.pov");
  const std::string frame3 = readText(folder_ / "first" / "frame-0003.pov");
  EXPECT_NE(frame1, frame3);  // the body stays, the awns move
  EXPECT_EQ(frame3, readText(again / "frame-0003.pov"));
  EXPECT_EQ(readText(folder_ / "first" / "frame-0003.obj"), readText(again / "frame-0003.obj"));
  // Other gusts, other frames.
  ASSERT_EQ(simulate("feather-grass", files, "--frames 3 --gust-seed 99", folder_ / "other").status,
            0);
  EXPECT_NE(frame3, readText(folder_ / "other" / "frame-0003.pov"));
}

TEST_F(SimulateCommand, AnAnimatedDefineMovesTheBody) {
  const Output out = simulate("coat-bending", "bending.l bending.v",
                              "--animate BEND=0:9 --frames 3", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(readText(folder_ / "frame-0001.pov"), readText(folder_ / "frame-0003.pov"));
  // The hidden copy that held the frame's value is gone.
  for (const auto& entry : fs::directory_iterator(kModels / "coat-bending"))
    EXPECT_EQ(entry.path().filename().string().find(".hirsute-simulate"), std::string::npos);
  const Output wrong =
      simulate("coat-bending", "bending.l bending.v", "--animate BENDS=0:9 --frames 2", folder_);
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.text.find("--animate takes NAME=FROM:TO"), std::string::npos) << wrong.text;
}

TEST_F(SimulateCommand, AModelWithoutFeathersIsAnError) {
  const Output out = simulate("herb", "herb.l herb.v", "--frames 2", folder_);
  EXPECT_EQ(out.status, 2) << out.text;
  EXPECT_NE(out.text.find("herb.l: error: the model has no feathers to simulate"),
            std::string::npos)
      << out.text;
  EXPECT_FALSE(fs::exists(folder_ / "frame-0001.pov"));
}

}  // namespace

// A colour bank past int's range ended the run with std::stoi's out_of_range ("hirsute: error:
// stoi", exit code 1); reproduced through simulate_options_fuzzer. It is bad input like bank 13.
TEST_F(SimulateCommand, AColourBankPastIntIsBadInput) {
  for (const char* bank : {"99999999999", "13"}) {
    const Output out = simulate("coat-bending", "bending.l bending.v",
                                std::string("--frames 2 -m ") + bank + ":feather-coat.map", folder_);
    EXPECT_EQ(out.status, 2) << bank << ": " << out.text;
    EXPECT_NE(out.text.find(std::string("feather-coat.map: error: colour bank ") + bank +
                            " is outside 1 to 12"),
              std::string::npos)
        << bank << ": " << out.text;
  }
}

// An animation of more frames than the limit is an error before any frame is listed past it (a
// billion steps once listed 40 GB of frames); --frames N takes its first N.
TEST_F(SimulateCommand, AnAnimationOfTooManyFramesIsBadInput) {
  const Output out =
      simulate("coat-bending", "bending.l bending.v bending.a", "-n 1000000000 --no-frames", folder_);
  EXPECT_EQ(out.status, 2) << out.text;
  EXPECT_NE(out.text.find("bending.a: error: the animation has more than 1000000 frames (the "
                          "limit); --frames N draws its first N"),
            std::string::npos)
      << out.text;
}

// Options that are no finite number in range end the run with exit code 2 before a frame is
// written: an earlier run's frames stay as they were.
TEST_F(SimulateCommand, NonFiniteOptionsAreBadInputBeforeAnyFrame) {
  fs::create_directories(folder_);
  std::ofstream(folder_ / "frame-0001.pov") << "// an earlier run\n";
  for (const char* options : {"--fps nan", "--fps inf", "--gravity nan 0 0", "--wind 1e308 0 0",
                              "--gravity 0 -1e12 0", "--drag nan", "--droplet-radius nan"}) {
    const Output out = simulate("coat-bending", "bending.l bending.v",
                                std::string("--frames 2 ") + options, folder_);
    EXPECT_EQ(out.status, 2) << options << ": " << out.text;
    EXPECT_NE(out.text.find("is not a finite number from"), std::string::npos)
        << options << ": " << out.text;
    EXPECT_EQ(readText(folder_ / "frame-0001.pov"), "// an earlier run\n") << options;
  }
}
