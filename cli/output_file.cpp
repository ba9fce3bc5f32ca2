#include "output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace hirsute::cli {

OutputFile::OutputFile(const std::string& path) : target_(path) {
  if (path.empty() || path == "-") {
    toStdout_ = true;
    stream_ = stdout;
    return;
  }
  std::filesystem::path target(path);
  std::string folder = target.parent_path().empty() ? "." : target.parent_path().string();
  temporary_ = folder + "/." + target.filename().string() + ".tmp-XXXXXX";
  int fd = mkstemp(temporary_.data());
  if (fd < 0) throw std::runtime_error(path + ": cannot create the output file: " + std::strerror(errno));
  // mkstemp creates the file private (0600); the result gets the usual mode under the umask.
  mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  stream_ = fdopen(fd, "wb");
  if (!stream_) {
    close(fd);
    unlink(temporary_.c_str());
    throw std::runtime_error(path + ": cannot open the output file: " + std::strerror(errno));
  }
}

OutputFile::~OutputFile() {
  if (toStdout_ || committed_) return;
  if (stream_) std::fclose(stream_);
  unlink(temporary_.c_str());
}

bool OutputFile::commit() {
  if (toStdout_) return std::fflush(stdout) == 0;
  bool ok = std::fflush(stream_) == 0;
  ok = (std::fclose(stream_) == 0) && ok;
  stream_ = nullptr;
  if (ok) ok = std::rename(temporary_.c_str(), target_.c_str()) == 0;
  if (!ok) {
    int saved = errno;
    unlink(temporary_.c_str());
    errno = saved;
  }
  committed_ = true;
  return ok;
}

}  // namespace hirsute::cli
