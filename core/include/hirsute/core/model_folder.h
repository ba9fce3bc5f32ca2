// The folder a model is confined to.
//
// A model is untrusted code: its blocks call fopen, its view file names files, its environment
// file names exchange files. Every file it makes Hirsute open is opened through here, by a name
// relative to the model's folder, and resolves beneath that folder: an absolute name, a `..`
// and a symbolic link that leads out (tar keeps links, so a downloaded model may carry one to the
// user's shell start-up file) are refused. Links that stay inside the folder are followed.
//
// Linux resolves the name itself (openat2 with RESOLVE_BENEATH). Where the kernel or a seccomp
// filter refuses openat2, each component is opened with O_NOFOLLOW and no link is followed.
// Only regular files are opened: a FIFO or a device is refused at once, never waited on.
// A file with more than one name (a hard link, which may lead anywhere on the same file system)
// is opened for reading only: writing it would change the file under its other names.
#pragma once

#include <filesystem>
#include <string>

namespace hirsute {

enum class FileAccess {
  Read,        // "r"
  ReadWrite,   // "r+"
  Write,       // "w": created or truncated
  WriteRead,   // "w+"
  Append,      // "a": created, written at the end
  AppendRead,  // "a+"
};

// The access an fopen mode asks for ("r", "w+", "ab", "a+b"...); false when it is none of them.
bool fileAccessOfMode(const std::string& mode, FileAccess& access);

// An open file descriptor, closed with the object unless released.
class FileDescriptor {
 public:
  FileDescriptor() = default;
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor();
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(other.release()) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept;
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;

  int get() const { return fd_; }
  int release() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
  }
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// The result of opening a name beneath the folder: the descriptor, or why there is none, in
// words that complete "cannot open 'NAME': ".
struct ConfinedFile {
  FileDescriptor fd;
  std::string failure;
  // Whether the name was refused (it leaves the folder: an absolute name, `..`, a link out; or
  // it is no regular file), as opposed to a missing file or a permission the system denied.
  bool refused = false;
  explicit operator bool() const { return static_cast<bool>(fd); }
};

class ModelFolder {
 public:
  // How names are resolved: by the kernel beneath the folder (openat2), falling back to the
  // component walk where it is refused; or by the component walk alone (for tests of the
  // fallback, as on a kernel without openat2).
  enum class Resolution { Beneath, ComponentWalk };

  // The current folder.
  ModelFolder() = default;
  explicit ModelFolder(std::filesystem::path folder, Resolution resolution = Resolution::Beneath);

  const std::filesystem::path& path() const { return folder_; }
  // The name as the user would find it: the folder joined with the name.
  std::filesystem::path pathOf(const std::string& name) const;

  // Opens `name` beneath the folder. A file opened for writing is created with mode 0666 under
  // the umask; Write and WriteRead truncate it only once it is known to be a regular file.
  ConfinedFile open(const std::string& name, FileAccess access) const;

  // Why `name` may not be opened: it leaves the folder or is no regular file (the refusals of
  // open()); empty when it may, and when it is missing or the system denies it (those are for
  // the reader to report, as cpfg reports a missing file). For references a model's file makes
  // to files that a reader opens by path afterwards: a model is files at rest, and the check is
  // made when they are read.
  std::string refusal(const std::string& name) const;

  // Reads a whole regular file beneath the folder into `text`; false with `failure` set when it
  // cannot be opened or is larger than maxBytes.
  bool read(const std::string& name, std::string& text, std::string& failure,
            std::size_t maxBytes = kMaxReadBytes) const;

  // Removes a regular file or link beneath the folder (never a file the link names); no error
  // when there is none.
  void remove(const std::string& name) const;

  static constexpr std::size_t kMaxReadBytes = std::size_t{1} << 30;

 private:
  std::filesystem::path folder_ = ".";
  Resolution resolution_ = Resolution::Beneath;
};

}  // namespace hirsute
