// `hirsute simulate` on the shipped models: numbered POV-Ray frames and the table of what each
// frame's steps did, no intersection left in any frame, the body of an animation carrying its
// feathers, the wind moving awns on a still body, the same frames from the same run, fur moving
// in the wind, wetted by droplets and rain and drying, and the errors of a model without feathers
// or fur and of bad fur options.
#include <gtest/gtest.h>

#include <algorithm>
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
  const Output out = simulate("coat-bending", "bending.l bending.v bending.a",
                              "--frames 4 --vane-collisions -v", folder_);
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
    EXPECT_NE(rows[r][5], "0") << "frame " << r;  // candidates: the coat is dense
  }
  // The body bends from frame to frame, and so the scenes differ.
  EXPECT_NE(readText(folder_ / "frame-0001.pov"), readText(folder_ / "frame-0004.pov"));
  // The vanes collide (docs/dynamics.md, "Vanes"): candidates every frame, none left meeting.
  EXPECT_NE(out.text.find("vanes colliding"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find(" 0 vane intersections left"), std::string::npos) << out.text;
  ASSERT_EQ(rows[0].size(), 25u);
  EXPECT_EQ(rows[0][16], "vane_candidates");
  EXPECT_EQ(rows[0][19], "vane_intersections_left");
  // The resting stage's columns (docs/dynamics.md, "Resting contacts"): the layered coat holds
  // contacts every step, and the net's searches find fewer contacts than it holds.
  EXPECT_EQ(rows[0][20], "resting_contacts");
  EXPECT_EQ(rows[0][23], "ccd_queries");
  EXPECT_EQ(rows[0][24], "net_contacts");
  for (std::size_t r = 2; r < rows.size(); ++r) {
    EXPECT_NE(rows[r][16], "0") << "frame " << r;
    EXPECT_EQ(rows[r][19], "0") << "frame " << r;
    EXPECT_GT(std::stoll(rows[r][20]), 0) << "frame " << r;
    EXPECT_GT(std::stoll(rows[r][21]), 0) << "frame " << r;  // searches
    EXPECT_LT(std::stoll(rows[r][24]), std::stoll(rows[r][20])) << "frame " << r;
  }
}

// Without vane collisions the same frames have vanes passing through each other (so the test
// above can fail), and no vane is a candidate.
TEST_F(SimulateCommand, WithoutVaneCollisionsTheBendingCoatsVanesPassThrough) {
  const Output out = simulate(
      "coat-bending", "bending.l bending.v bending.a",
      "--frames 4 --no-frames --no-vane-collisions --count-vane-intersections -v", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("vanes not colliding: 0 vane candidates"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("0 left;"), std::string::npos) << out.text;  // the stems still don't
  // The vanes overlapping where the coat is placed are left out of the count.
  EXPECT_NE(out.text.find("118 pairs of segments whose vanes overlapped at the start left out"),
            std::string::npos)
      << out.text;
  const auto rows = table(folder_);
  ASSERT_EQ(rows.size(), 5u);
  int met = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) met += std::stoi(rows[r][19]);
  EXPECT_GT(met, 0);
}

// Vanes that do not collide are counted only when asked: the column stays empty, and the vanes
// overlapping where the coat is placed are not looked for.
TEST_F(SimulateCommand, VanesNotCollidingAreCountedOnlyWhenAsked) {
  const Output out = simulate("coat-bending", "bending.l bending.v bending.a",
                              "--frames 2 --no-frames --no-vane-collisions -v", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("vane intersections not counted"), std::string::npos) << out.text;
  EXPECT_EQ(out.text.find("overlapped at the start"), std::string::npos) << out.text;
  const auto rows = table(folder_);
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), 25u);
    EXPECT_EQ(rows[r][19], "");  // vane_intersections_left
  }
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
  const Output out =
      simulate("coat-bending", "bending.l bending.v", "--animate BEND=0:9 --frames 3", folder_);
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

// A mesh sequence (models/mesh-bird/nod.####.obj, docs/meshes.md) is a moving body: frame k
// draws its k-th mesh, the coat's roots follow its triangles, nothing intersects, and without
// --frames the run is as long as the sequence.
TEST_F(SimulateCommand, AMeshSequenceMovesTheBodyAndItsCoat) {
  const Output out = simulate("mesh-bird", "bird.l nod.v", "--frames 4 -v", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("4 frames of"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("rooted on the body"), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("0 left"), std::string::npos) << out.text;
  EXPECT_NE(readText(folder_ / "frame-0001.pov"), readText(folder_ / "frame-0004.pov"));
  const auto rows = table(folder_);
  ASSERT_EQ(rows.size(), 5u);
  for (std::size_t r = 1; r < rows.size(); ++r) EXPECT_EQ(rows[r][10], "0") << "frame " << r;

  const Output whole = simulate("mesh-bird", "bird.l nod.v", "--no-frames -v", folder_ / "whole");
  ASSERT_EQ(whole.status, 0) << whole.text;
  EXPECT_NE(whole.text.find("12 frames of"), std::string::npos) << whole.text;
}

// The run ends with one short line on standard output; the counts behind it come with -v. Off
// a terminal (a pipe here) nothing else is written: no progress line, no carriage return.
TEST_F(SimulateCommand, TheClosingLineIsShortAndTheCountsComeWithVerbose) {
  const Output out = simulate("fur-square", "square.l square.v", "--frames 3 --no-frames", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  const std::string start = "simulated 3 frames of 625 strands of fur (0.0833 s of motion) in ";
  const std::string end = " \u2192 " + folder_.string() + "/\n";
  ASSERT_GT(out.text.size(), start.size() + end.size()) << out.text;
  EXPECT_EQ(out.text.substr(0, start.size()), start) << out.text;
  EXPECT_EQ(out.text.substr(out.text.size() - end.size()), end) << out.text;
  EXPECT_EQ(std::count(out.text.begin(), out.text.end(), '\n'), 1) << out.text;
  EXPECT_EQ(out.text.find_first_of("\r\x1b"), std::string::npos) << out.text;

  const Output verbose =
      simulate("fur-square", "square.l square.v", "--frames 3 --no-frames -v", folder_);
  ASSERT_EQ(verbose.status, 0) << verbose.text;
  EXPECT_NE(verbose.text.find(start), std::string::npos) << verbose.text;
  EXPECT_NE(verbose.text.find("3 frames of fur (625 strands on 1 surfaces) in "), std::string::npos)
      << verbose.text;
  EXPECT_NE(verbose.text.find(" droplets; at the end a mean bend of "), std::string::npos)
      << verbose.text;
}

TEST_F(SimulateCommand, AModelWithoutFeathersOrFurIsAnError) {
  const Output out = simulate("herb", "herb.l herb.v", "--frames 2", folder_);
  EXPECT_EQ(out.status, 2) << out.text;
  EXPECT_NE(out.text.find("herb.l: error: the model has no feathers or fur to simulate"),
            std::string::npos)
      << out.text;
  EXPECT_FALSE(fs::exists(folder_ / "frame-0001.pov"));
}

// fur.csv's rows as numbers, the header left out; each row has the header's nine columns.
std::vector<std::vector<double>> furTable(const fs::path& folder) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(readText(folder / "fur.csv"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "frame,time,droplets,mean_bend,largest_bend,largest_speed,wet_texels,"
            "mean_wetness,seconds");
  while (std::getline(in, line)) {
    std::vector<double> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
    EXPECT_EQ(cells.size(), 9u) << line;
    rows.push_back(cells);
  }
  return rows;
}

enum FurColumn { kFrame, kTime, kDroplets, kMeanBend, kLargestBend, kSpeed, kWetTexels, kWetness };

// Fur over time (docs/fur.md, "Fur over time"): on the fur square, a wind with gusts bends the
// strands away from rest where without wind they stay at rest; six droplets at frame 2 wet the
// mask; drying from frame 4 makes the wet texels drier frame by frame (0.5 a second at 24 frames
// a second); every frame has its POV-Ray scene, and the fur in the last differs from the first.
TEST_F(SimulateCommand, FurMovesInTheWindAndDropletsWetItAndItDries) {
  const std::string files = "square.l square.v";
  const Output out = simulate("fur-square", files,
                              "--frames 8 --wind 3 0 0 --gusts 1 --drop 2:6 --dry 0.5 "
                              "--dry-from 4 --size 80x60 -v",
                              folder_ / "windy");
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("8 frames of fur (625 strands on 1 surfaces)"), std::string::npos)
      << out.text;
  EXPECT_FALSE(fs::exists(folder_ / "windy" / "simulation.csv"));  // no feathers
  const auto windy = furTable(folder_ / "windy");
  ASSERT_EQ(windy.size(), 8u);
  EXPECT_EQ(windy[0][kMeanBend], 0);
  EXPECT_GT(windy[7][kMeanBend], 0.1);  // a fifth of the way to the fur's bend in this wind
  EXPECT_EQ(windy[0][kWetTexels], 0);
  EXPECT_EQ(windy[1][kDroplets], 6);
  EXPECT_GT(windy[1][kWetTexels], 500);
  EXPECT_EQ(windy[2][kWetness], 1);  // not yet drying
  for (std::size_t k = 3; k < 8; ++k) {
    EXPECT_NEAR(windy[k][kWetness], windy[k - 1][kWetness] - 0.5 / 24, 1e-4) << "frame " << k + 1;
  }
  EXPECT_NE(readText(folder_ / "windy" / "frame-0001.pov"),
            readText(folder_ / "windy" / "frame-0008.pov"));

  ASSERT_EQ(simulate("fur-square", files, "--frames 8 --no-frames", folder_ / "still").status, 0);
  const auto still = furTable(folder_ / "still");
  ASSERT_EQ(still.size(), 8u);
  EXPECT_LT(still[7][kMeanBend], 1e-3);
  EXPECT_EQ(still[7][kWetTexels], 0);
  EXPECT_FALSE(fs::exists(folder_ / "still" / "frame-0001.pov"));
}

// Rain: droplets a second at random, the frame time's share each frame (48 a second over 7
// frame times at 24 frames a second: 14), the same for the same seed and elsewhere for another.
TEST_F(SimulateCommand, RainFallsAtItsRateAndTheSeedPlacesIt) {
  const std::string files = "square.l square.v";
  auto wet = [&](const std::string& options, const std::string& name) {
    const Output out =
        simulate("fur-square", files, "--frames 8 --no-frames " + options, folder_ / name);
    EXPECT_EQ(out.status, 0) << out.text;
    return furTable(folder_ / name);
  };
  const auto rain = wet("--rain 48:0.03", "rain");
  double fallen = 0;
  for (const auto& row : rain) fallen += row[kDroplets];
  EXPECT_EQ(fallen, 14);
  EXPECT_EQ(rain[0][kDroplets], 0);
  const auto again = wet("--rain 48:0.03", "again");
  const auto other = wet("--rain 48:0.03 --drop-seed 5", "other");
  EXPECT_EQ(again.back()[kWetTexels], rain.back()[kWetTexels]);
  EXPECT_NE(other.back()[kWetTexels], rain.back()[kWetTexels]);
}

// A body that moves (the square's side from 4 to 5, rounded: it grows at frame 4) carries its
// fur: the wet patches of frame 1 stay wet and keep drying, and the roots' jump drags the tips
// behind them.
TEST_F(SimulateCommand, AMovingBodyCarriesItsFurAndItsWetness) {
  const Output out =
      simulate("fur-square", "square.l square.v",
               "--frames 6 --animate SIDE=4:5 --drop 1:4 --dry 1 --no-frames", folder_);
  ASSERT_EQ(out.status, 0) << out.text;
  const auto rows = furTable(folder_);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_GT(rows[0][kWetTexels], 500);
  for (std::size_t k = 1; k < 6; ++k) {
    EXPECT_EQ(rows[k][kWetTexels], rows[0][kWetTexels]) << "frame " << k + 1;
    EXPECT_NEAR(rows[k][kWetness], 1 - k / 24.0, 1e-4) << "frame " << k + 1;
  }
  EXPECT_LT(rows[2][kMeanBend], 1e-3);  // still, and no wind
  EXPECT_GT(rows[3][kMeanBend], 0.5);   // the body grew under the fur
}

// Bad droplet and drying options end the run with exit code 2 before any frame, and so do
// droplets past what a run may blend.
TEST_F(SimulateCommand, BadFurOptionsAreBadInput) {
  for (const char* options :
       {"--drop 2", "--drop 0:5", "--drop 2:-1", "--drop 2:5:0", "--drop 2:5:0.1:2", "--drop 2.5:1",
        "--drop 2:nan", "--rain x", "--rain 5:0.1:1:1", "--dry -1", "--dry-from 0",
        "--fur-force 1 2", "--fur-drag inf"}) {
    const Output out =
        simulate("fur-square", "square.l square.v", std::string("--frames 2 ") + options, folder_);
    EXPECT_EQ(out.status, 2) << options << ": " << out.text;
    EXPECT_FALSE(fs::exists(folder_ / "frame-0001.pov")) << options;
  }
  const Output flood = simulate("fur-square", "square.l square.v",
                                "--frames 100 --rain 10000000:1 --no-frames", folder_);
  EXPECT_EQ(flood.status, 2) << flood.text;
  EXPECT_NE(flood.text.find("square.l: error: the run's droplets (--drop, --rain"),
            std::string::npos)
      << flood.text;
}

}  // namespace

// A colour bank past int's range ended the run with std::stoi's out_of_range ("hirsute: error:
// stoi", exit code 1); reproduced through simulate_options_fuzzer. It is bad input like bank 13.
TEST_F(SimulateCommand, AColourBankPastIntIsBadInput) {
  for (const char* bank : {"99999999999", "13"}) {
    const Output out =
        simulate("coat-bending", "bending.l bending.v",
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
  const Output out = simulate("coat-bending", "bending.l bending.v bending.a",
                              "-n 1000000000 --no-frames", folder_);
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
