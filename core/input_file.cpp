#include "hirsute/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hirsute {

std::string fileKindOf(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "a special file";
}

FileDescriptor openInputFile(const std::filesystem::path& file, std::string& failure) {
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for a writer;
  // O_NOCTTY: a terminal never becomes ours.
  FileDescriptor fd(::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (!fd) {
    failure = errno == ENXIO ? "it is a socket, not a regular file" : std::strerror(errno);
    return {};
  }
  struct stat st {};
  if (fstat(fd.get(), &st) != 0) {
    failure = std::strerror(errno);
    return {};
  }
  if (!S_ISREG(st.st_mode)) {
    failure = "it is " + fileKindOf(st.st_mode) + ", not a regular file";
    return {};
  }
  const int status = fcntl(fd.get(), F_GETFL);
  if (status >= 0) fcntl(fd.get(), F_SETFL, status & ~O_NONBLOCK);
  return fd;
}

bool readInputFile(const std::filesystem::path& file, std::string& text, std::string& failure,
                   std::size_t maxBytes) {
  const FileDescriptor fd = openInputFile(file, failure);
  return fd && readDescriptor(fd.get(), text, failure, maxBytes);
}

bool readDescriptor(int fd, std::string& text, std::string& failure, std::size_t maxBytes) {
  text.clear();
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      failure = std::strerror(errno);
      return false;
    }
    if (n == 0) return true;
    if (text.size() + static_cast<std::size_t>(n) > maxBytes) {
      failure = "it is larger than " + std::to_string(maxBytes) + " bytes";
      return false;
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace hirsute
