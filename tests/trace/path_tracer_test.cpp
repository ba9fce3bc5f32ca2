// The integrator against what can be worked out by hand: a diffuse sphere under a uniform sky
// and under the spherical light, the error of a pixel falling as 1/√samples, the same picture
// on any number of threads, and the hairy-plants paper's backlit halo (Fig. 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace {

using namespace hirsute;
using namespace hirsute::trace;

// A unit sphere at the origin of reflectance `albedo`.
void addSphere(TraceScene& scene, float albedo) {
  TraceMaterial m;
  m.surface.reflectance = glm::vec3(albedo);
  scene.addSpheres({glm::vec4(0, 0, 0, 1)}, scene.addMaterial(m));
}

// The mean of `samples` paths along -z through (0, h, 5), each with its own stream.
// With `stratified`, the samples of one pixel as traceImage draws them.
glm::vec3 pixel(const TraceScene& scene, const TraceLights& lights, float h, int samples,
                std::uint64_t seed, bool stratified = false) {
  TraceOptions options;
  glm::vec3 sum(0.0f);
  for (int i = 0; i < samples; ++i) {
    Random random = stratified ? Random::stratified(seed, 17, static_cast<std::uint32_t>(i))
                               : Random(seed, static_cast<std::uint64_t>(i));
    sum += traceRay(scene, lights, glm::vec3(0, h, 5), glm::vec3(0, 0, -1), random, options);
  }
  return sum / static_cast<float>(samples);
}

TEST(PathTracer, ADiffuseSphereUnderAUniformSkyHasItsAnalyticRadiance) {
  TraceScene scene(TraceSettings{});
  addSphere(scene, 0.7f);
  scene.commit();
  TraceLights lights;
  lights.sky = glm::vec3(0.5f);
  lights.up = glm::vec3(0, 1, 0);
  // A point whose normal makes angle α with the sky's up sees (1 + cos α)/2 of the sky's
  // irradiance π L; a convex body never sees itself: L_out = ρ L (1 + cos α) / 2.
  for (float h : {-0.8f, -0.3f, 0.0f, 0.5f, 0.9f}) {
    const float expected = 0.7f * 0.5f * (1 + h) / 2;
    EXPECT_NEAR(pixel(scene, lights, h, 20000, 1).g, expected, 0.01f * 0.35f + 0.002f) << "h " << h;
  }
}

TEST(PathTracer, TheSphericalLightGivesItsIrradiance) {
  TraceScene scene(TraceSettings{});
  addSphere(scene, 0.5f);
  scene.commit();
  TraceSettings look;
  look.lightDirection = glm::vec3(0, 0, 1);  // towards the eye: the point facing it is lit fully
  look.lightAngle = 4;
  look.lightIrradiance = glm::vec3(2.0f);
  Bounds plant;
  plant.add(glm::vec3(-1));
  plant.add(glm::vec3(1));
  TraceLights lights = traceLights(look, plant, glm::vec3(0, 0, 1));
  lights.sky = glm::vec3(0.0f);
  // A sphere of radius R and radiance L at distance d gives E = π L (R/d)² cos θ, and a
  // Lambertian surface returns ρ E / π of it.
  for (float degrees : {0.0f, 60.0f}) {
    const float h = std::sin(glm::radians(degrees));
    const glm::vec3 point(0, h, std::sqrt(1 - h * h));
    const glm::vec3 toLight = lights.centre - point;
    const float d = glm::length(toLight);
    const float cosine = glm::dot(point, toLight / d);
    const float expected = 0.5f * lights.radiance.g * (lights.radius / d) * (lights.radius / d) * cosine;
    EXPECT_NEAR(pixel(scene, lights, h, 4000, 2).g, expected, 0.01f * expected) << degrees;
  }
}

// The error of 200 pixels of `samples` paths each at h = 0.4 on a diffuse sphere (ρ 0.7) under a
// uniform sky: their mean (the bias) and RMS.
struct PixelErrors {
  double mean, rms;
};

PixelErrors skyLitPixelErrors(int samples, bool stratified) {
  TraceScene scene(TraceSettings{});
  addSphere(scene, 0.7f);
  scene.commit();
  TraceLights lights;
  lights.sky = glm::vec3(0.5f);
  const float h = 0.4f;
  const double expected = 0.7 * 0.5 * (1 + h) / 2;
  double sum = 0, squares = 0;
  const int pixels = 200;
  for (int p = 0; p < pixels; ++p) {
    const double e =
        pixel(scene, lights, h, samples, 100 + static_cast<std::uint64_t>(p), stratified).g - expected;
    sum += e;
    squares += e * e;
  }
  return {sum / pixels, std::sqrt(squares / pixels)};
}

TEST(PathTracer, APixelsErrorFallsAsOneOverTheRootOfItsSamples) {
  const double few = skyLitPixelErrors(16, false).rms, many = skyLitPixelErrors(256, false).rms;
  // Sixteen times the samples: a quarter of the error.
  EXPECT_GT(few / many, 3.0) << few << " " << many;
  EXPECT_LT(few / many, 5.3) << few << " " << many;
}

TEST(PathTracer, APixelsStratifiedSamplesConvergeFasterWithoutBias) {
  const PixelErrors few = skyLitPixelErrors(16, true), many = skyLitPixelErrors(256, true);
  const double independent = skyLitPixelErrors(256, false).rms;
  // Sixteen times the samples: well under a quarter of the error (the sky's hemisphere is
  // sampled evenly; 7.2 times less), and at 256 samples a third of the independent samples'
  // error at most.
  EXPECT_GT(few.rms / many.rms, 6.0) << few.rms << " " << many.rms;
  EXPECT_LT(many.rms, independent / 3) << many.rms << " " << independent;
  // No bias: over 200 pixels the mean error is about 1/14 of the spread, not a share of it.
  EXPECT_LT(std::abs(few.mean), 0.25 * few.rms) << few.mean;
  EXPECT_LT(std::abs(many.mean), 0.25 * many.rms) << many.mean;
}

Camera frontCamera(int width, int height, float half) {
  Camera camera;
  camera.projection = Projection::Parallel;
  camera.viewport = {width, height};
  camera.eye = glm::vec3(0, 0, 10);
  camera.forward = glm::vec3(0, 0, -1);
  camera.up = glm::vec3(0, 1, 0);
  camera.right = glm::vec3(1, 0, 0);
  camera.halfHeight = half;
  camera.halfWidth = half * static_cast<float>(width) / static_cast<float>(height);
  camera.nearPlane = 0;
  camera.farPlane = 20;
  return camera;
}

TEST(PathTracer, ASeedGivesOnePictureOnAnyNumberOfThreads) {
  TraceScene scene(TraceSettings{});
  addSphere(scene, 0.6f);
  scene.commit();
  TraceLights lights;
  lights.sky = glm::vec3(0.4f);
  TraceOptions options;
  options.samples = 3;
  options.seed = 42;
  options.threads = 1;
  const TraceImage one = traceImage(scene, frontCamera(24, 16, 1.5f), lights, options);
  options.threads = 3;
  const TraceImage three = traceImage(scene, frontCamera(24, 16, 1.5f), lights, options);
  ASSERT_EQ(one.radiance.size(), three.radiance.size());
  for (std::size_t i = 0; i < one.radiance.size(); ++i) EXPECT_EQ(one.radiance[i], three.radiance[i]);
  options.seed = 43;
  const TraceImage other = traceImage(scene, frontCamera(24, 16, 1.5f), lights, options);
  EXPECT_NE(one.radiance, other.radiance);
  // And adaptively, on a wider picture whose side tiles are background: each tile stops after
  // the same pass on any number of threads.
  options.seed = 42;
  options.samples = 40;
  options.firstSamples = 8;
  options.noise = 6;
  options.threads = 1;
  const TraceImage adaptiveOne = traceImage(scene, frontCamera(40, 24, 1.5f), lights, options);
  options.threads = 3;
  const TraceImage adaptiveThree = traceImage(scene, frontCamera(40, 24, 1.5f), lights, options);
  EXPECT_EQ(adaptiveOne.samples, adaptiveThree.samples);
  EXPECT_EQ(adaptiveOne.radiance, adaptiveThree.radiance);
  const auto [fewest, most] =
      std::minmax_element(adaptiveOne.samples.begin(), adaptiveOne.samples.end());
  EXPECT_LT(*fewest, *most);  // some tiles stopped early, others did not
}

// Adaptive sampling on a diffuse sphere (ρ 0.7) under a uniform sky in front of a black
// background, seen from the front by a parallel camera over [-1.5, 1.5]²: a pixel at (x, y)
// inside the disc sees the point whose normal is (x, y, z), of radiance ρ L (1 + y) / 2.
struct SkyLitSphere {
  TraceScene scene{TraceSettings{}};
  TraceLights lights;
  SkyLitSphere() {
    addSphere(scene, 0.7f);
    scene.commit();
    lights.sky = glm::vec3(0.5f);
  }
  static constexpr int kSide = 48;
  static constexpr float kHalf = 1.5f;
  static glm::vec2 world(int x, int y) {
    return {kHalf * ((x + 0.5f) / kSide * 2 - 1), kHalf * (1 - (y + 0.5f) / kSide * 2)};
  }
};

TEST(PathTracer, AdaptiveSamplingStopsOnTheFlatBackgroundAndGoesOnWhereItIsNoisy) {
  SkyLitSphere sky;
  TraceOptions options;
  options.samples = 64;
  options.firstSamples = 16;
  options.noise = 0.5f;
  options.seed = 3;
  const TraceImage image = traceImage(
      sky.scene, frontCamera(SkyLitSphere::kSide, SkyLitSphere::kSide, 1.5f), sky.lights, options);
  EXPECT_EQ(image.passes, 64);
  int background = 0, noisy = 0;
  for (int y = 0; y < SkyLitSphere::kSide; ++y) {
    for (int x = 0; x < SkyLitSphere::kSide; ++x) {
      // The distance from the disc of the tile's nearest and farthest pixel centres.
      float nearest = 1e9f, farthest = 0;
      const int tx = x / kTileSize * kTileSize, ty = y / kTileSize * kTileSize;
      for (int v = ty; v < ty + kTileSize; ++v) {
        for (int u = tx; u < tx + kTileSize; ++u) {
          const float r = glm::length(SkyLitSphere::world(u, v));
          nearest = std::min(nearest, r);
          farthest = std::max(farthest, r);
        }
      }
      const std::uint32_t n = image.samples[static_cast<std::size_t>(y) * SkyLitSphere::kSide + x];
      if (nearest > 1.05f) {  // a tile of background alone: every sample black, no noise
        EXPECT_EQ(n, 16u) << x << " " << y;
        ++background;
      } else if (farthest < 0.95f) {  // a tile on the sphere: a few levels of noise at 64
        EXPECT_EQ(n, 64u) << x << " " << y;
        ++noisy;
      }
    }
  }
  EXPECT_GT(background, 500);
  EXPECT_GT(noisy, 200);
  EXPECT_LT(image.meanSamples(), 48);
}

// The width in pixels over which the middle rows of the sky-lit sphere rise from 10% to 90% of
// their inside at the disc's left edge (which falls on a pixel boundary), by linear interpolation.
float edgeWidth(PixelFilterKind filter, int threads = 0, TraceImage* out = nullptr,
                float aperture = 0, float focus = 0) {
  SkyLitSphere sky;
  TraceOptions options;
  options.samples = 64;
  options.seed = 5;
  options.filter = filter;
  options.threads = threads;
  options.aperture = aperture;
  options.focusDistance = focus;
  const TraceImage image = traceImage(
      sky.scene, frontCamera(SkyLitSphere::kSide, SkyLitSphere::kSide, 1.5f), sky.lights, options);
  if (out) *out = image;
  const int side = SkyLitSphere::kSide;
  std::vector<float> row(side / 2);
  for (int x = 0; x < side / 2; ++x) {
    for (int y = side / 2 - 2; y < side / 2 + 2; ++y) {
      row[x] += image.at(x, y).g + image.at(side - 1 - x, y).g;
    }
  }
  float inside = 0;
  for (int x = 14; x < 20; ++x) inside += row[x] / 6;
  auto crossing = [&](float level) {
    for (int x = 1; x < side / 2; ++x) {
      if (row[x] >= level * inside) {
        return static_cast<float>(x - 1) + (level * inside - row[x - 1]) / (row[x] - row[x - 1]);
      }
    }
    return static_cast<float>(side);
  };
  return crossing(0.9f) - crossing(0.1f);
}

TEST(PathTracer, AGaussianFilterSoftensAnEdgeThatTheBoxKeepsSharp) {
  const float box = edgeWidth(PixelFilterKind::Box);
  const float gaussian = edgeWidth(PixelFilterKind::Gaussian);
  const float mitchell = edgeWidth(PixelFilterKind::Mitchell);
  std::printf("edge 10-90%% widths: box %.3f, gaussian %.3f, mitchell %.3f pixels\n", box, gaussian,
              mitchell);
  EXPECT_LT(box, 1.0f);
  EXPECT_GT(gaussian, box + 0.4f);
  EXPECT_GT(mitchell, box + 0.4f);  // its main lobe reaches past the pixel too
  // The filters keep one picture a seed on any number of threads.
  for (const PixelFilterKind kind : {PixelFilterKind::Gaussian, PixelFilterKind::Mitchell}) {
    TraceImage one, three;
    edgeWidth(kind, 1, &one);
    edgeWidth(kind, 3, &three);
    EXPECT_EQ(one.radiance, three.radiance);
  }
}

TEST(PathTracer, AThinLensKeepsThePlaneInFocusSharpAndBlursTheRest) {
  // The camera looks at the sphere's centre from 10 away: its silhouette lies in that plane.
  const float pinhole = edgeWidth(PixelFilterKind::Box);
  const float inFocus = edgeWidth(PixelFilterKind::Box, 0, nullptr, 0.5f);
  const float nearer = edgeWidth(PixelFilterKind::Box, 0, nullptr, 0.5f, 5);
  std::printf(
      "edge 10-90%% widths: pinhole %.3f, in focus %.3f, focused at half the distance "
      "%.3f pixels\n",
      pinhole, inFocus, nearer);
  EXPECT_LT(inFocus, pinhole + 0.3f);
  // Focused at 5, a lens 0.5 across spreads the silhouette over a disc 0.5 across, 8 pixels.
  EXPECT_GT(nearer, 3.0f);
  TraceImage one, three;
  edgeWidth(PixelFilterKind::Box, 1, &one, 0.5f, 5);
  edgeWidth(PixelFilterKind::Box, 3, &three, 0.5f, 5);
  EXPECT_EQ(one.radiance, three.radiance);
}

TEST(PathTracer, AdaptiveSamplingLeavesTheSkyLitSphereUnbiased) {
  SkyLitSphere sky;
  TraceOptions options;
  options.samples = 256;
  options.firstSamples = 16;
  options.noise = 3.5f;
  double sum = 0, squares = 0, levels = 0;
  int count = 0;
  std::uint32_t fewest = 1u << 30u, most = 0;
  for (std::uint64_t seed : {5u, 6u}) {
    options.seed = seed;
    const TraceImage image =
        traceImage(sky.scene, frontCamera(SkyLitSphere::kSide, SkyLitSphere::kSide, 1.5f),
                   sky.lights, options);
    for (int y = 0; y < SkyLitSphere::kSide; ++y) {
      for (int x = 0; x < SkyLitSphere::kSide; ++x) {
        const glm::vec2 p = SkyLitSphere::world(x, y);
        if (glm::length(p) > 0.9f) continue;
        const std::size_t index = static_cast<std::size_t>(y) * SkyLitSphere::kSide + x;
        const float expected = 0.7f * 0.5f * (1 + p.y) / 2;
        const float value = image.radiance[index].g;
        sum += value - expected;
        squares += (value - expected) * (value - expected);
        const float off = displayLevel(value) - displayLevel(expected);
        levels += off * off;
        fewest = std::min(fewest, image.samples[index]);
        most = std::max(most, image.samples[index]);
        ++count;
      }
    }
  }
  // The tiles stopped at many different counts (the darker lower half takes more).
  EXPECT_LT(fewest + 32, most) << fewest << " " << most;
  // Each pixel within the target: the estimate from the samples' spread ignores their
  // stratification and errs on the safe side.
  EXPECT_LT(std::sqrt(levels / count), options.noise) << std::sqrt(levels / count);
  // No bias from stopping where the first samples happened to agree: the mean error over the
  // 1 200 pixels within three of its standard errors of 0.
  const double mean = sum / count, rms = std::sqrt(squares / count);
  EXPECT_LT(std::abs(mean), 3 * rms / std::sqrt(count)) << mean << " " << rms << " " << count;
}

// The denoiser on a traced picture: at 8 samples a pixel, the sky-lit sphere's error against
// its analytic radiance falls by half or more, without bias, and the background stays black.
TEST(PathTracer, DenoisingCutsTheSphereErrorAndKeepsTheBackground) {
  SkyLitSphere sky;
  TraceOptions options;
  options.samples = 8;
  options.seed = 11;
  const Camera camera = frontCamera(SkyLitSphere::kSide, SkyLitSphere::kSide, 1.5f);
  const TraceImage raw = traceImage(sky.scene, camera, sky.lights, options);
  options.denoise = true;
  const TraceImage filtered = traceImage(sky.scene, camera, sky.lights, options);
  EXPECT_GE(filtered.denoiseSeconds, 0.0);
  double rawSquares = 0, squares = 0, sum = 0;
  int count = 0;
  for (int y = 0; y < SkyLitSphere::kSide; ++y) {
    for (int x = 0; x < SkyLitSphere::kSide; ++x) {
      const std::size_t index = static_cast<std::size_t>(y) * SkyLitSphere::kSide + x;
      const glm::vec2 p = SkyLitSphere::world(x, y);
      if (glm::length(p) > 1.15f) {  // past the rim's pixels and their neighbours
        EXPECT_EQ(filtered.radiance[index], glm::vec3(0.0f)) << x << " " << y;
        continue;
      }
      if (glm::length(p) > 0.9f) continue;  // the rim: pixels partly background
      const float expected = 0.7f * 0.5f * (1 + p.y) / 2;
      rawSquares += (raw.radiance[index].g - expected) * (raw.radiance[index].g - expected);
      squares += (filtered.radiance[index].g - expected) * (filtered.radiance[index].g - expected);
      sum += filtered.radiance[index].g - expected;
      ++count;
    }
  }
  const double rawRms = std::sqrt(rawSquares / count), rms = std::sqrt(squares / count);
  EXPECT_LT(rms, rawRms / 2) << rawRms << " -> " << rms;
  EXPECT_LT(std::abs(sum / count), rawRms / 10) << sum / count;
}

// Fig. 5 of the hairy-plants paper: a twig with fine hairs, lit from behind, glows in a band
// just outside its silhouette; without the hairs the band is the background. Front lit, the
// same hairs are much fainter.
struct Twig {
  float band = 0;   // mean radiance just outside the silhouette
  float body = 0;   // mean radiance on the twig
};

Twig twig(bool hairs, const glm::vec3& towardsLight) {
  TraceSettings look;
  look.hairBackscatter = 0.2f;
  look.hairSpecular = 0.05f;
  TraceScene scene(look);
  // A cylinder of radius 0.5 along x, as triangles.
  const int sides = 32, rings = 2;
  TriangleBuffers body = scene.addTriangles(sides * rings, 2 * sides, scene.surfaceOfColour(glm::vec3(0.3f, 0.2f, 0.1f)), true, false);
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < sides; ++s) {
      const float a = 2 * kPi * static_cast<float>(s) / sides;
      const glm::vec3 n(0, std::cos(a), std::sin(a));
      body.positions[r * sides + s] = glm::vec3(r == 0 ? -4.0f : 4.0f, 0, 0) + 0.5f * n;
      body.normals[r * sides + s] = n;
    }
  }
  for (int s = 0; s < sides; ++s) {
    const std::uint32_t a = s, b = (s + 1) % sides, c = sides + s, d = sides + (s + 1) % sides;
    const std::uint32_t tri[6] = {a, b, d, a, d, c};
    std::copy(tri, tri + 6, body.indices + 6 * s);
  }
  if (hairs) {
    // Straight hairs 0.3 long standing out of the surface, 0.004 thick, a dense fuzz.
    const int count = 6000;
    CurveBuffers b = scene.addCurves(CurveShape::Round, 2 * count, count,
                                     scene.hairOfColour(glm::vec3(0.9f)), false);
    Random random(9, 9);
    for (int i = 0; i < count; ++i) {
      const float x = -4 + 8 * random.uniform();
      const float a = 2 * kPi * random.uniform();
      const glm::vec3 n(0, std::cos(a), std::sin(a));
      b.vertices[2 * i] = glm::vec4(glm::vec3(x, 0, 0) + 0.5f * n, 0.004f);
      b.vertices[2 * i + 1] = glm::vec4(glm::vec3(x, 0, 0) + 0.8f * n, 0.004f);
      b.segments[i] = static_cast<std::uint32_t>(2 * i);
    }
  }
  scene.commit();
  look.lightDirection = towardsLight;
  look.lightIrradiance = glm::vec3(3.0f);
  Bounds box;
  box.add(glm::vec3(-4, -1, -1));
  box.add(glm::vec3(4, 1, 1));
  TraceLights lights = traceLights(look, box, towardsLight);
  lights.sky = glm::vec3(0.0f);
  TraceOptions options;
  options.samples = 24;
  const int width = 48, height = 48;
  const TraceImage image = traceImage(scene, frontCamera(width, height, 1.2f), lights, options);
  Twig out;
  int inBand = 0, onBody = 0;
  for (int y = 0; y < height; ++y) {
    const float world = 1.2f * (1 - (y + 0.5f) / height * 2);
    for (int x = 0; x < width; ++x) {
      const float value = luminance(image.at(x, y));
      if (std::abs(world) > 0.55f && std::abs(world) < 0.75f) {
        out.band += value;
        ++inBand;
      } else if (std::abs(world) < 0.4f) {
        out.body += value;
        ++onBody;
      }
    }
  }
  out.band /= static_cast<float>(inBand);
  out.body /= static_cast<float>(onBody);
  return out;
}

TEST(PathTracer, BacklitHairsMakeAHaloOutsideTheSilhouette) {
  const glm::vec3 behind = glm::normalize(glm::vec3(0, 0.25f, -1));
  const glm::vec3 front = glm::normalize(glm::vec3(0, 0.25f, 1));
  const Twig bare = twig(false, behind), hairy = twig(true, behind), frontLit = twig(true, front);
  EXPECT_EQ(bare.band, 0.0f);
  // The halo: the band glows at more than a twentieth of the light's white-surface radiance.
  EXPECT_GT(hairy.band, 0.05f * 3.0f / kPi) << hairy.band;
  // And the glow is the light passed through the hairs: lit from the front, they are fainter.
  EXPECT_GT(hairy.band, 1.5f * frontLit.band) << hairy.band << " " << frontLit.band;
  // The twig's own surface is lit from the front, not from behind.
  EXPECT_GT(frontLit.body, 3 * hairy.body);
}

}  // namespace

namespace {

// A square of side 4 at height z facing +z, of `material`.
void addSquare(TraceScene& scene, float z, int material) {
  const TriangleBuffers b = scene.addTriangles(4, 2, material, false, false);
  const glm::vec3 corners[4] = {{-2, -2, z}, {2, -2, z}, {2, 2, z}, {-2, 2, z}};
  std::copy(corners, corners + 4, b.positions);
  const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::copy(indices, indices + 6, b.indices);
}

// Light reaches a white floor through two half-transparent black sheets: a quarter of it on
// the way down (the shadow ray counts each sheet once, in one traversal) and a quarter of what
// the floor returns on the way up (camera rays pass each sheet half the time).
TEST(PathTracer, ShadowRaysThroughTransparentSheetsCountEachOnce) {
  TraceScene scene(TraceSettings{});
  TraceMaterial white;
  white.surface.reflectance = glm::vec3(1.0f);
  TraceMaterial sheet;
  sheet.surface.reflectance = glm::vec3(0.0f);
  sheet.opacity = 0.5f;
  addSquare(scene, 0, scene.addMaterial(white));
  const int sheets = scene.addMaterial(sheet);
  addSquare(scene, 0.5f, sheets);
  addSquare(scene, 1.0f, sheets);
  scene.commit();
  ASSERT_TRUE(scene.hasTransparency());
  TraceSettings look;
  look.lightDirection = glm::vec3(0, 0, 1);
  look.lightAngle = 2;
  look.lightIrradiance = glm::vec3(kPi);  // a white surface facing it returns 1
  Bounds box;
  box.add(glm::vec3(-2, -2, 0));
  box.add(glm::vec3(2, 2, 1));
  TraceLights lights = traceLights(look, box, glm::vec3(0, 0, 1));
  lights.sky = glm::vec3(0.0f);
  glm::vec3 sum(0.0f);
  constexpr int kSamples = 40000;
  for (int i = 0; i < kSamples; ++i) {
    Random random(9, static_cast<std::uint64_t>(i));
    sum += traceRay(scene, lights, glm::vec3(0.1f, 0.2f, 5), glm::vec3(0, 0, -1), random,
                    TraceOptions{});
  }
  const float expected = 0.25f * 0.25f;
  EXPECT_NEAR(sum.g / kSamples, expected, 0.05f * expected);
}

}  // namespace
