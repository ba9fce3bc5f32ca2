// A feather type: the parameters of Streit & Heidrich 2002 (Table 1, Fig. 4) as read from a
// `.fea` file (docs/feathers.md, "The feather file"; the reader is hairs/feathers/feather_file.h).
// A FeatherType holds parameters only; the geometry is recomputed from it at a level of detail
// (hirsute/hairs/feathers/feather_geometry.h), never stored in it. The Scene carries the model's
// feather types so that every output can build its feathers from them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/core/diagnostic.h"

namespace hirsute {

enum class BarbSide { Left, Right, Both };
enum class BarbStyle { Lines, Strips };
enum class FeatherColourKind { Rgb, ColourIndex, Material };
enum class FeatherTextureMapping { Barb, Vane, Growth };

// One silhouette boundary point (Sec. 4.1, 4.2.2): the barb attached at `position` (the fraction
// of the rachis, 0 at its base, 1 at its tip) is `length` long. Barbs between points take the
// linear interpolation; two points at the same position make a discontinuity.
struct SilhouettePoint {
  float position = 0;
  float length = 0;
  bool operator==(const SilhouettePoint&) const = default;
};

// One vane (Fig. 4): its barb angles at the rachis base and tip and its barb length.
struct Vane {
  // Degrees, in the vane plane, between the barb's chord cv0→cvn and the rachis direction towards
  // the feather's base: 90° is perpendicular to the rachis, 180° along it towards the tip.
  float baseAngle = 120;  // vlba / vrba
  float tipAngle = 150;   // vlta / vrta
  // Used when `silhouette` is empty.
  float barbLength = 0.3f;
  // Sorted by position (non-decreasing), at most two points at one position.
  std::vector<SilhouettePoint> silhouette;
  bool operator==(const Vane&) const = default;
};

// A key barb (Sec. 4.1, 4.2.1). Control vertices are in the barb's own frame: x along the barb
// (away from the rachis), y in the vane plane towards the feather tip, z front-to-back (+z the
// feather's front). Only the shape matters: the barb is rotated so that cv0→cvn lies in the
// vane plane at its barb angle and scaled by its barb length. |cv0 cvn| is at most 1.
struct KeyBarb {
  BarbSide side = BarbSide::Both;
  float position = 0;               // rp in [0, 1] along the rachis
  std::vector<glm::vec3> vertices;  // cv0..cvn, at least 2
  // Degrees; when set, the barb angle at this key barb instead of the vane's (growth uses it).
  std::optional<float> angle;
  // How much of the default plumulaceous barb Bdf1 is mixed into this key barb, 0..1: blending
  // with a feather without key barbs (all Bdf1) sets it.
  float plumulaceous = 0;
  SourceLocation where;  // the `key barb:` line; empty for key barbs not read from a file
  bool operator==(const KeyBarb& other) const {
    return side == other.side && position == other.position && vertices == other.vertices &&
           angle == other.angle && plumulaceous == other.plumulaceous;
  }
};

// One texture of a blended type's cross-fade: the texture of a key type (empty: a key type
// without one, drawn as white) in its mapping, and its weight in the blend.
struct FeatherTextureLayer {
  std::string texture;
  FeatherTextureMapping mapping = FeatherTextureMapping::Barb;
  int sceneTexture = -1;
  float weight = 0;
  bool operator==(const FeatherTextureLayer&) const = default;
};

// How a feather is drawn (Sec. 4.3.1, 4.3.3); the geometry carries a copy for the renderer.
struct FeatherAppearance {
  BarbStyle drawing = BarbStyle::Lines;
  float stripWidth = 0;  // with Strips: the width of each of the two triangle strips of a barb
  FeatherColourKind colourKind = FeatherColourKind::Rgb;
  glm::vec3 colour{0.8f, 0.75f, 0.65f};  // with Rgb, each channel in [0, 1]
  int colourIndex = 0;                   // with ColourIndex (colour map) or Material
  std::string texture;                   // resolved against the .fea file's folder; empty: none
  FeatherTextureMapping textureMapping = FeatherTextureMapping::Barb;
  // The texture's index in Scene::textures once the feather stage has read it (-1: none).
  int sceneTexture = -1;
  // A type blended from key types of different textures cross-fades them: the barbs' colour is
  // `colour` times the weighted sum of the layers' texels, weights summing to 1 (Sec. 4.2.3
  // blends the shape; the texture follows it). Empty: `texture` alone.
  std::vector<FeatherTextureLayer> crossFade;
  bool operator==(const FeatherAppearance&) const = default;
};

struct FeatherType {
  std::string file;  // the .fea file, as given to loadFeatherType; empty for built types

  // The shaft (Sec. 4.1, 4.3.1). Lengths in the model's units.
  float calamusLength = 0.1f;      // cl
  float calamusWidthRatio = 1.0f;  // cwr: calamus width at its base / rachis base width rw
  float rachisLength = 1.0f;       // rl
  float rachisWidth = 0.02f;       // rw, at the rachis base; the tip is a point
  float rachisSideCurvature = 0;   // rlc, towards the left vane (+y)
  float rachisFrontCurvature = 0;  // rvdc, towards the front (+x)

  // The barbs (Sec. 4.1). Spacing is the distance along the rachis between neighbouring barbs.
  float barbSpacingBase = 0.02f;  // spb
  float barbSpacingTip = 0.02f;   // spt
  Vane left;                      // +y
  Vane right;                     // -y
  std::vector<KeyBarb> keyBarbs;  // in file order
  std::uint64_t seed = 1;         // of the random table behind Bdf1 (Sec. 4.3.1)
  // A blended type's tables: the key types' seeds with their weights (summing to 1), whose
  // tables are mixed entry by entry, so that Bdf1 changes with the blend as its shape does;
  // empty: the table of `seed` alone.
  std::vector<std::pair<std::uint64_t, float>> seedBlend;

  FeatherAppearance appearance;

  // The afterfeather (Sec. 3.1): a feather of its own type at the calamus, `afterfeatherSize`
  // times its own size.
  std::shared_ptr<const FeatherType> afterfeather;
  float afterfeatherSize = 0.5f;

  const Vane& vane(BarbSide side) const { return side == BarbSide::Right ? right : left; }
  Vane& vane(BarbSide side) { return side == BarbSide::Right ? right : left; }
};

}  // namespace hirsute
