#include "hirsute/viewer/trace/veins.h"

#include <algorithm>
#include <cmath>

#include "hirsute/viewer/trace/sampling.h"

namespace hirsute::trace {
namespace {

// A point of the Catmull-Rom spline through p0…p3 between p1 and p2, at t in [0, 1].
glm::vec2 catmullRom(glm::vec2 p0, glm::vec2 p1, glm::vec2 p2, glm::vec2 p3, float t) {
  const float t2 = t * t, t3 = t2 * t;
  return 0.5f * (2.0f * p1 + (p2 - p0) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                 (3.0f * p1 - p0 - 3.0f * p2 + p3) * t3);
}

// A normal deviate by Box and Muller, from two uniform numbers.
float gaussian(Random& random) {
  const float a = std::max(random.uniform(), 1e-7f), b = random.uniform();
  return std::sqrt(-2 * std::log(a)) * std::cos(2 * kPi * b);
}

}  // namespace

VeinMap::VeinMap(const VeinSettings& settings, float aspect, int variant)
    : aspect_(std::isfinite(aspect) ? std::clamp(aspect, 0.02f, 50.0f) : 0.4f),
      height_(static_cast<std::size_t>(kAcross) * kAlong, 0.0f) {
  const std::uint64_t seed = (static_cast<std::uint64_t>(settings.seed) << 8u) ^
                             static_cast<std::uint64_t>(variant) ^ 0x9e3779b97f4a7c15ull;
  if (settings.pattern == VeinPattern::Splines) {
    splines(settings, seed);
  } else {
    particles(settings, seed);
  }
}

void VeinMap::stroke(glm::vec2 a, glm::vec2 b, float wa, float wb, float peak) {
  // In the surface's proportions: x = u·aspect, y = v.
  const glm::vec2 scale(aspect_, 1.0f);
  const glm::vec2 pa = a * scale, pb = b * scale;
  const float reach = std::max(wa, wb) / 2;
  const glm::vec2 low = (glm::min(pa, pb) - reach) / scale, high = (glm::max(pa, pb) + reach) / scale;
  const int i0 = std::max(0, static_cast<int>(std::floor(low.x * kAcross - 0.5f)));
  const int i1 = std::min(kAcross - 1, static_cast<int>(std::ceil(high.x * kAcross - 0.5f)));
  const int j0 = std::max(0, static_cast<int>(std::floor(low.y * kAlong - 0.5f)));
  const int j1 = std::min(kAlong - 1, static_cast<int>(std::ceil(high.y * kAlong - 0.5f)));
  if (i1 < i0 || j1 < j0) return;
  const auto box = static_cast<std::size_t>(i1 - i0 + 1) * static_cast<std::size_t>(j1 - j0 + 1);
  if (work_ + box > kMaxWork) return;
  work_ += box;
  const glm::vec2 ab = pb - pa;
  const float length2 = glm::dot(ab, ab);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const glm::vec2 p = glm::vec2((static_cast<float>(i) + 0.5f) / kAcross,
                                    (static_cast<float>(j) + 0.5f) / kAlong) * scale;
      const float t = length2 > 0 ? std::clamp(glm::dot(p - pa, ab) / length2, 0.0f, 1.0f) : 0.0f;
      const float half = (wa + (wb - wa) * t) / 2;
      const float d = glm::length(p - (pa + t * ab));
      if (d >= half || half <= 0) continue;
      // A rounded ridge: flat on top, falling smoothly to 0 at its edges.
      const float r = d / half;
      const float h = peak * (1 - r * r) * (1 - r * r);
      float& cell = height_[static_cast<std::size_t>(j) * kAcross + static_cast<std::size_t>(i)];
      cell = std::max(cell, h);
    }
  }
}

// Veins fanning from the base to the tip, each through jittered points joined by a spline; some
// fork on the way (the crocus's petals).
void VeinMap::splines(const VeinSettings& settings, std::uint64_t seed) {
  Random random(seed, 1);
  const int veins = settings.count > 0 ? settings.count : 11;
  const float width = settings.width;
  constexpr int kPoints = 7;  // jittered points along a vein
  constexpr int kSteps = 10;  // spline samples between two points
  const float spacing = 0.88f / static_cast<float>(veins);
  auto draw = [&](const std::vector<glm::vec2>& points, float w0, float w1, float peak) {
    const int spans = static_cast<int>(points.size()) - 1;
    glm::vec2 last = points.front();
    for (int s = 0; s < spans; ++s) {
      const glm::vec2 p0 = points[static_cast<std::size_t>(std::max(s - 1, 0))];
      const glm::vec2 p3 = points[static_cast<std::size_t>(std::min(s + 2, spans))];
      for (int k = 1; k <= kSteps; ++k) {
        const float t = static_cast<float>(k) / kSteps;
        const glm::vec2 p = catmullRom(p0, points[static_cast<std::size_t>(s)],
                                       points[static_cast<std::size_t>(s + 1)], p3, t);
        const float along0 = (static_cast<float>(s) + static_cast<float>(k - 1) / kSteps) / spans;
        const float along1 = (static_cast<float>(s) + t) / spans;
        stroke(last, p, w0 + (w1 - w0) * along0, w0 + (w1 - w0) * along1, peak);
        last = p;
      }
    }
  };
  for (int k = 0; k < veins; ++k) {
    const float side = (static_cast<float>(k) + 0.5f) / static_cast<float>(veins) - 0.5f;
    const float tip = 0.5f + 0.88f * side + 0.25f * spacing * gaussian(random);
    const float base = 0.5f + 0.22f * side;
    std::vector<glm::vec2> points;
    for (int i = 0; i < kPoints; ++i) {
      const float v = 0.01f + 0.96f * static_cast<float>(i) / (kPoints - 1);
      // The fan opens quickly above the base, then the veins run nearly parallel.
      const float open = std::sqrt(v);
      const float jitter = i == 0 ? 0.0f : 0.12f * spacing * gaussian(random);
      points.emplace_back(std::clamp(base + (tip - base) * open + jitter, 0.01f, 0.99f), v);
    }
    // The middle vein is the strongest.
    const float peak = 1 - 0.35f * std::abs(side) * 2;
    draw(points, width, 0.35f * width, peak);
    // A fork towards the neighbour on the outer side, from a third to two thirds of the way.
    if (random.uniform() < 0.6f) {
      const int from = 2 + static_cast<int>(random.uniform() * 2);
      std::vector<glm::vec2> branch{points[static_cast<std::size_t>(from - 1)],
                                    points[static_cast<std::size_t>(from)]};
      const float outward = side >= 0 ? 1.0f : -1.0f;
      for (int i = from + 1; i < kPoints; ++i) {
        const float share = static_cast<float>(i - from) / static_cast<float>(kPoints - 1 - from);
        const glm::vec2 on = points[static_cast<std::size_t>(i)];
        branch.emplace_back(
            std::clamp(on.x + outward * spacing * 0.5f * share + 0.1f * spacing * gaussian(random),
                       0.01f, 0.99f),
            on.y);
      }
      const float along = static_cast<float>(from) / (kPoints - 1);
      draw(branch, width * (1 - 0.65f * along) * 0.8f, 0.3f * width, 0.8f * peak);
    }
  }
}

// Particles scattered over the leaf move towards the midrib and the base and towards their
// nearest neighbour, merging when they meet; their paths are the veins, thicker the more
// particles have merged into them (Rodkaew et al. 2003). The midrib runs up the middle.
void VeinMap::particles(const VeinSettings& settings, std::uint64_t seed) {
  Random random(seed, 2);
  const int count = settings.count > 0 ? settings.count : 160;
  const float width = settings.width;
  // In the leaf's proportions: x across (0 at the midrib), y along.
  const float half = aspect_ / 2;
  auto toUv = [&](glm::vec2 p) { return glm::vec2(p.x / aspect_ + 0.5f, p.y); };
  const float midribTip = 0.96f;
  auto midribWidth = [&](float y) { return width * (1.6f - 1.2f * std::clamp(y, 0.0f, 1.0f)); };
  stroke({0.5f, 0.0f}, {0.5f, midribTip}, midribWidth(0), midribWidth(midribTip), 1.0f);

  struct Particle {
    glm::vec2 p;
    float mass = 1;
    bool alive = true;
  };
  std::vector<Particle> all;
  for (int k = 0; k < count; ++k) {
    // Uniform over the leaf, away from its very edge and base.
    all.push_back({glm::vec2((random.uniform() * 2 - 1) * half * 0.92f,
                             0.04f + 0.93f * random.uniform())});
  }
  const float step = 0.004f;
  const float reach = 0.08f;               // neighbours further off do not attract
  const float slant = 1 / std::tan(glm::radians(50.0f));  // secondary veins meet the midrib at 50°
  const float veinWidth = 0.45f * width;
  // The walk ends when every particle has joined the midrib, or when its neighbour searches or
  // its strokes have cost what a map may (the map is full long before).
  constexpr std::size_t kMaxComparisons = std::size_t{200} << 20;
  std::size_t comparisons = 0;
  for (int iteration = 0; iteration < 2000; ++iteration) {
    if (comparisons > kMaxComparisons || work_ >= kMaxWork) break;
    comparisons += all.size() * all.size();
    bool moved = false;
    for (std::size_t a = 0; a < all.size(); ++a) {
      Particle& p = all[a];
      if (!p.alive) continue;
      moved = true;
      // Towards the midrib, down towards the base at the veins' angle.
      const glm::vec2 target(0.0f, p.p.y - std::abs(p.p.x) * slant);
      glm::vec2 direction = glm::normalize(target - p.p + glm::vec2(0, -1e-6f));
      std::size_t nearest = all.size();
      float nearestDistance = reach;
      for (std::size_t b = 0; b < all.size(); ++b) {
        if (b == a || !all[b].alive) continue;
        const float d = glm::distance(p.p, all[b].p);
        if (d < nearestDistance) {
          nearestDistance = d;
          nearest = b;
        }
      }
      if (nearest < all.size()) {
        const glm::vec2 towards = (all[nearest].p - p.p) / std::max(nearestDistance, 1e-6f);
        direction = glm::normalize(direction + 0.8f * (1 - nearestDistance / reach) * towards);
      }
      const glm::vec2 next = p.p + step * direction;
      const float w = veinWidth * std::min(2.5f, std::sqrt(p.mass));
      const float peak = std::min(1.0f, 0.55f + 0.1f * p.mass);
      if (nearest < all.size() && nearestDistance < 1.5f * step) {
        // Merged: the path ends on the neighbour, which carries both on.
        stroke(toUv(p.p), toUv(all[nearest].p), w, w, peak);
        all[nearest].mass += p.mass;
        p.alive = false;
        continue;
      }
      stroke(toUv(p.p), toUv(next), w, w, peak);
      p.p = next;
      if (std::abs(p.p.x) < midribWidth(p.p.y) * 0.25f || p.p.y <= 0.0f ||
          std::abs(p.p.x) > half) {
        p.alive = false;  // joined the midrib, or left the leaf
      }
    }
    if (!moved) break;
  }
}

float VeinMap::texel(int i, int j) const {
  i = std::clamp(i, 0, kAcross - 1);
  j = std::clamp(j, 0, kAlong - 1);
  return height_[static_cast<std::size_t>(j) * kAcross + static_cast<std::size_t>(i)];
}

float VeinMap::height(glm::vec2 uv) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return 0;  // a surface point of no number
  const float x = std::clamp(uv.x, 0.0f, 1.0f) * kAcross - 0.5f;
  const float y = std::clamp(uv.y, 0.0f, 1.0f) * kAlong - 0.5f;
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(i), fy = y - static_cast<float>(j);
  const float bottom = texel(i, j) + (texel(i + 1, j) - texel(i, j)) * fx;
  const float top = texel(i, j + 1) + (texel(i + 1, j + 1) - texel(i, j + 1)) * fx;
  return bottom + (top - bottom) * fy;
}

glm::vec2 VeinMap::slope(glm::vec2 uv) const {
  const float du = 1.0f / kAcross, dv = 1.0f / kAlong;
  return {(height(uv + glm::vec2(du, 0)) - height(uv - glm::vec2(du, 0))) / (2 * du),
          (height(uv + glm::vec2(0, dv)) - height(uv - glm::vec2(0, dv))) / (2 * dv)};
}

float VeinMap::coverage() const {
  const auto covered = std::count_if(height_.begin(), height_.end(), [](float h) { return h > 0.5f; });
  return static_cast<float>(covered) / static_cast<float>(height_.size());
}

}  // namespace hirsute::trace
