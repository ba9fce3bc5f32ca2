// Feather-coat attributes carried by the turtle (docs/design.md, "Feathers": the @F modules), as it
// carries the hair attributes: `[ ]` save and restore them, generalized-cylinder segments record
// them at their two control points, and hairs/feathers/ places the coat feathers from them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "hirsute/interpreter/organ_attributes.h"

namespace hirsute {

// The sides of a coat: closed cylinders have only a front. The numbers are the `loc` parameter.
enum class FeatherSide : std::uint8_t { Front = 1, Back = 2 };
inline constexpr int kFeatherSides = 2;

struct FeatherSideAttributes {
  bool enabled = false;      // @Ff / @Fb
  OrganValue density{1.0f};  // @Fd: follicles per unit area
  OrganValue age{1.0f};      // @Fa: 0 to 1 (1 grown), Streit & Heidrich 2002, Sec. 4.2.4
  OrganValue size{1.0f};     // @Fs: scales every length of the feather's type
  OrganValue lie{20.0f};     // @Fl: degrees of the rachis above the surface
  OrganValue twist{0.0f};    // @Ft: degrees about the surface normal, from the axis direction

  bool operator==(const FeatherSideAttributes&) const = default;
};

// @Fk(k1[,k2[,fun]]): the key feather at this control point, type k1 (0: none set), or blended
// towards k2 around the girth by function fun of the girth position (without fun: linearly, k1
// at s = 0 to k2 at s = 1).
struct KeyFeather {
  int type = 0;
  int blendType = 0;
  int function = 0;

  bool operator==(const KeyFeather&) const = default;
};

struct FeatherAttributes {
  static constexpr char kOrgan = 'F';  // its modules are @F…
  // The @F modules' `loc` parameter picks sides by these names (organ_modules.h).
  using Side = FeatherSideAttributes;
  static constexpr int kSides = kFeatherSides;
  static constexpr std::array<std::string_view, kSides> kSideNames{"front", "back"};

  std::array<FeatherSideAttributes, kFeatherSides> sides;  // by FeatherSide - 1
  KeyFeather key;

  FeatherSideAttributes& side(FeatherSide s) { return sides[static_cast<int>(s) - 1]; }
  const FeatherSideAttributes& side(FeatherSide s) const { return sides[static_cast<int>(s) - 1]; }
  bool anyEnabled() const { return sides[0].enabled || sides[1].enabled; }

  bool operator==(const FeatherAttributes&) const = default;
};

// The feathers' lines of the view file (feather_view_lines.cpp), for organViewLines()
// (view_lines.h).
struct ViewLineCommand;
class OrganModuleTable;

// The feathers' module table (feather_modules.cpp, organ_modules.h): @Fe @Fi @Ff @Fb @Fd @Fk @Fa
// @Fs @Fl @Ft.
const OrganModuleTable& featherModuleTable();
std::span<const ViewLineCommand> featherViewLines();

}  // namespace hirsute
