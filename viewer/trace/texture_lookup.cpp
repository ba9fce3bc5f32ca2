#include "hirsute/viewer/trace/texture_lookup.h"

#include <cmath>
#include <cstddef>

namespace hirsute::trace {

glm::vec3 bilinearColourAt(const Texture& texture, const glm::vec2& uv) {
  const int width = texture.width, height = texture.height;
  if (width <= 0 || height <= 0) return glm::vec3(0.0f);
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (texture.rgba.size() < 4 * texels) return glm::vec3(0.0f);
  // The texel below the sample point and the share of the next one, in texel units.
  struct Axis {
    int low, high;
    float share;
  };
  auto axis = [](float t, int n) {
    if (!(std::abs(t) < 1e6f)) t = 0;  // no int holds the texel of a coordinate past this
    // Repeating: only the fraction of t matters, which keeps s small enough for a float's steps.
    const float s = (t - std::floor(t)) * static_cast<float>(n) - 0.5f;
    const float below = std::floor(s);
    const int i = static_cast<int>(below);
    return Axis{((i % n) + n) % n, (((i + 1) % n) + n) % n, s - below};
  };
  const Axis x = axis(uv.x, width), y = axis(uv.y, height);
  auto texel = [&](int i, int j) {
    const int row = height - 1 - j;  // v = 0 is the last row
    const std::uint8_t* p =
        &texture.rgba[4 * (static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(i))];
    return glm::vec3(p[0], p[1], p[2]);
  };
  const glm::vec3 bottom = glm::mix(texel(x.low, y.low), texel(x.high, y.low), x.share);
  const glm::vec3 top = glm::mix(texel(x.low, y.high), texel(x.high, y.high), x.share);
  return glm::mix(bottom, top, y.share) / 255.0f;
}

}  // namespace hirsute::trace
