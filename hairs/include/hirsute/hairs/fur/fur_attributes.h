// Fur attributes carried by the turtle (docs/design.md, "Fur": the @U modules; Silva, Bando, Chen &
// Nishita 2010). Like the hair and feather records, `[ ]` save and restore them and the surfaces
// the turtle draws record them; hairs/fur/ turns every covered surface into a fur surface.
#pragma once

#include <array>
#include <span>
#include <string_view>

namespace hirsute {

// Fur has one side: the front of the surface, where its normals point.
struct FurSideAttributes {
  bool enabled = false;  // @Uf

  bool operator==(const FurSideAttributes&) const = default;
};

struct FurAttributes {
  static constexpr char kOrgan = 'U';  // its modules are @U…
  // The organ tables' shape (organ_modules.h): fur has one side.
  using Side = FurSideAttributes;
  static constexpr int kSides = 1;
  static constexpr std::array<std::string_view, kSides> kSideNames{"surface"};

  std::array<FurSideAttributes, kSides> sides;
  float length = 0.2f;      // @Ul: L0, world units
  float density = 0.4f;     // @Ud: the fill of the fur texture, strands per texel (0, 1]
  float curlRadius = 0.0f;  // @Uc: K_alpha of Eq. 4, as a fraction of the length
  float curlFrequency = 0;  // @Uc: omega of Eq. 4, radians over the length
  float stiffness = 40;     // @Us: k of the strand's spring (per unit mass: k/m is what moves it)
  float mass = 1;           // @Us: m
  float specular = 0.3f;    // @Uh: K_s of Eq. 6
  float phong = 24;         // @Uh: p_phong
  float shadow = 2;         // @Uh: K_shadow >= 1 of gamma = (K_shadow - 1 + h) / K_shadow
  float clumpShape = 0.5f;  // @Uw: w of Eq. 5 (0: straight clumps, 1: bent in)
  int texture = 0;          // @Ut: the view file's texture (1-based), 0: the surface's colour

  // The index of @Ut's texture in Scene::textures (which holds the view file's `texture:` lines
  // in order, from 0), or -1 for the surface's colour.
  int sceneTexture() const { return texture - 1; }

  bool enabled() const { return sides[0].enabled; }

  bool operator==(const FurAttributes&) const = default;
};

// The fur's lines of the view file (fur_view_lines.cpp), for organViewLines() (view_lines.h).
struct ViewLineCommand;
class OrganModuleTable;

// The fur's module table (fur_modules.cpp, organ_modules.h): @Uf @Ul @Ud @Uc @Us @Uh @Uw @Ut.
const OrganModuleTable& furModuleTable();
std::span<const ViewLineCommand> furViewLines();

}  // namespace hirsute
