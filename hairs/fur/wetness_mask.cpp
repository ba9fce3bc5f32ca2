#include "hirsute/hairs/fur/wetness_mask.h"

#include <algorithm>
#include <cmath>

namespace hirsute::fur {

void clearWetness(FurSurface& surface, int size) {
  surface.wetnessSize = size;
  surface.wetness.clear();
  surface.wetness.shrink_to_fit();
}

glm::vec2 parameterDifference(const FurSurface& surface, const glm::vec2& a, const glm::vec2& b) {
  glm::vec2 d = a - b;
  if (surface.wrapsU) d.x -= std::round(d.x);
  return d;
}

void blendDroplet(FurSurface& surface, const glm::vec2& centre, float radius, float wetness) {
  const int n = surface.wetnessSize;
  if (n <= 0 || radius <= 0) return;
  if (surface.wetness.empty()) {
    surface.wetness.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), glm::vec4(0.0f));
  }
  const float texel = 1.0f / static_cast<float>(n);
  // The texel rows and columns the droplet can reach (columns may run past the edges: they wrap
  // on a wrapping surface and are dropped on another).
  const int row0 = std::max(0, static_cast<int>(std::floor((centre.y - radius) * n)));
  const int row1 = std::min(n - 1, static_cast<int>(std::floor((centre.y + radius) * n)));
  const int column0 = static_cast<int>(std::floor((centre.x - radius) * n));
  int column1 = static_cast<int>(std::floor((centre.x + radius) * n));
  if (surface.wrapsU) column1 = std::min(column1, column0 + n - 1);  // each column once
  for (int row = row0; row <= row1; ++row) {
    for (int column = column0; column <= column1; ++column) {
      int c = column;
      if (surface.wrapsU) {
        c = ((column % n) + n) % n;
      } else if (column < 0 || column >= n) {
        continue;
      }
      const glm::vec2 at((static_cast<float>(c) + 0.5f) * texel, (static_cast<float>(row) + 0.5f) * texel);
      if (glm::length(parameterDifference(surface, at, centre)) > radius) continue;
      glm::vec4& mask = surface.wetness[static_cast<std::size_t>(row) * n + static_cast<std::size_t>(c)];
      const glm::vec2 maskCentre(mask.x, mask.y);
      if (mask.w != 0 && glm::length(parameterDifference(surface, maskCentre, centre)) <= radius) {
        const float total = std::clamp(mask.w + wetness, 0.0f, 1.0f);
        if (total != 0) {
          const float alpha = wetness / total;
          // Move the centre the short way round, then bring it back into [0, 1).
          glm::vec2 moved = maskCentre + alpha * parameterDifference(surface, centre, maskCentre);
          if (surface.wrapsU) moved.x -= std::floor(moved.x);
          mask.x = moved.x;
          mask.y = moved.y;
          mask.z = (1 - alpha) * mask.z + alpha * radius;
        }
        mask.w = total;
      } else {
        mask = glm::vec4(centre, radius, wetness);
      }
    }
  }
}

glm::vec4 wetnessAt(const FurSurface& surface, const glm::vec2& uv) {
  const int n = surface.wetnessSize;
  if (n <= 0 || surface.wetness.empty()) return glm::vec4(0.0f);
  auto index = [n](float t) { return static_cast<int>(std::floor(t * static_cast<float>(n))); };
  int column = index(uv.x), row = index(uv.y);
  column = surface.wrapsU ? ((column % n) + n) % n : std::clamp(column, 0, n - 1);
  row = std::clamp(row, 0, n - 1);
  return surface.wetness[static_cast<std::size_t>(row) * n + static_cast<std::size_t>(column)];
}

bool dry(FurSurface& surface, float amount) {
  bool wet = false;
  for (glm::vec4& texel : surface.wetness) {
    if (texel.w == 0) continue;
    texel.w = std::max(0.0f, texel.w - amount);
    if (texel.w == 0) texel = glm::vec4(0.0f);
    wet = wet || texel.w > 0;
  }
  return wet;
}

}  // namespace hirsute::fur
