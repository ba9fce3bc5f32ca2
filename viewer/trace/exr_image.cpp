#include "hirsute/viewer/trace/exr_image.h"

#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "hirsute/core/output_target.h"

namespace hirsute::trace {
namespace {

// OpenEXR seeks back to write its table of line offsets, which a pipe or a device cannot do:
// the file is made in memory and written out in one piece.
class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const auto count = static_cast<std::size_t>(n);
    if (position_ + count > bytes_.size()) bytes_.resize(position_ + count);
    std::memcpy(bytes_.data() + position_, c, count);
    position_ += count;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
  std::size_t position_ = 0;
};

half toHalf(float v) {
  constexpr float kLargest = 65504.0f;  // the largest finite half
  if (std::isnan(v)) return half(0.0f);
  return half(std::clamp(v, -kLargest, kLargest));
}

}  // namespace

void writeExr(const std::filesystem::path& path, int width, int height,
              const std::vector<glm::vec3>& pixels, OutputGroup* group) {
  const std::size_t count =
      static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0));
  if (count == 0 || pixels.size() != count) {
    throw std::runtime_error(path.string() + ": cannot write: the image is empty");
  }
  std::vector<Imf::Rgba> rgba(count);
  for (std::size_t i = 0; i < count; ++i) {
    rgba[i] = Imf::Rgba(toHalf(pixels[i].r), toHalf(pixels[i].g), toHalf(pixels[i].b), 1.0f);
  }
  MemoryStream memory;
  try {
    Imf::RgbaOutputFile file(memory, Imf::Header(width, height, 1.0f, Imath::V2f(0, 0), 1.0f,
                                                 Imf::INCREASING_Y, Imf::ZIP_COMPRESSION),
                             Imf::WRITE_RGB);
    file.setFrameBuffer(rgba.data(), 1, static_cast<std::size_t>(width));
    file.writePixels(height);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": cannot write: " + e.what());
  }
  OutputTarget target(path, group);
  const std::vector<char>& bytes = memory.bytes();
  if (std::fwrite(bytes.data(), 1, bytes.size(), target.stream()) != bytes.size()) {
    throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
  }
  target.commit();
}

}  // namespace hirsute::trace
