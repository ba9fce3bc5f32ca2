#include "hirsute/viewer/png_image.h"

#include <png.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace hirsute {
namespace {

// libpng's simplified API (png_image_*) reports errors in the struct instead of longjmp, so no
// C frame is ever unwound by a C++ exception.
class PngStruct {
 public:
  PngStruct() {
    std::memset(&image_, 0, sizeof image_);
    image_.version = PNG_IMAGE_VERSION;
  }
  ~PngStruct() { png_image_free(&image_); }
  PngStruct(const PngStruct&) = delete;
  PngStruct& operator=(const PngStruct&) = delete;
  png_image* get() { return &image_; }
  png_image* operator->() { return &image_; }

 private:
  png_image image_;
};

std::runtime_error writeError(const std::filesystem::path& path, const std::string& why) {
  return std::runtime_error(path.string() + ": cannot write: " + why);
}

}  // namespace

void writePng(const std::filesystem::path& path, const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0) throw writeError(path, "the image is empty");
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i) {
    std::memcpy(&rgb[i * 3], &image.rgba[i * 4], 3);
  }

  std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  std::string name = ".";
  name.append(path.filename().string()).append(".tmp-XXXXXX");
  std::string temporary = (folder / name).string();
  int fd = mkstemp(temporary.data());
  if (fd < 0) throw writeError(path, std::strerror(errno));
  // mkstemp makes the file private (0600); the result gets the usual mode under the umask.
  mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  std::FILE* stream = fdopen(fd, "wb");
  if (!stream) {
    int saved = errno;
    close(fd);
    unlink(temporary.c_str());
    throw writeError(path, std::strerror(saved));
  }

  PngStruct png;
  png->width = static_cast<png_uint_32>(image.width);
  png->height = static_cast<png_uint_32>(image.height);
  png->format = PNG_FORMAT_RGB;
  bool ok = png_image_write_to_stdio(png.get(), stream, 0, rgb.data(), image.width * 3, nullptr);
  std::string why = ok ? "" : png->message;
  if (std::fflush(stream) != 0 && ok) {
    ok = false;
    why = std::strerror(errno);
  }
  if (std::fclose(stream) != 0 && ok) {
    ok = false;
    why = std::strerror(errno);
  }
  if (ok && std::rename(temporary.c_str(), path.c_str()) != 0) {
    ok = false;
    why = std::strerror(errno);
  }
  if (!ok) {
    unlink(temporary.c_str());
    throw writeError(path, why);
  }
}

RgbaImage readPng(const std::filesystem::path& path) {
  PngStruct png;
  if (!png_image_begin_read_from_file(png.get(), path.c_str())) {
    throw std::runtime_error(path.string() + ": cannot read: " + png->message);
  }
  png->format = PNG_FORMAT_RGBA;
  RgbaImage image(static_cast<int>(png->width), static_cast<int>(png->height));
  if (!png_image_finish_read(png.get(), nullptr, image.rgba.data(), image.width * 4, nullptr)) {
    throw std::runtime_error(path.string() + ": cannot read: " + png->message);
  }
  return image;
}

}  // namespace hirsute
