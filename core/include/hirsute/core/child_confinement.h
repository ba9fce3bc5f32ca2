// Confining a program Hirsute runs on a model's files (the C preprocessor, which opens the
// model's `#include` files itself) to reading beneath the model's folder.
//
// Linux's Landlock: the child, between fork and exec, gives up every file access but reading
// beneath the model's folder and reading and running the system's programs and libraries
// (/usr, /lib, /lib64, /bin, /etc/ld.so.cache). A link in the model's folder to a file
// elsewhere, an absolute `#include`, a `..` out of the folder then fail as a denied permission,
// and the child can write no file by name (its output goes to descriptors it was handed).
// Where the kernel lacks Landlock the child runs unconfined; available() says which.
#pragma once

#include <filesystem>

#include "hirsute/core/model_folder.h"

namespace hirsute {

class ChildConfinement {
 public:
  explicit ChildConfinement(const std::filesystem::path& folder);
  ChildConfinement(const ChildConfinement&) = delete;
  ChildConfinement& operator=(const ChildConfinement&) = delete;

  // Whether the kernel has Landlock and the rules are made.
  bool available() const { return static_cast<bool>(ruleset_); }

  // In the child after fork, before exec: only system calls (async-signal-safe). Returns 0, or
  // -1 with errno when the rules could not be applied (the child should then exit).
  int applyInChild() const noexcept;

 private:
  FileDescriptor ruleset_;
};

}  // namespace hirsute
