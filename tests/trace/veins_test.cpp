// Procedural veins: spline veins run from base to tip, particle veins are joined to the midrib,
// each variant is another pattern, and in the tracer a vein changes the colour by its share and
// leans the normal as a raised vein would (a grazing light lights one flank, not the other).
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <utility>

#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/trace_scene.h"
#include "hirsute/viewer/trace/veins.h"

namespace {

using namespace hirsute;
using namespace hirsute::trace;

constexpr int kAcross = VeinMap::kAcross, kAlong = VeinMap::kAlong;

glm::vec2 texelCentre(int i, int j) {
  return {(static_cast<float>(i) + 0.5f) / kAcross, (static_cast<float>(j) + 0.5f) / kAlong};
}

// The separate runs of texels above `level` across the row at v.
int runsAcross(const VeinMap& map, float v, float level) {
  int runs = 0;
  bool inside = false;
  for (int i = 0; i < kAcross; ++i) {
    const bool above = map.height({texelCentre(i, 0).x, v}) > level;
    if (above && !inside) ++runs;
    inside = above;
  }
  return runs;
}

VeinSettings settingsOf(VeinPattern pattern) {
  VeinSettings s;
  s.pattern = pattern;
  return s;
}

TEST(VeinMaps, SplineVeinsRunFromBaseToTip) {
  VeinSettings s = settingsOf(VeinPattern::Splines);
  s.count = 9;
  s.width = 0.02f;
  const VeinMap map(s, 0.5f, 0);
  // Every row above the base crosses each vein (and some forks), none is lost on the way.
  for (float v : {0.15f, 0.3f, 0.5f, 0.7f, 0.9f}) {
    const int runs = runsAcross(map, v, 0.3f);
    EXPECT_GE(runs, 7) << "v " << v;
    EXPECT_LE(runs, 18) << "v " << v;
  }
  // The veins fan out: at the tip they spread wider than at the base.
  auto spread = [&](float v) {
    float low = 1, high = 0;
    for (int i = 0; i < kAcross; ++i) {
      const float u = texelCentre(i, 0).x;
      if (map.height({u, v}) > 0.3f) {
        low = std::min(low, u);
        high = std::max(high, u);
      }
    }
    return high - low;
  };
  EXPECT_GT(spread(0.9f), 1.8f * spread(0.05f));
  EXPECT_GT(map.coverage(), 0.03f);
  EXPECT_LT(map.coverage(), 0.4f);
}

TEST(VeinMaps, ParticleVeinsAreJoinedToTheMidrib) {
  const VeinMap map(settingsOf(VeinPattern::Particles), 0.45f, 0);
  // The midrib runs up the middle.
  for (float v : {0.05f, 0.3f, 0.6f, 0.9f}) EXPECT_GT(map.height({0.5f, v}), 0.8f) << v;
  // Veins branch off it on both sides.
  EXPECT_GE(runsAcross(map, 0.5f, 0.3f), 5);
  // Each vein was traced by a particle on its way to the midrib: from the midrib, one walk over
  // the veins reaches nearly all of them.
  std::vector<char> seen(static_cast<std::size_t>(kAcross * kAlong), 0);
  auto vein = [&](int i, int j) { return map.height(texelCentre(i, j)) > 0.2f; };
  std::deque<std::pair<int, int>> open{{kAcross / 2, kAlong / 4}};
  seen[static_cast<std::size_t>(kAlong / 4 * kAcross + kAcross / 2)] = 1;
  int reached = 0;
  while (!open.empty()) {
    const auto [i, j] = open.front();
    open.pop_front();
    ++reached;
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int a = i + di, b = j + dj;
      if (a < 0 || b < 0 || a >= kAcross || b >= kAlong) continue;
      char& mark = seen[static_cast<std::size_t>(b * kAcross + a)];
      if (!mark && vein(a, b)) {
        mark = 1;
        open.emplace_back(a, b);
      }
    }
  }
  int veins = 0;
  for (int j = 0; j < kAlong; ++j) {
    for (int i = 0; i < kAcross; ++i) veins += vein(i, j) ? 1 : 0;
  }
  EXPECT_GT(reached, 0.9 * veins) << reached << " of " << veins;
}

TEST(VeinMaps, AVariantIsAnotherPatternAndASeedGivesOne) {
  for (VeinPattern pattern : {VeinPattern::Splines, VeinPattern::Particles}) {
    const VeinSettings s = settingsOf(pattern);
    const VeinMap a(s, 0.4f, 0), again(s, 0.4f, 0), other(s, 0.4f, 1);
    int same = 0, differ = 0;
    for (int j = 0; j < kAlong; j += 7) {
      for (int i = 0; i < kAcross; i += 3) {
        const glm::vec2 uv = texelCentre(i, j);
        same += a.height(uv) == again.height(uv) ? 1 : 0;
        differ += std::abs(a.height(uv) - other.height(uv)) > 0.3f ? 1 : 0;
      }
    }
    EXPECT_EQ(same, (kAlong / 7 + 1) * (kAcross / 3 + 1));
    EXPECT_GT(differ, 50);
  }
}

// A 1 × 2 leaf in the plane z = 0 facing +z, its u along x and v along y, of grey 0.6 with
// the veins of `veins`.
struct VeinedLeaf {
  Scene scene;
  TraceSettings look;
  std::unique_ptr<TraceScene> traced;

  explicit VeinedLeaf(const VeinSettings& veins) {
    Material grey;
    grey.diffuse = glm::vec3(0.6f);
    scene.materials.push_back(grey);
    look.veins.push_back(veins);
    traced = std::make_unique<TraceScene>(look);
    const int material = traced->veinedMaterial(scene, 0, 0.5f);
    const TriangleBuffers b = traced->addTriangles(4, 2, material, true, false, true);
    const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 4; ++k) {
      b.positions[k] = corners[k];
      b.normals[k] = glm::vec3(0, 0, 1);
      b.surface[k] = SurfacePoint(uv[k], 0, 2);  // variant 0, 2 long
    }
    const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::copy(indices, indices + 6, b.indices);
    traced->commit();
  }

  glm::vec3 at(glm::vec2 uv, const TraceLights& lights, int samples) const {
    glm::vec3 sum(0.0f);
    for (int i = 0; i < samples; ++i) {
      Random random(3, static_cast<std::uint64_t>(i));
      sum += traceRay(*traced, lights, glm::vec3(uv.x, 2 * uv.y, 3), glm::vec3(0, 0, -1), random,
                      TraceOptions{});
    }
    return sum / static_cast<float>(samples);
  }
};

TEST(VeinsInTheTracer, AVeinTakesItsColourByItsHeight) {
  VeinSettings s = settingsOf(VeinPattern::Splines);
  s.veinColour = glm::vec3(0.2f, 0.6f, 0.6f);  // display values: linear 0.033 and 0.319
  s.bump = 0;
  s.strength = 0.8f;
  const VeinedLeaf leaf(s);
  const VeinMap& map = leaf.traced->veinMap(0, 0);
  // The highest texel of the row at v = 0.5, and one without a vein.
  glm::vec2 top(0.0f), bare(-1.0f);
  for (int i = 0; i < kAcross; ++i) {
    const glm::vec2 uv(texelCentre(i, 0).x, 0.5f);
    if (map.height(uv) > map.height(top)) top = uv;
    if (bare.x < 0 && map.height(uv) == 0 && i > 10) bare = uv;
  }
  ASSERT_GT(map.height(top), 0.9f);
  ASSERT_GE(bare.x, 0);
  TraceLights sky;  // a uniform sky over the leaf: radiance ρ L
  sky.sky = glm::vec3(1.0f);
  sky.up = glm::vec3(0, 0, 1);
  const glm::vec3 plain = leaf.at(bare, sky, 3000), onVein = leaf.at(top, sky, 3000);
  const float share = 0.8f * map.height(top);
  const float grey = linearColour(glm::vec3(0.6f)).r;
  EXPECT_NEAR(plain.r, grey, 0.02f * grey);
  EXPECT_NEAR(onVein.r, grey * (1 - share) + linearColour(glm::vec3(0.2f)).r * share, 0.02f * grey);
  EXPECT_NEAR(onVein.g, grey, 0.02f * grey);  // the same value in green
}

TEST(VeinsInTheTracer, ARaisedVeinIsLitOnTheFlankThatFacesTheLight) {
  VeinSettings s = settingsOf(VeinPattern::Splines);
  s.width = 0.03f;
  s.strength = 0;  // the colour stays: only the normal changes
  // Light from +x, grazing (about 17° above the leaf).
  TraceSettings look;
  look.lightDirection = glm::vec3(1, 0, 0.3f);
  look.lightIrradiance = glm::vec3(1.0f);
  Bounds box;
  box.add(glm::vec3(0));
  box.add(glm::vec3(1, 2, 0));
  const TraceLights light = traceLights(look, box, glm::vec3(0, 0, 1));
  auto flanks = [&](float bump) {
    s.bump = bump;
    const VeinedLeaf leaf(s);
    const VeinMap& map = leaf.traced->veinMap(0, 0);
    // The steepest rising and falling texels (along u) of the row at v = 0.5.
    glm::vec2 rising(0.5f), falling(0.5f);
    for (int i = 0; i < kAcross; ++i) {
      const glm::vec2 uv(texelCentre(i, 0).x, 0.5f);
      if (map.slope(uv).x > map.slope(rising).x) rising = uv;
      if (map.slope(uv).x < map.slope(falling).x) falling = uv;
    }
    TraceLights only = light;
    only.sky = glm::vec3(0.0f);
    return std::pair{leaf.at(rising, only, 400).g, leaf.at(falling, only, 400).g};
  };
  const auto [risingFlat, fallingFlat] = flanks(0);
  EXPECT_NEAR(risingFlat, fallingFlat, 0.03f * fallingFlat);
  // Raised, the flank falling towards +x faces the light and the other turns from it.
  const auto [rising, falling] = flanks(1);
  EXPECT_GT(falling, 1.3f * fallingFlat);
  EXPECT_LT(rising, 0.7f * risingFlat);
}

}  // namespace

namespace {

TEST(TexturesInTheTracer, ATexturedSurfaceTakesItsTexelsColour) {
  Scene scene;
  Material white;
  white.diffuse = glm::vec3(1.0f);
  scene.materials.push_back(white);
  Texture image;  // two texels: red on the left, blue on the right
  image.width = 2;
  image.height = 1;
  image.rgba = {255, 0, 0, 255, 0, 0, 255, 255};
  scene.textures.push_back(image);
  TraceScene traced{TraceSettings{}};
  const int texture = traced.addTexture(scene, 0);
  ASSERT_EQ(texture, 0);
  EXPECT_EQ(traced.addTexture(scene, 1), -1);  // no such texture
  const TriangleBuffers b =
      traced.addTriangles(4, 2, traced.surfaceMaterial(scene, 0), true, false, false, texture);
  ASSERT_NE(b.texcoords, nullptr);
  const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (int k = 0; k < 4; ++k) {
    b.positions[k] = corners[k];
    b.normals[k] = glm::vec3(0, 0, 1);
    b.texcoords[k] = glm::vec2(corners[k]) * 0.999f;
  }
  const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::copy(indices, indices + 6, b.indices);
  traced.commit();
  TraceLights sky;
  sky.sky = glm::vec3(1.0f);
  sky.up = glm::vec3(0, 0, 1);
  auto at = [&](float x) {
    glm::vec3 sum(0.0f);
    for (int i = 0; i < 500; ++i) {
      Random random(5, static_cast<std::uint64_t>(i));
      sum += traceRay(traced, sky, glm::vec3(x, 0.5f, 2), glm::vec3(0, 0, -1), random, TraceOptions{});
    }
    return sum / 500.0f;
  };
  const glm::vec3 left = at(0.25f), right = at(0.75f);
  EXPECT_NEAR(left.r, 1.0f, 0.02f);
  EXPECT_NEAR(left.b, 0.0f, 0.01f);
  EXPECT_NEAR(right.b, 1.0f, 0.02f);
  EXPECT_NEAR(right.r, 0.0f, 0.01f);
}

}  // namespace
