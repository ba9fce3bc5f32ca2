#include "hirsute/core/model_folder.h"

#include <fcntl.h>
#include <linux/openat2.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "hirsute/core/input_file.h"

namespace hirsute {
namespace {

int flagsFor(FileAccess access) {
  switch (access) {
    case FileAccess::Read:
      return O_RDONLY;
    case FileAccess::ReadWrite:
      return O_RDWR;
    case FileAccess::Write:
      return O_WRONLY | O_CREAT;
    case FileAccess::WriteRead:
      return O_RDWR | O_CREAT;
    case FileAccess::Append:
      return O_WRONLY | O_CREAT | O_APPEND;
    case FileAccess::AppendRead:
      return O_RDWR | O_CREAT | O_APPEND;
  }
  return O_RDONLY;
}

bool truncates(FileAccess access) {
  return access == FileAccess::Write || access == FileAccess::WriteRead;
}

// openat2 beneath `folder`; -1 with errno, ENOSYS where the kernel or a filter refuses the call.
int openBeneath(int folder, const char* name, int flags) {
#ifdef SYS_openat2
  open_how how{};
  how.flags = static_cast<unsigned long long>(flags);
  how.mode = (flags & O_CREAT) ? 0666 : 0;
  how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
  long fd = syscall(SYS_openat2, folder, name, &how, sizeof how);
  // Some seccomp filters answer EPERM for calls they do not know; E2BIG and EINVAL are what an
  // older kernel says of a structure or flag it lacks.
  if (fd < 0 && (errno == EPERM || errno == E2BIG)) errno = ENOSYS;
  return static_cast<int>(fd);
#else
  (void)folder;
  (void)name;
  (void)flags;
  errno = ENOSYS;
  return -1;
#endif
}

// Opens each component with O_NOFOLLOW: no link is followed at all.
int openByComponents(int folder, const std::filesystem::path& name, int flags) {
  std::vector<std::string> parts;
  for (const auto& part : name) {
    if (part.empty() || part == ".") continue;
    parts.push_back(part.string());
  }
  if (parts.empty()) {
    errno = EISDIR;
    return -1;
  }
  FileDescriptor current(fcntl(folder, F_DUPFD_CLOEXEC, 0));
  if (!current) return -1;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    FileDescriptor next(
        openat(current.get(), parts[i].c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (!next) {
      // A link where a folder is expected reads as ENOTDIR with O_NOFOLLOW; say it is a link.
      struct stat st {};
      if (fstatat(current.get(), parts[i].c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
          S_ISLNK(st.st_mode)) {
        errno = ELOOP;
      }
      return -1;
    }
    current = std::move(next);
  }
  return openat(current.get(), parts.back().c_str(), flags | O_NOFOLLOW);
}

}  // namespace

bool fileAccessOfMode(const std::string& mode, FileAccess& access) {
  if (mode.empty() || mode.find_first_not_of("rwab+") != std::string::npos) return false;
  if (std::count(mode.begin(), mode.end(), '+') > 1 ||
      std::count(mode.begin(), mode.end(), 'b') > 1)
    return false;
  const bool plus = mode.find('+') != std::string::npos;
  switch (mode[0]) {
    case 'r':
      access = plus ? FileAccess::ReadWrite : FileAccess::Read;
      break;
    case 'w':
      access = plus ? FileAccess::WriteRead : FileAccess::Write;
      break;
    case 'a':
      access = plus ? FileAccess::AppendRead : FileAccess::Append;
      break;
    default:
      return false;
  }
  return mode.find_first_of("rwa", 1) == std::string::npos;
}

FileDescriptor::~FileDescriptor() {
  if (fd_ >= 0) ::close(fd_);
}

FileDescriptor& FileDescriptor::operator=(FileDescriptor&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

ModelFolder::ModelFolder(std::filesystem::path folder, Resolution resolution)
    : folder_(folder.empty() ? std::filesystem::path(".") : std::move(folder)),
      resolution_(resolution) {}

std::filesystem::path ModelFolder::pathOf(const std::string& name) const {
  return folder_ == "." ? std::filesystem::path(name) : folder_ / name;
}

ConfinedFile ModelFolder::open(const std::string& name, FileAccess access) const {
  ConfinedFile result;
  const std::filesystem::path path(name);
  if (name.empty()) {
    result.failure = "the name is empty";
    return result;
  }
  if (path.is_absolute()) {
    result.failure = "an absolute name leaves the model's folder";
    result.refused = true;
    return result;
  }
  for (const auto& part : path) {
    if (part == "..") {
      result.failure = "'..' leaves the model's folder";
      result.refused = true;
      return result;
    }
  }

  FileDescriptor folder(::open(folder_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!folder) {
    result.failure =
        "cannot open the model's folder " + folder_.string() + ": " + std::strerror(errno);
    return result;
  }
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for its writer
  // or reader; O_NOCTTY: a terminal never becomes ours. Truncation waits until the file is
  // known to be a regular one.
  const int flags = flagsFor(access) | O_CLOEXEC | O_NOCTTY | O_NONBLOCK;
  int fd = -1;
  bool walked = resolution_ == Resolution::ComponentWalk;
  if (!walked) {
    fd = openBeneath(folder.get(), name.c_str(), flags);
    walked = fd < 0 && errno == ENOSYS;
  }
  if (walked) fd = openByComponents(folder.get(), path, flags);
  if (fd < 0) {
    const int error = errno;
    if (error == EXDEV) {
      result.failure = "a symbolic link leads out of the model's folder";
      result.refused = true;
    } else if (error == ELOOP && walked) {
      result.failure =
          "a symbolic link on the way is not followed (links are followed only where the "
          "system resolves them beneath the folder)";
      result.refused = true;
    } else if (error == ELOOP) {
      result.failure = "too many symbolic links";
    } else if (error == ENXIO) {
      result.failure = "it is a FIFO or socket with no reader, not a regular file";
      result.refused = true;
    } else {
      result.failure = std::strerror(error);
    }
    return result;
  }
  FileDescriptor file(fd);
  struct stat st {};
  if (fstat(file.get(), &st) != 0) {
    result.failure = std::strerror(errno);
    return result;
  }
  if (!S_ISREG(st.st_mode)) {
    result.failure = "it is " + fileKindOf(st.st_mode) + ", not a regular file";
    result.refused = true;
    return result;
  }
  // A hard link is the same file under a second name, which may be anywhere on the file system
  // (a downloaded model's folder may carry one, made where the user's files are): written
  // through, it would change that file. Only a file whose one name is this one is written.
  if (access != FileAccess::Read && st.st_nlink > 1) {
    result.failure = "it has " + std::to_string(st.st_nlink) +
                     " names (hard links), and one may be outside the model's folder; a file "
                     "is written only where its one name is in the folder";
    result.refused = true;
    return result;
  }
  const int status = fcntl(file.get(), F_GETFL);
  if (status >= 0) fcntl(file.get(), F_SETFL, status & ~O_NONBLOCK);
  if (truncates(access) && ftruncate(file.get(), 0) != 0) {
    result.failure = std::strerror(errno);
    return result;
  }
  result.fd = std::move(file);
  return result;
}

std::string ModelFolder::refusal(const std::string& name) const {
  const ConfinedFile file = open(name, FileAccess::Read);
  return file.refused ? file.failure : std::string();
}

bool ModelFolder::read(const std::string& name, std::string& text, std::string& failure,
                       std::size_t maxBytes) const {
  ConfinedFile file = open(name, FileAccess::Read);
  if (!file) {
    failure = file.failure;
    return false;
  }
  return readDescriptor(file.fd.get(), text, failure, maxBytes);
}

void ModelFolder::remove(const std::string& name) const {
  const std::filesystem::path path(name);
  if (name.empty() || path.is_absolute()) return;
  for (const auto& part : path)
    if (part == "..") return;
  std::filesystem::path parent = path.parent_path();
  FileDescriptor folder(::open(folder_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!folder) return;
  if (!parent.empty()) {
    int fd = -1;
    if (resolution_ == Resolution::Beneath)
      fd = openBeneath(folder.get(), parent.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (resolution_ == Resolution::ComponentWalk || (fd < 0 && errno == ENOSYS))
      fd = openByComponents(folder.get(), parent, O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    folder = FileDescriptor(fd);
  }
  // unlinkat removes a link itself, never what it names.
  unlinkat(folder.get(), path.filename().c_str(), 0);
}

}  // namespace hirsute
