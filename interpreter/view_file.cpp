// The view file (.v) as cpfg's ReadViewData reads it (cpfg-features.md (e), manual §8.1).
//
// Every line is `label: arguments`. The label runs from the first non-space character to the
// first ':' and must be spelled exactly (lower case, single spaces); an unknown label is a warning
// and the line is skipped. Arguments are read as cpfg's sscanf reads them: numbers from the front
// of a word, triples with commas (`viewpoint: 0,0,1`).
//
// Errors and warnings follow one rule. A setting whose value cannot be read is a warning and the
// setting keeps its value, as in cpfg, where sscanf fails and assigns nothing (the conformance
// model 01-Introduction-02-snowflake-exercise has `angle increment: ?`). A line that declares
// something — a light, a texture, a tropism, a contour, a surface, an organ's file — is an error
// when broken, because what it declares would otherwise be dropped or half-defined without the
// user noticing.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "hirsute/core/model_folder.h"
#include "hirsute/interpreter/contour.h"
#include "hirsute/interpreter/mesh_file.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/view_lines.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {
namespace {

using view_text::inQuotes;
using view_text::integerAtFront;
using view_text::isBlank;
using view_text::numberAtFront;
using view_text::wholeNumber;

// A word of a subcommand list (light, texture, tropism, shadow map): words are separated by
// blanks and commas (`tropism: T: 0,1,0`), and `V:5.0` is the key `V:` and the value `5.0`.
struct Token {
  std::string_view text;
  SourceLocation where;
};

std::vector<Token> subcommandTokens(const ViewFileLine& line) {
  std::vector<Token> tokens;
  const std::string_view text = line.rest;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (isBlank(text[i]) || text[i] == ',')) ++i;
    const std::size_t start = i;
    while (i < text.size() && !isBlank(text[i]) && text[i] != ',') ++i;
    if (i == start) continue;
    std::string_view word = text.substr(start, i - start);
    const std::size_t colon = word.find(':');
    if (colon != std::string_view::npos && colon + 1 < word.size() &&
        std::isalpha(static_cast<unsigned char>(word[0]))) {
      tokens.push_back(Token{word.substr(0, colon + 1), line.at(start)});
      tokens.push_back(Token{word.substr(colon + 1), line.at(start + colon + 1)});
    } else {
      tokens.push_back(Token{word, line.at(start)});
    }
  }
  return tokens;
}

// The one-letter key of a subcommand token (`V:`, `V`), or 0 when the token is no key.
char subcommandKey(std::string_view token) {
  if (token.empty() || !std::isalpha(static_cast<unsigned char>(token[0]))) return 0;
  if (token.size() == 1 || (token.size() == 2 && token[1] == ':')) return token[0];
  return 0;
}

// The numbers after a subcommand key; an error when there are fewer or they are no numbers.
std::vector<double> subcommandNumbers(const ViewLine& c, const std::vector<Token>& tokens,
                                      std::size_t& i, std::size_t count, const std::string& what) {
  const Token& key = tokens[i];
  std::vector<double> values;
  for (std::size_t k = 0; k < count; ++k) {
    if (i + 1 >= tokens.size()) {
      c.fail(key.where,
             "expected " + what + " after " + inQuotes(key.text) + " in " + inQuotes(c.label()));
    }
    const Token& token = tokens[++i];
    const std::optional<double> value = wholeNumber(token.text);
    if (!value) {
      c.fail(token.where, "expected " + what + " after " + inQuotes(key.text) + " in " +
                              inQuotes(c.label()) + ", found " + inQuotes(token.text));
    }
    values.push_back(*value);
  }
  return values;
}

glm::vec3 asVector(const std::vector<double>& v) {
  return glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

// The word after a subcommand key (texture file names and modes).
std::string_view subcommandWord(const ViewLine& c, const std::vector<Token>& tokens, std::size_t& i,
                                const std::string& what) {
  if (i + 1 >= tokens.size()) {
    c.fail(tokens[i].where, "expected " + what + " after " + inQuotes(tokens[i].text) + " in " +
                                inQuotes(c.label()));
  }
  return tokens[++i].text;
}

// ---------------------------------------------------------------------------------------------
// Commands with more than a value.

// `initial line width: w [unit]`. cpfg: the unit word also sets the line style — none: polygon
// (world units), a word starting with p: pixel, s: cylinder.
void initialLineWidth(ViewLine& c) {
  const std::optional<double> width = c.settingNumber();
  if (!width) return;
  LineStyle style = LineStyle::Polygon;
  const SourceLocation unitAt = c.args.here();
  if (const std::optional<std::string_view> unit = c.args.word()) {
    if (unit->front() == 'p') {
      style = LineStyle::Pixel;
    } else if (unit->front() == 's') {
      style = LineStyle::Cylinder;
    } else {
      c.warn(unitAt, "unknown line width unit " + inQuotes(*unit) +
                         " (pixels or shaded); the width is in world units (polygon lines)");
    }
  }
  c.view.initialLineWidth = static_cast<float>(*width);
  c.view.lineStyle = style;
  c.view.lineWidthInPixels = style == LineStyle::Pixel;
}

void lineStyle(ViewLine& c) {
  const std::string_view word = c.args.peekWord();
  static constexpr LineStyle kStyles[] = {LineStyle::Pixel, LineStyle::Polygon,
                                          LineStyle::Cylinder};
  std::optional<std::size_t> index;
  if (word == "pixel" || word == "1") index = 0;
  if (word == "polygon" || word == "2") index = 1;
  if (word == "cylinder" || word == "3") index = 2;
  if (!index) {
    // cpfg keeps the previous style (eight corpus lines say `wireframe`).
    c.ignoreLine(c.args.here(), "pixel, polygon or cylinder");
    return;
  }
  c.args.word();
  c.view.lineStyle = kStyles[*index];
  c.view.lineWidthInPixels = c.view.lineStyle == LineStyle::Pixel;
}

// `render mode:` a word, or its number 1–7 in the same order.
void renderMode(ViewLine& c) {
  static constexpr std::string_view kWords[] = {"wireframe", "filled", "flat",   "interpolated",
                                                "shaded",    "fast",   "shadows"};
  const std::string_view word = c.args.peekWord();
  for (std::size_t i = 0; i < std::size(kWords); ++i) {
    if (word == kWords[i] || word == std::to_string(i + 1)) {
      c.args.word();
      c.view.renderMode = static_cast<RenderMode>(i);
      return;
    }
  }
  c.ignoreLine(c.args.here(),
               "wireframe, filled, flat, interpolated, shaded, fast, shadows or 1 to 7");
}

// The legacy `shade mode:` (manual §8.1.10): 1 simple fill, 2 interpolated fill, 3 Gouraud
// shading, 4 B-spline, 5 closed B-spline, 6 two-sided, 7 wireframe. Modes 4–6 chose smooth
// surface variants on the old SGI machines; Hirsute shades them.
void shadeMode(ViewLine& c) {
  const SourceLocation where = c.args.here();
  const std::optional<int> mode = c.settingInteger();
  if (!mode) return;
  static constexpr RenderMode kModes[] = {
      RenderMode::Filled, RenderMode::Interpolated, RenderMode::Shaded,   RenderMode::Shaded,
      RenderMode::Shaded, RenderMode::Shaded,       RenderMode::Wireframe};
  if (*mode < 1 || *mode > 7) {
    c.warn(where,
           "'shade mode:' is 1 to 7, found " + std::to_string(*mode) + "; the line is ignored");
    return;
  }
  c.view.renderMode = kModes[*mode - 1];
}

// `box: x: a,b y: c,d z: e,f`.
void box(ViewLine& c) {
  Bounds bounds;
  for (std::string_view axis : {"x:", "y:", "z:"}) {
    const SourceLocation where = c.args.here();
    if (!c.args.literal(axis)) {
      c.ignoreLine(where, "'x: a,b y: c,d z: e,f'");
      return;
    }
    const SourceLocation valuesAt = c.args.here();
    const std::optional<double> low = c.args.number();
    const bool comma = low && c.args.literal(",");
    const std::optional<double> high = comma ? c.args.number() : std::nullopt;
    if (!high) {
      c.ignoreLine(valuesAt, "'min,max' after " + inQuotes(axis));
      return;
    }
    const int k = axis[0] - 'x';
    bounds.min[k] = static_cast<float>(std::min(*low, *high));
    bounds.max[k] = static_cast<float>(std::max(*low, *high));
  }
  c.view.box = bounds;
}

// `shadow map: size: n color: r g b offset: factor units`, every part optional. A shadow map is a
// square depth texture: no GL takes one wider than 16384 texels (llvmpipe's limit).
constexpr int kMaxShadowMapSize = 16384;

void shadowMap(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  ShadowMap map = c.view.shadowMap;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string_view key = tokens[i].text;
    const std::size_t count = key == "size:" ? 1 : key == "color:" ? 3 : key == "offset:" ? 2 : 0;
    if (count == 0 || i + count >= tokens.size()) {
      c.warn(tokens[i].where,
             "expected 'size: n', 'color: r g b' or 'offset: factor units' in "
             "'shadow map:', found " +
                 inQuotes(key) + "; the line is ignored");
      return;
    }
    std::vector<double> values;
    for (std::size_t k = 1; k <= count; ++k) {
      const std::optional<double> value = wholeNumber(tokens[i + k].text);
      if (!value) {
        c.warn(tokens[i + k].where, "expected a number after " + inQuotes(key) +
                                        " in 'shadow map:'; the line is ignored");
        return;
      }
      values.push_back(*value);
    }
    if (key == "size:") {
      // Checked as a double: a size past int's range (or NaN) cannot be cast.
      if (!(values[0] >= 1 && values[0] <= kMaxShadowMapSize)) {
        c.warn(tokens[i + 1].where, "the shadow map size must be from 1 to " +
                                        std::to_string(kMaxShadowMapSize) +
                                        "; the line is ignored");
        return;
      }
      map.size = static_cast<int>(values[0]);
    }
    if (key == "color:") map.color = asVector(values);
    if (key == "offset:") {
      map.offsetFactor = static_cast<float>(values[0]);
      map.offsetUnits = static_cast<float>(values[1]);
    }
    i += count;
  }
  c.view.shadowMap = map;
}

// `light: O: x y z  V: x y z  A: r g b  D: r g b  S: r g b  P: x y z e c  T: c l q`
// (manual §8.1.3). Each line adds a light. The colon after a key may be missing (tools-FernLeaf
// writes `D 0.6 0.6 0.6`) and numbers may be separated by commas (`V: 1.0, 0.5, 0.5`).
// The path tracer's lines (TraceSettings). Values out of range are errors at the value: a
// model's light or sky must not make the tracer compute with infinities.
float boundedValue(const ViewLine& c, const Token& token, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    c.fail(token.where, "the value " + std::string(token.text) + " in " + inQuotes(c.label()) +
                            " must be from " + fmt::format("{:g}", low) + " to " +
                            fmt::format("{:g}", high));
  }
  return value;
}

glm::vec3 boundedColour(const ViewLine& c, const std::vector<Token>& tokens, std::size_t& i,
                        double high) {
  const std::size_t first = i + 1;
  const std::vector<double> v = subcommandNumbers(c, tokens, i, 3, "r,g,b");
  for (std::size_t k = 0; k < 3; ++k) boundedValue(c, tokens[first + k], v[k], 0, high);
  return asVector(v);
}

// `trace sky:` and `trace up:`: three numbers separated by commas, into `out`; where each
// number starts. Unlike cpfg's settings, which keep their value with a warning, a tracer's line
// that cannot be read is an error at the value (docs/trace.md), as `trace light:` is.
std::array<SourceLocation, 3> traceTriple(ViewLine& c, const std::string& form, glm::vec3& out) {
  const auto expected = [&c, &form] {
    const std::string_view found = c.args.peekWord();
    return "expected " + form + " after " + inQuotes(c.label()) + ", found " +
           (found.empty() ? std::string("nothing") : inQuotes(found));
  };
  std::array<SourceLocation, 3> where;
  glm::vec3 read;
  for (std::size_t k = 0; k < 3; ++k) {
    const SourceLocation at = c.args.here();
    if (k > 0 && !c.args.literal(",")) c.fail(at, expected());
    where[k] = c.args.here();
    const std::optional<double> value = c.args.number();
    if (!value) c.fail(where[k], expected());
    read[static_cast<int>(k)] = static_cast<float>(*value);
  }
  out = read;
  return where;
}

void traceLight(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  TraceSettings& t = c.view.trace;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    if (key == 'D') {
      const std::size_t first = i + 1;
      const glm::vec3 d = asVector(subcommandNumbers(c, tokens, i, 3, "x,y,z"));
      for (int k = 0; k < 3; ++k) boundedValue(c, tokens[first + k], d[k], -1e6, 1e6);
      if (!(glm::length(d) > 0)) c.fail(tokens[first].where, "the light's direction is zero");
      t.lightDirection = d;
    } else if (key == 'A') {
      const std::size_t first = i + 1;
      t.lightAngle = static_cast<float>(boundedValue(
          c, tokens[first], subcommandNumbers(c, tokens, i, 1, "an angle in degrees")[0], 0.01, 179));
    } else if (key == 'I') {
      t.lightIrradiance = boundedColour(c, tokens, i, 1e4);
    } else {
      c.fail(tokens[i].where, "expected 'D: x,y,z', 'A: degrees' or 'I: r,g,b' in " +
                                  inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
}

void hairShading(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  TraceSettings& t = c.view.trace;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    const char* what = key == 'B' ? "the share scattered back" : key == 'R' ? "a roughness" : "a specular share";
    if (key != 'B' && key != 'R' && key != 'S') {
      c.fail(tokens[i].where, "expected 'B: backscatter', 'R: roughness' or 'S: specular' in " +
                                  inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
    const std::size_t first = i + 1;
    const double value = subcommandNumbers(c, tokens, i, 1, what)[0];
    if (key == 'B') t.hairBackscatter = static_cast<float>(boundedValue(c, tokens[first], value, 0, 1));
    if (key == 'R') t.hairRoughness = static_cast<float>(boundedValue(c, tokens[first], value, 0.01, 1.5));
    if (key == 'S') t.hairSpecular = static_cast<float>(boundedValue(c, tokens[first], value, 0, 1));
  }
}

// `fibre: hairs|fur|feathers [N] chiang|kajiya C: r,g,b M: eu,pheo L: βm A: βn T: tilt E: eta`
// (docs/trace.md, "Hairs").
void fibre(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  FibreSettings f;
  std::size_t i = 0;
  const std::string_view organ = tokens.empty() ? std::string_view() : tokens[0].text;
  if (organ != "hairs" && organ != "fur" && organ != "feathers") {
    c.fail(tokens.empty() ? c.labelAt() : tokens[0].where,
           "expected 'hairs', 'fur' or 'feathers' after " + inQuotes(c.label()));
  }
  f.organ = organ == "hairs" ? FibreOrgan::Hairs
            : organ == "fur" ? FibreOrgan::Fur
                             : FibreOrgan::Feathers;
  ++i;
  if (i < tokens.size() && f.organ != FibreOrgan::Feathers) {
    if (const auto n = integerAtFront(tokens[i].text); n && n->second == tokens[i].text.size()) {
      const long low = f.organ == FibreOrgan::Hairs ? 1 : 0;
      const long high = f.organ == FibreOrgan::Hairs ? 64 : 4095;
      if (n->first < low || n->first > high) {
        c.fail(tokens[i].where, f.organ == FibreOrgan::Hairs
                                    ? "expected a template hair's number from 1 to 64"
                                    : "expected a colour index from 0 to 4095");
      }
      f.index = static_cast<int>(n->first);
      ++i;
    }
  }
  if (i >= tokens.size() || (tokens[i].text != "chiang" && tokens[i].text != "kajiya")) {
    c.fail(i < tokens.size() ? tokens[i].where : tokens.back().where,
           "expected the model 'chiang' or 'kajiya' in " + inQuotes(c.label()));
  }
  f.model = tokens[i].text == "chiang" ? FibreModel::Chiang : FibreModel::KajiyaGoldman;
  for (++i; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    const std::size_t first = i + 1;
    if (f.model == FibreModel::KajiyaGoldman) {
      c.fail(tokens[i].where, "the 'kajiya' model takes its settings from 'hair shading:', found " +
                                  inQuotes(tokens[i].text));
    }
    switch (key) {
      case 'C':
        f.colour = boundedColour(c, tokens, i, 1);
        break;
      case 'M': {
        const std::vector<double> m = subcommandNumbers(c, tokens, i, 2, "eumelanin,pheomelanin");
        boundedValue(c, tokens[first], m[0], 0, 50);
        boundedValue(c, tokens[first + 1], m[1], 0, 50);
        f.melanin = glm::vec2(static_cast<float>(m[0]), static_cast<float>(m[1]));
        break;
      }
      case 'L':
        f.longitudinalRoughness = static_cast<float>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a roughness")[0], 0.01, 1));
        break;
      case 'A':
        f.azimuthalRoughness = static_cast<float>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a roughness")[0], 0.01, 1));
        break;
      case 'T':
        f.tiltDegrees = static_cast<float>(
            boundedValue(c, tokens[first],
                         subcommandNumbers(c, tokens, i, 1, "an angle in degrees")[0], -10, 10));
        break;
      case 'E':
        f.eta = static_cast<float>(
            boundedValue(c, tokens[first],
                         subcommandNumbers(c, tokens, i, 1, "an index of refraction")[0], 1.01, 3));
        break;
      default:
        c.fail(tokens[i].where, "expected 'C: r,g,b', 'M: eumelanin,pheomelanin', "
                                "'L: roughness', 'A: roughness', 'T: tilt' or 'E: index' in " +
                                    inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
  if (f.colour && f.melanin) {
    c.fail(c.labelAt(), "give the fibre's absorption by 'C:' or by 'M:', not both");
  }
  std::vector<FibreSettings>& all = c.view.trace.fibres;
  std::erase_if(all, [&](const FibreSettings& old) {
    return old.organ == f.organ && old.index == f.index;
  });
  constexpr std::size_t kMaxFibreLines = 256;
  if (all.size() >= kMaxFibreLines) {
    c.fail(c.labelAt(), "more than " + std::to_string(kMaxFibreLines) + " 'fibre:' lines");
  }
  all.push_back(f);
}

void translucency(ViewLine& c) {
  const SourceLocation colourAt = c.args.here();
  const std::optional<long> colour = c.args.integer();
  if (!colour || *colour < 0 || *colour > 4095) {
    c.fail(colourAt, "expected a colour index from 0 to 4095 after " + inQuotes(c.label()));
  }
  const SourceLocation shareAt = c.args.here();
  const std::optional<double> share = c.args.number();
  if (!share || !(*share >= 0 && *share <= 1)) {
    c.fail(shareAt, "expected the share of light passed through, from 0 to 1, after the colour "
                    "in " + inQuotes(c.label()));
  }
  c.view.trace.translucent.emplace_back(static_cast<int>(*colour), static_cast<float>(*share));
}

// `veins: COLOUR PATTERN C: r,g,b N: count W: width B: bump K: strength S: seed`.
void veins(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  VeinSettings v;
  const auto colour = tokens.empty() ? std::nullopt : integerAtFront(tokens[0].text);
  if (!colour || colour->first < 0 || colour->first > 4095 ||
      colour->second != tokens[0].text.size()) {
    c.fail(tokens.empty() ? c.labelAt() : tokens[0].where,
           "expected a colour index from 0 to 4095 after " + inQuotes(c.label()));
  }
  v.colour = static_cast<int>(colour->first);
  if (tokens.size() < 2 || (tokens[1].text != "splines" && tokens[1].text != "particles")) {
    c.fail(tokens.size() < 2 ? tokens[0].where : tokens[1].where,
           "expected the pattern 'splines' or 'particles' after the colour in " +
               inQuotes(c.label()));
  }
  v.pattern = tokens[1].text == "splines" ? VeinPattern::Splines : VeinPattern::Particles;
  for (std::size_t i = 2; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    const std::size_t first = i + 1;
    switch (key) {
      case 'C':
        v.veinColour = boundedColour(c, tokens, i, 1);
        break;
      case 'N':
        v.count = static_cast<int>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a count")[0], 1, 2000));
        break;
      case 'W':
        v.width = static_cast<float>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a width")[0], 0.001, 0.1));
        break;
      case 'B':
        v.bump = static_cast<float>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a height")[0], -4, 4));
        break;
      case 'K':
        v.strength = static_cast<float>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a strength")[0], 0, 1));
        break;
      case 'S':
        v.seed = static_cast<std::uint32_t>(boundedValue(
            c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a seed")[0], 0, 4294967295.0));
        break;
      default:
        c.fail(tokens[i].where, "expected 'C: r,g,b', 'N: count', 'W: width', 'B: height', "
                                "'K: strength' or 'S: seed' in " +
                                    inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
  std::vector<VeinSettings>& all = c.view.trace.veins;
  std::erase_if(all, [&](const VeinSettings& old) { return old.colour == v.colour; });
  // Each colour's veins are four maps the tracer makes before the first pixel.
  constexpr std::size_t kMaxVeinColours = 64;
  if (all.size() >= kMaxVeinColours) {
    c.fail(c.labelAt(), "more than " + std::to_string(kMaxVeinColours) + " colours with veins");
  }
  all.push_back(v);
}

// `subsurface: COLOUR M: mean free path H: thickness A: r,g,b`.
void subsurface(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  SubsurfaceSettings s;
  const auto colour = tokens.empty() ? std::nullopt : integerAtFront(tokens[0].text);
  if (!colour || colour->first < 0 || colour->first > 4095 ||
      colour->second != tokens[0].text.size()) {
    c.fail(tokens.empty() ? c.labelAt() : tokens[0].where,
           "expected a colour index from 0 to 4095 after " + inQuotes(c.label()));
  }
  s.colour = static_cast<int>(colour->first);
  for (std::size_t i = 1; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    const std::size_t first = i + 1;
    if (key == 'M') {
      s.meanFreePath = static_cast<float>(boundedValue(
          c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a mean free path")[0], 1e-9, 1e9));
    } else if (key == 'H') {
      s.thickness = static_cast<float>(boundedValue(
          c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a thickness")[0], 1e-9, 1e9));
    } else if (key == 'A') {
      s.albedo = boundedColour(c, tokens, i, 1);
    } else {
      c.fail(tokens[i].where, "expected 'M: mean free path', 'H: thickness' or 'A: r,g,b' in " +
                                  inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
  if (s.meanFreePath == 0 || s.thickness == 0) {
    c.fail(c.labelAt(), inQuotes(c.label()) + " needs a mean free path 'M:' and a thickness 'H:'");
  }
  // A walk across a sheet thousands of free paths thick would scatter without end: the ratio
  // is bounded so that kMaxWalkSteps ends few walks.
  if (s.thickness / s.meanFreePath > 100) {
    c.fail(c.labelAt(), "the thickness in " + inQuotes(c.label()) +
                            " is more than 100 mean free paths; such a sheet is opaque: drop the "
                            "line, or give it a 'translucency:' of 0");
  }
  std::vector<SubsurfaceSettings>& all = c.view.trace.subsurface;
  std::erase_if(all, [&](const SubsurfaceSettings& old) { return old.colour == s.colour; });
  all.push_back(s);
}

// `B: on|off` of the sky lines.
bool seenWord(const ViewLine& c, const std::vector<Token>& tokens, std::size_t& i) {
  const std::string_view word = subcommandWord(c, tokens, i, "on or off");
  if (word != "on" && word != "off") {
    c.fail(tokens[i].where,
           "expected on or off after 'B:' in " + inQuotes(c.label()) + ", found " + inQuotes(word));
  }
  return word == "on";
}

// `trace environment: FILE S: scale R: degrees B: on|off`.
void traceEnvironment(ViewLine& c) {
  const SourceLocation fileAt = c.args.here();
  const std::string_view file = c.requiredWord("an OpenEXR file name");
  TraceSettings& t = c.view.trace;
  c.resolve(file, fileAt);  // refuses a name that leaves the folder, here at the line
  t.environment = std::string(file);
  t.environmentFolder = c.folder().string();
  t.environmentAt = fileAt;
  t.sun.reset();  // one sky: the later line replaces the earlier
  const std::vector<Token> all = subcommandTokens(c.line());
  c.args.skipAll();
  for (std::size_t i = 1; i < all.size(); ++i) {
    const char key = subcommandKey(all[i].text);
    const std::size_t first = i + 1;
    if (key == 'S') {
      t.environmentScale = static_cast<float>(
          boundedValue(c, all[first], subcommandNumbers(c, all, i, 1, "a scale")[0], 0, 1e6));
    } else if (key == 'R') {
      t.environmentRotation = static_cast<float>(boundedValue(
          c, all[first], subcommandNumbers(c, all, i, 1, "an angle in degrees")[0], -360, 360));
    } else if (key == 'B') {
      t.skySeen = seenWord(c, all, i);
    } else {
      c.fail(all[i].where, "expected 'S: scale', 'R: degrees' or 'B: on|off' in " +
                               inQuotes(c.label()) + ", found " + inQuotes(all[i].text));
    }
  }
}

// `trace sun: E: elevation A: azimuth T: turbidity G: ground albedo B: on|off`.
void traceSun(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  c.args.skipAll();
  SunSkySettings s;
  TraceSettings& t = c.view.trace;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    const std::size_t first = i + 1;
    // Preetham et al.'s fit holds for turbidities from 2 to 10 and the sun above the horizon.
    if (key == 'E') {
      s.elevation = static_cast<float>(
          boundedValue(c, tokens[first],
                       subcommandNumbers(c, tokens, i, 1, "an elevation in degrees")[0], 1, 90));
    } else if (key == 'A') {
      s.azimuth = static_cast<float>(
          boundedValue(c, tokens[first],
                       subcommandNumbers(c, tokens, i, 1, "an azimuth in degrees")[0], -360, 360));
    } else if (key == 'T') {
      s.turbidity = static_cast<float>(boundedValue(
          c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a turbidity")[0], 2, 10));
    } else if (key == 'G') {
      s.groundAlbedo = static_cast<float>(boundedValue(
          c, tokens[first], subcommandNumbers(c, tokens, i, 1, "a ground albedo")[0], 0, 1));
    } else if (key == 'B') {
      t.skySeen = seenWord(c, tokens, i);
    } else {
      c.fail(tokens[i].where,
             "expected 'E: elevation', 'A: azimuth', 'T: turbidity', "
             "'G: ground albedo' or 'B: on|off' in " +
                 inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
  t.sun = s;
  t.environment.clear();  // one sky: the later line replaces the earlier
}

// A camera line of one number from `low` to `high`.
std::optional<float> traceNumber(ViewLine& c, double low, double high) {
  const SourceLocation at = c.args.here();
  const std::optional<double> value = c.args.number();
  if (!value || !(*value >= low && *value <= high)) {
    c.fail(at, "expected a number from " + fmt::format("{:g}", low) + " to " +
                   fmt::format("{:g}", high) + " after " + inQuotes(c.label()));
  }
  return static_cast<float>(*value);
}

// A camera line of one word among `words`.
std::string traceChoice(ViewLine& c, std::initializer_list<std::string_view> words) {
  const SourceLocation at = c.args.here();
  const std::optional<std::string_view> word = c.args.word();
  std::string list;
  for (const std::string_view w : words) {
    if (word && *word == w) return std::string(w);
    list += (list.empty() ? "" : ", ") + std::string(w);
  }
  c.fail(at, "expected one of " + list + " after " + inQuotes(c.label()) + ", found " +
                 (word ? inQuotes(*word) : std::string("nothing")));
  return {};
}

void light(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  LightSource light;
  light.ambient = glm::vec3(kLightLineAmbient);
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    switch (key) {
      case 'O':
      case 'V':
        light.directional = key == 'V';
        light.vector = asVector(subcommandNumbers(c, tokens, i, 3, "three coordinates"));
        break;
      case 'A':
        light.ambient = asVector(subcommandNumbers(c, tokens, i, 3, "r g b"));
        break;
      case 'D':
        light.diffuse = asVector(subcommandNumbers(c, tokens, i, 3, "r g b"));
        break;
      case 'S':
        light.specular = asVector(subcommandNumbers(c, tokens, i, 3, "r g b"));
        break;
      case 'P': {
        const std::vector<double> v = subcommandNumbers(c, tokens, i, 5, "'x y z exponent cutoff'");
        light.spot = true;
        light.spotDirection = asVector(v);
        light.spotExponent = static_cast<float>(v[3]);
        light.spotCutoff = static_cast<float>(v[4]);
        break;
      }
      case 'T': {
        const std::vector<double> v =
            subcommandNumbers(c, tokens, i, 3, "'constant linear quadratic'");
        light.constantAttenuation = static_cast<float>(v[0]);
        light.linearAttenuation = static_cast<float>(v[1]);
        light.quadraticAttenuation = static_cast<float>(v[2]);
        break;
      }
      default:
        c.fail(tokens[i].where, "expected a light subcommand O:, V:, A:, D:, S:, P: or T:, found " +
                                    inQuotes(tokens[i].text));
    }
  }
  c.view.lights.push_back(light);
  c.args.skipAll();
}

// `tropism:` / `torque:` with `T: x y z` (mandatory), `A: angle`, `I: intensity`,
// `E: elasticity`, `S: step` (manual §8.1.8). cpfg ignores A: for torques.
void tropismOrTorque(ViewLine& c, bool torque) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  Tropism tropism;
  tropism.torque = torque;
  bool hasDirection = false;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    switch (key) {
      case 'T':
        tropism.direction = asVector(subcommandNumbers(c, tokens, i, 3, "three coordinates"));
        hasDirection = true;
        break;
      case 'A': {
        const double angle = subcommandNumbers(c, tokens, i, 1, "an angle")[0];
        if (!torque) tropism.angle = static_cast<float>(angle);
        break;
      }
      case 'I':
        tropism.intensity = static_cast<float>(subcommandNumbers(c, tokens, i, 1, "a number")[0]);
        break;
      case 'E':
        tropism.elasticity = static_cast<float>(subcommandNumbers(c, tokens, i, 1, "a number")[0]);
        break;
      case 'S':
        tropism.elasticityStep =
            static_cast<float>(subcommandNumbers(c, tokens, i, 1, "a number")[0]);
        break;
      default:
        c.fail(tokens[i].where, "expected a subcommand T:, A:, I:, E: or S: in " +
                                    inQuotes(c.label()) + ", found " + inQuotes(tokens[i].text));
    }
  }
  if (!hasDirection) c.fail(c.labelAt(), inQuotes(c.label()) + " needs a direction 'T: x y z'");
  if (c.view.tropisms.size() >= kMaxTropisms) {
    c.fail(c.labelAt(),
           "at most " + std::to_string(kMaxTropisms) + " tropisms and torques may be declared");
  }
  c.view.tropisms.push_back(tropism);
  c.args.skipAll();
}

// `texture: F: file E: m|d|b S: R: ratio H: n|l L: n|l|m|mnn|mln|mnl|mll` (manual §8.1.7); ids
// are the order of the lines, from 1.
void texture(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  TextureDeclaration texture;
  bool hasFile = false;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const char key = subcommandKey(tokens[i].text);
    switch (key) {
      case 'F': {
        const std::string_view file = subcommandWord(c, tokens, i, "a file name");
        texture.where = tokens[i].where;
        texture.file = c.resolve(file, texture.where);
        hasFile = true;
        break;
      }
      case 'E': {
        const std::string_view mode = subcommandWord(c, tokens, i, "m, d or b");
        if (mode == "m" || mode == "modulate") {
          texture.mode = 'm';
        } else if (mode == "d" || mode == "decal") {
          texture.mode = 'd';
        } else if (mode == "b" || mode == "blend") {
          texture.mode = 'b';
        } else {
          c.fail(tokens[i].where,
                 "expected a texture mode m, d or b (modulate, decal, blend), "
                 "found " +
                     inQuotes(mode));
        }
        break;
      }
      case 'S':
        texture.perSurface = true;
        break;
      case 'R':
        texture.ratio = static_cast<float>(subcommandNumbers(c, tokens, i, 1, "a ratio")[0]);
        if (!(texture.ratio > 0)) c.fail(tokens[i].where, "the texture ratio must be positive");
        break;
      case 'H': {
        const std::string_view filter = subcommandWord(c, tokens, i, "n or l");
        if (filter == "n" || filter == "near") {
          texture.magnifyLinear = false;
        } else if (filter == "l" || filter == "linear") {
          texture.magnifyLinear = true;
        } else {
          c.fail(tokens[i].where,
                 "expected a magnification filter n or l, found " + inQuotes(filter));
        }
        break;
      }
      case 'L': {
        const std::string_view filter = subcommandWord(c, tokens, i, "a minification filter");
        if (filter == "n" || filter == "near") {
          texture.minify = "n";
        } else if (filter == "l" || filter == "linear") {
          texture.minify = "l";
        } else if (filter == "m" || filter == "mll") {
          texture.minify = "mll";
        } else if (filter == "mnn" || filter == "mln" || filter == "mnl") {
          texture.minify = std::string(filter);
        } else {
          c.fail(tokens[i].where,
                 "expected a minification filter n, l, m, mnn, mln, mnl or mll, found " +
                     inQuotes(filter));
        }
        break;
      }
      default:
        c.fail(tokens[i].where, "expected a texture subcommand F:, E:, S:, R:, H: or L:, found " +
                                    inQuotes(tokens[i].text));
    }
  }
  if (!hasFile) c.fail(c.labelAt(), "'texture:' needs an image file 'F: file'");
  c.view.textures.push_back(texture);
  c.args.skipAll();
}

// `contour: id file.con`.
void contour(ViewLine& c) {
  ContourDeclaration contour;
  contour.id = static_cast<int>(c.requiredInteger("a contour id", 1, 1000000));
  contour.where = c.args.here();
  contour.file = c.resolve(c.requiredWord("a contour file name"), contour.where);
  auto& contours = c.view.contours;
  const auto same = std::find_if(contours.begin(), contours.end(),
                                 [&](const ContourDeclaration& d) { return d.id == contour.id; });
  if (same != contours.end()) {
    c.warn(c.labelAt(), "contour " + std::to_string(contour.id) +
                            " is declared again; this declaration replaces the one at line " +
                            std::to_string(same->where.line));
    contours.erase(same);
  }
  contours.push_back(contour);
}

// `surface: X file.s size [s_prec t_prec] [texture]`. cpfg reads a texture id; the manual names
// a texture file there, which Hirsute also accepts (it becomes the next texture). A mesh file
// takes no precisions: `surface: X file.obj size [texture]`.
void surface(ViewLine& c) {
  SurfaceDeclaration surface;
  const SourceLocation idAt = c.args.here();
  const std::string_view id = c.requiredWord("a one-character surface id");
  if (id.size() != 1) {
    c.fail(idAt, "a surface id is one character (the X of ~X), found " + inQuotes(id));
  }
  surface.id = id[0];
  surface.where = c.args.here();
  surface.file = c.resolve(c.requiredWord("a surface file name"), surface.where);
  surface.size = static_cast<float>(c.requiredNumber("the surface's size"));
  // A mesh (mesh_file.h) has no precisions: `surface: X file.obj size [texture]`.
  const bool mesh = isMeshFile(surface.file);
  if (!mesh && !c.args.atEnd() && integerAtFront(c.args.peekWord())) {
    const SourceLocation precisionAt = c.args.here();
    surface.sPrecision = static_cast<int>(c.requiredInteger("the s precision", 0, 1000));
    if (c.args.atEnd()) {
      c.fail(precisionAt, "'surface:' takes both precisions 's t' or none");
    }
    surface.tPrecision = static_cast<int>(c.requiredInteger("the t precision", 0, 1000));
  }
  if (!c.args.atEnd()) {
    const std::string_view word = c.args.peekWord();
    if (integerAtFront(word) && integerAtFront(word)->second == word.size()) {
      surface.texture = static_cast<int>(c.requiredInteger("a texture id", 0, 1000000));
    } else {
      TextureDeclaration texture;
      texture.where = c.args.here();
      texture.file = c.resolve(*c.args.word(), texture.where);
      c.view.textures.push_back(texture);
      surface.texture = static_cast<int>(c.view.textures.size());
    }
  }
  auto& surfaces = c.view.surfaces;
  const auto same = std::find_if(surfaces.begin(), surfaces.end(),
                                 [&](const SurfaceDeclaration& d) { return d.id == surface.id; });
  if (same != surfaces.end()) {
    c.warn(idAt, "surface " + inQuotes(id) +
                     " is declared again; this declaration replaces the one at line " +
                     std::to_string(same->where.line));
    surfaces.erase(same);
  }
  surfaces.push_back(surface);
}

// `mesh flow: X x y z`: the direction, in the mesh file's coordinates, along which the coat of
// the mesh surface X lies (docs/meshes.md), projected on the surface at each follicle.
void meshFlow(ViewLine& c) {
  const SourceLocation idAt = c.args.here();
  const std::string_view id = c.requiredWord("a one-character surface id");
  auto& surfaces = c.view.surfaces;
  const auto surface = std::find_if(surfaces.begin(), surfaces.end(), [&](const SurfaceDeclaration& d) {
    return id.size() == 1 && d.id == id[0];
  });
  if (surface == surfaces.end()) {
    c.fail(idAt, "no surface " + inQuotes(id) + " is declared before this line");
  }
  if (!isMeshFile(surface->file)) {
    c.fail(idAt, "surface " + inQuotes(id) + " is no mesh: only a mesh's coat takes a flow");
  }
  const SourceLocation at = c.args.here();
  glm::dvec3 flow;
  flow.x = c.requiredNumber("the flow's x");
  flow.y = c.requiredNumber("the flow's y");
  flow.z = c.requiredNumber("the flow's z");
  if (!(glm::length(flow) > 0) || !std::isfinite(glm::length(flow))) {
    c.fail(at, "the flow is a direction: it cannot be 0 0 0");
  }
  surface->flow = flow;
}

void backgroundScene(ViewLine& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  if (tokens.empty()) c.fail(c.labelAt(), "expected a file name after 'background scene:'");
  for (const Token& token : tokens) c.view.backgroundScenes.push_back(c.resolve(token.text, token.where));
  c.args.skipAll();
}

// The readers of the lines that set one field of the view settings to the line's one value: a
// number, an integer, x,y,z or on/off (cpfg's sscanf forms, ViewLine), warning and leaving the
// field as it was when the value does not read.
template <auto Field>
void numberSetting(ViewLine& c) {
  if (const auto v = c.settingNumber()) c.view.*Field = static_cast<float>(*v);
}
template <auto Field>
void integerSetting(ViewLine& c) {
  if (const auto v = c.settingInteger()) c.view.*Field = *v;
}
template <auto Field>
void tripleSetting(ViewLine& c) {
  if (const auto v = c.settingTriple()) c.view.*Field = *v;
}
template <auto Field>
void flagSetting(ViewLine& c) {
  if (const auto on = c.settingFlag()) c.view.*Field = *on;
}

// A command Hirsute reads and has no use for: the rest of the line is skipped.
void ignoreArguments(ViewLine& c) {
  c.args.skipAll();
}

// A command whose effect Hirsute does not provide: a warning, so that the user knows.
void unsupported(ViewLine& c, const std::string& what) {
  c.warn(c.labelAt(), inQuotes(c.label()) + " is not supported: " + what);
  c.args.skipAll();
}

const std::unordered_map<std::string_view, ViewLineReader>& commandTable() {
  // Immutable after its first use: the registry of view-file commands, the view file's own and
  // then each organ's (organViewLines()).
  static const std::unordered_map<std::string_view, ViewLineReader> kCommands = [] {
    std::unordered_map<std::string_view, ViewLineReader> commands = {
        // Turtle (manual §8.1.1).
        {"angle factor:",
         [](ViewLine& c) {
           const SourceLocation where = c.args.here();
           if (const auto n = c.settingNumber()) {
             if (*n == 0) {
               c.warn(where, "'angle factor:' divides 360 and cannot be 0; the line is ignored");
             } else {
               c.view.angleIncrement = static_cast<float>(360.0 / *n);
             }
           }
         }},
        {"angle increment:", &numberSetting<&ViewSettings::angleIncrement>},
        {"initial color:",
         [](ViewLine& c) {
           const SourceLocation where = c.args.here();
           const std::optional<int> front = c.settingInteger();
           if (!front) return;
           std::optional<int> back;
           if (!c.args.atEnd()) {
             back = c.settingInteger();
             if (!back) return;
           }
           if (*front < 0 || back.value_or(0) < 0) {
             c.warn(where, "colour indices are 0 or more; the line is ignored");
             return;
           }
           c.view.initialColor = *front;
           if (back) c.view.initialBackColor = *back;
         }},
        {"color increment:",
         [](ViewLine& c) {
           const std::optional<int> front = c.settingInteger();
           if (!front) return;
           std::optional<int> back;
           if (!c.args.atEnd()) {
             back = c.settingInteger();
             if (!back) return;
           }
           c.view.colorIncrement = *front;
           c.view.backColorIncrement = back.value_or(*front);
         }},
        {"initial line width:", &initialLineWidth},
        {"line width increment:", &numberSetting<&ViewSettings::lineWidthIncrement>},
        {"initial scale:", &numberSetting<&ViewSettings::initialScale>},
        {"scale multiplier:", &numberSetting<&ViewSettings::scaleMultiplier>},
        {"interpretation past %:", &flagSetting<&ViewSettings::interpretationPastCut>},

        // View (§8.1.2).
        {"viewpoint:", &tripleSetting<&ViewSettings::viewpoint>},
        {"view reference point:", &tripleSetting<&ViewSettings::viewReference>},
        {"twist:",
         [](ViewLine& c) {
           // Tenths of a degree, read as an integer.
           if (const auto v = c.settingInteger()) c.view.twistDegrees = static_cast<float>(*v) / 10;
         }},
        {"projection:",
         [](ViewLine& c) {
           if (const auto w =
                   c.settingWord({"parallel", "perspective"}, "parallel or perspective")) {
             c.view.projection = *w == 0 ? Projection::Parallel : Projection::Perspective;
           }
         }},
        {"viewing angle:", &numberSetting<&ViewSettings::viewingAngle>},
        {"front distance:", &numberSetting<&ViewSettings::frontDistance>},
        {"back distance:", &numberSetting<&ViewSettings::backDistance>},
        {"scale factor:",
         [](ViewLine& c) {
           // cpfg: 0 means full size.
           if (const auto v = c.settingNumber())
             c.view.scaleFactor = *v == 0 ? 1.0f : static_cast<float>(*v);
         }},
        {"box:", &box},
        {"min zoom:", &numberSetting<&ViewSettings::minZoom>},
        {"max zoom:", &numberSetting<&ViewSettings::maxZoom>},
        {"generate on view change:",
         [](ViewLine& c) {
           if (c.args.peekWord() == "off") {
             c.args.word();
             return;
           }
           unsupported(c, "Hirsute does not derive the string again when the view changes");
         }},

        // Rendering (§8.1.4).
        {"z buffer:", &flagSetting<&ViewSettings::zBuffer>},
        {"render mode:", &renderMode},
        {"shade mode:", &shadeMode},
        {"shadow map:", &shadowMap},
        {"antialiasing:", &flagSetting<&ViewSettings::antialiasing>},
        {"concave polygons:", &flagSetting<&ViewSettings::concavePolygons>},
        {"background scene:", &backgroundScene},

        // Lights (§8.1.3).
        {"light direction:", &tripleSetting<&ViewSettings::lightDirection>},
        {"diffuse reflection:", &integerSetting<&ViewSettings::diffuseReflection>},
        {"surface ambient:", &numberSetting<&ViewSettings::surfaceAmbient>},
        {"surface diffuse:", &numberSetting<&ViewSettings::surfaceDiffuse>},
        {"light:", &light},
        // hirsute render --trace (docs/trace.md).
        {"trace light:", &traceLight},
        {"trace sky:",
         [](ViewLine& c) {
           const std::array<SourceLocation, 3> at = traceTriple(c, "r,g,b", c.view.trace.sky);
           for (int k = 0; k < 3; ++k) {
             if (!(c.view.trace.sky[k] >= 0 && c.view.trace.sky[k] <= 1e4f))
               c.fail(at[k], "the sky's radiance must be from 0 to 10000 a channel, found " +
                                 fmt::format("{:g}", c.view.trace.sky[k]));
           }
         }},
        {"trace up:",
         [](ViewLine& c) {
           const std::array<SourceLocation, 3> at = traceTriple(c, "x,y,z", c.view.trace.up);
           for (int k = 0; k < 3; ++k) {
             if (!(std::fabs(c.view.trace.up[k]) <= 1e6f))
               c.fail(at[k], "a coordinate of 'trace up:' must be from -1e+06 to 1e+06, found " +
                                 fmt::format("{:g}", c.view.trace.up[k]));
           }
           if (!(glm::length(c.view.trace.up) > 0)) c.fail(at[0], "the up direction is zero");
         }},
        {"translucency:", &translucency},
        {"hair shading:", &hairShading},
        {"fibre:", &fibre},
        {"veins:", &veins},
        {"subsurface:", &subsurface},
        {"trace environment:", &traceEnvironment},
        {"trace sun:", &traceSun},
        {"trace ground:",
         [](ViewLine& c) {
           glm::vec3 albedo;
           const std::array<SourceLocation, 3> at = traceTriple(c, "r,g,b", albedo);
           for (int k = 0; k < 3; ++k) {
             if (!(albedo[k] >= 0 && albedo[k] <= 1))
               c.fail(at[k], "the ground's albedo must be from 0 to 1 a channel, found " +
                                 fmt::format("{:g}", albedo[k]));
           }
           c.view.trace.ground = albedo;
         }},
        {"trace exposure:", [](ViewLine& c) { c.view.trace.exposure = traceNumber(c, -20, 20); }},
        {"trace tone:",
         [](ViewLine& c) {
           c.view.trace.tone = traceChoice(c, {"none", "filmic"});
         }},
        {"trace filter:",
         [](ViewLine& c) {
           c.view.trace.filter = traceChoice(c, {"box", "gaussian", "mitchell"});
         }},
        {"trace aperture:", [](ViewLine& c) { c.view.trace.aperture = traceNumber(c, 0, 1e9); }},
        {"trace focus:", [](ViewLine& c) { c.view.trace.focus = traceNumber(c, 1e-9, 1e12); }},

        // Lines, contours and surfaces (§8.1.5).
        {"line style:", &lineStyle},
        {"tapered lines:", &flagSetting<&ViewSettings::taperedLines>},
        {"contour sides:",
         [](ViewLine& c) {
           const SourceLocation where = c.args.here();
           const auto sides = c.settingInteger();
           if (!sides) return;
           if (*sides > kMaxContourSides) {
             c.warn(where, "at most " + std::to_string(kMaxContourSides) +
                               " contour sides; using " + std::to_string(kMaxContourSides));
           }
           // cpfg: fewer than 3 sides read as 3.
           c.view.contourSides = std::clamp(*sides, 3, kMaxContourSides);
         }},
        {"polygonization level:",
         [](ViewLine& c) {
           // Legacy: 2^(level+1) sides.
           const SourceLocation where = c.args.here();
           const auto level = c.settingInteger();
           if (!level) return;
           constexpr int kMaxLevel = 11;  // 2^12 = kMaxContourSides
           if (*level > kMaxLevel) {
             c.warn(where, "'polygonization level:' above " + std::to_string(kMaxLevel) +
                               " gives more than " + std::to_string(kMaxContourSides) +
                               " sides; using " + std::to_string(kMaxContourSides));
           }
           c.view.contourSides = std::max(3, 1 << (std::clamp(*level, 0, kMaxLevel) + 1));
         }},
        {"contour:", &contour},
        {"twist of cylinders:", &flagSetting<&ViewSettings::twistOfCylinders>},
        {"surface:", &surface},
        {"mesh flow:", &meshFlow},
        {"tsurface:", [](ViewLine& c) { unsupported(c, "triangle-list surfaces are not drawn"); }},
        // Obsolete: a surface used as a line segment, which cpfg's GL drawing ignores too.
        {"line:", &ignoreArguments},

        // User functions (§8.1.6): lsys reads these lines (readViewFunctions).
        {"function:", &ignoreArguments},
        {"function set:", &ignoreArguments},
        {"curve:", &ignoreArguments},

        // Textures (§8.1.7).
        {"texture:", &texture},

        // Tropisms (§8.1.8) and the deprecated single tropism for `_` (§8.1.10).
        {"tropism:", [](ViewLine& c) { tropismOrTorque(c, false); }},
        {"torque:", [](ViewLine& c) { tropismOrTorque(c, true); }},
        {"tropism direction:", &tripleSetting<&ViewSettings::tropismDirection>},
        {"initial elasticity:", &numberSetting<&ViewSettings::initialElasticity>},
        {"elasticity increment:", &numberSetting<&ViewSettings::elasticityIncrement>},

        // Read and without effect, in cpfg too or for Hirsute's outputs.
        {"cue range:", &ignoreArguments},
        {"font:", &ignoreArguments},
        {"winfont:", &ignoreArguments},
        {"interpretation step:", &ignoreArguments},
        {"rayshade objects:", &ignoreArguments},
        {"rayshade scale:", &ignoreArguments},
        {"PS linecap:", &ignoreArguments},
        {"environment display:",
         [](ViewLine& c) { unsupported(c, "environmental programs are not run"); }},
        {"blob:", [](ViewLine& c) { unsupported(c, "blob fields are not read"); }},
        {"background color:",
         [](ViewLine& c) {
           unsupported(c,
                       "cpfg ignores it too; the background is colour 0 of the colour map, or "
                       "the emission of material 0");
         }},
        {"ambient light:",
         [](ViewLine& c) {
           unsupported(c, "cpfg ignores it too; use 'surface ambient:' or the A: of 'light:'");
         }},
    };
    for (std::span<const ViewLineCommand> lines : organViewLines()) {
      for (const ViewLineCommand& line : lines) {
        if (!commands.emplace(line.label, line.read).second)
          throw std::logic_error("two view-file commands are labelled '" + std::string(line.label) +
                                 "'");
      }
    }
    return commands;
  }();
  return kCommands;
}

// A label as a user might have meant it: lower case, one space between words, none before ':'.
std::string normalizedLabel(std::string_view label) {
  std::string out;
  bool space = false;
  for (char ch : label) {
    if (isBlank(ch)) {
      space = !out.empty();
      continue;
    }
    if (space && ch != ':') out += ' ';
    space = false;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  }
  return out;
}

void warnUnknown(const ViewFileLine& line, Diagnostics& diagnostics) {
  SourceLocation where = line.where;
  where.column = line.restColumn - static_cast<int>(line.label.size());
  if (line.label.empty()) {
    diagnostics.warn(where,
                     "expected a command 'label: value', found " +
                         inQuotes(line.rest.substr(0, line.rest.find_last_not_of(" \t\r") + 1)) +
                         "; the line is ignored");
    return;
  }
  const std::string meant = normalizedLabel(line.label);
  for (const auto& [label, handler] : commandTable()) {
    std::string lower(label);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (lower == meant) {
      diagnostics.warn(where, "unknown command " + inQuotes(line.label) +
                                  "; cpfg needs the exact spelling " + inQuotes(label) +
                                  " (the line is ignored)");
      return;
    }
  }
  diagnostics.warn(where, "unknown command " + inQuotes(line.label) + "; the line is ignored");
}

}  // namespace

ViewSettings parseViewFile(const std::string& preprocessedText,
                           const std::filesystem::path& viewFile, Diagnostics& diagnostics) {
  ViewSettings view;
  const std::filesystem::path folder = viewFile.parent_path();
  for (const ViewFileLine& line : viewFileLines(preprocessedText, viewFile)) {
    const auto& commands = commandTable();
    const auto found = commands.find(line.label);
    if (found == commands.end()) {
      warnUnknown(line, diagnostics);
      continue;
    }
    ViewLine command(line, view, diagnostics, folder);
    found->second(command);
    command.finish();
  }
  return view;
}

}  // namespace hirsute
