// The feather file (.fea): one parameter per line, `keyword: values`, `#` to the end of a line a
// comment (docs/feathers.md, "The feather file"). Every broken line is an error at its
// file:line:col: a feather type that silently lost a parameter would look plausible and wrong.
#include "hirsute/hairs/feathers/feather_file.h"

#include "hirsute/core/model_folder.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <sstream>
#include <system_error>

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// Enough for any real feather (a flight feather has a few hundred barbs a side) and small
// enough that a typo in the spacing cannot ask for a billion barbs.
constexpr double kMaxBarbsPerVane = 100000;
// The papers' key barbs have four; every barb between two keys is raised to the larger degree.
constexpr std::size_t kMaxKeyBarbVertices = 64;

std::string inQuotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

struct Token {
  std::string_view text;
  int column = 0;  // 1-based
};

// The values of a line: words separated by blanks and commas; '(' and ')' are words of their own
// so that `(0 0)(1 0)` reads as six tokens.
std::vector<Token> tokensOf(std::string_view rest, int firstColumn) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < rest.size()) {
    if (isBlank(rest[i]) || rest[i] == ',') {
      ++i;
      continue;
    }
    const std::size_t start = i;
    if (rest[i] == '(' || rest[i] == ')') {
      ++i;
    } else {
      while (i < rest.size() && !isBlank(rest[i]) && rest[i] != ',' && rest[i] != '(' &&
             rest[i] != ')') {
        ++i;
      }
    }
    tokens.push_back(Token{rest.substr(start, i - start), firstColumn + static_cast<int>(start)});
  }
  return tokens;
}

std::optional<double> numberOf(std::string_view word) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);
  double value = 0;
  const auto [stop, error] =
      std::from_chars(word.data(), word.data() + word.size(), value, std::chars_format::general);
  if (error != std::errc() || stop != word.data() + word.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::string numberText(double value) {
  return fmt::format("{:g}", value);
}

// The files being loaded, outermost first: an afterfeather that names one of them is a cycle.
using LoadStack = std::vector<fs::path>;

FeatherType loadWithStack(const fs::path& file, LoadStack& stack, Diagnostics& diagnostics);

// One line being read: its keyword, its values and how it reports.
class Line {
 public:
  Line(std::shared_ptr<const std::string> file, int number, std::string_view keyword,
       int keywordColumn, std::vector<Token> tokens, int endColumn)
      : keyword(keyword),
        file_(std::move(file)),
        number_(number),
        keywordColumn_(keywordColumn),
        tokens_(std::move(tokens)),
        endColumn_(endColumn) {}

  std::string_view keyword;  // with its ':'

  SourceLocation at(int column) const { return SourceLocation{file_, number_, column}; }
  SourceLocation keywordAt() const { return at(keywordColumn_); }
  // Where the next value starts, or just after the line's last character when none is left.
  SourceLocation here() const {
    return at(next_ < tokens_.size() ? tokens_[next_].column : endColumn_);
  }
  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw DiagnosticError(where, message);
  }

  bool atEnd() const { return next_ >= tokens_.size(); }
  std::string_view peek() const { return atEnd() ? std::string_view() : tokens_[next_].text; }
  std::string found() const { return atEnd() ? "nothing" : inQuotes(peek()); }

  std::string_view word(const std::string& what) {
    if (atEnd())
      fail(here(), "expected " + what + " after " + inQuotes(keyword) + ", found nothing");
    return tokens_[next_++].text;
  }
  bool literal(std::string_view expected) {
    if (peek() != expected) return false;
    ++next_;
    return true;
  }
  void expectLiteral(std::string_view expected, const std::string& context) {
    if (!literal(expected)) {
      fail(here(), "expected " + inQuotes(expected) + " " + context + ", found " + found());
    }
  }
  bool nextIsNumber() const { return !atEnd() && numberOf(peek()).has_value(); }

  // A number in [min, max]: an error when missing, not a number, or out of range.
  float number(const std::string& what, double min, double max) {
    const SourceLocation where = here();
    if (atEnd() || peek() == "(" || peek() == ")") {
      fail(where, "expected " + what + " after " + inQuotes(keyword) + ", found " + found());
    }
    const std::optional<double> value = numberOf(peek());
    if (!value) fail(where, "expected " + what + " (a number), found " + found());
    ++next_;
    if (*value < min || *value > max) fail(where, rangeMessage(what, *value, min, max));
    return static_cast<float>(*value);
  }
  long long integer(const std::string& what, long long min, long long max) {
    const SourceLocation where = here();
    if (atEnd()) {
      fail(where, "expected " + what + " after " + inQuotes(keyword) + ", found nothing");
    }
    const std::string_view text = peek();
    long long value = 0;
    const auto [stop, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || stop != text.data() + text.size()) {
      fail(where, "expected " + what + " (a whole number), found " + found());
    }
    ++next_;
    if (value < min || value > max) fail(where, rangeMessage(what, double(value), min, max));
    return value;
  }
  BarbSide side() {
    const SourceLocation where = here();
    const std::string_view text = word("a side (left, right or both)");
    if (text == "left") return BarbSide::Left;
    if (text == "right") return BarbSide::Right;
    if (text == "both") return BarbSide::Both;
    fail(where, "expected a side (left, right or both), found " + inQuotes(text));
  }
  // `( a b [c] )`: between `min` and `max` numbers; their location is the '('.
  std::vector<float> group(const std::string& what, std::size_t min, std::size_t max, double low,
                           double high) {
    const SourceLocation open = here();
    expectLiteral("(", "to open " + what);
    std::vector<float> values;
    while (!literal(")")) {
      if (atEnd()) fail(here(), "expected ')' to close " + what + ", found nothing");
      if (values.size() == max) {
        fail(here(),
             what + " has at most " + std::to_string(max) + " numbers, found another: " + found());
      }
      values.push_back(number("a coordinate of " + what, low, high));
    }
    if (values.size() < min) {
      fail(open, what + " needs " + std::to_string(min) + (min == max ? "" : " or more") +
                     " numbers, found " + std::to_string(values.size()));
    }
    return values;
  }
  // Nothing may follow the values: a surplus number is a wrong count, not something to ignore.
  void finish() const {
    if (!atEnd()) {
      fail(here(), "unexpected " + found() + " after the values of " + inQuotes(keyword));
    }
  }
  // A file the line names, beside the .fea. It must stay beneath the .fea's folder
  // (model_folder.h): an absolute name, a `..`, a link out, a FIFO or a device is an error at it.
  fs::path resolve(std::string_view name, const SourceLocation& where) const {
    const ModelFolder folder(fs::path(*file_).parent_path());
    const std::string refused = folder.refusal(std::string(name));
    if (!refused.empty()) fail(where, "cannot open " + inQuotes(name) + ": " + refused);
    return folder.pathOf(std::string(name));
  }

 private:
  static std::string rangeMessage(const std::string& what, double value, double min, double max) {
    std::string range;
    if (max == HUGE_VAL || max >= 9e18) {
      range = (min == 0 ? "0 or more" : "at least " + numberText(min));
    } else {
      range = "from " + numberText(min) + " to " + numberText(max);
    }
    return what + " must be " + range + ", found " + numberText(value);
  }

  std::shared_ptr<const std::string> file_;
  int number_;
  int keywordColumn_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  int endColumn_;
};

constexpr double kInfinity = HUGE_VAL;

// What a line reads into; the state that spans lines (colour or material, where spacing was
// given) lives here too.
struct Reader {
  FeatherType& type;
  LoadStack& stack;
  Diagnostics& diagnostics;
  std::optional<SourceLocation> colourAt;  // a colour or material line
  std::optional<SourceLocation> spacingAt;
};

using Handler = std::function<void(Line&, Reader&)>;

float length(Line& line, const std::string& what) {
  return line.number(what, 0, kInfinity);
}

void readSilhouette(Line& line, Reader& reader, BarbSide side) {
  std::vector<SilhouettePoint> points;
  while (!line.atEnd()) {
    const SourceLocation where = line.here();
    const std::vector<float> values =
        line.group("a silhouette point (position length)", 2, 2, -kInfinity, kInfinity);
    const SilhouettePoint point{values[0], values[1]};
    if (point.position < 0 || point.position > 1) {
      line.fail(where, "the position of a silhouette point must be from 0 to 1, found " +
                           numberText(point.position));
    }
    if (point.length < 0) {
      line.fail(where, "the length of a silhouette point must be 0 or more, found " +
                           numberText(point.length));
    }
    if (!points.empty() && point.position < points.back().position) {
      line.fail(where, "silhouette points go from the rachis base to its tip: position " +
                           numberText(point.position) + " comes after " +
                           numberText(points.back().position));
    }
    if (points.size() >= 2 && point.position == points.back().position &&
        points[points.size() - 2].position == point.position) {
      line.fail(where,
                "at most two silhouette points share a position (a discontinuity), "
                "found a third at " +
                    numberText(point.position));
    }
    points.push_back(point);
  }
  if (points.empty()) {
    line.fail(line.here(), "expected silhouette points '(position length)' after " +
                               inQuotes(line.keyword) + ", found nothing");
  }
  if (side != BarbSide::Right) reader.type.left.silhouette = points;
  if (side != BarbSide::Left) reader.type.right.silhouette = points;
}

void readKeyBarb(Line& line, Reader& reader) {
  KeyBarb barb;
  barb.where = line.keywordAt();
  barb.side = line.side();
  barb.position = line.number("the key barb's position along the rachis", 0, 1);
  if (line.literal("angle")) barb.angle = line.number("the key barb's angle in degrees", 0, 180);
  const SourceLocation firstVertex = line.here();
  SourceLocation lastVertex = firstVertex;
  while (!line.atEnd()) {
    lastVertex = line.here();
    if (barb.vertices.size() == kMaxKeyBarbVertices) {
      line.fail(lastVertex, fmt::format("a key barb has at most {} control vertices (the barbs' "
                                        "Bézier curves cost the cube of their number)",
                                        kMaxKeyBarbVertices));
    }
    const std::vector<float> values = line.group("a control vertex", 2, 3, -kInfinity, kInfinity);
    barb.vertices.emplace_back(values[0], values[1], values.size() == 3 ? values[2] : 0.0f);
  }
  if (barb.vertices.size() < 2) {
    line.fail(firstVertex, "a key barb needs at least 2 control vertices '(x y [z])', found " +
                               std::to_string(barb.vertices.size()));
  }
  // Sec. 4.1: |cv0 cvn| is clamped to [0, 1]; the curve is scaled about cv0 to keep its shape.
  const glm::vec3 chord = barb.vertices.back() - barb.vertices.front();
  const float chordLength = glm::length(chord);
  if (chordLength > 1) {
    reader.diagnostics.warn(lastVertex, fmt::format("the key barb's chord |cv0 cvn| is {}; it is "
                                                    "scaled to 1",
                                                    chordLength));
    const glm::vec3 origin = barb.vertices.front();
    for (glm::vec3& vertex : barb.vertices) vertex = origin + (vertex - origin) / chordLength;
  }
  reader.type.keyBarbs.push_back(std::move(barb));
}

void readColour(Line& line, Reader& reader, bool material) {
  if (reader.colourAt) {
    line.fail(line.keywordAt(), "a feather has one colour or one material; the first is at " +
                                    reader.colourAt->text());
  }
  reader.colourAt = line.keywordAt();
  FeatherType& type = reader.type;
  if (material) {
    type.appearance.colourKind = FeatherColourKind::Material;
    type.appearance.colourIndex = static_cast<int>(line.integer("the material index", 0, 65535));
    return;
  }
  // One whole number is a colour-map index, three numbers an RGB colour.
  const SourceLocation first = line.here();
  const float r = line.number("a colour (r g b, or an index)", 0, kInfinity);
  if (line.atEnd()) {
    if (r != std::floor(r) || r > 65535) {
      line.fail(first, "a colour index is a whole number from 0 to 65535, found " + numberText(r) +
                           " (an RGB colour is three numbers)");
    }
    type.appearance.colourKind = FeatherColourKind::ColourIndex;
    type.appearance.colourIndex = static_cast<int>(r);
    return;
  }
  if (r > 1) line.fail(first, "the red of a colour must be from 0 to 1, found " + numberText(r));
  const float g = line.number("the green of the colour", 0, 1);
  const float b = line.number("the blue of the colour", 0, 1);
  type.appearance.colourKind = FeatherColourKind::Rgb;
  type.appearance.colour = glm::vec3(r, g, b);
}

void readAfterfeather(Line& line, Reader& reader) {
  const SourceLocation nameAt = line.here();
  const std::string_view name = line.word("an afterfeather file (.fea)");
  if (line.nextIsNumber()) {
    reader.type.afterfeatherSize = line.number("the afterfeather's size factor", 0, kInfinity);
  }
  line.finish();
  const fs::path path = line.resolve(name, nameAt);
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    line.fail(nameAt,
              "cannot read afterfeather file " + inQuotes(name) + " (" + path.string() + ")");
  }
  const fs::path canonical = fs::weakly_canonical(path, error);
  for (std::size_t i = 0; i < reader.stack.size(); ++i) {
    if (reader.stack[i] == canonical) {
      std::string chain;
      for (std::size_t j = i; j < reader.stack.size(); ++j) {
        chain += reader.stack[j].filename().string() + " -> ";
      }
      chain += canonical.filename().string();
      line.fail(nameAt, "afterfeather " + inQuotes(name) + " is a cycle: " + chain);
    }
  }
  reader.type.afterfeather =
      std::make_shared<const FeatherType>(loadWithStack(path, reader.stack, reader.diagnostics));
}

// The keyword table (the one place a keyword is added). Every keyword may appear once, except
// `key barb:`, once per key barb, and `silhouette:`, once per side.
const std::map<std::string_view, Handler>& handlers() {
  static const std::map<std::string_view, Handler> table = {
      {"calamus length:",
       [](Line& l, Reader& r) { r.type.calamusLength = length(l, "the calamus length"); }},
      {"calamus width ratio:",
       [](Line& l, Reader& r) {
         r.type.calamusWidthRatio = l.number("the calamus width ratio", 0, kInfinity);
       }},
      {"rachis length:",
       [](Line& l, Reader& r) { r.type.rachisLength = length(l, "the rachis length"); }},
      {"rachis width:",
       [](Line& l, Reader& r) { r.type.rachisWidth = length(l, "the rachis width"); }},
      {"rachis side curvature:",
       [](Line& l, Reader& r) {
         r.type.rachisSideCurvature = l.number("the side-to-side curvature", -1, 1);
       }},
      {"rachis front curvature:",
       [](Line& l, Reader& r) {
         r.type.rachisFrontCurvature = l.number("the front-to-back curvature", -1, 1);
       }},
      {"barb spacing:",
       [](Line& l, Reader& r) {
         r.spacingAt = l.here();
         const float base = l.number("the barb spacing at the rachis base", 1e-30, kInfinity);
         r.type.barbSpacingBase = base;
         r.type.barbSpacingTip =
             l.atEnd() ? base : l.number("the barb spacing at the rachis tip", 1e-30, kInfinity);
       }},
      {"left barb angles:",
       [](Line& l, Reader& r) {
         r.type.left.baseAngle = l.number("the barb angle at the base in degrees", 0, 180);
         r.type.left.tipAngle = l.number("the barb angle at the tip in degrees", 0, 180);
       }},
      {"right barb angles:",
       [](Line& l, Reader& r) {
         r.type.right.baseAngle = l.number("the barb angle at the base in degrees", 0, 180);
         r.type.right.tipAngle = l.number("the barb angle at the tip in degrees", 0, 180);
       }},
      {"barb length:",
       [](Line& l, Reader& r) {
         r.type.left.barbLength = r.type.right.barbLength = length(l, "the barb length");
       }},
      {"silhouette:", [](Line& l, Reader& r) { readSilhouette(l, r, l.side()); }},
      {"key barb:", readKeyBarb},
      {"drawing:",
       [](Line& l, Reader& r) {
         const SourceLocation where = l.here();
         const std::string_view word = l.word("'lines' or 'strips WIDTH'");
         if (word == "lines") {
           r.type.appearance.drawing = BarbStyle::Lines;
         } else if (word == "strips") {
           r.type.appearance.drawing = BarbStyle::Strips;
           r.type.appearance.stripWidth = l.number("the strip width", 1e-30, kInfinity);
         } else {
           l.fail(where, "expected 'lines' or 'strips WIDTH', found " + inQuotes(word));
         }
       }},
      {"colour:", [](Line& l, Reader& r) { readColour(l, r, false); }},
      {"material:", [](Line& l, Reader& r) { readColour(l, r, true); }},
      {"texture:",
       [](Line& l, Reader& r) {
         const SourceLocation nameAt = l.here();
         const fs::path file = l.resolve(l.word("a texture file"), nameAt);
         std::error_code error;
         if (!fs::is_regular_file(file, error)) {
           l.fail(nameAt, "cannot read the texture image " + inQuotes(file.string()));
         }
         r.type.appearance.texture = file.string();
         if (l.atEnd()) return;
         const SourceLocation where = l.here();
         const std::string_view mapping = l.word("a mapping");
         if (mapping == "barb") {
           r.type.appearance.textureMapping = FeatherTextureMapping::Barb;
         } else if (mapping == "vane") {
           r.type.appearance.textureMapping = FeatherTextureMapping::Vane;
         } else if (mapping == "growth") {
           r.type.appearance.textureMapping = FeatherTextureMapping::Growth;
         } else {
           l.fail(where,
                  "expected a texture mapping (barb, vane or growth), found " + inQuotes(mapping));
         }
       }},
      {"afterfeather:", readAfterfeather},
      {"seed:",
       [](Line& l, Reader& r) {
         r.type.seed = static_cast<std::uint64_t>(
             l.integer("the seed", 0, std::numeric_limits<long long>::max()));
       }},
  };
  return table;
}

// The keyword of a line: its words up to the ':' joined by single spaces, so that alignment
// blanks do not matter.
std::string keywordOf(std::string_view text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isBlank(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !isBlank(text[i])) ++i;
    if (i == start) break;
    if (!out.empty()) out += ' ';
    out += text.substr(start, i - start);
  }
  return out + ":";
}

FeatherType parseWithStack(std::string_view text, const fs::path& file, LoadStack& stack,
                           Diagnostics& diagnostics) {
  FeatherType type;
  type.file = file.string();
  Reader reader{type, stack, diagnostics, std::nullopt, std::nullopt};
  const auto name = std::make_shared<const std::string>(file.string());
  std::map<std::string, SourceLocation> seen;
  int number = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view content = text.substr(start, end - start);
    start = end + 1;
    ++number;
    if (const std::size_t hash = content.find('#'); hash != std::string_view::npos) {
      content = content.substr(0, hash);
    }
    std::size_t first = 0;
    while (first < content.size() && isBlank(content[first])) ++first;
    if (first == content.size()) continue;
    std::size_t last = content.size();
    while (last > first && isBlank(content[last - 1])) --last;
    const int keywordColumn = static_cast<int>(first) + 1;
    const std::size_t colon = content.find(':');
    if (colon == std::string_view::npos) {
      throw DiagnosticError(
          SourceLocation{name, number, keywordColumn},
          "expected 'keyword: values', found " + inQuotes(content.substr(first, last - first)));
    }
    const std::string keyword = keywordOf(content.substr(first, colon - first));
    const auto handler = handlers().find(keyword);
    if (handler == handlers().end()) {
      throw DiagnosticError(SourceLocation{name, number, keywordColumn},
                            "unknown keyword " + inQuotes(keyword) +
                                " in a feather file (docs/feathers.md lists them)");
    }
    const std::string_view rest = content.substr(colon + 1, last > colon ? last - colon - 1 : 0);
    Line line(name, number, handler->first, keywordColumn,
              tokensOf(rest, static_cast<int>(colon) + 2), static_cast<int>(last) + 1);
    // A repeated keyword would silently win over the first: refuse it. A silhouette is given
    // once per side (`both` counts for the two).
    std::vector<std::string> keys;
    if (keyword == "silhouette:") {
      const std::string_view side = line.peek();
      if (side == "left" || side == "both") keys.push_back("silhouette: left");
      if (side == "right" || side == "both") keys.push_back("silhouette: right");
    } else if (keyword != "key barb:") {
      keys.push_back(keyword);
    }
    for (const std::string& key : keys) {
      if (const auto earlier = seen.find(key); earlier != seen.end()) {
        throw DiagnosticError(
            line.keywordAt(),
            inQuotes(key) + " is given twice; the first is at " + earlier->second.text());
      }
    }
    for (const std::string& key : keys) seen.emplace(key, line.keywordAt());
    handler->second(line, reader);
    line.finish();
  }
  // The spacing and the rachis length together fix the barb count; refuse absurd counts.
  const double perVane = type.rachisLength / std::min(type.barbSpacingBase, type.barbSpacingTip);
  if (perVane > kMaxBarbsPerVane) {
    throw DiagnosticError(reader.spacingAt.value_or(SourceLocation{name, 0, 0}),
                          fmt::format("the barb spacing gives about {:.0f} barbs per vane on a "
                                      "rachis of length {}; at most {:.0f} are allowed",
                                      perVane, type.rachisLength, kMaxBarbsPerVane));
  }
  return type;
}

FeatherType loadWithStack(const fs::path& file, LoadStack& stack, Diagnostics& diagnostics) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
                          "cannot read feather file " + inQuotes(file.string()));
  }
  std::ostringstream text;
  text << in.rdbuf();
  std::error_code error;
  stack.push_back(fs::weakly_canonical(file, error));
  FeatherType type = parseWithStack(text.str(), file, stack, diagnostics);
  stack.pop_back();
  return type;
}

}  // namespace

FeatherType loadFeatherType(const std::filesystem::path& file, Diagnostics& diagnostics) {
  LoadStack stack;
  return loadWithStack(file, stack, diagnostics);
}

FeatherType parseFeatherType(std::string_view text, const std::filesystem::path& file,
                             Diagnostics& diagnostics) {
  LoadStack stack;
  std::error_code error;
  stack.push_back(fs::weakly_canonical(file, error));
  return parseWithStack(text, file, stack, diagnostics);
}

}  // namespace hirsute
