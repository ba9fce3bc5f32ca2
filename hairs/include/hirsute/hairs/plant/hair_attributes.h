// Hair attributes carried by the turtle (Fuhrer, Jensen & Prusinkiewicz 2004, Table 1;
// docs/design.md, "Plant hairs"). The turtle keeps them as it keeps colour and width;
// generalized-cylinder segments record the attributes at their two ends, and hairs/ places hairs
// from them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "hirsute/interpreter/organ_attributes.h"

namespace hirsute {

// Where a hair grows. Closed cylinders have only a front; open ones a front, a back and two edges.
// The numbers are the `loc` parameter of the @H modules.
enum class HairSide : std::uint8_t { Front = 1, Back = 2, Edge = 3 };
inline constexpr int kHairSides = 3;

// Template hairs a model may declare (`hair:` lines of the view file); @Hp takes at most this
// many probabilities.
inline constexpr int kMaxHairTemplates = 16;

// One attribute of Table 1: value ± a uniform offset up to `range` per hair, times function
// `function` of the model's function set evaluated at the girth position s in [0, 1]
// (0: none).
using HairValue = OrganValue;

// The attributes of one side.
struct HairSideAttributes {
  bool enabled = false;
  HairValue density{
      1.0f};               // hairs per unit area (per unit length along an edge: see docs/hairs.md)
  HairValue length{1.0f};  // scales the template's vertices
  HairValue radius{0.01f};  // constant along a hair
  HairValue incline{};      // degrees, about the incline axis n × h
  HairValue twist{};        // degrees, about the hair direction d
  HairValue wrap{};         // degrees, about the wrapping axis n × (n × h)
  // Placement probabilities of the templates, normalised when used; probabilityCount 0 means
  // every template equally likely.
  std::array<float, kMaxHairTemplates> probability{};
  int probabilityCount = 0;

  bool operator==(const HairSideAttributes&) const = default;
};

struct HairAttributes {
  static constexpr char kOrgan = 'H';  // its modules are @H…
  // The @H modules' `loc` parameter picks sides by these names (organ_modules.h).
  using Side = HairSideAttributes;
  static constexpr int kSides = kHairSides;
  static constexpr std::array<std::string_view, kSides> kSideNames{"front", "back", "edge"};

  std::array<HairSideAttributes, kHairSides> sides;  // by HairSide - 1

  HairSideAttributes& side(HairSide s) { return sides[static_cast<int>(s) - 1]; }
  const HairSideAttributes& side(HairSide s) const { return sides[static_cast<int>(s) - 1]; }
  bool anyEnabled() const { return sides[0].enabled || sides[1].enabled || sides[2].enabled; }

  bool operator==(const HairAttributes&) const = default;
};

// The plant hairs' lines of the view file (hair_view_lines.cpp), for organViewLines()
// (view_lines.h).
struct ViewLineCommand;
class OrganModuleTable;

// The plant hairs' module table (hair_modules.cpp, organ_modules.h): @Hf @Hb @He @Hd @Hl @Hr @Hi
// @Ht @Hw @Hp.
const OrganModuleTable& plantHairModuleTable();
std::span<const ViewLineCommand> plantHairViewLines();

}  // namespace hirsute
