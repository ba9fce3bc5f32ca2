// The names a command derives inside its output folder (hirsute/core/output_folder.h): created
// beneath the folder, never through a link planted at the name, never into a FIFO or device.
#include "hirsute/core/output_folder.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "hirsute/core/output_target.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

class OutputFolderTest : public testing::TemporaryFolderTest {
 protected:
  OutputFolderTest() : TemporaryFolderTest("hirsute_output_folder_") {}
  void SetUp() override {
    TemporaryFolderTest::SetUp();
    out_ = folder_ / "out";
    outside_ = folder_ / "outside";
    fs::create_directories(out_);
    fs::create_directories(outside_);
    std::ofstream(outside_ / "profile", std::ios::binary) << "the user's own file\n";
  }
  static void writeName(const OutputFolder& folder, const std::string& name,
                        const std::string& text, OutputGroup* group = nullptr) {
    OutputTarget file(folder, name, group);
    ASSERT_EQ(std::fwrite(text.data(), 1, text.size(), file.stream()), text.size());
    file.commit();
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(out_), {}));
  }
  std::string profile() const { return testing::readText(outside_ / "profile"); }

  fs::path out_, outside_;
};

TEST_F(OutputFolderTest, ASymbolicLinkAtTheNameIsReplacedAndItsFileLeftAlone) {
  fs::create_symlink(outside_ / "profile", out_ / "frame-0001.pov");
  writeName(OutputFolder(out_), "frame-0001.pov", "a scene\n");
  EXPECT_EQ(profile(), "the user's own file\n");
  EXPECT_FALSE(fs::is_symlink(out_ / "frame-0001.pov"));
  EXPECT_EQ(testing::readText(out_ / "frame-0001.pov"), "a scene\n");
  EXPECT_EQ(entries(), 1u);  // no temporary file left
}

TEST_F(OutputFolderTest, AHardLinkAtTheNameIsReplacedAndItsFileLeftAlone) {
  ASSERT_EQ(link((outside_ / "profile").c_str(), (out_ / "side.mtl").c_str()), 0);
  writeName(OutputFolder(out_), "side.mtl", "newmtl m\n");
  EXPECT_EQ(profile(), "the user's own file\n");
  EXPECT_EQ(testing::readText(out_ / "side.mtl"), "newmtl m\n");
  EXPECT_EQ(fs::hard_link_count(outside_ / "profile"), 1u);
}

TEST_F(OutputFolderTest, ALinkToAFolderAtTheNameIsReplacedNotEntered) {
  fs::create_directory_symlink(outside_, out_ / "fur.csv");
  writeName(OutputFolder(out_), "fur.csv", "frame\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(outside_), {}), 1);
  EXPECT_EQ(testing::readText(out_ / "fur.csv"), "frame\n");
}

TEST_F(OutputFolderTest, AFifoAtTheNameIsRefusedAtOnce) {
  ASSERT_EQ(mkfifo((out_ / "simulation.csv").c_str(), 0600), 0);
  const auto started = std::chrono::steady_clock::now();
  try {
    OutputTarget file(OutputFolder(out_), "simulation.csv");
    FAIL() << "a FIFO at a derived name was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("simulation.csv: cannot write: it is a FIFO"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
  EXPECT_TRUE(fs::is_fifo(out_ / "simulation.csv"));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFolderTest, AFolderAtTheNameOrANameWithAFolderIsRefused) {
  fs::create_directories(out_ / "frame-0001.pov");
  EXPECT_THROW(OutputTarget(OutputFolder(out_), "frame-0001.pov"), std::runtime_error);
  EXPECT_THROW(OutputTarget(OutputFolder(out_), "../outside/profile"), std::runtime_error);
  EXPECT_THROW(OutputTarget(OutputFolder(out_), ".."), std::runtime_error);
  EXPECT_EQ(profile(), "the user's own file\n");
}

TEST_F(OutputFolderTest, TheFolderItselfMayBeALinkTheUserChose) {
  fs::create_directory_symlink(outside_, folder_ / "chosen");
  writeName(OutputFolder(folder_ / "chosen"), "frame-0001.pov", "a scene\n");
  EXPECT_EQ(testing::readText(outside_ / "frame-0001.pov"), "a scene\n");
}

TEST_F(OutputFolderTest, AGroupRenamesItsFilesTogetherAndCountsTheirBytes) {
  const OutputFolder folder(out_);
  {
    OutputGroup group;
    writeName(folder, "frame-0001.pov", "12345", &group);
    writeName(folder, "frame-0001.obj", "678", &group);
    EXPECT_EQ(group.bytes(), 8u);
    EXPECT_FALSE(fs::exists(out_ / "frame-0001.pov"));
    // Destroyed before commit(): nothing lands and no temporary is left.
  }
  EXPECT_EQ(entries(), 0u);
  OutputGroup group;
  writeName(folder, "frame-0001.pov", "12345", &group);
  writeName(folder, "frame-0001.obj", "678", &group);
  group.commit();
  EXPECT_EQ(testing::readText(out_ / "frame-0001.pov"), "12345");
  EXPECT_EQ(testing::readText(out_ / "frame-0001.obj"), "678");
  EXPECT_EQ(entries(), 2u);
}

TEST_F(OutputFolderTest, ARegularFileKeepsItsModeAndAMissingFolderIsAnError) {
  std::ofstream(out_ / "simulation.csv") << "old\n";
  chmod((out_ / "simulation.csv").c_str(), 0640);
  writeName(OutputFolder(out_), "simulation.csv", "new\n");
  struct stat st {};
  ASSERT_EQ(stat((out_ / "simulation.csv").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
  EXPECT_THROW(OutputFolder(folder_ / "missing"), std::runtime_error);
}

}  // namespace
}  // namespace hirsute
