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
//
// That is the rule for a name the user typed. A name Hirsute derives itself (a frame of
// `simulate -o DIR`, the .mtl beside an OBJ) is written in an OutputFolder (output_folder.h):
// created beneath the folder without following any link, renamed over whatever entry has the
// name; a FIFO, device or folder at such a name is refused.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/core/output_folder.h"

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

  // The bytes of the files written and not yet renamed (their temporary files), for a limit on
  // what a run writes.
  std::uint64_t bytes() const;

 private:
  friend class OutputTarget;
  struct Pending {
    std::shared_ptr<const FileDescriptor> folder;  // the names' folder; none: the current one
    std::string temporary, destination;
    std::filesystem::path target;
  };
  std::vector<Pending> pending_;
};

class OutputTarget {
 public:
  // Opens the target for writing; throws std::runtime_error naming the path and the reason.
  // In a group, commit() leaves the renaming to the group.
  explicit OutputTarget(std::filesystem::path target, OutputGroup* group = nullptr);
  // Opens `name`, a name Hirsute derives (a plain file name), in `folder` (output_folder.h): a
  // temporary file is created in the folder without following links and renamed over `name` on
  // commit(), replacing a symbolic or hard link there instead of writing what it leads to. A
  // folder, FIFO, device or socket at `name` is refused: throws std::runtime_error
  // "FOLDER/NAME: REASON".
  OutputTarget(const OutputFolder& folder, const std::string& name, OutputGroup* group = nullptr);
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
  // The file being written, by its path: the temporary file, or the target written in place; for
  // a program that writes the output by name (POV-Ray's +O). A temporary file in an
  // OutputFolder keeps the name's extension last (".plant.tmp-XXXXXX.png").
  std::filesystem::path writtenPath() const;
  // True when the target is a device, FIFO or descriptor written directly.
  bool writesInPlace() const { return temporary_.empty(); }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const;

  std::filesystem::path target_;
  std::filesystem::path destination_;  // what the temporary file is renamed to
  std::string temporary_;
  // In an OutputFolder: its descriptor, which temporary_ and destination_ are relative to.
  std::shared_ptr<const FileDescriptor> folder_;
  int fd_ = -1;
  std::FILE* stream_ = nullptr;
  OutputGroup* group_ = nullptr;
  bool committed_ = false;
};

}  // namespace hirsute
