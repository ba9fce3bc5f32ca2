// The tracer's texture lookup is GL's linear filter: a texel's centre gives the texel, halfway
// between two centres their mean, and the edges repeat.
#include <gtest/gtest.h>

#include "hirsute/viewer/trace/texture_lookup.h"

namespace hirsute::trace {
namespace {

// Two texels side by side in one row: black on the left, (200, 100, 40) on the right.
Texture twoTexels() {
  Texture t;
  t.width = 2;
  t.height = 1;
  t.rgba = {0, 0, 0, 255, 200, 100, 40, 255};
  return t;
}

void expectNear(const glm::vec3& a, const glm::vec3& b) {
  EXPECT_NEAR(a.r, b.r, 1e-5f);
  EXPECT_NEAR(a.g, b.g, 1e-5f);
  EXPECT_NEAR(a.b, b.b, 1e-5f);
}

TEST(TextureLookup, HalfwayBetweenTwoTexelsIsTheirMean) {
  const Texture t = twoTexels();
  const glm::vec3 right = glm::vec3(200, 100, 40) / 255.0f;
  expectNear(bilinearColourAt(t, {0.25f, 0.5f}), glm::vec3(0.0f));  // the left texel's centre
  expectNear(bilinearColourAt(t, {0.75f, 0.5f}), right);            // the right one's
  expectNear(bilinearColourAt(t, {0.5f, 0.5f}), right / 2.0f);      // halfway: the mean
  expectNear(bilinearColourAt(t, {0.375f, 0.5f}), right / 4.0f);    // a quarter of the way
  // Nearest-texel lookup would give one texel or the other there.
  EXPECT_EQ(t.colourAt({0.5f, 0.5f}), right);
}

TEST(TextureLookup, TheEdgesRepeatAsGlsDo) {
  const Texture t = twoTexels();
  const glm::vec3 right = glm::vec3(200, 100, 40) / 255.0f;
  // At u = 0 the left texel's centre is half a texel on, the right one's half a texel back.
  expectNear(bilinearColourAt(t, {0.0f, 0.5f}), right / 2.0f);
  expectNear(bilinearColourAt(t, {1.0f, 0.5f}), right / 2.0f);
  expectNear(bilinearColourAt(t, {-0.25f, 0.5f}), right);
  expectNear(bilinearColourAt(t, {2.25f, 7.5f}), glm::vec3(0.0f));
  expectNear(bilinearColourAt(t, {1e30f, 0.5f}), right / 2.0f);  // past any texel: as u = 0
  expectNear(bilinearColourAt(Texture{}, {0.5f, 0.5f}), glm::vec3(0.0f));
}

TEST(TextureLookup, RowsCountFromTheBottomAsGlUploadsThem) {
  Texture t;
  t.width = 1;
  t.height = 2;
  t.rgba = {255, 255, 255, 255, 0, 0, 0, 255};  // row 0, the top, white; the bottom black
  expectNear(bilinearColourAt(t, {0.5f, 0.25f}), glm::vec3(0.0f));
  expectNear(bilinearColourAt(t, {0.5f, 0.75f}), glm::vec3(1.0f));
  expectNear(bilinearColourAt(t, {0.5f, 0.5f}), glm::vec3(0.5f));
}

}  // namespace
}  // namespace hirsute::trace
