// The fibre model (fibre_bsdf.h, after Chiang et al. 2016): a fibre that absorbs nothing returns
// all the light it receives (white furnace), its far-field form is reciprocal where the model is,
// its sampled directions follow the density it reports (a chi-square test, as pbrt-v4 tests its
// BSDFs), and its reflection leaves about the mirror direction of the normal the ray met.
#include "hirsute/viewer/trace/fibre_bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "hirsute/viewer/trace/sampling.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace {

using namespace hirsute::trace;

const glm::vec3 kTangent(0, 0, 1);
constexpr double kHalfTurn = 3.14159265358979323846;

// A direction at longitudinal angle θ (from the plane across the fibre) and azimuth φ about it.
glm::vec3 direction(double theta, double phi) {
  return glm::vec3(static_cast<float>(std::cos(theta) * std::cos(phi)),
                   static_cast<float>(std::cos(theta) * std::sin(phi)),
                   static_cast<float>(std::sin(theta)));
}

// ∫ value(wo, ω) dω by the midpoint rule in (sin θ, φ), where dω = d(sin θ) dφ.
glm::dvec3 integral(const FibreBsdf& bsdf, const glm::vec3& wo, int steps) {
  glm::dvec3 sum(0.0);
  for (int i = 0; i < steps; ++i) {
    const double z = -1 + 2 * (i + 0.5) / steps;
    const double theta = std::asin(z);
    for (int j = 0; j < 2 * steps; ++j) {
      const double phi = -kHalfTurn + 2 * kHalfTurn * (j + 0.5) / (2 * steps);
      sum += glm::dvec3(bsdf.value(wo, direction(theta, phi)));
    }
  }
  return sum * (2.0 / steps) * (2 * kHalfTurn / (2 * steps));
}

TEST(FibreBsdf, WhiteFurnaceReturnsAllTheLightWithoutAbsorption) {
  for (float roughness : {0.15f, 0.3f, 0.6f, 0.9f}) {
    for (float thetaO : {-1.1f, 0.2f, 1.3f}) {
      for (float h : {-0.7f, 0.4f}) {
        FibreMaterial m;
        m.longitudinalRoughness = roughness;
        m.azimuthalRoughness = std::max(0.2f, 1 - roughness);
        const glm::vec3 wo = direction(thetaO, 0.3);
        const FibreBsdf bsdf(m, kTangent, wo, h);
        const glm::dvec3 e = integral(bsdf, wo, 300);
        EXPECT_NEAR(e.g, 1.0, 0.01) << "βm " << roughness << " θo " << thetaO << " h " << h;
      }
    }
  }
}

TEST(FibreBsdf, SamplingEstimatesTheSameEnergy) {
  Random random(3, 5);
  for (float roughness : {0.2f, 0.5f}) {
    FibreMaterial m;
    m.longitudinalRoughness = roughness;
    m.azimuthalRoughness = roughness;
    m.absorption = absorptionFromColour(glm::vec3(0.8f, 0.5f, 0.3f), roughness);
    const glm::vec3 wo = direction(0.4, 1.0);
    const FibreBsdf bsdf(m, kTangent, wo, 0.3f);
    glm::dvec3 sampled(0.0);
    constexpr int kSamples = 100000;
    for (int i = 0; i < kSamples; ++i) {
      const glm::vec2 a = random.uniform2(), b = random.uniform2();
      const HairSample s = bsdf.sample(wo, glm::vec4(a, b));
      if (s.pdf > 0) sampled += glm::dvec3(s.value / s.pdf);
    }
    sampled /= kSamples;
    const glm::dvec3 exact = integral(bsdf, wo, 400);
    glm::dvec3 shares(0.0);
    for (int p = 0; p < 4; ++p) shares += glm::dvec3(bsdf.shares()[p]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sampled[c], exact[c], 0.01 * exact[c] + 1e-4) << "channel " << c;
      EXPECT_NEAR(exact[c], shares[c], 0.01 * shares[c] + 1e-4) << "channel " << c;
    }
    // A coloured fibre absorbs: it returns less than it receives, the red most.
    EXPECT_LT(exact.b, exact.r);
    EXPECT_LT(exact.r, 1.0);
  }
}

// Swapping the two directions mirrors the azimuth and the offset h alike, so over the fibre's
// width (h uniform, the far field) the model is reciprocal where the shares Ap, which Chiang et
// al. compute from θo alone, see the same angle: |θi| = |θo|, without the cuticle's tilt.
TEST(FibreBsdf, FarFieldIsReciprocalWhereTheSharesAgree) {
  Random random(11, 2);
  FibreMaterial m;
  m.tilt = 0;
  m.absorption = absorptionFromColour(glm::vec3(0.7f, 0.45f, 0.3f), 0.3f);
  auto farField = [&](const glm::vec3& wo, const glm::vec3& wi) {
    glm::dvec3 sum(0.0);
    constexpr int kOffsets = 400;
    for (int k = 0; k < kOffsets; ++k) {
      const float h = -1 + 2 * (static_cast<float>(k) + 0.5f) / kOffsets;
      sum += glm::dvec3(FibreBsdf(m, kTangent, wo, h).value(wo, wi));
    }
    return sum / static_cast<double>(kOffsets);
  };
  for (int i = 0; i < 20; ++i) {
    const glm::vec2 u = random.uniform2();
    const double thetaO = (u.x - 0.5) * 2.6;
    const double thetaI = i % 2 ? -thetaO : thetaO;
    const glm::vec3 wo = direction(thetaO, 2 * kHalfTurn * u.y);
    const glm::vec3 wi = direction(thetaI, 2 * kHalfTurn * random.uniform());
    const glm::dvec3 a = farField(wo, wi), b = farField(wi, wo);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-3 * std::max(a[c], 1e-3)) << i;
  }
  // And the longitudinal lobe is symmetric for any two angles.
  for (int i = 0; i < 20; ++i) {
    const glm::vec2 u = random.uniform2();
    const float a = (u.x - 0.5f) * 3, b = (u.y - 0.5f) * 3;
    const float ab = longitudinalLobe(std::sin(a), std::cos(a), std::sin(b), std::cos(b), 0.05f);
    const float ba = longitudinalLobe(std::sin(b), std::cos(b), std::sin(a), std::cos(a), 0.05f);
    EXPECT_NEAR(ab, ba, 1e-4f * ab);
  }
}

// The upper regularised gamma function Q(k/2, x/2): the chance that a chi-square of k degrees
// of freedom exceeds x (its series for x < a + 1, its continued fraction beyond).
double chiSquareTail(double x, int k) {
  const double a = k / 2.0, y = x / 2;
  if (y <= 0) return 1;
  const double front = std::exp(-y + a * std::log(y) - std::lgamma(a));
  if (y < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < 1000; ++n) {
      term *= y / (a + n);
      sum += term;
      if (term < sum * 1e-15) break;
    }
    return 1 - front * sum;
  }
  double b = y + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int n = 1; n < 1000; ++n) {
    const double an = -n * (n - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    h *= d * c;
    if (std::abs(d * c - 1) < 1e-15) break;
  }
  return front * h;
}

// Sampled directions, binned in (sin θ, φ), against the bins' integrals of the pdf; bins
// expecting fewer than five samples pooled (pbrt-v4's chi2test).
TEST(FibreBsdf, SampledDirectionsFollowTheirDensity) {
  struct Case {
    float longitudinal, azimuthal, thetaO, h;
    glm::vec3 colour;
  };
  const Case cases[] = {
      {0.3f, 0.3f, 0.2f, 0.1f, glm::vec3(0.9f)},
      {0.15f, 0.6f, -0.9f, -0.6f, glm::vec3(0.6f, 0.4f, 0.2f)},
      {0.7f, 0.2f, 1.2f, 0.8f, glm::vec3(0.95f, 0.9f, 0.8f)},
  };
  constexpr int kTheta = 40, kPhi = 80, kSamples = 400000, kSub = 6;
  const double significance = 0.01 / std::size(cases);
  Random random(21, 4);
  for (const Case& c : cases) {
    FibreMaterial m;
    m.longitudinalRoughness = c.longitudinal;
    m.azimuthalRoughness = c.azimuthal;
    m.absorption = absorptionFromColour(c.colour, c.azimuthal);
    const glm::vec3 wo = direction(c.thetaO, 0.5);
    const FibreBsdf bsdf(m, kTangent, wo, c.h);
    auto binOf = [&](const glm::vec3& w) {
      const int i = std::clamp(static_cast<int>((w.z + 1) / 2 * kTheta), 0, kTheta - 1);
      const double phi = std::atan2(w.y, w.x) + kHalfTurn;
      const int j = std::clamp(static_cast<int>(phi / (2 * kHalfTurn) * kPhi), 0, kPhi - 1);
      return i * kPhi + j;
    };
    std::vector<double> observed(kTheta * kPhi, 0.0), expected(kTheta * kPhi, 0.0);
    for (int s = 0; s < kSamples; ++s) {
      const glm::vec2 a = random.uniform2(), b = random.uniform2();
      const HairSample sample = bsdf.sample(wo, glm::vec4(a, b));
      ASSERT_GT(sample.pdf, 0);
      observed[binOf(sample.direction)] += 1;
    }
    for (int i = 0; i < kTheta; ++i) {
      for (int j = 0; j < kPhi; ++j) {
        double sum = 0;
        for (int a = 0; a < kSub; ++a) {
          for (int b = 0; b < kSub; ++b) {
            const double z = -1 + 2 * (i + (a + 0.5) / kSub) / kTheta;
            const double phi = -kHalfTurn + 2 * kHalfTurn * (j + (b + 0.5) / kSub) / kPhi;
            sum += bsdf.pdf(wo, direction(std::asin(z), phi));
          }
        }
        expected[i * kPhi + j] =
            sum / (kSub * kSub) * (2.0 / kTheta) * (2 * kHalfTurn / kPhi) * kSamples;
      }
    }
    // Pool the bins of small expectation, smallest first, into one.
    std::vector<int> order(expected.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pooledExpected = 0, pooledObserved = 0, chi2 = 0;
    int dof = 0;
    for (int k : order) {
      if (expected[k] == 0) {
        EXPECT_EQ(observed[k], 0) << "a sample where the density is zero";
      } else if (expected[k] < 5 || (pooledExpected > 0 && pooledExpected < 5)) {
        pooledExpected += expected[k];
        pooledObserved += observed[k];
      } else {
        const double d = observed[k] - expected[k];
        chi2 += d * d / expected[k];
        ++dof;
      }
    }
    if (pooledExpected > 0) {
      const double d = pooledObserved - pooledExpected;
      chi2 += d * d / pooledExpected;
      ++dof;
    }
    const double p = chiSquareTail(chi2, dof - 1);
    EXPECT_GT(p, significance) << "χ² " << chi2 << " over " << dof - 1 << " degrees of freedom, βm "
                               << c.longitudinal << " βn " << c.azimuthal;
  }
}

// The tail function itself, on values of the chi-square table.
TEST(FibreBsdf, ChiSquareTailMatchesItsTable) {
  EXPECT_NEAR(chiSquareTail(3.841, 1), 0.05, 1e-3);
  EXPECT_NEAR(chiSquareTail(18.307, 10), 0.05, 1e-3);
  EXPECT_NEAR(chiSquareTail(135.807, 100), 0.01, 1e-3);
}

// A ray that meets the fibre off its axis reflects (R) about the normal there, so h is read
// with the sign the model's deflection Φ = −2γo expects.
TEST(FibreBsdf, ReflectionLeavesAboutTheNormalTheRayMet) {
  FibreMaterial m;
  m.absorption = glm::vec3(50.0f);  // nothing passes through: R alone
  m.longitudinalRoughness = 0.2f;
  m.azimuthalRoughness = 0.1f;
  m.tilt = 0;
  const glm::vec3 wo(1, 0, 0);
  for (float psi : {-0.9f, -0.3f, 0.5f, 1.1f}) {
    const glm::vec3 normal(std::cos(psi), std::sin(psi), 0);
    const glm::vec3 mirror = 2 * glm::dot(normal, wo) * normal - wo;
    const FibreBsdf bsdf(m, kTangent, wo, fibreOffset(kTangent, normal, wo));
    const double mirrorPhi = std::atan2(mirror.y, mirror.x);
    double best = -1, bestPhi = 0;
    for (int j = 0; j < 3600; ++j) {
      const double phi = -kHalfTurn + 2 * kHalfTurn * (j + 0.5) / 3600;
      const double v = bsdf.value(wo, direction(0, phi)).g;
      if (v > best) best = v, bestPhi = phi;
    }
    EXPECT_NEAR(bestPhi, mirrorPhi, 0.02) << "ψ " << psi;
  }
}

// A `fibre:` line for one template or fur colour wins over its organ's line, which wins over
// the default (Kajiya and Goldman's model); each organ reads its own lines.
TEST(FibreBsdf, FibreLinesChooseEachKindOfHairsModel) {
  hirsute::TraceSettings look;
  hirsute::FibreSettings all;
  all.model = hirsute::FibreModel::KajiyaGoldman;
  hirsute::FibreSettings second;
  second.index = 2;
  second.longitudinalRoughness = 0.5f;
  second.melanin = glm::vec2(1.3f, 0.0f);
  hirsute::FibreSettings fur;
  fur.organ = hirsute::FibreOrgan::Fur;
  fur.index = 7;
  fur.colour = glm::vec3(1.0f, 0.5f, 0.25f);
  look.fibres = {second, all, fur};
  TraceScene scene(look);
  const glm::vec3 grey(0.4f);
  using hirsute::FibreOrgan;
  EXPECT_FALSE(scene.material(scene.hairOfColour(grey, FibreOrgan::Hairs, 1)).chiang);
  const TraceMaterial& two = scene.material(scene.hairOfColour(grey, FibreOrgan::Hairs, 2));
  ASSERT_TRUE(two.chiang);
  EXPECT_FLOAT_EQ(two.chiangFibre.longitudinalRoughness, 0.5f);
  EXPECT_TRUE(two.absorptionFixed);
  EXPECT_EQ(two.chiangFibre.absorption, absorptionFromMelanin(1.3f, 0));
  const TraceMaterial& seven = scene.material(scene.hairOfColour(grey, FibreOrgan::Fur, 7));
  ASSERT_TRUE(seven.chiang);
  EXPECT_EQ(seven.fibreColour, linearColour(glm::vec3(1.0f, 0.5f, 0.25f)));
  const TraceMaterial& other = scene.material(scene.hairOfColour(grey, FibreOrgan::Fur, 3));
  EXPECT_FALSE(other.chiang);
  EXPECT_FALSE(scene.material(scene.hairOfColour(grey, FibreOrgan::Feathers)).chiang);
  TraceScene unlined(hirsute::TraceSettings{});
  EXPECT_FALSE(unlined.material(unlined.hairOfColour(grey, FibreOrgan::Hairs, 1)).chiang);
}

}  // namespace
