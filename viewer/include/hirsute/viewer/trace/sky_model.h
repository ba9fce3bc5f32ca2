// A physical sun and sky for plants outdoors (`trace sun:`): the clear sky's radiance by the
// analytic model of Preetham, Shirley and Smits ("A practical analytic model for daylight",
// SIGGRAPH 1999), whose coefficients are a few dozen numbers of the paper. (Hosek and Wilkie's
// later fit is more accurate near the horizon and at high turbidity, but its published tables
// run to thousands of numbers; Preetham's is the one built here.)
//
// The sky: luminance Y and chromaticity x, y each follow Perez et al.'s formula
// F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ), θ the direction's angle from the
// zenith and γ its angle from the sun, relative to the zenith's: Y = Y_z F(θ, γ) / F(0, θs),
// the coefficients linear in the turbidity T (Preetham et al., Appendix A.2), Y_z and x_z, y_z
// from their zenith formulas. Below the horizon the ground reflects: the ground albedo times the
// horizontal irradiance of sun and sky, over π (a Lambertian ground).
//
// The sun: a disc 0.53° across whose light, 128 klx outside the atmosphere, is thinned along
// its path (Kasten's relative air mass) by Rayleigh scattering and by aerosols with Ångström's
// law at the turbidity's β (Preetham et al., Appendix A.1), at one wavelength for each of red,
// green and blue; ozone and water vapour, which take a few per cent in the visible, are left
// out.
//
// Units: the tracer's radiance 1 is 100/π kcd/m², the luminance of a white sheet under 100 klx,
// a bright midday: a white surface facing a high sun in a clear sky is about white. Darker
// skies (a low sun, a hazy day) want a higher exposure, as a camera does.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>

#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/trace/environment_map.h"
#include "hirsute/viewer/trace/path_tracer.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace hirsute::trace {

// The tracer's radiance of 1 kcd/m².
inline constexpr float kSkyUnit = 3.14159265f / 100.0f;
// The angle the sun subtends, in degrees.
inline constexpr float kSunAngleDegrees = 0.53f;

class PreethamSky {
 public:
  // `sunZenith`: the sun's angle from the zenith, in radians (below π/2).
  PreethamSky(float turbidity, float sunZenith);

  // The sky's luminance (kcd/m²) and chromaticity at angle `theta` from the zenith (at most
  // π/2) and `gamma` from the sun: (x, y, Y).
  glm::vec3 xyY(float theta, float gamma) const;
  float zenithLuminance() const { return zenith_.z; }
  // The sun's light on a surface facing it, in klx, as linear RGB.
  glm::vec3 sunIlluminance() const;

 private:
  float perez(const float c[5], float theta, float gamma) const;

  float turbidity_, sunZenith_;
  float coefficients_[3][5];  // x, y, Y
  glm::vec3 zenith_;          // x, y, Y at the zenith
};

// Linear sRGB of a colour given as chromaticity and luminance.
glm::vec3 rgbOfxyY(const glm::vec3& xyY);

// The sun and the sky of `settings` about `up`: the sun's direction, with azimuth 0 towards
// `towardsEye` and 90 towards `right` (both across `up`), its irradiance in the tracer's units
// and the sky (and the ground below the horizon, of `groundAlbedo` when given, else of the
// settings' grey albedo) as an environment map of `width` × width/2 texels.
struct SunSky {
  glm::vec3 sunDirection{0, 1, 0};
  glm::vec3 sunIrradiance{0.0f};
  std::shared_ptr<const EnvironmentMap> sky;
};
SunSky makeSunSky(const SunSkySettings& settings, const glm::vec3& up, const glm::vec3& towardsEye,
                  const glm::vec3& right, int width = 512,
                  std::optional<glm::vec3> groundAlbedo = std::nullopt);

// The view file's sky for a plant in `plant` seen with `camera`, into `lights`: with
// `trace environment:`, its map in place of the hemispherical sky (read beneath the view file's
// folder; throws DiagnosticError at the line for a file it cannot read), and the spherical
// light only where a `trace light:` line gives its direction, since a photographed sky holds its
// sun; with `trace sun:`, the physical sky and the sun as the spherical light. Without either,
// `lights` is left as it is.
void addViewSky(const TraceSettings& look, const Bounds& plant, const Camera& camera,
                TraceLights& lights);

// A ground plane under the plant, across `up` at its lowest point, of the reflectance `albedo`
// (linear), a hundred times the plant's size each way: opaque, Lambertian.
void addGroundPlane(TraceScene& scene, const Bounds& plant, const glm::vec3& up,
                    const glm::vec3& albedo);

}  // namespace hirsute::trace
