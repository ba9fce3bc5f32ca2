// Feather types read from scans (feather_scan.h): shipped feather types drawn flat as a scanner
// sees a feather (opaque barbs to their tips, a dark shaft) at a scan's resolution, tilted,
// blurred and noisy, come back within the tolerances docs/feathers.md states; the .fea text
// reads back; what is no feather is an error.
#include "hirsute/hairs/feathers/feather_scan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <ostream>
#include <random>
#include <string>

#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/interpreter/texture_image.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kTypes = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "feather-types";

FeatherType typeOf(const std::string& name) {
  Diagnostics diagnostics;
  return loadFeatherType(kTypes / (name + ".fea"), diagnostics);
}

// A flatbed scan of `type` as the scanner sees a real feather: front up, its calamus at the
// bottom turned by `tilt` degrees (to the left for positive), `pixelsPerUnit`, on a plain light
// background; the shaft dark, every barb opaque to its tip, one pixel wide (antialiased), in the
// type's colour times its texture; then blurred (sigma 0.8 pixels) and given Gaussian noise of
// `noise` levels. Returns the image and its size.
Texture scanOf(const FeatherType& type, double tilt, double pixelsPerUnit, double noise) {
  const FeatherGeometry g = buildFeatherGeometry(type, FeatherDetail{64, 32, 8});
  Texture texture;
  if (!type.appearance.texture.empty()) texture = loadTexture(type.appearance.texture);
  // The feather's (y, z) to pixels: z up the picture, y (left) to the picture's left.
  const double c = std::cos(tilt * std::numbers::pi / 180),
               s = std::sin(tilt * std::numbers::pi / 180);
  // The picture: the turned feather's box and a margin of a tenth of its length.
  const double length = type.calamusLength + type.rachisLength;
  auto turned = [&](const glm::vec3& p) {
    const double x = -p.y, y = p.z;
    return glm::dvec2(c * x - s * y, -(s * x + c * y));  // picture units, y down
  };
  glm::dvec2 low(1e30), high(-1e30);
  for (const glm::vec3& p : g.vertices.positions) {
    low = glm::min(low, turned(p));
    high = glm::max(high, turned(p));
  }
  for (const glm::vec3& p : g.shaft.positions) {
    low = glm::min(low, turned(p));
    high = glm::max(high, turned(p));
  }
  low -= 0.1 * length;
  high += 0.1 * length;
  const int width = static_cast<int>((high.x - low.x) * pixelsPerUnit);
  const int height = static_cast<int>((high.y - low.y) * pixelsPerUnit);
  auto toPixel = [&](const glm::vec3& p) { return (turned(p) - low) * pixelsPerUnit; };
  std::vector<glm::vec3> picture(static_cast<std::size_t>(width) * height,
                                 glm::vec3(240, 238, 232));
  auto paint = [&](int x, int y, const glm::vec3& colour, double cover) {
    if (x < 0 || y < 0 || x >= width || y >= height || cover <= 0) return;
    glm::vec3& p = picture[static_cast<std::size_t>(y) * width + x];
    p += static_cast<float>(std::min(cover, 1.0)) * (colour - p);
  };
  // Barbs: segments one pixel wide, coverage by distance.
  const glm::vec3 colour = 255.0f * type.appearance.colour;
  for (const Barb& barb : g.barbs) {
    for (std::uint32_t k = 0; k + 1 < barb.vertexCount; ++k) {
      const std::size_t i = barb.firstVertex + k;
      const glm::dvec2 a = toPixel(g.vertices.positions[i]),
                       b = toPixel(g.vertices.positions[i + 1]);
      glm::vec3 tint = colour;
      if (texture.width > 0) tint *= texture.colourAt(g.vertices.vaneUv[i]);
      const glm::dvec2 lo = glm::min(a, b) - 2.0, hi = glm::max(a, b) + 2.0;
      for (int y = static_cast<int>(lo.y); y <= static_cast<int>(hi.y); ++y)
        for (int x = static_cast<int>(lo.x); x <= static_cast<int>(hi.x); ++x) {
          const glm::dvec2 p(x, y), d = b - a;
          const double t =
              std::clamp(glm::dot(p - a, d) / std::max(1e-12, glm::dot(d, d)), 0.0, 1.0);
          paint(x, y, tint, 1.0 - glm::length(p - (a + t * d)));
        }
    }
  }
  // The shaft over them: its triangles seen from the front, a darker shade of the colour.
  const glm::vec3 shaft = 0.45f * colour;
  for (std::size_t t = 0; t + 2 < g.shaft.indices.size(); t += 3) {
    const glm::dvec2 a = toPixel(g.shaft.positions[g.shaft.indices[t]]),
                     b = toPixel(g.shaft.positions[g.shaft.indices[t + 1]]),
                     q = toPixel(g.shaft.positions[g.shaft.indices[t + 2]]);
    const double area = (b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y);
    if (std::abs(area) < 1e-9) continue;
    const glm::dvec2 lo = glm::min(a, glm::min(b, q)), hi = glm::max(a, glm::max(b, q));
    for (int y = static_cast<int>(lo.y); y <= static_cast<int>(hi.y) + 1; ++y)
      for (int x = static_cast<int>(lo.x); x <= static_cast<int>(hi.x) + 1; ++x) {
        const double u = ((b.x - x) * (q.y - y) - (q.x - x) * (b.y - y)) / area;
        const double v = ((q.x - x) * (a.y - y) - (a.x - x) * (q.y - y)) / area;
        if (u >= 0 && v >= 0 && u + v <= 1) paint(x, y, shaft, 1.0);
      }
  }
  // Blur (sigma 0.8), then noise.
  const float kernel[5] = {0.0219f, 0.2285f, 0.4992f, 0.2285f, 0.0219f};
  std::vector<glm::vec3> across(picture.size());
  for (int pass = 0; pass < 2; ++pass) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        glm::vec3 sum(0.0f);
        for (int k = -2; k <= 2; ++k) {
          const int xx = pass == 0 ? std::clamp(x + k, 0, width - 1) : x;
          const int yy = pass == 1 ? std::clamp(y + k, 0, height - 1) : y;
          sum += kernel[k + 2] * picture[static_cast<std::size_t>(yy) * width + xx];
        }
        across[static_cast<std::size_t>(y) * width + x] = sum;
      }
    std::swap(picture, across);
  }
  std::mt19937 random(7);
  std::normal_distribution<float> gaussian(0.0f, static_cast<float>(noise));
  Texture scan;
  scan.width = width;
  scan.height = height;
  scan.rgba.resize(picture.size() * 4);
  for (std::size_t i = 0; i < picture.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      scan.rgba[4 * i + k] =
          static_cast<std::uint8_t>(std::clamp(picture[i][k] + gaussian(random), 0.0f, 255.0f));
    scan.rgba[4 * i + 3] = 255;
  }
  return scan;
}

// The silhouette's barb length at rp (linear between points).
double lengthAt(const Vane& vane, double rp) {
  const std::vector<SilhouettePoint>& s = vane.silhouette;
  if (s.empty()) return vane.barbLength;
  if (rp <= s.front().position) return s.front().length;
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (rp <= s[i].position) {
      const double t =
          (rp - s[i - 1].position) / std::max(1e-9f, s[i].position - s[i - 1].position);
      return s[i - 1].length + t * (s[i].length - s[i - 1].length);
    }
  }
  return s.back().length;
}

struct Case {
  const char* name;
  double tilt;
  friend void PrintTo(const Case& c, std::ostream* os) { *os << c.name << " turned " << c.tilt; }
};

class FeatherScanOfType : public ::testing::TestWithParam<Case> {};

// The stated tolerances (docs/feathers.md): calamus length within 3% of the feather's length,
// rachis length within 6%, rachis width within 15%, side curvature within 0.012, the tilt
// within 1°; each vane's barb angles within 20° at base and tip and their sum within 24°; the
// silhouette's barb lengths over the pennaceous vane (rp = 0.35 … 0.85) within 25% of the
// vane's longest barb, their RMS within 18%.
TEST_P(FeatherScanOfType, ComesBackWithinTheTolerances) {
  const Case c = GetParam();
  const FeatherType truth = typeOf(c.name);
  const double length = truth.calamusLength + truth.rachisLength;
  FeatherScanOptions options;
  options.unitsPerPixel = length / 1000;  // the feather 1 000 pixels long
  const FeatherScan scan = scanFeather(scanOf(truth, c.tilt, 1000 / length, 4), options);
  const FeatherType& found = scan.type;
  SCOPED_TRACE(featherFileText(scan, c.name));
  EXPECT_NEAR(found.calamusLength, truth.calamusLength, 0.03 * length);
  EXPECT_NEAR(found.rachisLength, truth.rachisLength, 0.06 * length);
  EXPECT_NEAR(found.rachisWidth, truth.rachisWidth, 0.15 * truth.rachisWidth);
  EXPECT_NEAR(found.rachisSideCurvature, truth.rachisSideCurvature, 0.012);
  EXPECT_EQ(found.rachisFrontCurvature, 0);     // a flat scan cannot show it
  EXPECT_NEAR(scan.tiltDegrees, -c.tilt, 1.0);  // a turn to the left leans the tip left
  EXPECT_TRUE(scan.barbsSeen);
  for (BarbSide side : {BarbSide::Left, BarbSide::Right}) {
    SCOPED_TRACE(side == BarbSide::Left ? "left" : "right");
    const Vane& t = truth.vane(side);
    const Vane& f = found.vane(side);
    EXPECT_NEAR(f.baseAngle, t.baseAngle, 20);
    EXPECT_NEAR(f.tipAngle, t.tipAngle, 20);
    EXPECT_NEAR(f.baseAngle + f.tipAngle, t.baseAngle + t.tipAngle, 24);
    double longest = 0, squares = 0;
    for (double rp = 0; rp <= 1; rp += 0.05) longest = std::max(longest, lengthAt(t, rp));
    int n = 0;
    for (double rp = 0.35; rp <= 0.8501; rp += 0.05, ++n) {
      const double error = lengthAt(f, rp) - lengthAt(t, rp);
      EXPECT_LT(std::abs(error), 0.25 * longest) << "rp " << rp;
      squares += error * error;
    }
    EXPECT_LT(std::sqrt(squares / n), 0.18 * longest);
  }
  EXPECT_EQ(found.keyBarbs.size(), 6u);
  for (const KeyBarb& k : found.keyBarbs) {
    EXPECT_FLOAT_EQ(glm::length(k.vertices.back() - k.vertices.front()), 1.0f);  // normalised
  }
  // The text reads back as the same type.
  Diagnostics diagnostics;
  const FeatherType again =
      parseFeatherType(featherFileText(scan, c.name), "scan.fea", diagnostics);
  EXPECT_NEAR(again.rachisLength, found.rachisLength, 1e-3 * found.rachisLength);
  EXPECT_EQ(again.keyBarbs.size(), found.keyBarbs.size());
  EXPECT_EQ(again.left.silhouette.size(), found.left.silhouette.size());
}

INSTANTIATE_TEST_SUITE_P(ShippedTypes, FeatherScanOfType,
                         ::testing::Values(Case{"hawk", 3}, Case{"budgie", -4}, Case{"contour", 2}),
                         [](const auto& info) { return std::string(info.param.name); });

// A flight feather's vanes differ: models/feather-types/flight.fea has a narrow leading vane
// (left: barbs 0.7 long at 150° to 166°, nearly along the rachis) and a broad trailing one (right:
// 2.5 long at 132° to 156°); mirrored, the narrow vane is the right one. Drawn flat at 300 dpi,
// turned and blurred, each vane comes back with its own barb angles within 8° at base and tip,
// their rise from base to tip within 8° (so the trend keeps its sign), the barb lengths over
// rp 0.1 … 0.85 within 20% of the vane's longest barb (15% in RMS), and the broad vane's key
// barbs bowed towards the tip as the type's are, by as much within 2% of the chord (the type's
// bow by about 4%).
FeatherType mirrored(FeatherType type) {
  std::swap(type.left, type.right);
  type.rachisSideCurvature = -type.rachisSideCurvature;
  for (KeyBarb& k : type.keyBarbs) {
    if (k.side == BarbSide::Left)
      k.side = BarbSide::Right;
    else if (k.side == BarbSide::Right)
      k.side = BarbSide::Left;
  }
  return type;
}

struct FlightCase {
  bool narrowRight;
  double tilt;
  friend void PrintTo(const FlightCase& c, std::ostream* os) {
    *os << (c.narrowRight ? "narrow right vane" : "narrow left vane") << " turned " << c.tilt;
  }
};

// How far a key barb bows towards the tip: its inner control points' mean distance from its
// chord, towards the tip, a fraction of the chord (its first two coordinates: in the vane).
double bowOf(const KeyBarb& k) {
  const glm::vec2 chord = glm::vec2(k.vertices.back() - k.vertices.front());
  const glm::vec2 towardsTip = glm::vec2(-chord.y, chord.x) / glm::dot(chord, chord);
  double sum = 0;
  for (std::size_t i = 1; i + 1 < k.vertices.size(); ++i)
    sum += glm::dot(glm::vec2(k.vertices[i] - k.vertices.front()), towardsTip);
  return k.vertices.size() > 2 ? sum / static_cast<double>(k.vertices.size() - 2) : 0.0;
}

// What a vane came back with against the type: the angles' errors at base and tip and of their
// rise, the barb lengths' largest and RMS error over rp 0.1 … 0.85 as fractions of the vane's
// longest barb, and the mean bow of the key barbs at rp 0.3 … 0.7 (a fraction of the chord,
// positive towards the tip).
struct VaneReading {
  double base = 0, tip = 0, rise = 0, worstLength = 0, rmsLength = 0, bow = 0;
  int bows = 0;
};

VaneReading readingOf(const FeatherType& truth, const FeatherType& found, BarbSide side) {
  const Vane& t = truth.vane(side);
  const Vane& f = found.vane(side);
  VaneReading out;
  out.base = f.baseAngle - t.baseAngle;
  out.tip = f.tipAngle - t.tipAngle;
  out.rise = (f.tipAngle - f.baseAngle) - (t.tipAngle - t.baseAngle);
  double longest = 0, squares = 0;
  for (double rp = 0; rp <= 1; rp += 0.05) longest = std::max(longest, lengthAt(t, rp));
  int n = 0;
  for (double rp = 0.1; rp <= 0.8501; rp += 0.05, ++n) {
    const double error = (lengthAt(f, rp) - lengthAt(t, rp)) / longest;
    out.worstLength = std::max(out.worstLength, std::abs(error));
    squares += error * error;
  }
  out.rmsLength = std::sqrt(squares / n);
  for (const KeyBarb& k : found.keyBarbs) {
    if (k.side != side || k.position < 0.3 || k.position > 0.7) continue;
    out.bow += bowOf(k);
    ++out.bows;
  }
  if (out.bows > 0) out.bow /= out.bows;
  return out;
}

std::ostream& operator<<(std::ostream& os, const VaneReading& r) {
  return os << "angle errors: base " << r.base << "°, tip " << r.tip << "°, rise " << r.rise
            << "°; length errors: worst " << r.worstLength << ", RMS " << r.rmsLength
            << " of the longest barb; key barbs' bow " << r.bow;
}

class FlightFeatherScan : public ::testing::TestWithParam<FlightCase> {};

TEST_P(FlightFeatherScan, EachVaneComesBackWithItsOwnAnglesAndLengths) {
  const FlightCase c = GetParam();
  const FeatherType flight = typeOf("flight");
  const FeatherType truth = c.narrowRight ? mirrored(flight) : flight;
  const double length = truth.calamusLength + truth.rachisLength;
  // A 300 dpi scan of this 16.5 cm feather, about 1 950 pixels long: the narrow vane's barbs,
  // 0.6 to 0.9 mm apart along the rachis at 14° to 30° from it, are 2 to 5 pixels apart across.
  const double pixelsPerUnit = 300 / 2.54;
  FeatherScanOptions options;
  options.unitsPerPixel = 1 / pixelsPerUnit;
  const Texture picture = scanOf(truth, c.tilt, pixelsPerUnit, 4);
  const FeatherScan scan = scanFeather(picture, options);
  const FeatherType& found = scan.type;
  SCOPED_TRACE(featherFileText(scan, "flight"));
  EXPECT_NEAR(found.rachisLength, truth.rachisLength, 0.06 * length);
  EXPECT_NEAR(scan.tiltDegrees, -c.tilt, 1.0);
  const BarbSide narrow = c.narrowRight ? BarbSide::Right : BarbSide::Left;
  for (BarbSide side : {BarbSide::Left, BarbSide::Right}) {
    const VaneReading r = readingOf(truth, found, side);
    SCOPED_TRACE(::testing::Message()
                 << (side == narrow ? "narrow " : "broad ")
                 << (side == BarbSide::Left ? "left" : "right") << " vane: " << r);
    EXPECT_LT(std::abs(r.base), 8);
    EXPECT_LT(std::abs(r.tip), 8);
    EXPECT_LT(std::abs(r.rise), 8);
    EXPECT_LT(r.worstLength, 0.2);
    EXPECT_LT(r.rmsLength, 0.15);
    // The type's middle key barb serves both vanes; on the narrow one its bow is two pixels:
    // there, never read more than that the wrong way.
    const auto middle = std::find_if(truth.keyBarbs.begin(), truth.keyBarbs.end(),
                                     [](const KeyBarb& k) { return k.position == 0.5f; });
    ASSERT_NE(middle, truth.keyBarbs.end());
    EXPECT_GT(r.bows, 0);
    if (side == narrow)
      EXPECT_GT(r.bow, -0.03);
    else
      EXPECT_NEAR(r.bow, bowOf(*middle), 0.02);
  }
}

INSTANTIATE_TEST_SUITE_P(NarrowAndBroadVanes, FlightFeatherScan,
                         ::testing::Values(FlightCase{false, 3}, FlightCase{false, -9},
                                           FlightCase{true, -2}, FlightCase{true, 11}),
                         [](const auto& info) {
                           return std::string(info.param.narrowRight ? "NarrowRight"
                                                                     : "NarrowLeft") +
                                  (info.param.tilt < 0 ? "TurnedRight" : "TurnedLeft") +
                                  std::to_string(static_cast<int>(std::abs(info.param.tilt)));
                         });

TEST(FeatherScan, AnImageWithoutAFeatherIsAnError) {
  Texture blank;
  blank.width = blank.height = 64;
  blank.rgba.assign(64 * 64 * 4, 255);
  EXPECT_THROW(scanFeather(blank, {}), std::invalid_argument);
  // A speck is no feather either.
  for (int y = 30; y < 34; ++y)
    for (int x = 30; x < 34; ++x) blank.rgba[4 * (y * 64 + x)] = 0;
  EXPECT_THROW(scanFeather(blank, {}), std::invalid_argument);
  Texture tiny;
  tiny.width = tiny.height = 4;
  tiny.rgba.assign(64, 0);
  EXPECT_THROW(scanFeather(tiny, {}), std::invalid_argument);
}

}  // namespace
}  // namespace hirsute
