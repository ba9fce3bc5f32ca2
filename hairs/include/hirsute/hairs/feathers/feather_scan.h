// Feather types from flatbed scans (Streit & Heidrich 2002, Sec. 4.2.2: barb lengths, key barbs,
// barb spacing and angles read from the scan of a real feather; the front-to-back curvature
// added by hand). docs/feathers.md, "Feather types from scans".
//
// The scan is a feather lying flat on a plain background, front up. The feather is the largest
// connected region that differs from the background (the border's median colour) by more than
// Otsu's threshold; its principal axis and the narrower end (the bare calamus) give its base and
// tip. The rachis is tracked from the calamus along the line where the barbs' orientation (a
// structure tensor of the image) turns from one vane's to the other's, and fitted with the
// parabola that a .fea rachis bends by (rachis side curvature). Barbs are traced from the rachis
// along the orientation field to the vane's edge: each traced barb's chord gives the barb length
// at its place (the silhouettes) and its angle (the barb angles at base and tip, fitted
// linearly); its shape, in the barb's frame with the chord normalised to 1, a proposed key
// barb. The barb spacing is the period of the barbs along a line beside the rachis.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/hairs/feathers/feather_type.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

enum class ScanBase { Auto, Top, Bottom, Left, Right };

struct FeatherScanOptions {
  // The scan's scale: model units a pixel (default a 300 dpi scan in centimetres), unless
  // `length` gives the feather's length (calamus base to rachis tip) in model units.
  double unitsPerPixel = 2.54 / 300;
  std::optional<double> length;
  ScanBase base = ScanBase::Auto;  // where the calamus is; Auto: the narrower end
  bool back = false;               // the scan shows the feather's back: the vanes swap sides
  int keyBarbs = 3;                // proposed key barbs a vane, 1 to 8
};

// The largest scan read: 16 Mpixel (a 1 200 dpi scan of a feather 20 cm long and 4 cm wide); the
// scan's working images take about 60 bytes a pixel, 1 GB at the limit.
inline constexpr long long kMaxScanPixels = 16LL << 20;

struct FeatherScan {
  FeatherType type;  // lengths in model units; front curvature 0

  // What was found, for the file's comments and the summary.
  glm::vec3 background{1.0f};  // 0..1
  int threshold = 0;           // of the colour distance, 0..255
  std::size_t featherPixels = 0;
  double unitsPerPixel = 0;
  glm::dvec2 base{0.0}, rachisBase{0.0}, rachisTip{0.0};  // pixels, row 0 at the top
  glm::dvec2 left{-1, 0};  // the feather's left (+y) in the picture, a unit vector
  double tiltDegrees = 0;  // of the calamus-to-tip line from the image's vertical
  bool barbsSeen = false;    // the barbs' orientation was visible: angles and shapes measured
  bool spacingSeen = false;  // the barbs' period along the rachis was found
  double coherence = 0;      // the mean orientation coherence along the traced barbs, 0..1
  // The traced barbs, pixels, for pictures and tests: per vane, each from its attachment.
  std::vector<std::vector<glm::dvec2>> tracedLeft, tracedRight;
  std::vector<std::string> notes;  // what could not be measured and was guessed
};

// Reads the feather in `scan`. Throws std::invalid_argument with a message when there is no
// feather to read (an empty or uniform image, a feather too small or touching every border).
FeatherScan scanFeather(const Texture& scan, const FeatherScanOptions& options);

// The .fea text of a scan, commented line by line so that it can be edited: where each value
// came from and what a flat scan cannot show. `scanName` names the scan in the header; a
// non-empty `textureName` adds `texture: NAME vane`.
std::string featherFileText(const FeatherScan& scan, const std::string& scanName,
                            const std::string& textureName = {});

// The scan's vane as a texture for the type's vane mapping (Sec. 4.3.3): `size`² texels, the
// scan resampled over the straightened vane's box, so that the type drawn with
// `texture: FILE vane` shows the scanned colours where the scan had them.
Texture vaneTextureOf(const Texture& scan, const FeatherScan& found, int size);

}  // namespace hirsute
