// The sky of the path tracer: an environment map's sampling against its density, a white
// furnace and a sphere's irradiance under a map, the physical sky's luminance against
// Preetham et al.'s formulas, and environment files that cannot be read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/viewer/trace/environment_map.h"
#include "hirsute/viewer/trace/exr_image.h"
#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/sky_model.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace {

using namespace hirsute;
using namespace hirsute::trace;

// A map with a bright patch, a gradient and a dark band, so that its density is far from even.
EnvironmentMap unevenMap(int width = 32, int height = 16) {
  std::vector<glm::vec3> pixels(static_cast<std::size_t>(width * height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float v = 0.2f + static_cast<float>(x) / static_cast<float>(width);
      if (y >= height / 2 + 2) v *= 0.05f;
      if (x >= 5 && x < 8 && y >= 3 && y < 6) v = 40;
      pixels[static_cast<std::size_t>(y * width + x)] = glm::vec3(v, 0.8f * v, 0.5f * v);
    }
  }
  return EnvironmentMap(width, height, std::move(pixels), glm::vec3(0, 1, 0), 30);
}

TEST(EnvironmentMap, DirectionsAndMapPointsAreInverse) {
  const EnvironmentMap map = unevenMap();
  for (const glm::vec2 p : {glm::vec2(0.1f, 0.2f), glm::vec2(0.7f, 0.9f), glm::vec2(0.5f, 0.5f)}) {
    const glm::vec2 back = map.pointOf(map.directionOf(p));
    EXPECT_NEAR(back.x, p.x, 1e-4f);
    EXPECT_NEAR(back.y, p.y, 1e-4f);
  }
  // The top row looks up; the middle column, unturned, along +z.
  const EnvironmentMap plain(4, 2, std::vector<glm::vec3>(8, glm::vec3(1.0f)), glm::vec3(0, 1, 0));
  EXPECT_NEAR(plain.directionOf({0.5f, 0.0f}).y, 1.0f, 1e-5f);
  EXPECT_NEAR(plain.directionOf({0.5f, 0.5f}).z, 1.0f, 1e-5f);
  EXPECT_NEAR(plain.directionOf({0.75f, 0.5f}).x, 1.0f, 1e-5f);
}

// Chi-square of the samples' cells against the density integrated over each cell.
TEST(EnvironmentMap, SamplesFollowTheirDensity) {
  const EnvironmentMap map = unevenMap();
  const int cellsTheta = 16, cellsPhi = 32;
  std::vector<double> observed(cellsTheta * cellsPhi, 0.0), expected(observed.size(), 0.0);
  const int n = 400000;
  int disagreements = 0;
  Random random(7, 1);
  for (int i = 0; i < n; ++i) {
    const EnvironmentSample s = map.sample(random.uniform2());
    ASSERT_GT(s.pdf, 0);
    // The density evaluated for the direction is the sampled one, but on a texel's edge, where
    // rounding may put the direction in its neighbour, and near the poles, where sin θ is small.
    if (std::abs(map.pdf(s.direction) - s.pdf) > 0.02f * s.pdf) ++disagreements;
    const float theta = std::acos(std::clamp(s.direction.y, -1.0f, 1.0f));
    const float phi = std::atan2(s.direction.x, s.direction.z) + kPi;
    const int a = std::min(cellsTheta - 1, static_cast<int>(theta / kPi * cellsTheta));
    const int b = std::min(cellsPhi - 1, static_cast<int>(phi / (2 * kPi) * cellsPhi));
    observed[static_cast<std::size_t>(a * cellsPhi + b)] += 1;
  }
  // The density integrated over each cell of the world's (θ, φ) grid, by a fine midpoint rule.
  const int fine = 12;
  for (int a = 0; a < cellsTheta; ++a) {
    for (int b = 0; b < cellsPhi; ++b) {
      double mass = 0;
      for (int i = 0; i < fine; ++i) {
        const double theta = (a + (i + 0.5) / fine) * kPi / cellsTheta;
        for (int j = 0; j < fine; ++j) {
          const double phi = (b + (j + 0.5) / fine) * 2 * kPi / cellsPhi - kPi;
          const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                            std::sin(theta) * std::cos(phi));
          mass += map.pdf(d) * std::sin(theta) * (kPi / cellsTheta / fine) *
                  (2 * kPi / cellsPhi / fine);
        }
      }
      expected[static_cast<std::size_t>(a * cellsPhi + b)] = mass * n;
    }
  }
  double chi2 = 0, total = 0;
  int dof = -1;
  double pooledObserved = 0, pooledExpected = 0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    total += expected[k];
    if (expected[k] < 5) {  // small cells pooled, as the test wants
      pooledObserved += observed[k];
      pooledExpected += expected[k];
      continue;
    }
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++dof;
  }
  if (pooledExpected > 0) {
    chi2 += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
    ++dof;
  }
  EXPECT_LT(disagreements, n / 1000);
  EXPECT_NEAR(total, n, 0.01 * n);  // the density integrates to 1
  // The chi-square's mean is dof and its deviation √(2 dof): 5 deviations above is a failure.
  EXPECT_LT(chi2, dof + 5 * std::sqrt(2.0 * dof)) << "dof " << dof;
}

TEST(EnvironmentMap, TheMeanOfRadianceOverDensityIsTheMapsIntegral) {
  const EnvironmentMap map = unevenMap();
  // ∫ L dω by quadrature over a fine grid of directions.
  double exact = 0;
  const int rows = 400, columns = 800;
  for (int i = 0; i < rows; ++i) {
    const double theta = (i + 0.5) * kPi / rows;
    for (int j = 0; j < columns; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / columns;
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      exact += map.radiance(d).r * std::sin(theta) * (kPi / rows) * (2 * kPi / columns);
    }
  }
  double sum = 0;
  const int n = 100000;
  Random random(3, 2);
  for (int i = 0; i < n; ++i) {
    const EnvironmentSample s = map.sample(random.uniform2());
    sum += s.radiance.r / s.pdf;
  }
  EXPECT_NEAR(sum / n, exact, 0.01 * exact);
}

// A unit sphere of reflectance 1 seen from (0, h, 5) along −z, the mean of `samples` paths.
glm::vec3 spherePixel(const TraceScene& scene, const TraceLights& lights, float h, int samples) {
  TraceOptions options;
  glm::vec3 sum(0.0f);
  for (int i = 0; i < samples; ++i) {
    Random random(11, static_cast<std::uint64_t>(i));
    sum += traceRay(scene, lights, glm::vec3(0, h, 5), glm::vec3(0, 0, -1), random, options);
  }
  return sum / static_cast<float>(samples);
}

TEST(EnvironmentMap, AWhiteEnvironmentIsAFurnace) {
  TraceScene scene(TraceSettings{});
  TraceMaterial white;
  white.surface.reflectance = glm::vec3(1.0f);
  scene.addSpheres({glm::vec4(0, 0, 0, 1)}, scene.addMaterial(white));
  scene.commit();
  TraceLights lights;
  lights.environment = std::make_shared<EnvironmentMap>(
      16, 8, std::vector<glm::vec3>(128, glm::vec3(1.0f)), glm::vec3(0, 1, 0));
  for (float h : {-0.7f, 0.0f, 0.6f}) {
    const glm::vec3 v = spherePixel(scene, lights, h, 4000);
    EXPECT_NEAR(v.r, 1.0f, 0.01f) << h;
    EXPECT_NEAR(v.b, 1.0f, 0.01f) << h;
  }
  // Seen past the sphere, the map is the background only when asked.
  Random random(1, 1);
  TraceOptions options;
  EXPECT_EQ(traceRay(scene, lights, glm::vec3(0, 3, 5), glm::vec3(0, 0, -1), random, options).g, 0);
  lights.skySeen = true;
  EXPECT_EQ(traceRay(scene, lights, glm::vec3(0, 3, 5), glm::vec3(0, 0, -1), random, options).g, 1);
}

TEST(EnvironmentMap, ASphereUnderAnUnevenMapGetsItsIrradiance) {
  TraceScene scene(TraceSettings{});
  TraceMaterial grey;
  grey.surface.reflectance = glm::vec3(0.5f);
  scene.addSpheres({glm::vec4(0, 0, 0, 1)}, scene.addMaterial(grey));
  scene.commit();
  TraceLights lights;
  lights.environment = std::make_shared<EnvironmentMap>(unevenMap());
  // The sphere's point facing the eye (+z): L = ρ/π ∫ L(ω) max(ω·z, 0) dω.
  double irradiance = 0;
  const int rows = 400, columns = 800;
  for (int i = 0; i < rows; ++i) {
    const double theta = (i + 0.5) * kPi / rows;
    for (int j = 0; j < columns; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / columns;
      const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      if (d.z > 0) {
        irradiance += lights.environment->radiance(d).r * d.z * std::sin(theta) * (kPi / rows) *
                      (2 * kPi / columns);
      }
    }
  }
  const double expected = 0.5 / kPi * irradiance;
  EXPECT_NEAR(spherePixel(scene, lights, 0, 20000).r, expected, 0.015 * expected);
}

// Preetham et al.'s sky at turbidity 3, the sun 45° from the zenith: the zenith luminance of
// their formula, (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192 with χ = (4/9 − T/120)(π − 2θs),
// worked by hand: 7.330 kcd/m²; the horizon opposite the sun (θ = 90°, γ = 135°) 1.086 times
// the zenith, from Perez's F with the paper's coefficients, also by hand.
TEST(SkyModel, ZenithAndHorizonAreAsPreethamsFormulas) {
  const PreethamSky sky(3, kPi / 4);
  EXPECT_NEAR(sky.zenithLuminance(), 7.330f, 0.01f);
  EXPECT_NEAR(sky.xyY(0, kPi / 4).z, sky.zenithLuminance(), 1e-4f);
  EXPECT_NEAR(sky.xyY(kPi / 2, 3 * kPi / 4).z / sky.zenithLuminance(), 1.086f, 0.01f);
  // Brighter towards the sun than away from it, at the horizon and at 60° from the zenith.
  EXPECT_GT(sky.xyY(kPi / 2, kPi / 4).z, 1.5f * sky.xyY(kPi / 2, 3 * kPi / 4).z);
  EXPECT_GT(sky.xyY(kPi / 3, 0.2f).z, sky.xyY(kPi / 3, 2.5f).z);
  // A clear sky is blue at the zenith: its chromaticity's x and y below the white point's.
  EXPECT_LT(sky.xyY(0, kPi / 4).x, 0.3127f);
  EXPECT_LT(sky.xyY(0, kPi / 4).y, 0.3290f);
  // A hazier sky is brighter at the zenith and its horizon glows more against it, away from the
  // sun, than a clear one's.
  const PreethamSky hazy(8, kPi / 4);
  EXPECT_GT(hazy.zenithLuminance(), sky.zenithLuminance());
  // The sun is dimmer through a hazier, longer path.
  EXPECT_LT(hazy.sunIlluminance().g, sky.sunIlluminance().g);
  EXPECT_LT(PreethamSky(3, 1.4f).sunIlluminance().g, sky.sunIlluminance().g);
  // Redder low: blue is thinned more than red.
  const glm::vec3 low = PreethamSky(3, 1.45f).sunIlluminance();
  EXPECT_LT(low.b / low.r, sky.sunIlluminance().b / sky.sunIlluminance().r);
}

TEST(SkyModel, TheBakedSkyPlacesTheSunAndTheGround) {
  SunSkySettings settings;
  settings.elevation = 30;
  settings.azimuth = 90;  // to the right
  settings.turbidity = 3;
  settings.groundAlbedo = 0.3f;
  const SunSky s =
      makeSunSky(settings, glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), 256);
  EXPECT_NEAR(s.sunDirection.y, 0.5f, 1e-4f);
  EXPECT_NEAR(s.sunDirection.x, std::cos(glm::radians(30.0f)), 1e-4f);
  // The sky near the sun is brighter than opposite it; the ground is grey and even.
  const glm::vec3 nearSun = glm::normalize(s.sunDirection + glm::vec3(0, 0.15f, 0));
  const glm::vec3 opposite = glm::normalize(glm::vec3(-s.sunDirection.x, 0.6f, 0));
  EXPECT_GT(luminance(s.sky->radiance(nearSun)), 2 * luminance(s.sky->radiance(opposite)));
  const glm::vec3 ground = s.sky->radiance(glm::vec3(0.3f, -0.9f, 0.1f));
  EXPECT_EQ(ground, s.sky->radiance(glm::vec3(-0.5f, -0.4f, 0.6f)));
  EXPECT_GT(s.sunIrradiance.g, 0.5f);
}

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("hirsute-sky-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  return folder / name;
}

TEST(EnvironmentFile, AWrittenMapIsReadBack) {
  const std::filesystem::path file = scratch("map.exr");
  std::vector<glm::vec3> pixels(8 * 4);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = glm::vec3(0.25f * static_cast<float>(i), 1, 2);
  writeExr(file, 8, 4, pixels);
  SourceLocation where;
  where.file = std::make_shared<const std::string>("view.v");
  where.line = 3;
  where.column = 20;
  const EnvironmentImage image =
      readEnvironmentImage(file.parent_path().string(), "map.exr", where);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 4);
  EXPECT_FLOAT_EQ(image.pixels[5].r, 1.25f);
  EXPECT_FLOAT_EQ(image.pixels[31].b, 2.0f);
}

TEST(EnvironmentFile, ABrokenFileIsAnErrorAtTheLine) {
  SourceLocation where;
  where.file = std::make_shared<const std::string>("view.v");
  where.line = 3;
  where.column = 20;
  const std::filesystem::path file = scratch("map.exr");
  writeExr(file, 8, 4, std::vector<glm::vec3>(32, glm::vec3(1.0f)));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  for (const std::string& broken :
       {std::string("not an image at all"), bytes.substr(0, bytes.size() / 2), std::string()}) {
    try {
      decodeEnvironmentImage(broken, "sky.exr", where);
      ADD_FAILURE() << "no error for " << broken.size() << " bytes";
    } catch (const DiagnosticError& e) {
      const std::string text = e.diagnostic().text();
      EXPECT_NE(text.find("view.v:3:20: error: cannot read the environment map 'sky.exr'"),
                std::string::npos)
          << text;
    }
  }
  try {
    readEnvironmentImage(file.parent_path().string(), "../elsewhere.exr", where);
    ADD_FAILURE() << "a name out of the folder was read";
  } catch (const DiagnosticError& e) {
    EXPECT_NE(e.diagnostic().text().find("view.v:3:20: error:"), std::string::npos);
  }
}

}  // namespace
