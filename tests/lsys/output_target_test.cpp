// The one rule for output files (hirsute/core/output_target.h): regular files are replaced in one
// piece, everything else that exists is written where it is.
#include "hirsute/core/output_target.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

class OutputTargetTest : public testing::TemporaryFolderTest {
 protected:
  OutputTargetTest() : TemporaryFolderTest("hirsute_output_target_") {}

  static void write(OutputTarget& out, const std::string& text) {
    ASSERT_EQ(std::fwrite(text.data(), 1, text.size(), out.stream()), text.size());
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder_), {}));
  }
};

TEST_F(OutputTargetTest, RegularFileIsReplacedOnlyOnCommit) {
  const fs::path path = file("scene.txt");
  { std::ofstream(path) << "old\n"; }
  chmod(path.c_str(), 0640);
  {
    OutputTarget out(path);
    EXPECT_FALSE(out.writesInPlace());
    write(out, "new\n");
    EXPECT_EQ(testing::readText(path), "old\n");  // still the old file until commit
    out.commit();
  }
  EXPECT_EQ(testing::readText(path), "new\n");
  struct stat info {};
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0640u);  // the replaced file's mode is kept
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputTargetTest, AbandonedOutputLeavesTheOldFileAndNoTemporary) {
  const fs::path path = file("scene.txt");
  { std::ofstream(path) << "old\n"; }
  {
    OutputTarget out(path);
    write(out, "half of a new");
  }
  EXPECT_EQ(testing::readText(path), "old\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputTargetTest, LinkToARegularFileReplacesTheFileAndKeepsTheLink) {
  const fs::path real = file("real.txt");
  const fs::path link = file("link.txt");
  { std::ofstream(real) << "old\n"; }
  fs::create_symlink(real, link);
  {
    OutputTarget out(link);
    write(out, "new\n");
    out.commit();
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(testing::readText(real), "new\n");
  EXPECT_EQ(entries(), 2u);
}

TEST_F(OutputTargetTest, FifoIsWrittenInPlace) {
  const fs::path fifo = file("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    int fd = open(fifo.c_str(), O_RDONLY);
    char buffer[256];
    for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;)
      received.append(buffer, static_cast<std::size_t>(n));
    close(fd);
  });
  {
    OutputTarget out(fifo);
    EXPECT_TRUE(out.writesInPlace());
    write(out, "through the pipe\n");
    out.commit();
  }
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputTargetTest, DevNullIsWrittenInPlace) {
  struct stat before {};
  ASSERT_EQ(stat("/dev/null", &before), 0);
  {
    OutputTarget out("/dev/null");
    EXPECT_TRUE(out.writesInPlace());
    write(out, "nothing\n");
    out.commit();
  }
  struct stat after {};
  ASSERT_EQ(stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(after.st_ino, before.st_ino);
}

TEST_F(OutputTargetTest, FolderOrMissingFolderIsAnErrorNamingThePath) {
  try {
    OutputTarget out(folder_);
    FAIL() << "a folder was opened as an output";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(folder_.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(OutputTarget(file("no/such/folder/out.txt")), std::runtime_error);
}

}  // namespace
}  // namespace hirsute
