// The folder a model is confined to: names resolve beneath it, links out of it are refused,
// only regular files are opened, on the kernel's resolution and on the component walk.
#include "hirsute/core/model_folder.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using Resolution = ModelFolder::Resolution;

class ModelFolderTest : public testing::TemporaryFolderTest,
                        public ::testing::WithParamInterface<Resolution> {
 protected:
  ModelFolderTest() : TemporaryFolderTest("model_folder_") {}
  void SetUp() override {
    TemporaryFolderTest::SetUp();
    model_ = folder_ / "model";
    outside_ = folder_ / "outside";
    fs::create_directories(model_ / "sub");
    fs::create_directories(outside_);
    write(outside_ / "target.txt", "outside\n");
    write(model_ / "data.txt", "inside\n");
  }
  static void write(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
  }
  ModelFolder folder() const { return ModelFolder(model_, GetParam()); }
  std::string writeThrough(const std::string& name, FileAccess access, const std::string& text,
                           ConfinedFile* result = nullptr) const {
    ConfinedFile file = folder().open(name, access);
    std::string failure = file.failure;
    if (file) {
      EXPECT_EQ(::write(file.fd.get(), text.data(), text.size()), ssize_t(text.size()));
    }
    if (result) *result = std::move(file);
    return failure;
  }

  fs::path model_, outside_;
};

TEST_P(ModelFolderTest, ReadsAndWritesPlainNamesBeneathTheFolder) {
  std::string text, failure;
  ASSERT_TRUE(folder().read("data.txt", text, failure)) << failure;
  EXPECT_EQ(text, "inside\n");
  EXPECT_EQ(writeThrough("sub/new.txt", FileAccess::Write, "written"), "");
  EXPECT_EQ(testing::readText(model_ / "sub/new.txt"), "written");
  EXPECT_EQ(writeThrough("sub/new.txt", FileAccess::Append, "+more"), "");
  EXPECT_EQ(testing::readText(model_ / "sub/new.txt"), "written+more");
  EXPECT_EQ(writeThrough("sub/new.txt", FileAccess::Write, "w"), "");
  EXPECT_EQ(testing::readText(model_ / "sub/new.txt"), "w");  // truncated
}

TEST_P(ModelFolderTest, AbsoluteNamesAndParentsAreRefused) {
  for (const std::string& name :
       {(outside_ / "target.txt").string(), std::string("../outside/target.txt"),
        std::string("sub/../../outside/target.txt")}) {
    ConfinedFile file = folder().open(name, FileAccess::Append);
    EXPECT_FALSE(file) << name;
    EXPECT_TRUE(file.refused) << name;
  }
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
}

TEST_P(ModelFolderTest, ALinkToAFileOutsideIsNotWrittenThrough) {
  fs::create_symlink(outside_ / "target.txt", model_ / "link.txt");
  for (FileAccess access :
       {FileAccess::Write, FileAccess::Append, FileAccess::ReadWrite, FileAccess::Read}) {
    ConfinedFile file;
    writeThrough("link.txt", access, "pwned", &file);
    EXPECT_FALSE(file);
    EXPECT_TRUE(file.refused);
  }
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
  EXPECT_TRUE(fs::is_symlink(model_ / "link.txt"));
}

TEST_P(ModelFolderTest, AHardLinkIsReadButNeverWritten) {
  ASSERT_EQ(link((outside_ / "target.txt").c_str(), (model_ / "hard.txt").c_str()), 0);
  for (FileAccess access : {FileAccess::Write, FileAccess::WriteRead, FileAccess::Append,
                            FileAccess::AppendRead, FileAccess::ReadWrite}) {
    ConfinedFile file;
    const std::string failure = writeThrough("hard.txt", access, "pwned", &file);
    EXPECT_FALSE(file);
    EXPECT_TRUE(file.refused);
    EXPECT_NE(failure.find("it has 2 names (hard links)"), std::string::npos) << failure;
  }
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
  std::string text, failure;
  ASSERT_TRUE(folder().read("hard.txt", text, failure)) << failure;
  EXPECT_EQ(text, "outside\n");
}

TEST_P(ModelFolderTest, ARelativeLinkOutIsRefusedToo) {
  fs::create_symlink("../outside/target.txt", model_ / "up.txt");
  ConfinedFile file = folder().open("up.txt", FileAccess::Append);
  EXPECT_FALSE(file);
  EXPECT_TRUE(file.refused);
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
}

TEST_P(ModelFolderTest, ALinkedFolderOutsideIsNotEntered) {
  fs::create_directory_symlink(outside_, model_ / "home");
  ConfinedFile file = folder().open("home/x", FileAccess::Append);
  EXPECT_FALSE(file);
  EXPECT_TRUE(file.refused);
  EXPECT_FALSE(fs::exists(outside_ / "x"));
  ConfinedFile existing = folder().open("home/target.txt", FileAccess::Write);
  EXPECT_FALSE(existing);
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
}

TEST_P(ModelFolderTest, ADanglingLinkIsNotCreatedThrough) {
  fs::create_symlink(outside_ / "created.txt", model_ / "dangling.txt");
  ConfinedFile file = folder().open("dangling.txt", FileAccess::Write);
  EXPECT_FALSE(file);
  EXPECT_FALSE(fs::exists(outside_ / "created.txt"));
}

TEST_P(ModelFolderTest, ALinkInsideTheFolderIsFollowedOnlyByTheKernel) {
  fs::create_symlink("data.txt", model_ / "alias.txt");
  std::string text, failure;
  const bool read = folder().read("alias.txt", text, failure);
  if (GetParam() == Resolution::Beneath) {
    ASSERT_TRUE(read) << failure;
    EXPECT_EQ(text, "inside\n");
  } else {
    // Without openat2 no link is followed: refused, with a reason that says so.
    EXPECT_FALSE(read);
    EXPECT_NE(failure.find("symbolic link"), std::string::npos) << failure;
  }
}

TEST_P(ModelFolderTest, AFifoIsRefusedAtOnceNotWaitedOn) {
  ASSERT_EQ(mkfifo((model_ / "pipe").c_str(), 0600), 0);
  for (FileAccess access : {FileAccess::Read, FileAccess::Write, FileAccess::Append}) {
    ConfinedFile file = folder().open("pipe", access);
    EXPECT_FALSE(file);
    EXPECT_TRUE(file.refused);
    EXPECT_NE(file.failure.find("FIFO"), std::string::npos) << file.failure;
  }
}

TEST_P(ModelFolderTest, AFolderAndADeviceAreNoRegularFiles) {
  ConfinedFile folderAsFile = folder().open("sub", FileAccess::Read);
  EXPECT_FALSE(folderAsFile);
  EXPECT_TRUE(folderAsFile.refused) << folderAsFile.failure;
  if (GetParam() == Resolution::Beneath) {
    // A link to a device is an absolute link: refused before the device is looked at.
    fs::create_symlink("/dev/zero", model_ / "zero");
    ConfinedFile zero = folder().open("zero", FileAccess::Read);
    EXPECT_FALSE(zero);
    EXPECT_TRUE(zero.refused);
  }
}

TEST_P(ModelFolderTest, RemovingALinkLeavesWhatItNames) {
  fs::create_symlink(outside_ / "target.txt", model_ / ".to_field1.0");
  folder().remove(".to_field1.0");
  EXPECT_FALSE(fs::is_symlink(model_ / ".to_field1.0"));
  EXPECT_EQ(testing::readText(outside_ / "target.txt"), "outside\n");
  folder().remove("../outside/target.txt");
  EXPECT_TRUE(fs::exists(outside_ / "target.txt"));
}

TEST_P(ModelFolderTest, AReadLargerThanTheLimitFails) {
  std::string text, failure;
  EXPECT_FALSE(folder().read("data.txt", text, failure, 3));
  EXPECT_NE(failure.find("larger than 3 bytes"), std::string::npos) << failure;
}

INSTANTIATE_TEST_SUITE_P(Resolutions, ModelFolderTest,
                         ::testing::Values(Resolution::Beneath, Resolution::ComponentWalk),
                         [](const auto& info) {
                           return info.param == Resolution::Beneath ? "Beneath" : "ComponentWalk";
                         });

TEST(FileAccessOfMode, ReadsTheModesOfFopen) {
  FileAccess access{};
  ASSERT_TRUE(fileAccessOfMode("r", access));
  EXPECT_EQ(access, FileAccess::Read);
  ASSERT_TRUE(fileAccessOfMode("wb", access));
  EXPECT_EQ(access, FileAccess::Write);
  ASSERT_TRUE(fileAccessOfMode("a+", access));
  EXPECT_EQ(access, FileAccess::AppendRead);
  ASSERT_TRUE(fileAccessOfMode("r+b", access));
  EXPECT_EQ(access, FileAccess::ReadWrite);
  for (const char* bad : {"", "x", "rw", "w++", "bb", "+w", "ra"})
    EXPECT_FALSE(fileAccessOfMode(bad, access)) << bad;
}

}  // namespace
}  // namespace hirsute
