// How the traced picture's linear radiance becomes display light for the 8-bit picture: an
// exposure (a multiplier 2^EV) and a tone curve. `None` is a straight line clamped at 1 (a
// highlight brighter than white clips); `Filmic` rolls highlights off towards white as film
// does, after Narkowicz's fit of the ACES reference rendering transform (Krzysztof Narkowicz,
// "ACES Filmic Tone Mapping Curve", 2015). The OpenEXR output stays linear radiance.
#pragma once

#include <optional>
#include <string_view>

#include <glm/glm.hpp>

namespace hirsute::trace {

enum class ToneCurve { None, Filmic };

// The curve a name (`none`, `filmic`) gives, or nothing for another name.
std::optional<ToneCurve> toneCurveNamed(std::string_view name);

struct DisplayTransform {
  float exposure = 0;  // in stops: linear radiance is multiplied by 2^exposure
  ToneCurve tone = ToneCurve::None;
};

// One channel's display light in [0, 1] for its linear value, exposure already applied.
float toneMap(float linear, ToneCurve tone);

// A pixel's display light (linear, in [0, 1], before the sRGB encoding) for its radiance.
glm::vec3 displayLight(const glm::vec3& radiance, const DisplayTransform& transform);

// The radiance `transform` shows as `light` (each channel in [0, 1]): its inverse, for a colour
// that must look the same under any exposure and curve (the background).
glm::vec3 radianceShownAs(const glm::vec3& light, const DisplayTransform& transform);

}  // namespace hirsute::trace
