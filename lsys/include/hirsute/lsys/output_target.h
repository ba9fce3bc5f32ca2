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

namespace hirsute {

class OutputTarget {
 public:
  // Opens the target for writing; throws std::runtime_error naming the path and the reason.
  explicit OutputTarget(std::filesystem::path target);
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
  bool committed_ = false;
};

}  // namespace hirsute
