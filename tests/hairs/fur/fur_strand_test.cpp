// The formulas of shell fur (Silva et al. 2010), measured: the strand's tip stays in the
// hemisphere of Eq. 3 under any force, rests where the spring balances the force, and the
// stepped strand comes to that rest; the curl of Eq. 4 has its radius and frequency and
// vanishes when wet; Eq. 5's profile is 0 at the root and 1 at the tip; Algorithm 1 blends
// droplets; the fur texture has its fill.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hirsute/hairs/fur/fur_strand.h"
#include "hirsute/hairs/fur/fur_texture.h"
#include "hirsute/hairs/fur/wetness_mask.h"

namespace hirsute::fur {
namespace {

constexpr float kPi = 3.14159265358979f;

TEST(FurStrand, TipStaysInTheHemisphereUnderAnyForce) {
  std::mt19937 random(3);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const StrandRoot strand{glm::vec3(1, 2, 3), glm::normalize(glm::vec3(0.2f, 1, -0.3f)), 0.5f};
  for (int trial = 0; trial < 200; ++trial) {
    const glm::vec3 force = 50.0f * glm::vec3(normal(random), normal(random), normal(random));
    StrandState state{strand.restTip(), glm::vec3(0.0f)};
    for (int step = 0; step < 200; ++step) {
      stepStrand(strand, 40, 1, 2, force, 1.0f / 60, state);
      const glm::vec3 offset = state.tip - strand.root;
      ASSERT_LE(glm::length(offset), strand.length * (1 + 1e-5f));
      ASSERT_GE(glm::dot(offset, strand.normal), -1e-5f);
    }
    const glm::vec3 rest = restingTip(strand, 40, 1, force);
    EXPECT_LE(glm::length(rest - strand.root), strand.length * (1 + 1e-5f));
    EXPECT_GE(glm::dot(rest - strand.root, strand.normal), -1e-5f);
  }
}

TEST(FurStrand, SteppedStrandComesToItsRest) {
  const StrandRoot strand{glm::vec3(0.0f), glm::vec3(0, 0, 1), 1.0f};
  const glm::vec3 wind(3, 0, 0);  // spring 40: a displacement of 3/40 = 0.075 across the normal
  StrandState state{strand.restTip(), glm::vec3(0.0f)};
  for (int step = 0; step < 2000; ++step) stepStrand(strand, 40, 1, 4, wind, 1.0f / 120, state);
  const glm::vec3 rest = restingTip(strand, 40, 1, wind);
  // p_0 + (0.075, 0, 0) lies just outside the length: pulled back onto the sphere of radius L0.
  EXPECT_NEAR(rest.x, 0.075f / std::sqrt(1 + 0.075f * 0.075f), 1e-6f);
  EXPECT_NEAR(glm::length(rest), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(state.tip, rest), 0.0f, 1e-4f);
  // A strong gravity presses the particle onto the surface, never through it: the nearest point
  // of the half ball to p_0 + (1, 0, -1000) / 40 is straight above it on the base disc.
  const glm::vec3 down = restingTip(strand, 40, 1, glm::vec3(1, 0, -1000));
  EXPECT_NEAR(down.z, 0.0f, 1e-6f);
  EXPECT_NEAR(down.x, 0.025f, 1e-6f);
}

TEST(FurStrand, BendFollowsTheBezierOfRootRestTipAndParticle) {
  const StrandRoot strand{glm::vec3(0.0f), glm::vec3(0, 0, 1), 2.0f};
  const glm::vec3 tip(1, 0, 1.5f);
  EXPECT_EQ(bendPoint(strand, tip, 0), strand.root);
  EXPECT_EQ(bendPoint(strand, tip, 1), tip);
  // The midpoint of a quadratic Bézier: (p_root + 2 p_0 + p) / 4.
  const glm::vec3 mid = (strand.root + 2.0f * strand.restTip() + tip) / 4.0f;
  EXPECT_LT(glm::distance(bendPoint(strand, tip, 0.5f), mid), 1e-6f);
  // The tangent is the derivative: a central difference agrees.
  const float h = 0.3f, e = 1e-3f;
  const glm::vec3 difference = (bendPoint(strand, tip, h + e) - bendPoint(strand, tip, h - e)) / (2 * e);
  EXPECT_LT(glm::distance(difference, bendTangent(strand, tip, h)), 1e-3f);
}

TEST(FurCurl, RadiusAndFrequencyOfEquation4) {
  const glm::vec3 u(1, 0, 0), v(0, 1, 0);
  const float ka = 0.2f, omega = 6 * kPi, length = 2;
  for (float h : {0.1f, 0.35f, 0.8f, 1.0f}) {
    const glm::vec3 offset = curlOffset(h, 0, ka, omega, length, u, v);
    EXPECT_NEAR(glm::length(offset), ka * length * h, 1e-5f);  // alpha(h) = K_alpha h
    EXPECT_NEAR(std::atan2(offset.y, offset.x), std::remainder(omega * h, 2 * kPi), 1e-4f);
  }
  // Wet fur loses its curl: alpha = (1 - rho) K_alpha h.
  EXPECT_NEAR(glm::length(curlOffset(0.7f, 1, ka, omega, length, u, v)), 0.0f, 1e-7f);
  EXPECT_NEAR(glm::length(curlOffset(0.7f, 0.5f, ka, omega, length, u, v)),
              0.5f * ka * length * 0.7f, 1e-5f);
  const float h = 0.42f, e = 1e-3f;
  const glm::vec3 difference = (curlOffset(h + e, 0, ka, omega, length, u, v) -
                                curlOffset(h - e, 0, ka, omega, length, u, v)) / (2 * e);
  EXPECT_LT(glm::distance(difference, curlTangent(h, 0, ka, omega, length, u, v)), 2e-3f);
}

TEST(FurClump, DisplacementOfEquation5AtRootAndTip) {
  for (int layers : {1, 4, 16, 64}) {
    for (float w : {0.0f, 0.3f, 1.0f}) {
      EXPECT_NEAR(clumpProfile(0, w, layers), 0.0f, 1e-7f);
      EXPECT_NEAR(clumpProfile(1, w, layers), 1.0f, 1e-6f);
      // Rising from the root to the tip.
      float last = -1;
      for (int i = 0; i <= 100; ++i) {
        const float p = clumpProfile(i / 100.0f, w, layers);
        EXPECT_GE(p, last - 1e-6f);
        last = p;
      }
    }
  }
  // w = 1 bends in at once: at the second of 16 layers already ln 2 / ln 16 of the way.
  EXPECT_NEAR(clumpProfile(2.0f / 16, 1, 16), std::log(2.0f) / std::log(16.0f), 1e-6f);
  // At the tip the displacement is rho · r (in 256ths) times the distance from the centre; at
  // the root none: the strand from the root is seen at the centre + (root - centre) / (1 + s).
  const glm::vec2 centre(0.5f, 0.5f), root(0.52f, 0.5f);
  const float tip = clumpScale(1, 0.5f, 16, 0.8f, 0.05f);
  EXPECT_NEAR(tip, 0.8f * 0.05f * 256, 1e-4f);
  EXPECT_EQ(clumpedPosition(root, centre, clumpScale(0, 0.5f, 16, 0.8f, 0.05f)), root);
  EXPECT_NEAR(glm::distance(clumpedPosition(root, centre, tip), centre), 0.02f / (1 + tip), 1e-6f);
}

FurSurface maskedSurface(bool wraps) {
  FurSurface s;
  s.wrapsU = wraps;
  clearWetness(s, 64);
  return s;
}

TEST(WetnessMask, DropletBlendedTwiceRaisesWetnessAndMovesTheCentre) {
  FurSurface s = maskedSurface(false);
  blendDroplet(s, glm::vec2(0.5f, 0.5f), 0.1f, 0.4f);
  glm::vec4 texel = wetnessAt(s, glm::vec2(0.5f, 0.5f));
  EXPECT_FLOAT_EQ(texel.w, 0.4f);
  EXPECT_FLOAT_EQ(texel.z, 0.1f);
  // Outside the droplet the mask stays dry.
  EXPECT_EQ(wetnessAt(s, glm::vec2(0.7f, 0.5f)).w, 0.0f);
  // A second droplet whose disc holds the first one's centre: rho_total = 0.4 + 0.3, alpha =
  // 0.3 / 0.7, the centre and the radius move towards the new droplet's by alpha.
  blendDroplet(s, glm::vec2(0.55f, 0.5f), 0.08f, 0.3f);
  texel = wetnessAt(s, glm::vec2(0.52f, 0.5f));
  const float alpha = 0.3f / 0.7f;
  EXPECT_NEAR(texel.w, 0.7f, 1e-6f);
  EXPECT_NEAR(texel.x, 0.5f + alpha * 0.05f, 1e-6f);
  EXPECT_NEAR(texel.y, 0.5f, 1e-6f);
  EXPECT_NEAR(texel.z, (1 - alpha) * 0.1f + alpha * 0.08f, 1e-6f);
  // Wetness adds up to 1 and no further.
  for (int i = 0; i < 5; ++i) blendDroplet(s, glm::vec2(0.55f, 0.5f), 0.08f, 0.3f);
  EXPECT_FLOAT_EQ(wetnessAt(s, glm::vec2(0.52f, 0.5f)).w, 1.0f);
  // A droplet far from the clump's centre starts a clump of its own where it falls.
  blendDroplet(s, glm::vec2(0.62f, 0.5f), 0.03f, 0.5f);
  texel = wetnessAt(s, glm::vec2(0.62f, 0.5f));
  EXPECT_EQ(texel, glm::vec4(0.62f, 0.5f, 0.03f, 0.5f));
}

TEST(WetnessMask, WrapsAroundTheGirthAndDries) {
  FurSurface s = maskedSurface(true);
  blendDroplet(s, glm::vec2(0.01f, 0.5f), 0.05f, 1.0f);
  EXPECT_EQ(wetnessAt(s, glm::vec2(0.98f, 0.5f)).w, 1.0f);  // across the seam
  FurSurface open = maskedSurface(false);
  blendDroplet(open, glm::vec2(0.01f, 0.5f), 0.05f, 1.0f);
  EXPECT_EQ(wetnessAt(open, glm::vec2(0.98f, 0.5f)).w, 0.0f);
  EXPECT_TRUE(dry(s, 0.6f));
  EXPECT_NEAR(wetnessAt(s, glm::vec2(0.01f, 0.5f)).w, 0.4f, 1e-6f);
  EXPECT_FALSE(dry(s, 0.6f));
  EXPECT_EQ(wetnessAt(s, glm::vec2(0.01f, 0.5f)), glm::vec4(0.0f));
}

TEST(FurTexture, FillAndSeed) {
  const FurTexture a = makeFurTexture(128, 5, 0.3f);
  EXPECT_EQ(strandCount(a), static_cast<std::size_t>(std::lround(0.3 * 128 * 128)));
  for (std::uint8_t l : a.lengths) {
    if (l != 0) {
      EXPECT_GE(l, static_cast<int>(std::floor(255 * kShortestStrand)));
    }
  }
  EXPECT_EQ(makeFurTexture(128, 5, 0.3f).lengths, a.lengths);
  EXPECT_NE(makeFurTexture(128, 6, 0.3f).lengths, a.lengths);
  EXPECT_EQ(strandCount(makeFurTexture(64, 1, 1.0f)), 64u * 64u);
  EXPECT_EQ(strandCount(makeFurTexture(64, 1, 0.0f)), 0u);
}

}  // namespace
}  // namespace hirsute::fur
