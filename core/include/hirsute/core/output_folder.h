// The folder a command writes the files it names itself into: `simulate -o DIR`'s frames and
// tables, the material library and texture images an exported scene names beside it.
//
// The folder is the user's choice (a link to it is followed, as any name the user typed); the
// names inside it are Hirsute's. A name the program derives is never opened through what is
// there already: each file is created under a fresh temporary name in the folder (O_EXCL,
// O_NOFOLLOW, through the descriptor of the folder opened once) and renamed over the name
// (renameat), which replaces a symbolic or hard link planted at the name by the new file and
// never writes the file such a link leads to. A FIFO, device, socket or folder at the name is
// refused, never waited on or written (OutputTarget(const OutputFolder&, …), output_target.h).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "hirsute/core/model_folder.h"

namespace hirsute {

class OutputFolder {
 public:
  // Opens the folder `path` (the current folder when empty); throws std::runtime_error
  // "PATH: cannot open the output folder: REASON".
  explicit OutputFolder(const std::filesystem::path& path);

  const std::filesystem::path& path() const { return path_; }
  // The name as the user would find it: the folder joined with the name.
  std::filesystem::path pathOf(const std::string& name) const;
  // The descriptor of the folder (O_PATH), for the *at() calls; valid while any copy of this
  // object or a file opened in it lives.
  int descriptor() const { return folder_->get(); }
  // Shares the descriptor with what outlives this object (a file whose rename is pending).
  std::shared_ptr<const FileDescriptor> shared() const { return folder_; }

  // Whether `name` is a name of this folder's own: one component, not "." or "..".
  static bool isPlainName(const std::string& name);

 private:
  std::filesystem::path path_;
  std::shared_ptr<const FileDescriptor> folder_;
};

}  // namespace hirsute
