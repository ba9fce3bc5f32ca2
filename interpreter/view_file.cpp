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
// something — a light, a texture, a tropism, a contour, a surface, a hair template — is an error
// when broken, because what it declares would otherwise be dropped or half-defined without the
// user noticing.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "hirsute/core/model_folder.h"
#include "hirsute/interpreter/contour.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {
namespace {

std::string inQuotes(std::string_view text) {
  return "'" + std::string(text) + "'";
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// A number at the front of `text` as sscanf's %f reads it: an optional sign, digits, a fraction,
// an exponent. Returns the value and the characters used; nothing when no number starts there.
// Infinite and NaN values are refused: no view setting means them.
std::optional<std::pair<double, std::size_t>> numberAtFront(std::string_view text) {
  std::size_t skip = 0;
  if (!text.empty() && text[0] == '+' && text.size() > 1 && text[1] != '-') skip = 1;
  const char* begin = text.data() + skip;
  const char* end = text.data() + text.size();
  if (begin == end ||
      !(std::isdigit(static_cast<unsigned char>(*begin)) || *begin == '-' || *begin == '.')) {
    return std::nullopt;
  }
  double value = 0.0;
  const auto [stop, error] = std::from_chars(begin, end, value, std::chars_format::general);
  if (error != std::errc() || !std::isfinite(value)) return std::nullopt;
  return std::make_pair(value, static_cast<std::size_t>(stop - text.data()));
}

// An integer at the front of `text`, as %d reads it.
std::optional<std::pair<long, std::size_t>> integerAtFront(std::string_view text) {
  std::size_t skip = 0;
  if (!text.empty() && text[0] == '+' && text.size() > 1 && text[1] != '-') skip = 1;
  long value = 0;
  const char* begin = text.data() + skip;
  const auto [stop, error] = std::from_chars(begin, text.data() + text.size(), value);
  if (error != std::errc() || stop == begin) return std::nullopt;
  return std::make_pair(value, static_cast<std::size_t>(stop - text.data()));
}

// A whole word as a number; used where words are separated first (light, texture, tropism).
std::optional<double> wholeNumber(std::string_view word) {
  const auto number = numberAtFront(word);
  if (!number || number->second != word.size()) return std::nullopt;
  return number->first;
}

// The arguments of one command, read front to back as sscanf reads them.
class ArgumentReader {
 public:
  explicit ArgumentReader(const ViewFileLine& line) : line_(line), text_(line.rest) {}

  void skipBlanks() {
    while (position_ < text_.size() && isBlank(text_[position_])) ++position_;
  }
  bool atEnd() {
    skipBlanks();
    return position_ >= text_.size();
  }
  // Where the next argument starts (after blanks).
  SourceLocation here() {
    skipBlanks();
    return line_.at(position_);
  }
  // The next blank-separated word, without consuming it ("" at the end).
  std::string_view peekWord() {
    skipBlanks();
    std::size_t end = position_;
    while (end < text_.size() && !isBlank(text_[end])) ++end;
    return text_.substr(position_, end - position_);
  }
  std::optional<std::string_view> word() {
    const std::string_view next = peekWord();
    if (next.empty()) return std::nullopt;
    position_ += next.size();
    return next;
  }
  std::optional<double> number() {
    skipBlanks();
    const auto number = numberAtFront(text_.substr(position_));
    if (!number) return std::nullopt;
    position_ += number->second;
    return number->first;
  }
  std::optional<long> integer() {
    skipBlanks();
    const auto number = integerAtFront(text_.substr(position_));
    if (!number) return std::nullopt;
    position_ += number->second;
    return number->first;
  }
  // A literal such as ',' or "x:"; blanks before it are allowed (sscanf would not skip them
  // before a comma; accepting `0 , 1` costs nothing).
  bool literal(std::string_view expected) {
    skipBlanks();
    if (text_.substr(position_, expected.size()) != expected) return false;
    position_ += expected.size();
    return true;
  }
  void skipAll() { position_ = text_.size(); }
  std::string_view remaining() {
    skipBlanks();
    std::string_view rest = text_.substr(position_);
    while (!rest.empty() && isBlank(rest.back())) rest.remove_suffix(1);
    return rest;
  }

 private:
  const ViewFileLine& line_;
  std::string_view text_;
  std::size_t position_ = 0;
};

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

class Command;
using Handler = void (*)(Command&);

// One view-file line being read: its arguments, the settings it changes, and how it reports.
class Command {
 public:
  Command(const ViewFileLine& line, ViewSettings& view, Diagnostics& diagnostics,
          const std::filesystem::path& folder)
      : args(line), view(view), line_(line), diagnostics_(diagnostics), folder_(folder) {}

  const ViewFileLine& line() const { return line_; }
  std::string_view label() const { return line_.label; }
  // Where the label starts: messages about the whole line point there.
  SourceLocation labelAt() const {
    SourceLocation where = line_.where;
    where.column = line_.restColumn - static_cast<int>(line_.label.size());
    return where;
  }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    throw DiagnosticError(where, message);
  }
  void warn(const SourceLocation& where, const std::string& message) {
    diagnostics_.warn(where, message);
  }

  // A setting that cannot be read: a warning, and the setting keeps its value (cpfg).
  void ignoreLine(const SourceLocation& where, const std::string& expected) {
    const std::string found = std::string(args.peekWord());
    warn(where, "expected " + expected + " after " + inQuotes(label()) + ", found " +
                    (found.empty() ? std::string("nothing") : inQuotes(found)) +
                    "; the line is ignored");
    args.skipAll();
    ignored_ = true;
  }
  bool ignored() const { return ignored_; }

  // Settings: nothing is returned (and a warning given) when the value cannot be read.
  std::optional<double> settingNumber() {
    const SourceLocation where = args.here();
    const std::optional<double> value = args.number();
    if (!value) ignoreLine(where, "a number");
    return value;
  }
  std::optional<int> settingInteger() {
    const SourceLocation where = args.here();
    const std::optional<long> value = args.integer();
    if (!value || *value < std::numeric_limits<int>::min() ||
        *value > std::numeric_limits<int>::max()) {
      ignoreLine(where, "an integer");
      return std::nullopt;
    }
    return static_cast<int>(*value);
  }
  // `x,y,z`.
  std::optional<glm::vec3> settingTriple() {
    glm::vec3 out;
    for (int k = 0; k < 3; ++k) {
      const SourceLocation where = args.here();
      if (k > 0 && !args.literal(",")) {
        ignoreLine(where, "three numbers separated by commas (x,y,z)");
        return std::nullopt;
      }
      const SourceLocation numberAt = args.here();
      const std::optional<double> value = args.number();
      if (!value) {
        ignoreLine(numberAt, "three numbers separated by commas (x,y,z)");
        return std::nullopt;
      }
      out[k] = static_cast<float>(*value);
    }
    return out;
  }
  // One of `words`; the index of the word found.
  std::optional<std::size_t> settingWord(std::initializer_list<std::string_view> words,
                                         const std::string& expected) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    std::size_t index = 0;
    for (std::string_view candidate : words) {
      if (word == candidate) {
        args.word();
        return index;
      }
      ++index;
    }
    ignoreLine(where, expected);
    return std::nullopt;
  }
  std::optional<bool> settingFlag() {
    const std::optional<std::size_t> word = settingWord({"on", "off"}, "on or off");
    if (!word) return std::nullopt;
    return *word == 0;
  }

  // Declarations: an error when the value cannot be read.
  std::string_view requiredWord(const std::string& what) {
    const SourceLocation where = args.here();
    const std::optional<std::string_view> word = args.word();
    if (!word) fail(where, "expected " + what + " after " + inQuotes(label()));
    return *word;
  }
  long requiredInteger(const std::string& what, long min, long max) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    const auto number = integerAtFront(word);
    if (!number || number->second != word.size()) {
      fail(where, "expected " + what + " after " + inQuotes(label()) + ", found " +
                      (word.empty() ? std::string("nothing") : inQuotes(word)));
    }
    if (number->first < min || number->first > max) {
      fail(where, what + " must be from " + std::to_string(min) + " to " + std::to_string(max) +
                      ", found " + std::to_string(number->first));
    }
    args.word();
    return number->first;
  }
  double requiredNumber(const std::string& what) {
    const SourceLocation where = args.here();
    const std::string_view word = args.peekWord();
    const std::optional<double> value = wholeNumber(word);
    if (!value) {
      fail(where, "expected " + what + " after " + inQuotes(label()) + ", found " +
                      (word.empty() ? std::string("nothing") : inQuotes(word)));
    }
    args.word();
    return *value;
  }

  // Text left after the arguments: cpfg's sscanf ignores it; Hirsute says so.
  void finish() {
    if (ignored_) return;
    const SourceLocation where = args.here();
    const std::string_view rest = args.remaining();
    if (!rest.empty()) {
      warn(where, inQuotes(rest) + " after the arguments of " + inQuotes(label()) + " is ignored");
    }
  }

  // A file name of the view file, resolved against its folder. The name must stay beneath that
  // folder (model_folder.h): an absolute name, a `..`, a link out of the folder, a FIFO or a
  // device is an error here, at the reference; a missing file is for its reader to report.
  std::string resolve(std::string_view name, const SourceLocation& where) const {
    const ModelFolder folder(folder_);
    const std::string refused = folder.refusal(std::string(name));
    if (!refused.empty()) fail(where, "cannot open " + inQuotes(name) + ": " + refused);
    return folder.pathOf(std::string(name)).string();
  }

  ArgumentReader args;
  ViewSettings& view;

 private:
  const ViewFileLine& line_;
  Diagnostics& diagnostics_;
  const std::filesystem::path& folder_;
  bool ignored_ = false;
};

// The numbers after a subcommand key; an error when there are fewer or they are no numbers.
std::vector<double> subcommandNumbers(const Command& c, const std::vector<Token>& tokens,
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
std::string_view subcommandWord(const Command& c, const std::vector<Token>& tokens, std::size_t& i,
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
void initialLineWidth(Command& c) {
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

void lineStyle(Command& c) {
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
void renderMode(Command& c) {
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
void shadeMode(Command& c) {
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
void box(Command& c) {
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

void shadowMap(Command& c) {
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
void light(Command& c) {
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
void tropismOrTorque(Command& c, bool torque) {
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
void texture(Command& c) {
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
void contour(Command& c) {
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
// a texture file there, which Hirsute also accepts (it becomes the next texture).
void surface(Command& c) {
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
  if (!c.args.atEnd() && integerAtFront(c.args.peekWord())) {
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

void backgroundScene(Command& c) {
  const std::vector<Token> tokens = subcommandTokens(c.line());
  if (tokens.empty()) c.fail(c.labelAt(), "expected a file name after 'background scene:'");
  for (const Token& token : tokens) c.view.backgroundScenes.push_back(c.resolve(token.text, token.where));
  c.args.skipAll();
}

// `hair texture: SIZE SEED [FILL]` (DESIGN.md): the point-diffusion texture is SIZE×SIZE cells
// with FILL points per cell (0.02 to 0.3 measured; default 0.1).
void hairTexture(Command& c) {
  c.view.hairTextureSize = static_cast<int>(c.requiredInteger("the texture size", 4, 4096));
  c.view.hairTextureSeed =
      static_cast<unsigned>(c.requiredInteger("the seed", 0, std::numeric_limits<unsigned>::max()));
  if (!c.args.atEnd()) {
    const SourceLocation where = c.args.here();
    const double fill = c.requiredNumber("the fill (points per cell)");
    if (!(fill >= 0.02 && fill <= 0.3)) c.fail(where, "the fill must be from 0.02 to 0.3 points per cell");
    c.view.hairTextureFill = fill;
  }
}

void hairInterpolation(Command& c) {
  const SourceLocation where = c.args.here();
  const std::string_view word = c.requiredWord("on or off");
  if (word != "on" && word != "off") c.fail(where, "expected on or off, found " + inQuotes(word));
  c.view.hairInterpolation = word == "on";
}

// `fur texture: SIZE SEED [TEXELS]` (docs/fur.md): SIZE² texels from SEED, TEXELS texels along
// the length of a strand (default 40: strands are a fortieth of their length thick).
void furTexture(Command& c) {
  c.view.furTextureSize =
      static_cast<int>(c.requiredInteger("the texture size", 16, kMaxFurTextureSize));
  c.view.furTextureSeed =
      static_cast<unsigned>(c.requiredInteger("the seed", 0, std::numeric_limits<unsigned>::max()));
  if (!c.args.atEnd()) {
    const SourceLocation where = c.args.here();
    const double texels = c.requiredNumber("the texels along a strand's length");
    if (!(texels >= 1 && texels <= 4096)) c.fail(where, "the texels per length must be from 1 to 4096");
    c.view.furTexelsPerLength = static_cast<float>(texels);
  }
}

// A number of a `dynamics …:` line that must lie in [lo, hi].
double dynamicsNumber(Command& c, const std::string& what, double lo, double hi) {
  const SourceLocation where = c.args.here();
  const double value = c.requiredNumber(what);
  if (!(value >= lo && value <= hi)) {
    char range[128];
    std::snprintf(range, sizeof range, " must be from %g to %g, found %g", lo, hi, value);
    c.fail(where, what + range);
  }
  return value;
}

glm::vec3 dynamicsVector(Command& c, const std::string& what) {
  glm::vec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = static_cast<float>(dynamicsNumber(c, what + "'s x, y and z", -1e6, 1e6));
  return v;
}

// `dynamics gusts: strength scale period [seed]` (docs/dynamics.md).
void dynamicsGusts(Command& c) {
  FeatherDynamicsSettings& d = c.view.dynamics;
  d.gustStrength = static_cast<float>(dynamicsNumber(c, "the gusts' strength", 0, 1e6));
  d.gustScale = static_cast<float>(dynamicsNumber(c, "the gusts' scale", 1e-6, 1e6));
  d.gustPeriod = static_cast<float>(dynamicsNumber(c, "the gusts' period", 1e-6, 1e6));
  if (!c.args.atEnd())
    d.gustSeed = static_cast<unsigned>(
        c.requiredInteger("the gusts' seed", 0, std::numeric_limits<unsigned>::max()));
}

// `droplet: u v r rho [surface]` (docs/fur.md).
void droplet(Command& c) {
  Droplet d;
  d.where = c.labelAt();
  const SourceLocation uAt = c.args.here();
  const double u = c.requiredNumber("the droplet's u");
  const SourceLocation vAt = c.args.here();
  const double v = c.requiredNumber("the droplet's v");
  if (!(u >= 0 && u <= 1)) c.fail(uAt, "the droplet's u must be in [0, 1] (the fur surface's parametrization)");
  if (!(v >= 0 && v <= 1)) c.fail(vAt, "the droplet's v must be in [0, 1] (the fur surface's parametrization)");
  const SourceLocation rAt = c.args.here();
  const double r = c.requiredNumber("the droplet's radius");
  if (!(r > 0 && r <= 1)) c.fail(rAt, "the droplet's radius must be in (0, 1]");
  const SourceLocation rhoAt = c.args.here();
  const double rho = c.requiredNumber("the droplet's wetness");
  if (!(rho >= 0 && rho <= 1)) c.fail(rhoAt, "the droplet's wetness must be in [0, 1]");
  if (!c.args.atEnd())
    d.surface = static_cast<int>(c.requiredInteger("the fur surface (1-based, 0: all)", 0, 1 << 30));
  d.centre = glm::vec2(static_cast<float>(u), static_cast<float>(v));
  d.radius = static_cast<float>(r);
  d.wetness = static_cast<float>(rho);
  c.view.droplets.push_back(d);
}

// A command Hirsute reads and has no use for: the rest of the line is skipped.
void ignoreArguments(Command& c) {
  c.args.skipAll();
}

// A command whose effect Hirsute does not provide: a warning, so that the user knows.
void unsupported(Command& c, const std::string& what) {
  c.warn(c.labelAt(), inQuotes(c.label()) + " is not supported: " + what);
  c.args.skipAll();
}

const std::unordered_map<std::string_view, Handler>& commandTable() {
  // Immutable after its first use: the registry of view-file commands.
  static const std::unordered_map<std::string_view, Handler> kCommands = {
      // Turtle (manual §8.1.1).
      {"angle factor:",
       [](Command& c) {
         const SourceLocation where = c.args.here();
         if (const auto n = c.settingNumber()) {
           if (*n == 0) {
             c.warn(where, "'angle factor:' divides 360 and cannot be 0; the line is ignored");
           } else {
             c.view.angleIncrement = static_cast<float>(360.0 / *n);
           }
         }
       }},
      {"angle increment:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.angleIncrement = static_cast<float>(*v);
       }},
      {"initial color:",
       [](Command& c) {
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
       [](Command& c) {
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
      {"line width increment:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.lineWidthIncrement = static_cast<float>(*v);
       }},
      {"initial scale:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.initialScale = static_cast<float>(*v);
       }},
      {"scale multiplier:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.scaleMultiplier = static_cast<float>(*v);
       }},
      {"interpretation past %:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.interpretationPastCut = *on;
       }},

      // View (§8.1.2).
      {"viewpoint:",
       [](Command& c) {
         if (const auto v = c.settingTriple()) c.view.viewpoint = *v;
       }},
      {"view reference point:",
       [](Command& c) {
         if (const auto v = c.settingTriple()) c.view.viewReference = *v;
       }},
      {"twist:",
       [](Command& c) {
         // Tenths of a degree, read as an integer.
         if (const auto v = c.settingInteger()) c.view.twistDegrees = static_cast<float>(*v) / 10;
       }},
      {"projection:",
       [](Command& c) {
         if (const auto w = c.settingWord({"parallel", "perspective"}, "parallel or perspective")) {
           c.view.projection = *w == 0 ? Projection::Parallel : Projection::Perspective;
         }
       }},
      {"viewing angle:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.viewingAngle = static_cast<float>(*v);
       }},
      {"front distance:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.frontDistance = static_cast<float>(*v);
       }},
      {"back distance:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.backDistance = static_cast<float>(*v);
       }},
      {"scale factor:",
       [](Command& c) {
         // cpfg: 0 means full size.
         if (const auto v = c.settingNumber())
           c.view.scaleFactor = *v == 0 ? 1.0f : static_cast<float>(*v);
       }},
      {"box:", &box},
      {"min zoom:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.minZoom = static_cast<float>(*v);
       }},
      {"max zoom:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.maxZoom = static_cast<float>(*v);
       }},
      {"generate on view change:",
       [](Command& c) {
         if (c.args.peekWord() == "off") {
           c.args.word();
           return;
         }
         unsupported(c, "Hirsute does not derive the string again when the view changes");
       }},

      // Rendering (§8.1.4).
      {"z buffer:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.zBuffer = *on;
       }},
      {"render mode:", &renderMode},
      {"shade mode:", &shadeMode},
      {"shadow map:", &shadowMap},
      {"antialiasing:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.antialiasing = *on;
       }},
      {"concave polygons:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.concavePolygons = *on;
       }},
      {"background scene:", &backgroundScene},

      // Lights (§8.1.3).
      {"light direction:",
       [](Command& c) {
         if (const auto v = c.settingTriple()) c.view.lightDirection = *v;
       }},
      {"diffuse reflection:",
       [](Command& c) {
         if (const auto v = c.settingInteger()) c.view.diffuseReflection = *v;
       }},
      {"surface ambient:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.surfaceAmbient = static_cast<float>(*v);
       }},
      {"surface diffuse:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.surfaceDiffuse = static_cast<float>(*v);
       }},
      {"light:", &light},

      // Lines, contours and surfaces (§8.1.5).
      {"line style:", &lineStyle},
      {"tapered lines:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.taperedLines = *on;
       }},
      {"contour sides:",
       [](Command& c) {
         const SourceLocation where = c.args.here();
         const auto sides = c.settingInteger();
         if (!sides) return;
         if (*sides > kMaxContourSides) {
           c.warn(where, "at most " + std::to_string(kMaxContourSides) + " contour sides; using " +
                             std::to_string(kMaxContourSides));
         }
         // cpfg: fewer than 3 sides read as 3.
         c.view.contourSides = std::clamp(*sides, 3, kMaxContourSides);
       }},
      {"polygonization level:",
       [](Command& c) {
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
      {"twist of cylinders:",
       [](Command& c) {
         if (const auto on = c.settingFlag()) c.view.twistOfCylinders = *on;
       }},
      {"surface:", &surface},
      {"tsurface:", [](Command& c) { unsupported(c, "triangle-list surfaces are not drawn"); }},
      // Obsolete: a surface used as a line segment, which cpfg's GL drawing ignores too.
      {"line:", &ignoreArguments},

      // User functions (§8.1.6): lsys reads these lines (readViewFunctions).
      {"function:", &ignoreArguments},
      {"function set:", &ignoreArguments},
      {"curve:", &ignoreArguments},

      // Textures (§8.1.7).
      {"texture:", &texture},

      // Tropisms (§8.1.8) and the deprecated single tropism for `_` (§8.1.10).
      {"tropism:", [](Command& c) { tropismOrTorque(c, false); }},
      {"torque:", [](Command& c) { tropismOrTorque(c, true); }},
      {"tropism direction:",
       [](Command& c) {
         if (const auto v = c.settingTriple()) c.view.tropismDirection = *v;
       }},
      {"initial elasticity:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.initialElasticity = static_cast<float>(*v);
       }},
      {"elasticity increment:",
       [](Command& c) {
         if (const auto v = c.settingNumber()) c.view.elasticityIncrement = static_cast<float>(*v);
       }},

      // Read and without effect, in cpfg too or for Hirsute's outputs.
      {"cue range:", &ignoreArguments},
      {"font:", &ignoreArguments},
      {"winfont:", &ignoreArguments},
      {"interpretation step:", &ignoreArguments},
      {"rayshade objects:", &ignoreArguments},
      {"rayshade scale:", &ignoreArguments},
      {"PS linecap:", &ignoreArguments},
      {"environment display:",
       [](Command& c) { unsupported(c, "environmental programs are not run"); }},
      {"blob:", [](Command& c) { unsupported(c, "blob fields are not read"); }},
      {"background color:",
       [](Command& c) {
         unsupported(c,
                     "cpfg ignores it too; the background is colour 0 of the colour map, or "
                     "the emission of material 0");
       }},
      {"ambient light:",
       [](Command& c) {
         unsupported(c, "cpfg ignores it too; use 'surface ambient:' or the A: of 'light:'");
       }},

      // Hairs (DESIGN.md).
      {"hair:",
       [](Command& c) {
         const SourceLocation where = c.args.here();
         const std::string file = c.resolve(c.requiredWord("a template L-system file"), where);
         if (c.view.hairTemplates.size() >= static_cast<std::size_t>(kMaxHairTemplates)) {
           c.fail(where, "at most " + std::to_string(kMaxHairTemplates) + " template hairs per model");
         }
         c.view.hairTemplates.push_back(HairTemplateDeclaration{file, where});
       }},
      {"hair texture:", &hairTexture},
      {"hair interpolation:", &hairInterpolation},

      // Feathers (DESIGN.md, docs/feathers.md).
      {"feather:",
       [](Command& c) {
         const SourceLocation where = c.args.here();
         const std::string file = c.resolve(c.requiredWord("a feather type file (.fea)"), where);
         if (c.view.featherTypes.size() >= static_cast<std::size_t>(kMaxFeatherTypes)) {
           c.fail(where, "at most " + std::to_string(kMaxFeatherTypes) + " feather types per model");
         }
         c.view.featherTypes.push_back(FeatherTypeDeclaration{file, where});
       }},
      {"feather follicles:",
       [](Command& c) {
         const SourceLocation where = c.args.here();
         const std::string_view word = c.requiredWord("diffusion or hexagonal");
         if (word != "diffusion" && word != "hexagonal")
           c.fail(where, "expected diffusion or hexagonal, found " + inQuotes(word));
         c.view.follicleLayout =
             word == "hexagonal" ? FollicleLayout::Hexagonal : FollicleLayout::Diffusion;
       }},

      // Fur (DESIGN.md, docs/fur.md).
      {"fur layers:",
       [](Command& c) {
         c.view.furLayers = static_cast<int>(c.requiredInteger("the number of layers", 1, kMaxFurLayers));
       }},
      {"fur texture:", &furTexture},
      {"wetness mask:",
       [](Command& c) {
         c.view.wetnessMaskSize =
             static_cast<int>(c.requiredInteger("the mask size", 8, kMaxFurTextureSize));
       }},
      {"droplet:", &droplet},
      {"fur force:",
       [](Command& c) {
         glm::vec3 force;
         for (int i = 0; i < 3; ++i) {
           const SourceLocation where = c.args.here();
           const double value = c.requiredNumber("the force's x, y and z");
           if (!std::isfinite(value) || std::abs(value) > 1e6) c.fail(where, "a fur force component must be finite, at most 1e6");
           force[i] = static_cast<float>(value);
         }
         c.view.furForce = force;
       }},

      // Feather-coat dynamics (docs/dynamics.md).
      {"dynamics gravity:",
       [](Command& c) { c.view.dynamics.gravity = dynamicsVector(c, "the gravity"); }},
      {"dynamics wind:", [](Command& c) { c.view.dynamics.wind = dynamicsVector(c, "the wind"); }},
      {"dynamics gusts:", &dynamicsGusts},
      {"dynamics drag:",
       [](Command& c) {
         c.view.dynamics.drag = static_cast<float>(dynamicsNumber(c, "the drag", 0, 1e6));
       }},
      {"dynamics springs:",
       [](Command& c) {
         c.view.dynamics.stiffness =
             static_cast<float>(dynamicsNumber(c, "the springs' stiffness", 0, 1e9));
         c.view.dynamics.damping =
             static_cast<float>(dynamicsNumber(c, "the springs' damping", 0, 1e9));
       }},
      {"dynamics thickness:",
       [](Command& c) {
         FeatherDynamicsSettings& d = c.view.dynamics;
         d.thickness = static_cast<float>(dynamicsNumber(c, "the thickness", 1e-9, 1e6));
         d.separation = static_cast<float>(
             dynamicsNumber(c, "the minimum separation", 1e-9, static_cast<double>(d.thickness)));
       }},
      {"dynamics segments:",
       [](Command& c) {
         c.view.dynamics.segments =
             static_cast<int>(c.requiredInteger("the segments of a stem", 1, 64));
       }},
      {"dynamics substeps:",
       [](Command& c) {
         c.view.dynamics.substeps =
             static_cast<int>(c.requiredInteger("the steps per frame", 1, 1000));
       }},
  };
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
    Command command(line, view, diagnostics, folder);
    found->second(command);
    command.finish();
  }
  return view;
}

}  // namespace hirsute
