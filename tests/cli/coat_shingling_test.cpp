// A static coat laid shingled (docs/feathers.md, "Shingling"), end to end: every shipped model
// with a feather coat is drawn with none of its feathers through another (the stage's count of
// what is left, by the exact check, is 0), --no-deintersect and the view file's `feather
// shingling: off` draw the groom as it grew, and the laid coat is the same on any number of
// threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

// The .l files of the shipped models (the benchmarks aside) that grow a coat (@Ff or @Fb, in
// the file or a file it includes), each
// with its view file as a user runs it: the .v of the same name, else the folder's.
std::vector<std::vector<std::string>> shippedCoats() {
  std::vector<std::vector<std::string>> models;
  for (const auto& folder : fs::directory_iterator(kModels)) {
    if (!folder.is_directory() || folder.path().filename() == "bench") continue;
    std::vector<fs::path> views;
    for (const auto& entry : fs::directory_iterator(folder.path()))
      if (entry.path().extension() == ".v") views.push_back(entry.path());
    for (const auto& entry : fs::directory_iterator(folder.path())) {
      if (entry.path().extension() != ".l") continue;
      // The model's text with the files it includes from its folder (a page's coat.inc).
      std::string text = readText(entry.path());
      static const std::regex kInclude(R"re(#include\s+"([^"]+)")re");
      for (std::sregex_iterator i(text.begin(), text.end(), kInclude), end; i != end; ++i) {
        const fs::path included = folder.path() / (*i)[1].str();
        if (fs::is_regular_file(included)) text += readText(included);
      }
      if (text.find("@Ff") == std::string::npos && text.find("@Fb") == std::string::npos) continue;
      std::vector<std::string> model{entry.path().string()};
      const fs::path sameName = fs::path(entry.path()).replace_extension(".v");
      const fs::path folderView = folder.path() / (folder.path().filename().string() + ".v");
      if (fs::exists(sameName))
        model.push_back(sameName.string());
      else if (fs::exists(folderView))
        model.push_back(folderView.string());
      else if (views.size() == 1)
        model.push_back(views.front().string());
      models.push_back(model);
    }
  }
  std::sort(models.begin(), models.end());
  return models;
}

const std::regex kReport(
    R"(shingled coat: (\d+) feathers, (\d+) lifted \(at most [0-9.]+ degrees\), (\d+) intersections left)");

TEST(CoatShingling, EveryShippedCoatIsLaidWithNoFeatherThroughAnother) {
  if (kAddressSanitizer) GTEST_SKIP() << "a dozen whole-program runs: the release build checks";
  TemporaryFolder folder;
  const std::vector<std::vector<std::string>> models = shippedCoats();
  std::size_t lifted = 0;
  for (const std::vector<std::string>& model : models) {
    std::vector<std::string> arguments{"render"};
    arguments.insert(arguments.end(), model.begin(), model.end());
    arguments.insert(arguments.end(),
                     {"-o", (folder.path() / "coat.png").string(), "--size", "32x24", "-v"});
    const RunResult run = runHirsute(arguments);
    ASSERT_EQ(run.exitCode, 0) << model.front() << ": " << run.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(run.err, m, kReport)) << model.front() << ": " << run.err;
    EXPECT_GT(std::stoul(m[1]), 0u) << model.front();
    EXPECT_EQ(m[3], "0") << model.front() << ": " << m[0];
    EXPECT_EQ(run.err.find("could not be laid"), std::string::npos) << run.err;
    lifted += std::stoul(m[2]);
  }
  // The shipped coats: the patch and its follicle layouts, the bending strip, the coat
  // parameters' pages, the bird on its mesh.
  EXPECT_GE(models.size(), 10u);
  // Their grooms pass through one another: a feather is lifted only where it meets the layer.
  EXPECT_GT(lifted, 0u);
}

class ShingledCoat : public ::testing::Test {
 protected:
  // models/coat-bending exported for POV-Ray at 64x48 with `extra` arguments into a folder of
  // its own named `name` (the scene names its file); returns the scene's text.
  std::string exported(const std::string& name, const std::vector<std::string>& extra,
                       std::string* err = nullptr) {
    const fs::path model = kModels / "coat-bending";
    fs::create_directory(folder_.path() / name);
    const fs::path scene = folder_.path() / name / "coat.pov";
    std::vector<std::string> arguments{"export",
                                       (model / "bending.l").string(),
                                       (model / "bending.v").string(),
                                       "--pov",
                                       scene.string(),
                                       "--width",
                                       "64",
                                       "--height",
                                       "48",
                                       "-v"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const RunResult run = runHirsute(arguments);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    if (err) *err = run.err;
    return readText(scene);
  }
  TemporaryFolder folder_;
};

TEST_F(ShingledCoat, NoDeintersectDrawsTheGroomAsItGrew) {
  std::string laidErr, rawErr;
  const std::string laid = exported("laid", {}, &laidErr);
  const std::string raw = exported("raw", {"--no-deintersect"}, &rawErr);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(laidErr, m, kReport)) << laidErr;
  EXPECT_GT(std::stoul(m[2]), 0u);  // some feathers met the layer beneath as groomed
  EXPECT_EQ(rawErr.find("shingled coat"), std::string::npos) << rawErr;
  EXPECT_FALSE(laid.empty());
  EXPECT_NE(laid, raw);
  // The view file's line does the same.
  const fs::path model = kModels / "coat-bending";
  for (const auto& entry : fs::directory_iterator(model))
    fs::copy_file(entry.path(), folder_.path() / entry.path().filename());
  std::ofstream(folder_.path() / "bending.v", std::ios::app) << "feather shingling: off\n";
  const RunResult run = runHirsute(
      {"export", (folder_.path() / "bending.l").string(), (folder_.path() / "bending.v").string(),
       "--pov", (folder_.path() / "off.pov").string(), "--width", "64", "--height", "48", "-v"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err.find("shingled coat"), std::string::npos) << run.err;
}

TEST_F(ShingledCoat, TheLaidCoatIsTheSameOnAnyNumberOfThreads) {
  const std::string one = exported("one", {"--threads", "1"});
  const std::string three = exported("three", {"--threads", "3"});
  EXPECT_FALSE(one.empty());
  EXPECT_EQ(one, three);
}

}  // namespace
