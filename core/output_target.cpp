#include "hirsute/core/output_target.h"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace hirsute {
namespace {

// The descriptor a path names directly: /dev/stdout, /dev/stderr, /dev/stdin, /dev/fd/N and
// /proc/self/fd/N. Opening those anew would start a new file offset (overwriting what the shell
// appended before), so they are written through a duplicate of the descriptor itself.
std::optional<int> descriptorNamedBy(const std::filesystem::path& path) {
  const std::string text = path.lexically_normal().string();
  if (text == "/dev/stdout") return 1;
  if (text == "/dev/stderr") return 2;
  for (std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (text.size() > prefix.size() && text.compare(0, prefix.size(), prefix) == 0) {
      int fd = -1;
      const char* first = text.data() + prefix.size();
      const char* last = text.data() + text.size();
      auto [end, error] = std::from_chars(first, last, fd);
      if (error == std::errc() && end == last && fd >= 0) return fd;
    }
  }
  return std::nullopt;
}

int descriptorOf(const std::shared_ptr<const FileDescriptor>& folder) {
  return folder ? folder->get() : AT_FDCWD;
}

// What kind of file a mode is, for a message.
std::string kindOf(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

// Creates a new file ".STEM.tmp-XXXXXX.EXT" for NAME = STEM.EXT in `folder` (never through a
// link: O_EXCL and O_NOFOLLOW) and sets `temporary` to its name; -1 with errno when it cannot.
// The extension stays last for a program that writes the file by name and adds the extension
// its format has when the name lacks it (POV-Ray's +O).
int createTemporary(int folder, const std::string& name, std::string& temporary) {
  static constexpr char kLetters[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  const std::filesystem::path path(name);
  std::string extension = path.extension().string();
  // Cut so that the temporary's name stays within the system's 255 bytes.
  if (extension.size() > 32) extension.clear();
  const std::string stem = extension.empty() ? name : path.stem().string();
  // (Appended piece by piece: GCC 12 warns falsely about "." + a string, -Wrestrict.)
  std::string base(1, '.');
  base.append(stem, 0, 200);
  base += ".tmp-";
  for (int attempt = 0; attempt < 100; ++attempt) {
    unsigned char random[6] = {};
    if (getrandom(random, sizeof random, GRND_NONBLOCK) != static_cast<ssize_t>(sizeof random)) {
      const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
      for (std::size_t i = 0; i < sizeof random; ++i)
        random[i] = static_cast<unsigned char>((now >> (8 * i)) ^ (getpid() >> i) ^ attempt);
    }
    temporary = base;
    for (unsigned char r : random) temporary += kLetters[r % (sizeof kLetters - 1)];
    temporary += extension;
    const int fd = openat(folder, temporary.c_str(),
                          O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

OutputGroup::~OutputGroup() {
  for (const Pending& file : pending_)
    unlinkat(descriptorOf(file.folder), file.temporary.c_str(), 0);
}

void OutputGroup::commit() {
  std::vector<Pending> files = std::move(pending_);
  pending_.clear();
  for (std::size_t i = 0; i < files.size(); ++i) {
    const int folder = descriptorOf(files[i].folder);
    if (renameat(folder, files[i].temporary.c_str(), folder, files[i].destination.c_str()) != 0) {
      const int error = errno;
      for (std::size_t j = i; j < files.size(); ++j)
        unlinkat(descriptorOf(files[j].folder), files[j].temporary.c_str(), 0);
      throw std::runtime_error(files[i].target.string() + ": cannot write: " + std::strerror(error));
    }
  }
}

std::uint64_t OutputGroup::bytes() const {
  std::uint64_t total = 0;
  for (const Pending& file : pending_) {
    struct stat st {};
    if (fstatat(descriptorOf(file.folder), file.temporary.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0)
      total += static_cast<std::uint64_t>(st.st_size);
  }
  return total;
}

OutputTarget::OutputTarget(const OutputFolder& folder, const std::string& name, OutputGroup* group)
    : target_(folder.pathOf(name)), destination_(name), folder_(folder.shared()), group_(group) {
  if (!OutputFolder::isPlainName(name)) {
    throw std::runtime_error(target_.string() +
                             ": cannot write: not a plain file name in the output folder");
  }
  // What is at the name now, not followed: a link (symbolic or hard) is replaced by the rename;
  // a folder cannot be, and a FIFO or device is never written in place at a name the user did
  // not type.
  struct stat there {};
  const bool exists = fstatat(folder.descriptor(), name.c_str(), &there, AT_SYMLINK_NOFOLLOW) == 0;
  if (exists && S_ISDIR(there.st_mode)) fail("cannot write", EISDIR);
  if (exists && !S_ISREG(there.st_mode) && !S_ISLNK(there.st_mode)) {
    throw std::runtime_error(target_.string() + ": cannot write: it is " + kindOf(there.st_mode) +
                             ", and a file Hirsute names itself is written only as a regular "
                             "file");
  }
  fd_ = createTemporary(folder.descriptor(), name, temporary_);
  if (fd_ < 0) {
    const int error = errno;
    temporary_.clear();
    fail("cannot create the output file", error);
  }
  // The file it replaces keeps its mode; a new one (or one that replaces a link) gets the usual
  // mode under the umask.
  mode_t mode = 0666;
  if (exists && S_ISREG(there.st_mode)) {
    mode = there.st_mode & 07777;
  } else {
    const mode_t mask = umask(0);
    umask(mask);
    mode &= ~mask;
  }
  fchmod(fd_, mode);
}

OutputTarget::OutputTarget(std::filesystem::path target, OutputGroup* group)
    : target_(std::move(target)), destination_(target_), group_(group) {
  if (std::optional<int> fd = descriptorNamedBy(target_)) {
    fd_ = fcntl(*fd, F_DUPFD_CLOEXEC, 3);
    if (fd_ < 0) fail("cannot open the output", errno);
    return;
  }

  struct stat link {};
  struct stat file {};
  const bool exists = lstat(target_.c_str(), &link) == 0;
  bool replace = !exists || S_ISREG(link.st_mode);
  if (exists && S_ISLNK(link.st_mode)) {
    if (stat(target_.c_str(), &file) != 0) {
      replace = true;  // a dangling link is replaced by the file
    } else if (S_ISREG(file.st_mode)) {
      std::error_code error;
      std::filesystem::path resolved = std::filesystem::canonical(target_, error);
      replace = !error;
      if (replace) destination_ = resolved;
    } else {
      link = file;  // a link to a device or FIFO: written in place below
    }
  }
  if (exists && S_ISDIR(link.st_mode)) fail("cannot write", EISDIR);

  if (!replace) {
    // A device, FIFO, socket or terminal: open what is there. A FIFO waits for its reader, as
    // a shell redirection does.
    fd_ = open(target_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) fail("cannot open the output", errno);
    return;
  }

  std::filesystem::path folder = destination_.parent_path();
  temporary_ = (folder.empty() ? std::string(".") : folder.string()) + "/." +
               destination_.filename().string() + ".tmp-XXXXXX";
  fd_ = mkostemp(temporary_.data(), O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    temporary_.clear();
    fail("cannot create the output file", error);
  }
  // mkstemp makes the file private (0600); the result gets the usual mode under the umask, or
  // keeps the mode of the file it replaces.
  mode_t mode = 0666;
  if (exists && stat(destination_.c_str(), &file) == 0) {
    mode = file.st_mode & 07777;
  } else {
    const mode_t mask = umask(0);
    umask(mask);
    mode &= ~mask;
  }
  fchmod(fd_, mode);
}

std::filesystem::path OutputTarget::writtenPath() const {
  if (temporary_.empty()) return target_;
  if (folder_) return target_.parent_path() / temporary_;
  return temporary_;
}

OutputTarget::~OutputTarget() {
  if (committed_) return;
  if (stream_ != nullptr) {
    std::fclose(stream_);
  } else if (fd_ >= 0) {
    close(fd_);
  }
  if (!temporary_.empty()) unlinkat(descriptorOf(folder_), temporary_.c_str(), 0);
}

std::FILE* OutputTarget::stream() {
  if (stream_ == nullptr && fd_ >= 0) {
    stream_ = fdopen(fd_, "wb");
    if (stream_ == nullptr) fail("cannot open the output", errno);
  }
  return stream_;
}

void OutputTarget::commit() {
  if (committed_) return;
  int error = 0;
  if (stream_ != nullptr) {
    if (std::fflush(stream_) != 0) error = errno;
    if (std::fclose(stream_) != 0 && error == 0) error = errno;
    stream_ = nullptr;
  } else if (fd_ >= 0 && close(fd_) != 0) {
    error = errno;
  }
  fd_ = -1;
  if (error == 0 && !temporary_.empty() && group_ != nullptr) {
    // The group renames it with the others, or removes it.
    group_->pending_.push_back({folder_, temporary_, destination_.string(), target_});
    committed_ = true;
    return;
  }
  const int folder = descriptorOf(folder_);
  if (error == 0 && !temporary_.empty() &&
      renameat(folder, temporary_.c_str(), folder, destination_.c_str()) != 0) {
    error = errno;
  }
  if (error != 0) fail("cannot write", error);
  committed_ = true;
}

void OutputTarget::fail(const std::string& what, int error) const {
  throw std::runtime_error(target_.string() + ": " + what + ": " + std::strerror(error));
}

}  // namespace hirsute
