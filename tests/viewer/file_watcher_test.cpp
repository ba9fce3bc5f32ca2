// The viewer's file watcher: a change to a model file is reported once, after it settles.
#include "hirsute/viewer/interaction/file_watcher.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class FileWatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("hirsute_watch_" + std::to_string(getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    write("plant.l", "axiom");
    write("plant.v", "view");
  }
  void TearDown() override { fs::remove_all(folder_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name, std::ios::trunc) << text;
  }
  fs::path folder_;
};

TEST_F(FileWatcherTest, ReportsAChangeOnceAfterItSettles) {
  FileWatcher watcher({folder_ / "plant.l"}, {folder_});
  auto t = FileWatcher::Clock::now();
  EXPECT_FALSE(watcher.poll(t));
  write("plant.l", "axiom changed");
  EXPECT_FALSE(watcher.poll(t + 10ms));  // seen, not settled
  EXPECT_FALSE(watcher.poll(t + 50ms));
  EXPECT_TRUE(watcher.poll(t + 10ms + FileWatcher::kSettle));
  EXPECT_FALSE(watcher.poll(t + 1s));  // once
}

TEST_F(FileWatcherTest, WatchesModelFilesOfTheFolderButNotOthers) {
  FileWatcher watcher({folder_ / "plant.l"}, {folder_});
  auto t = FileWatcher::Clock::now();
  write("leaf.con", "contour");  // a new file the model may read
  watcher.poll(t);
  EXPECT_TRUE(watcher.poll(t + 1s));
  write("notes.png", "image");  // not a model file
  write(".plant.l.hirsute-view.l", "hidden");
  watcher.poll(t + 2s);
  EXPECT_FALSE(watcher.poll(t + 3s));
}

TEST_F(FileWatcherTest, IgnoredFilesAreNotChanges) {
  FileWatcher watcher({folder_ / "plant.l"}, {folder_});
  watcher.ignore(folder_ / "shot.txt");
  auto t = FileWatcher::Clock::now();
  write("shot.txt", "written by the viewer");
  watcher.poll(t);
  EXPECT_FALSE(watcher.poll(t + 1s));
}

// The viewer ignores its screenshot before and after writing it; an edit of the model made
// meanwhile (a script's `wait-reload` waits for it) is still a change.
TEST_F(FileWatcherTest, IgnoringAFileKeepsAChangeElsewhere) {
  FileWatcher watcher({folder_ / "plant.l"}, {folder_});
  auto t = FileWatcher::Clock::now();
  watcher.ignore(folder_ / "shot.txt");
  write("shot.txt", "written by the viewer");
  write("plant.l", "axiom edited meanwhile");
  watcher.ignore(folder_ / "shot.txt");
  watcher.poll(t);
  EXPECT_TRUE(watcher.poll(t + 1s));
}

TEST_F(FileWatcherTest, FilesWatchedByNameAreChangesWhateverTheirExtension) {
  write("bark.png", "image");
  FileWatcher watcher({folder_ / "plant.l"}, {folder_});
  watcher.watch(folder_ / "bark.png");  // a texture the view file names
  auto t = FileWatcher::Clock::now();
  EXPECT_FALSE(watcher.poll(t)) << "watching a file is no change";
  EXPECT_FALSE(watcher.poll(t + 1s));
  write("bark.png", "another image");
  watcher.poll(t + 2s);
  EXPECT_TRUE(watcher.poll(t + 3s));
}

}  // namespace
}  // namespace hirsute
