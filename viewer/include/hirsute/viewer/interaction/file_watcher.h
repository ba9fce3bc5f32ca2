// Watches the model's files for the viewer's live editing: the files named on the command line
// and the model files in their folders (includes, contours, surfaces, functions, colour maps…),
// by polling their modification times and sizes, which works alike on every file system and
// editor (a save that replaces the file by renaming is seen as well as one that rewrites it).
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <vector>

namespace hirsute {

class FileWatcher {
 public:
  using Clock = std::chrono::steady_clock;
  // A change is reported once the files have been still this long, so that an editor's save in
  // several writes gives one re-derivation of the finished file.
  static constexpr std::chrono::milliseconds kSettle{120};

  // `files` are watched whatever their names; in each of `folders`, every file that is not
  // hidden and has one of cpfg's model extensions (.l .v .a .map .mat .con .s .func .fset .crv
  // .inc .h .txt .dat …).
  FileWatcher(std::vector<std::filesystem::path> files, std::vector<std::filesystem::path> folders);

  // Watches `file` too from now on (a file the model turns out to read, such as a texture image
  // named by the view file); its present state is not a change.
  void watch(const std::filesystem::path& file);

  // Files the program writes itself (screenshots) are not changes of the model.
  void ignore(const std::filesystem::path& file);

  // A model file the viewer's editors wrote and re-derived from itself: its new state is not a
  // change (a change of another file still is).
  void acknowledge(const std::filesystem::path& file);

  // True once when something changed and has since been still for kSettle.
  bool poll(Clock::time_point now = Clock::now());

  // The files being watched now (for messages and tests).
  std::vector<std::filesystem::path> watched() const;

  static bool isModelFile(const std::filesystem::path& file);

 private:
  struct Stamp {
    std::filesystem::file_time_type time;
    std::uintmax_t size = 0;
    bool operator==(const Stamp&) const = default;
  };
  std::map<std::filesystem::path, Stamp> scan() const;

  std::vector<std::filesystem::path> files_, folders_;
  std::set<std::filesystem::path> ignored_;
  std::map<std::filesystem::path, Stamp> stamps_;
  std::optional<Clock::time_point> lastChange_;
};

}  // namespace hirsute
