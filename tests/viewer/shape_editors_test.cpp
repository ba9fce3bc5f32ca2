// The shape editors of `hirsute view` (docs/viewer.md, "The shape editors") end to end in
// scripted mode under a virtual X server: a function point, a contour point and a surface point
// moved by the script change their files as asked and the re-derived picture, undo writes the
// file back as it was, a change the file cannot hold fails with its message, and each editor
// opens on a shipped model. Skips when xvfb-run is not installed.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hirsute/viewer/view/png_image.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Pixels whose colours differ between the two pictures (or within a rectangle of them).
std::size_t differentPixels(const RgbaImage& a, const RgbaImage& b, int x0 = 0, int y0 = 0,
                            int x1 = 1 << 30, int y1 = 1 << 30) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  std::size_t count = 0;
  for (int y = y0; y < std::min({a.height, b.height, y1}); ++y) {
    for (int x = x0; x < std::min({a.width, b.width, x1}); ++x) {
      glm::ivec4 d = glm::ivec4(a.pixel(x, y)) - glm::ivec4(b.pixel(x, y));
      if (std::abs(d.r) + std::abs(d.g) + std::abs(d.b) > 24) ++count;
    }
  }
  return count;
}

class ShapeEditorsTest : public ::testing::Test {
 protected:
  static constexpr int kWidth = 320, kHeight = 240;

  void SetUp() override {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
      GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps.sh installs it)";
    }
    folder_ = fs::temp_directory_path() /
              ("hirsute_shapes_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
               std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "out");
  }
  void TearDown() override {
    if (!folder_.empty()) fs::remove_all(folder_);
  }

  // A copy of a shipped model's folder, to edit.
  fs::path copyModel(const std::string& name) {
    fs::path to = folder_ / name;
    fs::copy(fs::path(HIRSUTE_SOURCE_DIR) / "models" / name, to, fs::copy_options::recursive);
    return to;
  }

  // `hirsute view MODEL --commands SCRIPT` in a virtual X server, as view_command_test.cpp runs
  // it (and tries again when the X server did not start).
  int view(const std::string& arguments, const std::string& script, int width = kWidth,
           int height = kHeight) {
    fs::path out = folder_ / "stdout.txt", err = folder_ / "stderr.txt";
    std::string command = "cd " + (folder_ / "out").string() + " && xvfb-run -a -f " +
                          (folder_ / "Xauthority").string() + " -s '-screen 0 1024x768x24' " +
                          HIRSUTE_BINARY + " view " + arguments + " --no-panel --size " +
                          std::to_string(width) + "x" + std::to_string(height) + " --commands '" +
                          script + "' >" + out.string() + " 2>" + err.string();
    int status = 0;
    for (int attempt = 0; attempt < 3; ++attempt) {
      status = std::system(command.c_str());
      stderr_ = readText(err);
      if (stderr_.find("Xvfb failed to start") == std::string::npos &&
          stderr_.find("LeakSanitizer has encountered a fatal error") == std::string::npos)
        break;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  RgbaImage shot(const std::string& name) { return readPng(folder_ / "out" / name); }

  fs::path folder_;
  std::string stderr_;
};

TEST_F(ShapeEditorsTest, AFunctionPointMovedByTheScriptChangesTheFileAndThePlant) {
  const fs::path herb = copyModel("herb");
  const std::string before = readText(herb / "herb.fset");
  ASSERT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "screenshot before.png; function leafsize point 3 0.5 0.2; "
                 "screenshot after.png; quit"),
            0)
      << stderr_;
  std::string expected = before;
  const std::string row = "0.500000 0.800000 1\n";
  ASSERT_NE(expected.find(row), std::string::npos);
  expected.replace(expected.find(row), row.size(), "0.500000 0.200000 1\n");
  EXPECT_EQ(readText(herb / "herb.fset"), expected) << "only the point's row changes";
  EXPECT_GT(differentPixels(shot("before.png"), shot("after.png")), 200u)
      << "smaller leaves half way up";
}

TEST_F(ShapeEditorsTest, UndoWritesTheFileBackAndAddAndRemoveCountThePoints) {
  const fs::path herb = copyModel("herb");
  const std::string before = readText(herb / "herb.fset");
  ASSERT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "screenshot before.png; function leafsize add 0.6 0.9; function herb remove 2; "
                 "function leafsize undo; function leafsize undo; screenshot undone.png; quit"),
            0)
      << stderr_;
  EXPECT_EQ(readText(herb / "herb.fset"), before);
  EXPECT_EQ(differentPixels(shot("before.png"), shot("undone.png")), 0u);
}

TEST_F(ShapeEditorsTest, AChangeTheFileCannotHoldFailsWithItsReason) {
  const fs::path herb = copyModel("herb");
  const std::string before = readText(herb / "herb.fset");
  EXPECT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "function leafsize point 2 0.9 0.5; quit"),
            1);
  EXPECT_NE(stderr_.find("--commands:1:1: error: x must stay between its neighbours' (0.0 to "
                         "0.5), so that y(x) stays a function"),
            std::string::npos)
      << stderr_;
  EXPECT_EQ(readText(herb / "herb.fset"), before);
  // A name the model does not have is refused with the ones it has.
  EXPECT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "contour leaf point 1 0 0; quit"),
            1);
  EXPECT_NE(stderr_.find("the model has no contour 'leaf' (its contours: none)"), std::string::npos)
      << stderr_;
}

TEST_F(ShapeEditorsTest, AContourPointMovedByTheScriptReshapesTheLeaves) {
  const fs::path leaf = copyModel("hairy-leaf");
  ASSERT_EQ(view((leaf / "hairy-leaf.l").string() + " " + (leaf / "hairy-leaf.v").string(),
                 "screenshot before.png; contour leaf point 4 0 -0.5; screenshot after.png; "
                 "contour leaf.con undo; screenshot undone.png; quit"),
            0)
      << stderr_;
  EXPECT_EQ(readText(leaf / "leaf.con"),
            readText(fs::path(HIRSUTE_SOURCE_DIR) / "models" / "hairy-leaf" / "leaf.con"));
  EXPECT_GT(differentPixels(shot("before.png"), shot("after.png")), 200u);
  EXPECT_EQ(differentPixels(shot("before.png"), shot("undone.png")), 0u);
}

TEST_F(ShapeEditorsTest, ASurfacePointMovedByTheScriptBendsTheLeaves) {
  const fs::path herb = copyModel("herb");
  ASSERT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "screenshot before.png; surface l point 7 -0.6 0.7 0.4; screenshot after.png; "
                 "quit"),
            0)
      << stderr_;
  EXPECT_NE(readText(herb / "leaf.s")
                .find("\n0.00 0.00 0.00  -0.08 0.30 0.10  -0.60 0.70 0.40  0.00 1.00 0.15  \n"),
            std::string::npos);
  EXPECT_GT(differentPixels(shot("before.png"), shot("after.png")), 200u);
}

// Each editor open on a shipped model: the panel is drawn over the plant (the picture with the
// overlays differs from the plant's own where the panel stands), and the files stay untouched.
TEST_F(ShapeEditorsTest, EachEditorOpensOnAShippedModel) {
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  const fs::path leaf = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "hairy-leaf";
  constexpr int kWide = 800, kHigh = 500;
  ASSERT_EQ(view((herb / "herb.l").string() + " " + (herb / "herb.v").string(),
                 "screenshot plant.png; function leafsize open; screenshot function.png ui; "
                 "function leafsize close; surface l open; screenshot surface.png ui; quit",
                 kWide, kHigh),
            0)
      << stderr_;
  ASSERT_EQ(
      view((leaf / "hairy-leaf.l").string() + " " + (leaf / "hairy-leaf.v").string(),
           "screenshot leaf.png; contour leaf open; screenshot contour.png ui; quit", kWide, kHigh),
      0)
      << stderr_;
  // The panels open at the window's right, 400 pixels wide.
  const RgbaImage plant = shot("plant.png");
  EXPECT_GT(differentPixels(plant, shot("function.png"), kWide - 390, 20, kWide - 20, 300), 30000u);
  EXPECT_GT(differentPixels(plant, shot("surface.png"), kWide - 390, 20, kWide - 20, 300), 30000u);
  EXPECT_GT(
      differentPixels(shot("leaf.png"), shot("contour.png"), kWide - 390, 20, kWide - 20, 300),
      30000u);
  // The function panel and the surface panel are not the same picture.
  EXPECT_GT(
      differentPixels(shot("function.png"), shot("surface.png"), kWide - 390, 20, kWide - 20, 300),
      5000u);
}

}  // namespace
}  // namespace hirsute
