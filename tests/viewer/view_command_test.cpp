// `hirsute view` end to end in scripted mode, under a virtual X server (xvfb-run): the window
// draws the plant, the mouse's and the keys' actions change the picture, an edit of the model
// on disk re-derives it (and a broken edit keeps the last good plant), the animation reaches its
// last frame, and the constants panel's values are applied and saved. Skips when xvfb-run is
// not installed (scripts/install-deps.sh installs it, as CI does).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "hirsute/viewer/view/png_image.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeText(const fs::path& file, const std::string& text) {
  // Written beside and renamed, as editors save.
  fs::path temporary = file;
  temporary += ".tmp~";
  std::ofstream(temporary, std::ios::binary | std::ios::trunc) << text;
  fs::rename(temporary, file);
}

// Pixels that differ from the top-left corner's colour (the background).
std::size_t plantPixels(const RgbaImage& image) {
  glm::u8vec4 background = image.pixel(0, 0);
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      glm::ivec4 d = glm::ivec4(image.pixel(x, y)) - glm::ivec4(background);
      if (std::abs(d.r) + std::abs(d.g) + std::abs(d.b) > 24) ++count;
    }
  }
  return count;
}

std::size_t differentPixels(const RgbaImage& a, const RgbaImage& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  std::size_t count = 0;
  for (int y = 0; y < std::min(a.height, b.height); ++y) {
    for (int x = 0; x < std::min(a.width, b.width); ++x) {
      glm::ivec4 d = glm::ivec4(a.pixel(x, y)) - glm::ivec4(b.pixel(x, y));
      if (std::abs(d.r) + std::abs(d.g) + std::abs(d.b) > 24) ++count;
    }
  }
  return count;
}

class ViewCommandTest : public ::testing::Test {
 protected:
  static constexpr int kWidth = 320, kHeight = 240;
  static constexpr std::size_t kPixels = kWidth * kHeight;

  void SetUp() override {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
      GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps.sh installs it)";
    }
    folder_ = fs::temp_directory_path() /
              ("hirsute_view_" +
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
  static fs::path shipped(const std::string& name) {
    return fs::path(HIRSUTE_SOURCE_DIR) / "models" / name;
  }

  // Runs `hirsute view ARGS --commands SCRIPT` in a virtual X server; returns the exit code and
  // keeps standard output and error.
  int view(const std::string& arguments, const std::string& script) {
    fs::path out = folder_ / "stdout.txt", err = folder_ / "stderr.txt";
    std::string command = "cd " + (folder_ / "out").string() + " && xvfb-run -a -f " +
                          (folder_ / "Xauthority").string() + " -s '-screen 0 1024x768x24' " +
                          HIRSUTE_BINARY + " view " + arguments + " --size " +
                          std::to_string(kWidth) + "x" + std::to_string(kHeight) + " --commands '" +
                          script + "' >" + out.string() + " 2>" + err.string();
    int status = 0;
    // Another xvfb-run started at the same moment (another program's tests) may take the display
    // number this one chose; the server then fails to start, and trying again is safe. So is a
    // run whose LeakSanitizer tracer crashed while stopping Mesa's threads at exit (a failure of
    // the sanitizer, not a leak, which reads "detected memory leaks"). The authority file is the
    // test's own: without -f, xvfb-run keeps it in a temporary folder of its own, and when it
    // cannot remove that folder after the run it exits with 5, losing the viewer's status.
    for (int attempt = 0; attempt < 3; ++attempt) {
      status = std::system(command.c_str());
      stdout_ = readText(out);
      stderr_ = readText(err);
      if (stderr_.find("Xvfb failed to start") == std::string::npos &&
          stderr_.find("LeakSanitizer has encountered a fatal error") == std::string::npos)
        break;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  RgbaImage shot(const std::string& name) { return readPng(folder_ / "out" / name); }

  // Waits until the viewer has written `name` (it runs on another thread).
  bool waitForShot(const std::string& name) {
    for (int i = 0; i < 600; ++i) {
      if (fs::exists(folder_ / "out" / name)) return true;
      std::this_thread::sleep_for(50ms);
    }
    return false;
  }

  fs::path folder_;
  std::string stdout_, stderr_;
};

TEST_F(ViewCommandTest, DrawsThePlantAndRotateAndStepChangeThePicture) {
  fs::path herb = shipped("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "screenshot first.png; rotate 90 0; screenshot turned.png; reset; step -8; "
                 "screenshot younger.png; step 8; screenshot again.png; wireframe on; "
                 "screenshot wires.png; quit"),
            0)
      << stderr_;
  RgbaImage first = shot("first.png");
  ASSERT_EQ(first.width, kWidth);
  ASSERT_EQ(first.height, kHeight);
  std::size_t plant = plantPixels(first);
  EXPECT_GT(plant, kPixels / 50) << "the plant is drawn";
  EXPECT_LT(plant, kPixels / 2);
  EXPECT_GT(differentPixels(first, shot("turned.png")), plant / 5) << "rotate turns it";
  EXPECT_LT(plantPixels(shot("younger.png")), plant * 3 / 4) << "eight steps back is smaller";
  EXPECT_EQ(differentPixels(first, shot("again.png")), 0u) << "and forward again the same";
  EXPECT_GT(differentPixels(first, shot("wires.png")), 0u) << "wireframe changes it";
}

TEST_F(ViewCommandTest, TheSamePictureAsHirsuteRender) {
  fs::path herb = shipped("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model, "screenshot view.png; quit"), 0) << stderr_;
  std::string render = std::string(HIRSUTE_BINARY) + " render " + model + " --size " +
                       std::to_string(kWidth) + "x" + std::to_string(kHeight) + " -o " +
                       (folder_ / "out" / "render.png").string();
  ASSERT_EQ(std::system(render.c_str()), 0);
  // One renderer, one camera: only antialiasing may differ along edges.
  EXPECT_LT(differentPixels(shot("view.png"), shot("render.png")), kPixels / 100);
}

TEST_F(ViewCommandTest, EditingTheModelOnDiskRederivesKeepingTheCamera) {
  fs::path herb = copyModel("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  int code = -1;
  std::thread viewer([&] {
    code = view(model,
                "rotate 30 0; screenshot before.png; wait-reload 30; screenshot after.png; "
                "rotate -30 0; screenshot after_front.png; quit");
  });
  bool started = waitForShot("before.png");
  if (started) {
    std::string text = readText(herb / "herb.l");
    text.replace(text.find("#define BRANCH_ANGLE 40"), 23, "#define BRANCH_ANGLE 75");
    writeText(herb / "herb.l", text);
  }
  viewer.join();
  ASSERT_TRUE(started) << stderr_;
  ASSERT_EQ(code, 0) << stderr_;
  EXPECT_GT(differentPixels(shot("before.png"), shot("after.png")), kPixels / 100);
  // The camera was kept: turning back gives the edited plant from the front, which is not the
  // picture a fresh window would show turned.
  EXPECT_GT(differentPixels(shot("after.png"), shot("after_front.png")), kPixels / 100);
}

TEST_F(ViewCommandTest, ABrokenEditShowsItsLocationAndKeepsTheLastGoodPlant) {
  fs::path herb = copyModel("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  int code = -1;
  std::thread viewer([&] {
    code = view(model, "screenshot good.png; wait-reload 30; screenshot broken.png; quit");
  });
  bool started = waitForShot("good.png");
  if (started) {
    std::string text = readText(herb / "herb.l");
    text.replace(text.find("B(order) --> *"), 14, "B(order --> *");
    writeText(herb / "herb.l", text);
  }
  viewer.join();
  ASSERT_TRUE(started) << stderr_;
  EXPECT_EQ(code, 2) << "the model shown last has an error";
  EXPECT_NE(stderr_.find("herb.l:25:2: error:"), std::string::npos) << stderr_;
  // The plant stays on screen (the screenshot leaves the overlays out).
  EXPECT_EQ(differentPixels(shot("good.png"), shot("broken.png")), 0u);
}

// Pixels in the error message's colour (overlays.cpp: a light red).
std::size_t errorColouredPixels(const RgbaImage& image) {
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      glm::ivec4 p = glm::ivec4(image.pixel(x, y));
      if (p.r > 180 && p.g < 150 && p.b < 150 && p.r - p.g > 70) ++count;
    }
  }
  return count;
}

// The window shows a broken save's error within a second, with no input event: `screenshot …
// shown` reads what is on the screen without drawing it again.
TEST_F(ViewCommandTest, ABrokenSaveShowsItsErrorOnTheScreenWithoutInput) {
  fs::path herb = copyModel("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  int code = -1;
  std::thread viewer([&] {
    code = view(model,
                "sleep 0.5; screenshot good.png shown; wait-reload 30; sleep 1; "
                "screenshot broken.png shown; quit");
  });
  bool started = waitForShot("good.png");
  if (started) {
    std::string text = readText(herb / "herb.l");
    text.replace(text.find("B(order) --> *"), 14, "B(order --> *");
    writeText(herb / "herb.l", text);
  }
  viewer.join();
  ASSERT_TRUE(started) << stderr_;
  EXPECT_EQ(code, 2) << stderr_;
  const std::size_t before = errorColouredPixels(shot("good.png"));
  const std::size_t after = errorColouredPixels(shot("broken.png"));
  EXPECT_GT(after, before + 100) << "the error is not on the screen: " << before << " then "
                                 << after << " pixels in its colour";
}

TEST_F(ViewCommandTest, TheAnimationRunsToItsLastFrame) {
  fs::path herb = shipped("herb");
  std::string model =
      (herb / "herb.l").string() + " " + (herb / "herb.v").string() + " " +
      (fs::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/viewer/herb_short.a").string();
  ASSERT_EQ(view(model,
                 "goto 10; animate; screenshot animated.png; goto 3; screenshot three.png; "
                 "goto 14; screenshot full.png; quit"),
            0)
      << stderr_;
  EXPECT_EQ(differentPixels(shot("animated.png"), shot("three.png")), 0u);
  EXPECT_GT(differentPixels(shot("animated.png"), shot("full.png")), kPixels / 100);
}

TEST_F(ViewCommandTest, ConstantsAreAppliedAndSavedIntoTheFile) {
  fs::path herb = copyModel("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "screenshot default.png; define BRANCH_ANGLE 80; screenshot wide.png; "
                 "save; quit"),
            0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("default.png"), shot("wide.png")), kPixels / 100);
  std::string text = readText(herb / "herb.l");
  EXPECT_NE(text.find("#define BRANCH_ANGLE 80\n"), std::string::npos);
  EXPECT_EQ(text.size(), readText(shipped("herb") / "herb.l").size());
  // No hidden copy is left behind.
  for (const auto& entry : fs::directory_iterator(herb)) {
    EXPECT_NE(entry.path().filename().string()[0], '.') << entry.path();
  }
}

TEST_F(ViewCommandTest, WithSaveAChangedConstantGoesIntoTheFileAtOnce) {
  fs::path herb = copyModel("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model + " --save", "define LEAF_STEPS 3; screenshot saved.png; quit"), 0)
      << stderr_;
  EXPECT_NE(readText(herb / "herb.l").find("#define LEAF_STEPS 3\n"), std::string::npos);
}

TEST_F(ViewCommandTest, AWaitWithoutAChangeFails) {
  fs::path herb = shipped("herb");
  EXPECT_EQ(view((herb / "herb.l").string(), "wait-reload 0.3; quit"), 1);
  EXPECT_NE(stderr_.find("--commands:1:1: error: no model file changed within the time given"),
            std::string::npos)
      << stderr_;
}

TEST_F(ViewCommandTest, HairsCanBeHidden) {
  fs::path model = shipped("hairy-cylinder");
  ASSERT_EQ(
      view((model / "hairy-cylinder.l").string() + " " + (model / "hairy-cylinder.v").string(),
           "screenshot hairy.png; hairs off; screenshot bare.png; quit"),
      0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("hairy.png"), shot("bare.png")), kPixels / 200);
}

TEST_F(ViewCommandTest, FeathersCanBeHidden) {
  fs::path model = shipped("feather-types");
  ASSERT_EQ(view((model / "feather-types.l").string() + " " + (model / "feather-types.v").string(),
                 "screenshot feathers.png; feathers off; screenshot bare.png; quit"),
            0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("feathers.png"), shot("bare.png")), kPixels / 200);
}

// The D key's simulation, from a script: the awns of feather grass in the wind move, and pausing
// it leaves them where they are.
TEST_F(ViewCommandTest, TheFeathersMoveWhileTheDynamicsRuns) {
  fs::path model = shipped("feather-grass");
  ASSERT_EQ(view((model / "feather-grass.l").string() + " " + (model / "wind.v").string(),
                 "screenshot still.png; dynamics on; sleep 1.5; dynamics off; "
                 "screenshot moved.png; sleep 0.5; screenshot paused.png; quit"),
            0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("still.png"), shot("moved.png")), kPixels / 500);
  EXPECT_EQ(differentPixels(shot("moved.png"), shot("paused.png")), 0);
}

// Every shipped model (bench aside) opens, draws something, and steps back and forth: the model
// named after its folder, and every .l with a .v of the same name.
TEST_F(ViewCommandTest, EveryShippedModelOpens) {
  std::vector<std::pair<fs::path, fs::path>> models;
  for (const auto& entry : fs::directory_iterator(fs::path(HIRSUTE_SOURCE_DIR) / "models")) {
    if (!entry.is_directory() || entry.path().filename() == "bench") continue;
    fs::path folder = entry.path();
    for (const auto& file : fs::directory_iterator(folder)) {
      fs::path l = file.path();
      if (l.extension() != ".l") continue;
      fs::path sameName = fs::path(l).replace_extension(".v");
      fs::path folderView = folder / (folder.filename().string() + ".v");
      if (fs::exists(sameName)) {
        models.emplace_back(l, sameName);
      } else if (l.stem() == folder.filename()) {
        models.emplace_back(l, fs::exists(folderView) ? folderView : fs::path());
      }
    }
  }
  ASSERT_FALSE(models.empty());
  for (const auto& [l, v] : models) {
    fs::remove(folder_ / "out" / "model.png");
    EXPECT_EQ(view(l.string() + " " + v.string(), "screenshot model.png; back; step; quit"), 0)
        << l << "\n"
        << stderr_;
    if (fs::exists(folder_ / "out" / "model.png")) {
      EXPECT_GT(plantPixels(shot("model.png")), 0u) << l;
    }
  }
}

// ---- the editors (docs/viewer.md, "Editors") ----

TEST_F(ViewCommandTest, AMaterialEditIsDrawnAtOnceAndSavedInCpfgsFormat) {
  fs::path herb = copyModel("herb");
  const std::string shippedMat = readText(herb / "herb.mat");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "screenshot before.png; material 2 diffuse 1 0 0; screenshot edited.png; "
                 "save colors; wait-reload 30; screenshot saved.png; quit"),
            0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("before.png"), shot("edited.png")), kPixels / 100)
      << "the internodes are drawn red";
  EXPECT_LT(differentPixels(shot("edited.png"), shot("saved.png")), kPixels / 200)
      << "derived again from the saved file, the same plant";
  // Material 2's record: index, transparency, ambient, then the diffuse colour.
  const std::string saved = readText(herb / "herb.mat");
  ASSERT_EQ(saved.size(), shippedMat.size());
  std::size_t record = 0;
  while (record < saved.size() && saved[record] != 2) record += 15;
  ASSERT_LT(record, saved.size());
  EXPECT_EQ(saved.substr(record + 5, 3), std::string("\xff\0\0", 3));
  std::string expected = shippedMat;
  expected.replace(record + 5, 3, std::string("\xff\0\0", 3));
  EXPECT_EQ(saved, expected) << "only the three bytes edited changed";
}

TEST_F(ViewCommandTest, AModelWithoutColoursCreatesAColourMapAndEditsIt) {
  fs::path herb = copyModel("herb");
  fs::remove(herb / "herb.mat");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "create colors; wait-reload 30; screenshot created.png; color 2 1 0 0; "
                 "screenshot red.png; save colors; quit"),
            0)
      << stderr_;
  EXPECT_NE(stdout_.find("herb.map (the model's folder's one colour file"), std::string::npos)
      << stdout_;
  const std::string map = readText(herb / "herb.map");
  ASSERT_EQ(map.size(), 768u);
  EXPECT_EQ(map.substr(6, 3), std::string("\xff\0\0", 3));
  EXPECT_GT(differentPixels(shot("created.png"), shot("red.png")), kPixels / 100);
}

TEST_F(ViewCommandTest, APanelsSliderDerivesThePlantAgainAndItsRangeIsSaved) {
  fs::path herb = copyModel("herb");
  const std::string lsystem = readText(herb / "herb.l");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "screenshot before.png; panel slider BRANCH_ANGLE 80; screenshot wide.png; "
                 "panel range BRANCH_ANGLE 0 120; save panel; quit"),
            0)
      << stderr_;
  EXPECT_GT(differentPixels(shot("before.png"), shot("wide.png")), kPixels / 100);
  const std::string panel = readText(herb / "herb.pnl");
  EXPECT_NE(panel.find("min/max: 0 120\nvalue: 40\nmessage: d BRANCH_ANGLE %d"), std::string::npos)
      << panel;
  EXPECT_EQ(readText(herb / "herb.l"), lsystem) << "the .l is written only by 'save'";
}

TEST_F(ViewCommandTest, EachEditorIsDrawnInTheWindow) {
  fs::path herb = shipped("herb");
  std::string model = (herb / "herb.l").string() + " " + (herb / "herb.v").string();
  ASSERT_EQ(view(model,
                 "panel off; controls off; screenshot plain.png ui; colors on; "
                 "screenshot colors.png ui; colors off; controls on; screenshot panel.png ui; "
                 "quit"),
            0)
      << stderr_;
  RgbaImage plain = shot("plain.png");
  // Each window covers a good part of the picture's right half, where the plant alone was.
  auto rightHalfChanged = [&](const RgbaImage& image) {
    std::size_t count = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = kWidth / 2; x < kWidth; ++x) {
        glm::ivec4 d = glm::ivec4(image.pixel(x, y)) - glm::ivec4(plain.pixel(x, y));
        if (std::abs(d.r) + std::abs(d.g) + std::abs(d.b) > 24) ++count;
      }
    }
    return count;
  };
  EXPECT_GT(rightHalfChanged(shot("colors.png")), kPixels / 8) << "the colours editor";
  EXPECT_GT(rightHalfChanged(shot("panel.png")), kPixels / 20) << "the herb's panel";
  EXPECT_EQ(differentPixels(plain, shot("plain.png")), 0u);
}

TEST_F(ViewCommandTest, AScriptMistakeIsBadInput) {
  fs::path herb = shipped("herb");
  EXPECT_EQ(view((herb / "herb.l").string(), "rotate 30; spin"), 2);
  EXPECT_NE(stderr_.find("--commands:1:12: error: unknown viewer command 'spin'"),
            std::string::npos)
      << stderr_;
}

}  // namespace
}  // namespace hirsute
