// The view file's `fibre:` lines (docs/trace.md, "Hairs"): which scattering model the path tracer
// shades a kind of hair with, plant hairs by template, fur by its surfaces' colour, feathers'
// barbs, and that model's settings.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>

namespace hirsute {

enum class FibreOrgan : std::uint8_t { Hairs, Fur, Feathers };

enum class FibreModel : std::uint8_t {
  Chiang,         // a rough dielectric cylinder: R, TT, TRT and the residual (fibre_bsdf.h)
  KajiyaGoldman,  // Kajiya's diffuse and specular terms split by Goldman's weights (hair_bsdf.h)
};

struct FibreSettings {
  FibreOrgan organ = FibreOrgan::Hairs;
  // Plant hairs: the template's number (its `hair:` line, from 1); fur: its surfaces' colour
  // index; feathers: none. -1: every one of the organ.
  int index = -1;
  FibreModel model = FibreModel::Chiang;
  // Chiang: the colour σa is fitted to (none: the hair's own colour), or the melanin
  // concentrations (eumelanin, pheomelanin) that give σa.
  std::optional<glm::vec3> colour;
  std::optional<glm::vec2> melanin;
  float longitudinalRoughness = 0.3f;  // βm
  float azimuthalRoughness = 0.3f;     // βn
  float tiltDegrees = 2;               // α
  float eta = 1.55f;
};

}  // namespace hirsute
