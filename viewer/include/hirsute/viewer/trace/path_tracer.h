// `hirsute render --trace`: a Monte-Carlo path tracer over the Embree scene (trace_scene.h), lit
// as the hairy-plants paper lit its pictures (papers/002_0e0bce38b72f21dc.txt, Sec. 5): one
// spherical light and a hemispherical skylight, each sampled directly and by the materials,
// the two combined by multiple importance sampling (Veach's power heuristic). The plant stands
// against a solid background, which camera rays that miss it see; the light lights but is not
// seen.
//
// The picture is made in passes of one sample a pixel, over all the threads; a pixel's samples
// depend on the seed, the pixel and the pass alone, so a seed gives the same picture on any
// number of threads. A time budget stops the passes between two of them.
//
// Adaptive sampling (TraceOptions::noise): after `firstSamples` passes, each tile of kTileSize²
// pixels is judged after each pass by the largest estimated standard error of its pixels'
// means, in display levels; a tile under the target takes no more samples. A pixel's samples
// stay its first ones (passes 0, 1, 2, ...), so their stratification holds, and a tile's fate
// depends on its own samples alone, so the picture is still one a seed on any number of
// threads.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/core/progress.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/view/png_image.h"
#include "hirsute/viewer/trace/environment_map.h"
#include "hirsute/viewer/trace/pixel_filter.h"
#include "hirsute/viewer/trace/sampling.h"
#include "hirsute/viewer/trace/tone_curve.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace hirsute::trace {

struct TraceLights {
  bool sphere = false;  // the spherical light
  glm::vec3 centre{0.0f};
  float radius = 0;
  glm::vec3 radiance{0.0f};
  glm::vec3 sky{0.0f};  // the sky's radiance over the hemisphere about `up`
  glm::vec3 up{0, 1, 0};
  // An environment map (environment_map.h: a file's, or the physical sky's) in place of `sky`,
  // and whether camera rays that miss the plant see it rather than the background.
  std::shared_ptr<const EnvironmentMap> environment;
  bool skySeen = false;
};

// The lights of `look` for a plant in `plant`: the spherical light far off (fifty times the
// plant's size) towards `look.lightDirection`, or `fallback` when the view file gives none,
// sized to subtend `look.lightAngle` and bright enough to give `look.lightIrradiance`.
TraceLights traceLights(const TraceSettings& look, const Bounds& plant, const glm::vec3& fallback);

// The side of the tiles adaptive sampling judges as one: a lucky pixel whose first samples
// happen to agree does not stop while its neighbours are noisy.
inline constexpr int kTileSize = 8;

struct TraceOptions {
  int samples = 64;  // a pixel, at most
  // Adaptive sampling: the standard error a pixel's mean may keep, in 8-bit sRGB display levels
  // (pixelNoise); 0 gives every pixel `samples`. Judged from `firstSamples` on.
  float noise = 0;
  int firstSamples = 16;
  double seconds = 0;  // the time budget (0: none); the passes stop before it runs out
  int threads = 0;     // 0: one a core
  std::uint64_t seed = 1;
  int maxBounces = 16;
  // Filter the finished picture by its noise and its first hits (denoise.h); needs two samples
  // a pixel or more.
  bool denoise = false;
  glm::vec3 background{0.0f};  // what camera rays that hit nothing see (a display colour)
  // How the picture will be shown (displayImage): the background is traced as the radiance it
  // shows as `background`, so that exposure and tone curve leave it as the view asks.
  DisplayTransform display;
  // How a pixel's samples spread about it (pixel_filter.h).
  PixelFilterKind filter = PixelFilterKind::Box;
  // A thin lens (depth of field): its diameter in world units (0: a pinhole, all sharp) and the
  // distance from the eye along the line of sight of the plane in focus (0: the point looked at).
  float aperture = 0;
  float focusDistance = 0;
  Progress* progress = nullptr;
};

// What a camera ray met first, for the denoiser: the colour of the shape it stopped at (a
// surface's reflectance and transmittance, a hair's diffuse and specular albedo) and its normal
// towards the eye (a hair's tangent); zero where it met nothing.
struct FirstHit {
  glm::vec3 albedo{0.0f};
  glm::vec3 normal{0.0f};
};

// Linear radiance a pixel, row 0 at the top, each the mean of its samples.
struct TraceImage {
  int width = 0, height = 0;
  int passes = 0;  // the most samples a pixel took
  double seconds = 0;
  double denoiseSeconds = 0;  // of `seconds`, the denoiser's
  std::vector<glm::vec3> radiance;
  std::vector<std::uint32_t> samples;  // a pixel's, in the order of `radiance`

  double meanSamples() const;

  glm::vec3 at(int x, int y) const {
    return radiance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x)];
  }
};

TraceImage traceImage(const TraceScene& scene, const Camera& camera, const TraceLights& lights,
                      const TraceOptions& options);

// The picture as a display shows it: exposed and tone-mapped by `transform` (tone_curve.h), then
// sRGB, 8 bits.
RgbaImage displayImage(const TraceImage& image, const DisplayTransform& transform = {});

// A linear value (1 = white) as 8-bit sRGB display levels, clamped to [0, 255], unrounded.
float displayLevel(float linear);

// The standard error of the mean of `count` samples of sum `sum` and sum of squares `squares`,
// in display levels: half the distance in display levels between the mean less and the mean
// plus its standard error in linear light (so that it follows sRGB's slope and its clamp),
// the most of the three channels, as `display` shows them. 0 for a single sample.
float pixelNoise(const glm::vec3& sum, const glm::dvec3& squares, std::uint32_t count,
                 const DisplayTransform& display = {});

// Each pixel's sample count as grey, white for `maximum` and black for none.
RgbaImage sampleCountImage(const TraceImage& image, int maximum);

// The radiance one path from `origin` along `direction` (unit) brings back, for tests of the
// integrator: `depth` 0 is a camera ray.
glm::vec3 traceRay(const TraceScene& scene, const TraceLights& lights, const glm::vec3& origin,
                   const glm::vec3& direction, Random& random, const TraceOptions& options);

}  // namespace hirsute::trace
