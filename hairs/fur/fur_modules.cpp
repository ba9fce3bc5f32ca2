// The @U modules of shell fur (Silva et al. 2010; docs/design.md, "Fur"): the switch, the strand,
// curl, shading and clump parameters of the following surfaces, one row each, read by the turtle
// through organ_modules.h.
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/interpreter/cpfg_numbers.h"
#include "hirsute/interpreter/organ_modules.h"

namespace hirsute {
namespace {

using FurRow = OrganModuleRow<FurAttributes>;

// One fur parameter: its member, what it is called in warnings, and the range it must lie in.
struct FurParameter {
  float FurAttributes::*member;
  std::string_view name;
  float min, max;
};

constexpr float kHuge = 1e30f;

std::string shown(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(v));
  return text;
}

// What is wrong with `v` as parameter `p` ("length -1 must be at least 0"), or nothing.
std::optional<std::string> rangeProblem(const FurParameter& p, float v) {
  const std::string value = std::string(p.name) + " " + shown(v);
  if (!std::isfinite(v)) return value + " is not a finite number";
  if (v >= p.min && v <= p.max) return std::nullopt;
  if (p.max >= kHuge) return value + " must be at least " + shown(p.min);
  return value + " is outside [" + shown(p.min) + ", " + shown(p.max) + "]";
}

// A module's parameters, in order: every one must be given and in range, else the module is
// ignored with a warning and the record stays as it was.
template <const auto& kParameters>
bool readNumbers(FurAttributes& record, const OrganModuleCall& call, const std::string& name) {
  std::string form;
  for (const FurParameter& p : kParameters) form += (form.empty() ? "" : ", ") + std::string(p.name);
  if (call.count < kParameters.size()) {
    call.warnOnce(name + " count", name + " needs (" + form + "); module ignored");
    return false;
  }
  if (call.count > kParameters.size())
    call.warnOnce(name + " many", name + " takes (" + form + "); the rest are ignored");
  for (std::size_t i = 0; i < kParameters.size(); ++i) {
    const FurParameter& p = kParameters[i];
    if (const auto problem = rangeProblem(p, call.parameters[i])) {
      call.warnOnce(name + " range " + std::string(p.name),
                    name + ": " + *problem + "; module ignored");
      return false;
    }
  }
  for (std::size_t i = 0; i < kParameters.size(); ++i)
    record.*(kParameters[i].member) = call.parameters[i];
  return true;
}

// The same ranges for the parameters the .l file gives as constants (OrganModuleTable::
// checkConstants); a missing parameter is left to the turtle's warning.
template <const auto& kParameters>
std::optional<ParameterProblem> checkNumbers(std::span<const std::optional<float>> parameters,
                                             const std::string& name) {
  for (std::size_t i = 0; i < kParameters.size() && i < parameters.size(); ++i) {
    if (!parameters[i]) continue;
    if (const auto problem = rangeProblem(kParameters[i], *parameters[i]))
      return ParameterProblem{i, name + ": " + *problem};
  }
  return std::nullopt;
}

template <const auto& kParameters>
FurRow numbers(char letter) {
  FurRow row;
  row.letter = letter;
  row.form = ParameterForm::Custom;
  row.custom = &readNumbers<kParameters>;
  row.checkConstants = &checkNumbers<kParameters>;
  return row;
}

constexpr std::array<FurParameter, 1> kLength{{{&FurAttributes::length, "length", 0, kHuge}}};
constexpr std::array<FurParameter, 1> kDensity{{{&FurAttributes::density, "density", 0, 1}}};
constexpr std::array<FurParameter, 2> kCurl{{{&FurAttributes::curlRadius, "Ka", 0, kHuge},
                                             {&FurAttributes::curlFrequency, "w", -kHuge, kHuge}}};
constexpr std::array<FurParameter, 2> kStrand{{{&FurAttributes::stiffness, "k", 0, kHuge},
                                               {&FurAttributes::mass, "m", 1e-6f, kHuge}}};
constexpr std::array<FurParameter, 3> kShading{{{&FurAttributes::specular, "Ks", 0, kHuge},
                                                {&FurAttributes::phong, "p", 0, 1e4f},
                                                {&FurAttributes::shadow, "Kshadow", 1, kHuge}}};
constexpr std::array<FurParameter, 1> kClump{{{&FurAttributes::clumpShape, "w", 0, 1}}};

// What is wrong with `v` as @Ut's texture number, or nothing. Whether the view file declares
// that texture is known only when the turtle reads the module; a negative number or one that is
// no number never names one.
std::optional<std::string> textureProblem(float v) {
  if (!std::isfinite(v) || std::fabs(v) >= 2e9f)
    return "texture " + shown(v) + " is not a texture's number";
  if (truncated(v) < 0)
    return "texture " + shown(v) + " must be at least 0 (0: the surface's colour)";
  return std::nullopt;
}

// @Ut(i): the view file's i-th `texture:` (0: the surface's colour).
FurRow colourTexture(char letter) {
  FurRow row;
  row.letter = letter;
  row.form = ParameterForm::Custom;
  row.custom = [](FurAttributes& record, const OrganModuleCall& call, const std::string& name) {
    if (call.count == 0) {
      call.warnOnce(name + " count", name + " needs (i), a texture of the view file or 0");
      return false;
    }
    if (const auto problem = textureProblem(call.parameters[0])) {
      call.warnOnce(name + " range", name + ": " + *problem + "; module ignored");
      return false;
    }
    const int index = truncated(call.parameters[0]);
    const std::size_t declared = call.resources.view.textures.size();
    if (index < 0 || static_cast<std::size_t>(index) > declared) {
      call.warnOnce(name + " texture " + std::to_string(index),
                    name + ": no texture " + std::to_string(index) + " (the view file declares " +
                        std::to_string(declared) + "); module ignored");
      return false;
    }
    record.texture = index;
    return true;
  };
  // A constant out of range is an error at it, as for the other @U modules.
  row.checkConstants = [](std::span<const std::optional<float>> parameters,
                          const std::string& name) -> std::optional<ParameterProblem> {
    if (parameters.empty() || !parameters[0]) return std::nullopt;
    if (const auto problem = textureProblem(*parameters[0]))
      return ParameterProblem{0, name + ": " + *problem};
    return std::nullopt;
  };
  return row;
}

}  // namespace

const OrganModuleTable& furModuleTable() {
  static const AttributeModuleTable<FurAttributes> table(
      "fur",
      [](Scene& scene) -> std::vector<FurAttributes>& { return scene.organ<FurPart>().attributes; },
      {
          switchRow<FurAttributes>('f', 1, &FurSideAttributes::enabled),
          numbers<kLength>('l'),
          numbers<kDensity>('d'),
          numbers<kCurl>('c'),
          numbers<kStrand>('s'),
          numbers<kShading>('h'),
          numbers<kClump>('w'),
          colourTexture('t'),
      });
  return table;
}

}  // namespace hirsute
