#include "hirsute/core/output_target.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
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

}  // namespace

OutputGroup::~OutputGroup() {
  for (const Pending& file : pending_) unlink(file.temporary.c_str());
}

void OutputGroup::commit() {
  std::vector<Pending> files = std::move(pending_);
  pending_.clear();
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (std::rename(files[i].temporary.c_str(), files[i].destination.c_str()) != 0) {
      const int error = errno;
      for (std::size_t j = i; j < files.size(); ++j) unlink(files[j].temporary.c_str());
      throw std::runtime_error(files[i].target.string() + ": cannot write: " + std::strerror(error));
    }
  }
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

OutputTarget::~OutputTarget() {
  if (committed_) return;
  if (stream_ != nullptr) {
    std::fclose(stream_);
  } else if (fd_ >= 0) {
    close(fd_);
  }
  if (!temporary_.empty()) unlink(temporary_.c_str());
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
    group_->pending_.push_back({temporary_, destination_, target_});
    committed_ = true;
    return;
  }
  if (error == 0 && !temporary_.empty() &&
      std::rename(temporary_.c_str(), destination_.c_str()) != 0) {
    error = errno;
  }
  if (error != 0) fail("cannot write", error);
  committed_ = true;
}

void OutputTarget::fail(const std::string& what, int error) const {
  throw std::runtime_error(target_.string() + ": " + what + ": " + std::strerror(error));
}

}  // namespace hirsute
