// Confining a program Hirsute runs on a model's files (the C preprocessor, which opens the
// model's `#include` files itself; POV-Ray and GNU parallel, which render its scenes) to the
// folders it needs.
//
// Linux's Landlock: the child, between fork and exec, gives up every file access but those its
// rules name, and reading and running the system's programs and libraries (/usr, /lib, /lib64,
// /bin, /sbin, /etc/ld.so.cache). A link in the model's folder to a file elsewhere, an absolute
// `#include`, a `..` out of the folder then fail as a denied permission: the rules hold for the
// file a name resolves to, whatever the name. Everything the child starts inherits them.
// Where the kernel lacks Landlock the child runs unconfined; available() says which.
#pragma once

#include <filesystem>
#include <vector>

#include "hirsute/core/model_folder.h"

namespace hirsute {

// What a confined child may touch besides the system's programs and libraries. A path that does
// not exist is left out.
struct ConfinementRules {
  // Files and folders read beneath these (a file names itself alone).
  std::vector<std::filesystem::path> read;
  // Files and folders read, created, written and removed beneath these; nothing run from them.
  std::vector<std::filesystem::path> write;
  // Programs run (and read), each a file or a folder of them.
  std::vector<std::filesystem::path> run;
  // Devices opened for reading and writing, such as /dev/null (Landlock gates their opening as
  // it gates files').
  std::vector<std::filesystem::path> devices;
};

class ChildConfinement {
 public:
  // Reading beneath `folder` only: the child can write no file by name (its output goes to
  // descriptors it was handed).
  explicit ChildConfinement(const std::filesystem::path& folder);
  explicit ChildConfinement(const ConfinementRules& rules);
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
