#include "hirsute/core/output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace hirsute {

OutputFolder::OutputFolder(const std::filesystem::path& path)
    : path_(path.empty() ? std::filesystem::path(".") : path) {
  const int fd = ::open(path_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    throw std::runtime_error(path_.string() +
                             ": cannot open the output folder: " + std::strerror(errno));
  }
  folder_ = std::make_shared<const FileDescriptor>(fd);
}

std::filesystem::path OutputFolder::pathOf(const std::string& name) const {
  return path_ == "." ? std::filesystem::path(name) : path_ / name;
}

bool OutputFolder::isPlainName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

}  // namespace hirsute
