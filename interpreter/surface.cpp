// Bicubic surfaces (`.s`) as bezieredit and stedit write them and cpfg reads them
// (cpfg-features.md "Bicubic surface .s", vlab-tools-manual §5.4):
//
//   xmin xmax ymin ymax zmin zmax
//   [PRECISION S: i T: j]
//   CONTACT POINT X: x Y: y Z: z
//   END POINT X: x Y: y Z: z
//   HEADING X: x Y: y Z: z
//   UP X: x Y: y Z: z
//   SIZE: s
// then per patch: its name; TOP COLOR: i DIFFUSE: x BOTTOM COLOR: j DIFFUSE: y; the neighbour
// lines AL: A: AR: / L: R: / BL: B: BR: (`~` for none); 4 rows of 4 control points x y z.
#include "hirsute/interpreter/surface.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/edited_text.h"
#include "hirsute/core/line_reader.h"

namespace hirsute {
namespace {

std::string inQuotes(std::string_view text) {
  // Built by appending: GCC 12's -O3 reports a false -Wrestrict on "'" + std::string(...).
  std::string quoted;
  quoted.reserve(text.size() + 2);
  quoted += '\'';
  quoted += text;
  quoted += '\'';
  return quoted;
}

// A surface file's lines: a label and its number are two words even when no blank parts them.
class SurfaceReader : public LineReader {
 public:
  SurfaceReader(std::string_view text, const std::string& file)
      : LineReader(text, file, WordSplit::AfterColons) {}

  static std::optional<double> number(std::string_view word) { return wordAsNumber(word); }
  static std::optional<int> integer(std::string_view word) { return wordAsInteger(word); }

  // A line of fixed words with numbers between them: `pattern` lists the words, and "#" where a
  // number stands. Returns the numbers in order.
  std::vector<double> labelled(const TextLine& line,
                               std::initializer_list<std::string_view> pattern,
                               const std::string& expected) const {
    std::vector<double> values;
    bool ok = line.words.size() == pattern.size();
    std::size_t i = 0;
    for (std::string_view part : pattern) {
      if (!ok) break;
      if (part == "#") {
        const std::optional<double> value = number(line.words[i]);
        ok = value.has_value();
        if (ok) values.push_back(*value);
      } else {
        ok = line.words[i] == part;
      }
      ++i;
    }
    if (!ok) fail(line.number, "expected " + inQuotes(expected) + ", found " + inQuotes(line.text));
    return values;
  }
};

glm::dvec3 asPoint(const std::vector<double>& v) {
  return glm::dvec3(v[0], v[1], v[2]);
}

BezierPatch readPatch(SurfaceReader& reader, std::array<int, 4>& rowLines) {
  BezierPatch patch;
  patch.name = std::string(reader.take("a patch name").text);

  const TextLine& colors = reader.take("the patch colours");
  const std::vector<double> c = reader.labelled(
      colors, {"TOP", "COLOR:", "#", "DIFFUSE:", "#", "BOTTOM", "COLOR:", "#", "DIFFUSE:", "#"},
      "TOP COLOR: i DIFFUSE: x BOTTOM COLOR: j DIFFUSE: y");
  const std::optional<int> top = SurfaceReader::integer(colors.words[2]);
  const std::optional<int> bottom = SurfaceReader::integer(colors.words[7]);
  if (!top || !bottom || *top < 0 || *bottom < 0) {
    reader.fail(colors.number, "patch colours are colour indices (whole numbers from 0)");
  }
  patch.topColor = *top;
  patch.topDiffuse = c[1];
  patch.bottomColor = *bottom;
  patch.bottomDiffuse = c[3];

  // AL A AR / L R / BL B BR, in BezierPatch::neighbours order.
  static const std::vector<std::vector<std::string_view>> kNeighbourLines = {
      {"AL:", "A:", "AR:"}, {"L:", "R:"}, {"BL:", "B:", "BR:"}};
  std::size_t slot = 0;
  for (const std::vector<std::string_view>& labels : kNeighbourLines) {
    std::string expected;
    for (std::string_view label : labels) expected += std::string(label) + " name ";
    expected.pop_back();
    const TextLine& line = reader.take(inQuotes(expected));
    bool ok = line.words.size() == 2 * labels.size();
    for (std::size_t k = 0; ok && k < labels.size(); ++k) ok = line.words[2 * k] == labels[k];
    if (!ok) {
      reader.fail(line.number,
                  "expected " + inQuotes(expected) + " (~ for none), found " + inQuotes(line.text));
    }
    for (std::size_t k = 0; k < labels.size(); ++k) {
      const std::string_view name = line.words[2 * k + 1];
      patch.neighbours[slot++] = name == "~" ? std::string() : std::string(name);
    }
  }

  for (int row = 0; row < 4; ++row) {
    const TextLine& line = reader.take("row " + std::to_string(row + 1) +
                                       " of the control points of patch " + inQuotes(patch.name));
    rowLines[static_cast<std::size_t>(row)] = line.number;
    if (line.words.size() != 12) {
      reader.fail(line.number, "expected 4 control points 'x y z' (12 numbers) in row " +
                                   std::to_string(row + 1) + " of patch " + inQuotes(patch.name) +
                                   ", found " + std::to_string(line.words.size()) + " words");
    }
    for (int k = 0; k < 12; ++k) {
      const std::optional<double> value = SurfaceReader::number(line.words[k]);
      if (!value) {
        reader.fail(line.number, "expected a number in the control points of patch " +
                                     inQuotes(patch.name) + ", found " + inQuotes(line.words[k]));
      }
      patch.points[static_cast<std::size_t>(row * 4 + k / 3)][k % 3] = *value;
    }
  }
  return patch;
}

// `rowLines` receives the lines of each patch's 4 rows of control points.
Surface parseSurface(std::string_view text, const std::string& file,
                     std::vector<std::array<int, 4>>& rowLines) {
  SurfaceReader reader(text, file);
  Surface surface;
  surface.file = file;

  const TextLine& bounds = reader.take("'xmin xmax ymin ymax zmin zmax'");
  const std::vector<double> b =
      reader.labelled(bounds, {"#", "#", "#", "#", "#", "#"}, "xmin xmax ymin ymax zmin zmax");
  surface.boundsMin = glm::dvec3(b[0], b[2], b[4]);
  surface.boundsMax = glm::dvec3(b[1], b[3], b[5]);

  if (!reader.atEnd() && reader.peek().words[0] == "PRECISION") {
    const TextLine& line = reader.take("PRECISION");
    const std::vector<double> p =
        reader.labelled(line, {"PRECISION", "S:", "#", "T:", "#"}, "PRECISION S: i T: j");
    const std::optional<int> s = SurfaceReader::integer(line.words[2]);
    const std::optional<int> t = SurfaceReader::integer(line.words[4]);
    if (!s || !t || *s < 1 || *t < 1) {
      reader.fail(line.number, "PRECISION takes whole numbers of at least 1");
    }
    surface.sPrecision = *s;
    surface.tPrecision = *t;
  }

  const auto readPoint = [&reader](std::string_view first, std::string_view second,
                                   const std::string& expected) {
    const TextLine& line = reader.take(inQuotes(expected));
    if (second.empty()) {
      return asPoint(reader.labelled(line, {first, "X:", "#", "Y:", "#", "Z:", "#"}, expected));
    }
    return asPoint(
        reader.labelled(line, {first, second, "X:", "#", "Y:", "#", "Z:", "#"}, expected));
  };
  surface.contact = readPoint("CONTACT", "POINT", "CONTACT POINT X: x Y: y Z: z");
  surface.endPoint = readPoint("END", "POINT", "END POINT X: x Y: y Z: z");
  surface.heading = readPoint("HEADING", "", "HEADING X: x Y: y Z: z");
  surface.up = readPoint("UP", "", "UP X: x Y: y Z: z");

  const TextLine& sizeLine = reader.take("'SIZE: s'");
  surface.fileSize = reader.labelled(sizeLine, {"SIZE:", "#"}, "SIZE: s")[0];
  if (!(surface.fileSize > 0)) reader.fail(sizeLine.number, "SIZE must be positive");

  while (!reader.atEnd()) {
    rowLines.emplace_back();
    surface.patches.push_back(readPatch(reader, rowLines.back()));
  }
  if (surface.patches.empty()) {
    reader.fail(sizeLine.number, "the surface has no patches after 'SIZE:'");
  }
  return surface;
}

}  // namespace

Surface loadSurface(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file), 0, 0},
                          "cannot open surface file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  std::vector<std::array<int, 4>> rowLines;
  return parseSurface(text.str(), file, rowLines);
}

SurfaceFile SurfaceFile::parse(std::string_view text, const std::string& fileName) {
  SurfaceFile file;
  file.fileName_ = fileName;
  file.text_ = EditedText::split(text);
  file.surface_ = parseSurface(text, fileName, file.rowLines_);
  return file;
}

SurfaceFile SurfaceFile::load(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file), 0, 0},
                          "cannot open surface file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse(text.str(), file);
}

std::string SurfaceFile::setPoint(std::size_t patch, std::size_t index, glm::dvec3 point) {
  if (patch >= surface_.patches.size() || index >= 16) return "no such control point";
  const std::size_t row = index / 4;
  std::array<glm::dvec3, 16> points = surface_.patches[patch].points;
  points[index] = point;
  // bezieredit's row: four points "x y z" with two blanks after each, in "%.2f" where that
  // reads back as the value (edited_text.h).
  std::string line;
  for (std::size_t k = 0; k < 4; ++k) {
    const glm::dvec3& p = points[row * 4 + k];
    line += formatFixed(p.x, 2) + ' ' + formatFixed(p.y, 2) + ' ' + formatFixed(p.z, 2) + "  ";
  }
  EditedText edited = text_;
  edited.lines[static_cast<std::size_t>(rowLines_[patch][row] - 1)] = line;
  std::vector<std::array<int, 4>> rowLines;
  try {
    surface_ = parseSurface(edited.joined(), fileName_, rowLines);
  } catch (const DiagnosticError& error) {
    return error.diagnostic().text();
  }
  text_ = std::move(edited);
  rowLines_ = std::move(rowLines);
  return std::string();
}

}  // namespace hirsute
