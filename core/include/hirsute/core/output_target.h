// Where a command's output goes: one rule for every file Hirsute writes (strings, PNG images,
// POV-Ray and OBJ scenes, CSV tables, texture images).
//
// A regular file (or a path that does not exist yet) is written under a temporary name beside
// it and renamed over it on commit(), so that a reader never sees half a file and a failed run
// leaves the old file (or nothing). Anything else that exists — a device such as /dev/null, a
// FIFO, a terminal, /dev/stdout — cannot be replaced without destroying it, so it is opened
// and written in place; /dev/stdout, /dev/stderr and /dev/fd/N write to the process's own
// descriptor, as the shell set it up. A symbolic link to a regular file replaces the file it
// points to and keeps the link.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace hirsute {

// Outputs that are committed together: a command asked for several files (`export --pov --obj
// --hairs`) writes them all, then renames them all, so that a failed run leaves every one of
// them as it was. A target opened in a group keeps its temporary file at commit(); the group
// renames them at its own commit(), or removes them when it is destroyed first.
class OutputGroup {
 public:
  OutputGroup() = default;
  ~OutputGroup();
  OutputGroup(const OutputGroup&) = delete;
  OutputGroup& operator=(const OutputGroup&) = delete;

  // Renames every file of the group into place; throws std::runtime_error "PATH: cannot
  // write: REASON" on the first that fails.
  void commit();

 private:
  friend class OutputTarget;
  struct Pending {
    std::string temporary;
    std::filesystem::path destination, target;
  };
  std::vector<Pending> pending_;
};

class OutputTarget {
 public:
  // Opens the target for writing; throws std::runtime_error naming the path and the reason.
  // In a group, commit() leaves the renaming to the group.
  explicit OutputTarget(std::filesystem::path target, OutputGroup* group = nullptr);
  // Unless commit() succeeded: removes the temporary file (the target is left as it was).
  ~OutputTarget();
  OutputTarget(const OutputTarget&) = delete;
  OutputTarget& operator=(const OutputTarget&) = delete;

  // The descriptor to write to (do not close it).
  int descriptor() const { return fd_; }
  // A stdio stream over the descriptor, made on first use and owned by this object.
  std::FILE* stream();

  // Flushes and closes, then renames the temporary file into place (regular files); throws
  // std::runtime_error "PATH: cannot write: REASON" on failure.
  void commit();

  const std::filesystem::path& target() const { return target_; }
  // True when the target is a device, FIFO or descriptor written directly.
  bool writesInPlace() const { return temporary_.empty(); }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const;

  std::filesystem::path target_;
  std::filesystem::path destination_;  // what the temporary file is renamed to
  std::string temporary_;
  int fd_ = -1;
  std::FILE* stream_ = nullptr;
  OutputGroup* group_ = nullptr;
  bool committed_ = false;
};

}  // namespace hirsute
