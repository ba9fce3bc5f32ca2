#include "hirsute/viewer/trace/sky_model.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "hirsute/viewer/trace/sampling.h"
#include "hirsute/viewer/view/view_lighting.h"

namespace hirsute::trace {
namespace {

// Preetham et al., Appendix A.2: each Perez coefficient of x, y and Y as a T + b.
constexpr float kDistribution[3][5][2] = {
    {{-0.0193f, -0.2592f},
     {-0.0665f, 0.0008f},
     {-0.0004f, 0.2125f},
     {-0.0641f, -0.8989f},
     {-0.0033f, 0.0452f}},
    {{-0.0167f, -0.2608f},
     {-0.0950f, 0.0092f},
     {-0.0079f, 0.2102f},
     {-0.0441f, -1.6537f},
     {-0.0109f, 0.0529f}},
    {{0.1787f, -1.4630f},
     {-0.3554f, 0.4275f},
     {-0.0227f, 5.3251f},
     {0.1206f, -2.5771f},
     {-0.0670f, 0.3703f}},
};

// The zenith's chromaticity: (T², T, 1) M (θs³, θs², θs, 1).
constexpr float kZenithX[3][4] = {{0.00166f, -0.00375f, 0.00209f, 0.0f},
                                  {-0.02903f, 0.06377f, -0.03202f, 0.00394f},
                                  {0.11693f, -0.21196f, 0.06052f, 0.25886f}};
constexpr float kZenithY[3][4] = {{0.00275f, -0.00610f, 0.00317f, 0.0f},
                                  {-0.04214f, 0.08970f, -0.04153f, 0.00516f},
                                  {0.15346f, -0.26756f, 0.06670f, 0.26688f}};

float zenithChromaticity(const float m[3][4], float turbidity, float sunZenith) {
  const float t[3] = {turbidity * turbidity, turbidity, 1};
  const float s[4] = {sunZenith * sunZenith * sunZenith, sunZenith * sunZenith, sunZenith, 1};
  float sum = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) sum += t[i] * m[i][j] * s[j];
  }
  return sum;
}

// The solar illuminance outside the atmosphere, at normal incidence, in klx.
constexpr float kSolarIlluminance = 128.0f;

}  // namespace

PreethamSky::PreethamSky(float turbidity, float sunZenith)
    : turbidity_(turbidity), sunZenith_(std::clamp(sunZenith, 0.0f, kPi / 2)) {
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 5; ++i) {
      coefficients_[k][i] = kDistribution[k][i][0] * turbidity + kDistribution[k][i][1];
    }
  }
  const float chi = (4.0f / 9.0f - turbidity / 120.0f) * (kPi - 2 * sunZenith_);
  zenith_.z = (4.0453f * turbidity - 4.9710f) * std::tan(chi) - 0.2155f * turbidity + 2.4192f;
  zenith_.z = std::max(zenith_.z, 0.0f);
  zenith_.x = zenithChromaticity(kZenithX, turbidity, sunZenith_);
  zenith_.y = zenithChromaticity(kZenithY, turbidity, sunZenith_);
}

float PreethamSky::perez(const float c[5], float theta, float gamma) const {
  const float cosTheta = std::max(std::cos(theta), 1e-3f);
  const float cosGamma = std::cos(gamma);
  return (1 + c[0] * std::exp(c[1] / cosTheta)) *
         (1 + c[2] * std::exp(c[3] * gamma) + c[4] * cosGamma * cosGamma);
}

glm::vec3 PreethamSky::xyY(float theta, float gamma) const {
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const float ratio =
        perez(coefficients_[k], theta, gamma) / perez(coefficients_[k], 0, sunZenith_);
    out[k] = zenith_[k] * ratio;
  }
  out.z = std::max(out.z, 0.0f);
  return out;
}

glm::vec3 PreethamSky::sunIlluminance() const {
  // Kasten's relative air mass, with the zenith angle in degrees in its correction.
  const float degrees = glm::degrees(sunZenith_);
  const float airMass =
      1 / (std::cos(sunZenith_) + 0.15f * std::pow(std::max(93.885f - degrees, 1e-3f), -1.253f));
  const float beta = 0.04608f * turbidity_ - 0.04586f;  // Ångström's turbidity coefficient
  constexpr float kAlpha = 1.3f;
  // Dominant wavelengths of red, green and blue, in µm.
  constexpr float kWavelength[3] = {0.61f, 0.55f, 0.465f};
  glm::vec3 out;
  for (int c = 0; c < 3; ++c) {
    const float lambda = kWavelength[c];
    const float rayleigh = 0.008735f * std::pow(lambda, -4.08f);
    const float aerosol = beta * std::pow(lambda, -kAlpha);
    out[c] = kSolarIlluminance * std::exp(-airMass * (rayleigh + aerosol));
  }
  return out;
}

glm::vec3 rgbOfxyY(const glm::vec3& c) {
  if (!(c.y > 0)) return glm::vec3(0.0f);
  const float X = c.x * c.z / c.y, Y = c.z, Z = (1 - c.x - c.y) * c.z / c.y;
  const glm::vec3 rgb(3.2406f * X - 1.5372f * Y - 0.4986f * Z,
                      -0.9689f * X + 1.8758f * Y + 0.0415f * Z,
                      0.0557f * X - 0.2040f * Y + 1.0570f * Z);
  return glm::max(rgb, glm::vec3(0.0f));
}

SunSky makeSunSky(const SunSkySettings& settings, const glm::vec3& upIn,
                  const glm::vec3& towardsEye, const glm::vec3& right, int width,
                  std::optional<glm::vec3> groundAlbedo) {
  const glm::vec3 up = glm::normalize(upIn);
  auto across = [&](const glm::vec3& v, const glm::vec3& fallback) {
    const glm::vec3 flat = v - glm::dot(v, up) * up;
    return glm::length(flat) > 1e-4f ? glm::normalize(flat) : fallback;
  };
  const glm::vec3 front = across(towardsEye, across(glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)));
  const glm::vec3 side = across(right, glm::cross(front, up));
  const float elevation = glm::radians(settings.elevation);
  const float azimuth = glm::radians(settings.azimuth);
  SunSky out;
  out.sunDirection =
      glm::normalize(std::cos(elevation) * (std::cos(azimuth) * front + std::sin(azimuth) * side) +
                     std::sin(elevation) * up);
  const float sunZenith = kPi / 2 - elevation;
  const PreethamSky model(settings.turbidity, sunZenith);
  out.sunIrradiance = model.sunIlluminance() * kSkyUnit;

  const int height = std::max(2, width / 2);
  std::vector<glm::vec3> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  // A map about `up` with no turn: its columns are placed by EnvironmentMap::directionOf.
  const EnvironmentMap frame(1, 1, {glm::vec3(0.0f)}, up);
  glm::vec3 skyIrradiance(0.0f);  // on a horizontal surface, from the sky above
  for (int y = 0; y < height / 2; ++y) {
    const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    const float theta = kPi * v;
    const float solidAngle = (2 * kPi / static_cast<float>(width)) *
                             (kPi / static_cast<float>(height)) * std::sin(theta);
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d =
          frame.directionOf({(static_cast<float>(x) + 0.5f) / static_cast<float>(width), v});
      const float gamma = std::acos(std::clamp(glm::dot(d, out.sunDirection), -1.0f, 1.0f));
      const glm::vec3 radiance = rgbOfxyY(model.xyY(theta, gamma)) * kSkyUnit;
      pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(x)] = radiance;
      skyIrradiance += radiance * std::cos(theta) * solidAngle;
    }
  }
  // The ground below the horizon: Lambertian, lit by the sun and the sky.
  const glm::vec3 ground = groundAlbedo.value_or(glm::vec3(settings.groundAlbedo)) *
                           (out.sunIrradiance * std::sin(elevation) + skyIrradiance) / kPi;
  for (int y = height / 2; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(x)] = ground;
    }
  }
  out.sky = std::make_shared<EnvironmentMap>(width, height, std::move(pixels), up);
  return out;
}

void addViewSky(const TraceSettings& look, const Bounds& plant, const Camera& camera,
                TraceLights& lights) {
  if (!look.environment.empty()) {
    EnvironmentImage image =
        readEnvironmentImage(look.environmentFolder, look.environment, look.environmentAt);
    lights.environment = std::make_shared<EnvironmentMap>(
        image.width, image.height, std::move(image.pixels), lights.up, look.environmentRotation,
        look.environmentScale);
    lights.sky = glm::vec3(0.0f);
    lights.skySeen = look.skySeen;
    if (!look.lightDirection) lights.sphere = false;
    return;
  }
  if (!look.sun) return;
  // A ground plane's colour is the ground the sky's lower half shows, so that the two meet.
  const SunSky sunSky =
      makeSunSky(*look.sun, lights.up, -camera.forward, camera.right, 512,
                 look.ground ? linearColour(*look.ground) : glm::vec3(look.sun->groundAlbedo));
  lights.environment = sunSky.sky;
  lights.sky = glm::vec3(0.0f);
  lights.skySeen = look.skySeen;
  TraceSettings sun = look;
  sun.lightDirection = sunSky.sunDirection;
  sun.lightAngle = kSunAngleDegrees;
  sun.lightIrradiance = sunSky.sunIrradiance;
  const SphereLight sphere = sphereLight(sun, plant, sunSky.sunDirection);
  lights.sphere = sphere.present;
  lights.centre = sphere.centre;
  lights.radius = sphere.radius;
  lights.radiance = sphere.radiance;
}

void addGroundPlane(TraceScene& scene, const Bounds& plant, const glm::vec3& upIn,
                    const glm::vec3& albedo) {
  const glm::vec3 up = glm::normalize(upIn);
  const glm::vec3 centre = plant.empty() ? glm::vec3(0.0f) : plant.center();
  const float size = plant.empty() ? 1.0f : std::max(plant.diagonal(), 1e-6f);
  // The plant's lowest point along up: the lowest corner of its box.
  float lowest = glm::dot(centre, up);
  if (!plant.empty()) {
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 corner((k & 1) ? plant.max.x : plant.min.x,
                             (k & 2) ? plant.max.y : plant.min.y,
                             (k & 4) ? plant.max.z : plant.min.z);
      lowest = std::min(lowest, glm::dot(corner, up));
    }
  }
  const glm::vec3 base = centre + (lowest - glm::dot(centre, up)) * up;
  const Frame frame = Frame::around(up);
  const float half = 100 * size;
  TraceMaterial material;
  material.surface.reflectance = glm::clamp(albedo, 0.0f, 1.0f);
  const int id = scene.addMaterial(material);
  TriangleBuffers buffers = scene.addTriangles(4, 2, id, true, false);
  const glm::vec3 corners[4] = {
      base + half * (-frame.x - frame.y), base + half * (frame.x - frame.y),
      base + half * (frame.x + frame.y), base + half * (-frame.x + frame.y)};
  for (int k = 0; k < 4; ++k) {
    buffers.positions[k] = corners[k];
    buffers.normals[k] = up;
  }
  const std::uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
  for (int k = 0; k < 6; ++k) buffers.indices[k] = indices[k];
}

}  // namespace hirsute::trace
