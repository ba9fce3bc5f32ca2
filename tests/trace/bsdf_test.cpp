// The tracer's materials conserve energy (white furnace): a hair or a surface returns at most the
// light it receives, all of it when its weights leave nothing absorbed, and each samples its
// directions with the density it reports.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "hirsute/viewer/trace/hair_bsdf.h"
#include "hirsute/viewer/trace/sampling.h"
#include "hirsute/viewer/trace/surface_bsdf.h"

namespace {

using namespace hirsute::trace;

constexpr int kSamples = 400000;

glm::vec3 direction(float theta, float phi) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

// ∫ value(wo, ω) dω by uniform directions, and the same through the material's own sampling.
template <class Bsdf>
void furnace(const Bsdf& bsdf, const glm::vec3& wo, glm::vec3& uniform, glm::vec3& sampled,
             float& pdfIntegral) {
  Random random(7, 11);
  uniform = glm::vec3(0.0f);
  sampled = glm::vec3(0.0f);
  pdfIntegral = 0;
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec3 wi = sampleUniformSphere(random.uniform2());
    uniform += bsdf.value(wo, wi) / kUniformSpherePdf;
    pdfIntegral += bsdf.pdf(wo, wi) / kUniformSpherePdf;
  }
  uniform /= static_cast<float>(kSamples);
  pdfIntegral /= static_cast<float>(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    if constexpr (std::is_same_v<Bsdf, HairBsdf>) {
      const auto s = bsdf.sample(
          wo, glm::vec4(random.uniform(), random.uniform(), random.uniform(), random.uniform()));
      if (s.pdf > 0) sampled += s.value / s.pdf;
    } else {
      const auto s = bsdf.sample(wo, glm::vec3(random.uniform(), random.uniform(), random.uniform()));
      if (s.pdf > 0) sampled += s.value / s.pdf;
    }
  }
  sampled /= static_cast<float>(kSamples);
}

TEST(LongitudinalLobe, IntegratesToOneOverTheSphere) {
  for (float variance : {0.005f, 0.02f, 0.09f, 0.3f, 1.0f}) {
    for (float thetaO : {-1.2f, -0.3f, 0.0f, 0.7f, 1.4f}) {
      double sum = 0;
      const int n = 20000;
      for (int i = 0; i < n; ++i) {
        const double theta = -kPi / 2 + kPi * (i + 0.5) / n;
        sum += longitudinalLobe(static_cast<float>(std::sin(theta)), static_cast<float>(std::cos(theta)),
                                std::sin(thetaO), std::cos(thetaO), variance) *
               std::cos(theta) * kPi / n;
      }
      EXPECT_NEAR(sum, 1.0, 0.01) << "variance " << variance << ", θo " << thetaO;
    }
  }
}

TEST(HairBsdf, ReturnsAllTheLightWhenNothingIsAbsorbed) {
  for (float back : {0.0f, 1.0f}) {
    for (float roughness : {0.1f, 0.8f}) {
      HairMaterial m;
      m.diffuse = glm::vec3(0.85f);
      m.specular = glm::vec3(0.15f);
      m.backscatter = back;
      m.roughness = roughness;
      const HairBsdf hair(m, glm::normalize(glm::vec3(0.2f, 1, 0.1f)));
      for (float thetaO : {-1.0f, 0.6f}) {
        glm::vec3 uniform, sampled;
        float pdf;
        furnace(hair, direction(thetaO, 0.4f), uniform, sampled, pdf);
        EXPECT_NEAR(uniform.g, 1.0f, 0.01f) << "back " << back << " roughness " << roughness;
        EXPECT_NEAR(sampled.g, 1.0f, 0.01f) << "back " << back << " roughness " << roughness;
        EXPECT_NEAR(pdf, 1.0f, 0.01f);
      }
    }
  }
}

TEST(HairBsdf, AbsorbsWhatItsColourDoesNotReturn) {
  HairMaterial m;
  m.diffuse = glm::vec3(0.5f, 0.3f, 0.1f);
  m.specular = glm::vec3(0.1f);
  const HairBsdf hair(m, glm::vec3(0, 1, 0));
  glm::vec3 uniform, sampled;
  float pdf;
  furnace(hair, direction(0.3f, 1.0f), uniform, sampled, pdf);
  EXPECT_NEAR(uniform.r, 0.6f, 0.01f);
  EXPECT_NEAR(uniform.g, 0.4f, 0.01f);
  EXPECT_NEAR(uniform.b, 0.2f, 0.01f);
  EXPECT_NEAR(sampled.r, 0.6f, 0.01f);
  // More than 1 in all is scaled down to 1.
  m.diffuse = glm::vec3(1.5f);
  m.specular = glm::vec3(0.5f);
  furnace(HairBsdf(m, glm::vec3(0, 1, 0)), direction(0.3f, 1.0f), uniform, sampled, pdf);
  EXPECT_NEAR(uniform.g, 1.0f, 0.01f);
}

// Kajiya's diffuse term with Goldman's weights is reciprocal. (The specular lobes are normalised
// for each eye direction, as d'Eon et al.'s are, so that energy is conserved for every one.)
TEST(HairBsdf, ItsDiffuseLobesAreReciprocal) {
  HairMaterial m;
  m.specular = glm::vec3(0.0f);
  const HairBsdf hair(m, glm::normalize(glm::vec3(1, 2, 0.5f)));
  Random random(3, 5);
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 a = sampleUniformSphere(random.uniform2());
    const glm::vec3 b = sampleUniformSphere(random.uniform2());
    // value is f·|cos θi|: f itself is value / |cos θi|.
    const float cosA = std::sqrt(1 - std::pow(glm::dot(a, glm::normalize(glm::vec3(1, 2, 0.5f))), 2.0f));
    const float cosB = std::sqrt(1 - std::pow(glm::dot(b, glm::normalize(glm::vec3(1, 2, 0.5f))), 2.0f));
    if (cosA < 1e-3f || cosB < 1e-3f) continue;
    EXPECT_NEAR(hair.value(a, b).g / cosB, hair.value(b, a).g / cosA,
                1e-4f + 1e-3f * hair.value(a, b).g / cosB);
  }
}

TEST(HairBsdf, BackscatterSendsLightBackTowardsItsSource) {
  // Goldman's weighting: light from the eye's side comes back with the backscatter share,
  // light from behind the hair passes through with the rest.
  HairMaterial m;
  m.specular = glm::vec3(0.0f);
  m.backscatter = 0.8f;
  const HairBsdf hair(m, glm::vec3(0, 1, 0));
  const glm::vec3 eye(0, 0, 1);
  EXPECT_GT(hair.value(eye, glm::vec3(0, 0, 1)).g, 3.5f * hair.value(eye, glm::vec3(0, 0, -1)).g);
  m.backscatter = 0.2f;
  const HairBsdf forward(m, glm::vec3(0, 1, 0));
  EXPECT_GT(forward.value(eye, glm::vec3(0, 0, -1)).g, 3.5f * forward.value(eye, glm::vec3(0, 0, 1)).g);
}

TEST(SurfaceBsdf, ReturnsAllTheLightWhenNothingIsAbsorbed) {
  for (float exponent : {0.0f, 10.0f, 100.0f}) {
    SurfaceMaterial m;
    m.reflectance = glm::vec3(0.4f);
    m.transmittance = glm::vec3(0.4f);
    m.specular = glm::vec3(0.2f);
    m.exponent = exponent;
    const SurfaceBsdf surface(m, glm::vec3(0, 0, 1));
    // The Phong lobe loses what falls below the surface, more the more grazing the eye: seen
    // from above, all of the diffuse lobes' light and nearly all of the Phong lobe's comes back.
    glm::vec3 uniform, sampled;
    float pdf;
    furnace(surface, glm::normalize(glm::vec3(0.1f, 0, 1)), uniform, sampled, pdf);
    EXPECT_LE(uniform.g, 1.01f);
    EXPECT_NEAR(uniform.g, 1.0f, exponent > 0 ? 0.03f : 0.01f) << "exponent " << exponent;
    EXPECT_NEAR(sampled.g, uniform.g, 0.01f) << "exponent " << exponent;
    EXPECT_NEAR(pdf, 1.0f, 0.01f);
  }
}

TEST(SurfaceBsdf, TranslucencyPassesItsShareToTheOtherSide) {
  SurfaceMaterial m;
  m.reflectance = glm::vec3(0.3f);
  m.transmittance = glm::vec3(0.5f);
  const SurfaceBsdf leaf(m, glm::vec3(0, 0, 1));
  Random random(1, 2);
  glm::vec3 front(0.0f), back(0.0f);
  const glm::vec3 wo(0, 0, 1);
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec3 wi = sampleUniformSphere(random.uniform2());
    (wi.z > 0 ? front : back) += leaf.value(wo, wi) / kUniformSpherePdf;
  }
  EXPECT_NEAR(front.g / kSamples, 0.3f, 0.01f);
  EXPECT_NEAR(back.g / kSamples, 0.5f, 0.01f);
}

TEST(Sampling, CosSquaredHasItsDensity) {
  // The share below z is (2z + sin 2z)/2π + 1/2.
  Random random(5, 9);
  int below = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) below += sampleCosSquared(random.uniform()) < 0.5f;
  const double expected = (1.0 + std::sin(1.0)) / (2 * kPi) + 0.5;
  EXPECT_NEAR(static_cast<double>(below) / n, expected, 0.005);
}

TEST(Sampling, AStratifiedCallCoversItsSquareEvenlyOverAPixelsSamples) {
  // The first 2^m samples of a pixel put one point of each call in each of the 2^m elementary
  // rectangles of every shape (1 x 2^m, 2 x 2^(m-1), ..., 2^m x 1), for every m up to 8, and
  // do so for calls made by uniform() (their first coordinate) as well.
  for (std::uint64_t pixel : {0ull, 7ull, 123456ull}) {
    constexpr int kCalls = 6, kSamples = 256;
    std::vector<std::array<glm::vec2, kCalls>> points(kSamples);
    for (int i = 0; i < kSamples; ++i) {
      Random random = Random::stratified(3, pixel, static_cast<std::uint32_t>(i));
      for (int c = 0; c < kCalls; ++c) {
        points[i][c] = c % 2 == 0 ? random.uniform2() : glm::vec2(random.uniform(), 0.5f);
      }
    }
    for (int c = 0; c < kCalls; ++c) {
      for (int m = 1; m <= 8; ++m) {
        const int n = 1 << m;
        for (int xBits = (c % 2 == 0 ? 0 : m); xBits <= m; ++xBits) {
          const int columns = 1 << xBits, rows = n / columns;
          std::vector<int> hits(static_cast<std::size_t>(n), 0);
          for (int i = 0; i < n; ++i) {
            const glm::vec2 p = points[i][c];
            const int x = static_cast<int>(p.x * static_cast<float>(columns));
            const int y = c % 2 == 0 ? static_cast<int>(p.y * static_cast<float>(rows)) : 0;
            ++hits[static_cast<std::size_t>(y * columns + x)];
          }
          for (int h : hits) ASSERT_EQ(h, 1) << "pixel " << pixel << " call " << c << " n " << n;
        }
      }
    }
  }
  // Past the stratified calls the numbers are independent ones, and seeds and pixels differ.
  Random a = Random::stratified(3, 1, 0), b = Random::stratified(4, 1, 0),
         c = Random::stratified(3, 2, 0);
  const glm::vec2 pa = a.uniform2(), pb = b.uniform2(), pc = c.uniform2();
  EXPECT_NE(pa, pb);
  EXPECT_NE(pa, pc);
  double sum = 0;
  for (int i = 0; i < 4096; ++i) {
    Random random = Random::stratified(9, 5, static_cast<std::uint32_t>(i));
    for (int k = 0; k < Random::kStratifiedCalls; ++k) random.uniform();
    sum += random.uniform();
  }
  EXPECT_NEAR(sum / 4096, 0.5, 0.015);
}

}  // namespace
