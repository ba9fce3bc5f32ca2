#include "hirsute/lsys/function_curve.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/line_reader.h"
#include "hirsute/core/model_folder.h"
#include "hirsute/lsys/view_file_lines.h"

namespace hirsute {
namespace {

// ---------------------------------------------------------------------------------------------
// Reading the text files of funcedit and cuspy: whitespace-separated words on numbered lines.

std::optional<double> parseDouble(std::string_view word) {
  return wordAsNumber(word);
}

std::optional<int> parseInt(std::string_view word) {
  return wordAsInteger(word);
}

// cuspy writes multiplicities 1 to 3; cpfg accepts any, so only absurd ones are refused.
constexpr int kMaxMultiplicity = 1000;

std::string quoted(std::string_view word) {
  return "'" + std::string(word) + "'";
}

// The lines of a funcedit or cuspy file, with the forms their lines take.
class CurveFileReader : public LineReader {
 public:
  using LineReader::LineReader;

  // The line must be `label` followed by exactly `count` numbers.
  std::vector<double> numbersAfter(const TextLine& line, std::string_view label, std::size_t count,
                                   const std::string& description) const {
    if (line.words[0] != label || line.words.size() != count + 1) {
      fail(line.number, "expected " + quoted(label) + " followed by " + description);
    }
    std::vector<double> values;
    for (std::size_t i = 1; i <= count; ++i) {
      const std::optional<double> value = parseDouble(line.words[i]);
      if (!value) fail(line.number, "expected " + quoted(label) + " followed by " + description);
      values.push_back(*value);
    }
    return values;
  }

  int countAfter(const TextLine& line, std::string_view label, const std::string& what) const {
    std::optional<int> count;
    if (line.words[0] == label && line.words.size() == 2) count = parseInt(line.words[1]);
    if (!count || *count < 0)
      fail(line.number, "expected " + quoted(label) + " followed by " + what);
    return *count;
  }

  // The text after the label, trimmed (names may contain spaces).
  static std::string restAfterLabel(const TextLine& line) {
    const std::size_t labelEnd =
        static_cast<std::size_t>(line.words[0].data() + line.words[0].size() - line.text.data());
    std::string_view rest = line.text.substr(labelEnd);
    const std::size_t first = rest.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return std::string();
    rest = rest.substr(first);
    return std::string(rest.substr(0, rest.find_last_not_of(" \t\r") + 1));
  }

  // Skips the `m` lines of a `markers: m` block: editor marks with no meaning for cpfg.
  void skipMarkers(const TextLine& markersLine) {
    const int count = countAfter(markersLine, "markers:", "a count");
    for (int i = 0; i < count; ++i) take("marker " + std::to_string(i + 1));
  }
};

std::string readFile(const std::filesystem::path& file, const std::string& kind) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file.string()), 0, 0},
                          "cannot open " + kind + " file");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// cpfg reads control points into float variables; the B-spline is then computed in double.
// Keeping the rounding makes func() agree with cpfg in the last printed digit (tools-LilyLeaf).
double asStoredByCpfg(double value) {
  return static_cast<double>(static_cast<float>(value));
}

// ---------------------------------------------------------------------------------------------
// Function files.

struct FunctionData {
  std::string name;
  int samples = 0;
  std::vector<std::array<double, 2>> points;
  CurveFileBlock block;  // the rows as written, for the editors
};

// `points: n` and the n rows `x y [multiplicity]` after it.
void readFunctionPoints(CurveFileReader& reader, const TextLine& pointsLine, FunctionData& data) {
  const int count = reader.countAfter(pointsLine, "points:", "a count");
  for (int i = 0; i < count; ++i) {
    const TextLine& row =
        reader.take("control point " + std::to_string(i + 1) + " of " + std::to_string(count));
    const std::string expected =
        "control point " + std::to_string(i + 1) + " as 'x y' or 'x y multiplicity'";
    if (row.words.size() != 2 && row.words.size() != 3)
      reader.fail(row.number, "expected " + expected);
    const std::optional<double> x = parseDouble(row.words[0]);
    const std::optional<double> y = parseDouble(row.words[1]);
    if (!x || !y) reader.fail(row.number, "expected " + expected);
    int multiplicity = 1;
    if (row.words.size() == 3) {
      const std::optional<int> m = parseInt(row.words[2]);
      if (!m || *m < 1 || *m > kMaxMultiplicity) {
        reader.fail(row.number,
                    "expected a multiplicity from 1 to " + std::to_string(kMaxMultiplicity));
      }
      multiplicity = *m;
    }
    for (int k = 0; k < multiplicity; ++k) {
      data.points.push_back({asStoredByCpfg(*x), asStoredByCpfg(*y)});
    }
    data.block.rows.push_back({{*x, *y, 0.0}, multiplicity, row.words.size() == 3, row.number});
  }
  data.block.form = CurveFileBlock::Form::Function;
  data.block.countLine = pointsLine.number;
  data.block.name = data.name;
  if (data.points.size() < 4) {
    reader.fail(pointsLine.number,
                "a function needs at least 4 control points (counting multiplicities), found " +
                    std::to_string(data.points.size()));
  }
}

// funcedit v1.01 (`fver 1 1`): name, samples, optional background and markers, flip, points.
// The file's own `samples:` is used; the count on the view's `function:` line is ignored.
FunctionData readVersion1Function(CurveFileReader& reader) {
  const TextLine& header = reader.take("'fver 1 1'");
  if (header.words.size() != 3 || header.words[0] != "fver" || header.words[1] != "1" ||
      !parseInt(header.words[2])) {
    reader.fail(header.number, "expected 'fver 1 1' at the start of a function");
  }
  FunctionData data;
  bool hasName = false;
  bool hasSamples = false;
  for (;;) {
    const TextLine& line = reader.take("'points:'");
    const std::string_view label = line.words[0];
    if (label == "name:") {
      data.name = CurveFileReader::restAfterLabel(line);
      hasName = true;
    } else if (label == "samples:") {
      data.samples = reader.countAfter(line, "samples:", "a count");
      if (data.samples > kMaxCurveSamples) {
        reader.fail(line.number, "at most " + std::to_string(kMaxCurveSamples) +
                                     " samples, found " + std::to_string(data.samples));
      }
      hasSamples = true;
    } else if (label == "flip:") {
      if (line.words.size() != 2)
        reader.fail(line.number, "expected 'flip:' followed by on or off");
    } else if (label == "background:") {
      // The editor's backdrop image; nothing for cpfg.
    } else if (label == "backgroundXY:") {
      reader.numbersAfter(line, "backgroundXY:", 2, "two coordinates");
    } else if (label == "markers:") {
      reader.skipMarkers(line);
    } else if (label == "points:") {
      if (!hasName) reader.fail(line.number, "missing 'name:' before 'points:'");
      if (!hasSamples) reader.fail(line.number, "missing 'samples:' before 'points:'");
      readFunctionPoints(reader, line, data);
      return data;
    } else {
      reader.fail(line.number,
                  "unexpected " + quoted(label) + " in a function; expected 'points:'");
    }
  }
}

// funcedit v1.0: `range: a b`, `points: n`, points. cpfg ignores the range (the domain is always
// [0, 1]) and takes the sample count from the view's `function:` line.
FunctionData readVersion0Function(CurveFileReader& reader, int viewSamples) {
  const TextLine& rangeLine = reader.take("'range:'");
  reader.numbersAfter(rangeLine, "range:", 2, "two numbers");
  FunctionData data;
  data.samples = viewSamples;
  readFunctionPoints(reader, reader.take("'points:'"), data);
  return data;
}

FunctionData readFunction(CurveFileReader& reader, int viewSamples) {
  if (reader.atEnd()) reader.fail(1, "empty function file; expected 'fver 1 1' or 'range:'");
  const std::string_view first = reader.peek().words[0];
  if (first == "fver") return readVersion1Function(reader);
  if (first == "range:") return readVersion0Function(reader, viewSamples);
  reader.fail(reader.peek().number, "expected 'fver 1 1' or 'range:' at the start of a function");
}

void expectEnd(const CurveFileReader& reader, const std::string& what) {
  if (!reader.atEnd()) {
    reader.fail(reader.peek().number,
                "unexpected " + quoted(reader.peek().words[0]) + " after " + what);
  }
}

FunctionData readFunctionText(std::string_view text, const std::string& fileName, int viewSamples) {
  CurveFileReader reader(text, fileName);
  FunctionData data = readFunction(reader, viewSamples);
  expectEnd(reader, "the last control point");
  return data;
}

std::vector<FunctionData> readFunctionSetText(std::string_view text, const std::string& fileName) {
  CurveFileReader reader(text, fileName);
  const TextLine& header = reader.take("'funcgalleryver 1 1'");
  if (header.words.size() != 3 || header.words[0] != "funcgalleryver" || header.words[1] != "1") {
    reader.fail(header.number, "expected 'funcgalleryver 1 1' at the start of a function set");
  }
  const int count = reader.countAfter(reader.take("'items:'"), "items:", "a count");
  std::vector<FunctionData> functions;
  for (int i = 0; i < count; ++i) {
    if (reader.atEnd()) {
      reader.take("function " + std::to_string(i + 1) + " of " + std::to_string(count));
    }
    // Each item is a complete v1.01 function with its own sample count, or (cpfg accepts it) a
    // version 0 function, which gets a table of 100 samples.
    const std::string_view first = reader.peek().words[0];
    if (first != "fver" && first != "range:") {
      reader.fail(reader.peek().number,
                  "expected 'fver 1 1' or 'range:' at the start of function " +
                      std::to_string(i + 1) + " of " + std::to_string(count));
    }
    constexpr int kVersion0ItemSamples = 100;
    functions.push_back(first == "fver" ? readVersion1Function(reader)
                                        : readVersion0Function(reader, kVersion0ItemSamples));
  }
  expectEnd(reader, "the last of the " + std::to_string(count) + " functions");
  return functions;
}

// ---------------------------------------------------------------------------------------------
// Contour files.

struct ContourData {
  std::string name;
  bool closed = false;
  std::vector<std::array<double, 3>> points;
  CurveFileBlock block;  // the rows as written, for the editors
};

bool contourTypeIsClosed(const CurveFileReader& reader, const TextLine& line) {
  if (line.words.size() == 2) {
    const std::string_view type = line.words[1];
    // cuspy: or/cr open/closed regular; the deprecated oe/ce (endpoint interpolation) are read
    // as regular by cpfg; cver 1.1 spells them open/closed.
    if (type == "or" || type == "oe" || type == "open") return false;
    if (type == "cr" || type == "ce" || type == "closed") return true;
  }
  reader.fail(line.number, "expected 'type:' followed by or, cr, oe, ce, open or closed");
}

// A control-point row of `dimension` numbers: x y, x y z or x y z multiplicity.
void readContourRow(const CurveFileReader& reader, const TextLine& row, std::size_t dimension,
                    ContourData& data) {
  const std::string expected = dimension == 4   ? "'x y z multiplicity'"
                               : dimension == 3 ? "'x y z'"
                                                : "'x y'";
  if (row.words.size() != dimension)
    reader.fail(row.number, "expected a control point as " + expected);
  std::array<double, 3> point{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < std::min<std::size_t>(dimension, 3); ++i) {
    const std::optional<double> value = parseDouble(row.words[i]);
    if (!value) reader.fail(row.number, "expected a control point as " + expected);
    point[i] = *value;
  }
  int multiplicity = 1;
  if (dimension == 4) {
    const std::optional<int> m = parseInt(row.words[3]);
    if (!m || *m < 1 || *m > kMaxMultiplicity) {
      reader.fail(row.number,
                  "expected a multiplicity from 1 to " + std::to_string(kMaxMultiplicity));
    }
    multiplicity = *m;
  }
  for (int k = 0; k < multiplicity; ++k) data.points.push_back(point);
  data.block.columns = static_cast<int>(dimension);
  data.block.rows.push_back({point, multiplicity, dimension == 4, row.number});
}

bool startsWithNumber(const TextLine& line) {
  return parseDouble(line.words[0]).has_value();
}

// cuspy `cver 1 x`: labelled lines (name, points n1 n2, type, samples, background, markers) and
// n1 rows `x y z multiplicity`. cver 1.3 puts type and samples before the rows, 1.1 and 1.2 put
// type after them, so labels are accepted in any order around the rows.
ContourData readCverContour(CurveFileReader& reader) {
  const TextLine& header = reader.take("'cver 1 3'");
  if (header.words.size() != 3 || header.words[1] != "1" || !parseInt(header.words[2])) {
    reader.fail(header.number, "expected 'cver 1 n' at the start of a contour");
  }
  ContourData data;
  std::optional<int> pointsLineNumber;
  int distinctPoints = 0;
  int totalPoints = 0;
  int rows = 0;
  bool hasType = false;
  while (!reader.atEnd()) {
    const TextLine& line = reader.take("a line");
    const std::string_view label = line.words[0];
    if (startsWithNumber(line)) {
      if (!pointsLineNumber) reader.fail(line.number, "control point before 'points:'");
      if (rows == distinctPoints) {
        reader.fail(line.number, "more control points than the " + std::to_string(distinctPoints) +
                                     " given by 'points:'");
      }
      readContourRow(reader, line, 4, data);
      ++rows;
    } else if (label == "name:") {
      data.name = CurveFileReader::restAfterLabel(line);
    } else if (label == "points:") {
      std::optional<int> distinct;
      std::optional<int> total;
      if (line.words.size() == 3) {
        distinct = parseInt(line.words[1]);
        total = parseInt(line.words[2]);
      }
      if (!distinct || !total || *distinct < 1 || *total < *distinct) {
        reader.fail(line.number,
                    "expected 'points:' followed by the number of points and their total "
                    "multiplicity");
      }
      distinctPoints = *distinct;
      totalPoints = *total;
      pointsLineNumber = line.number;
    } else if (label == "type:") {
      data.closed = contourTypeIsClosed(reader, line);
      hasType = true;
    } else if (label == "samples:") {
      // cpfg reads it and ignores it: the sample count comes from the view file.
      reader.countAfter(line, "samples:", "a count");
    } else if (label == "background:") {
      // The editor's backdrop image; nothing for cpfg.
    } else if (label == "backgroundXY:") {
      reader.numbersAfter(line, "backgroundXY:", 2, "two coordinates");
    } else if (label == "markers:") {
      reader.skipMarkers(line);
    } else {
      reader.fail(line.number, "unexpected " + quoted(label) + " in a contour");
    }
  }
  if (!pointsLineNumber) reader.fail(header.number, "missing 'points:' in the contour");
  if (rows != distinctPoints) {
    reader.fail(*pointsLineNumber, "'points:' announces " + std::to_string(distinctPoints) +
                                       " control points, the file has " + std::to_string(rows));
  }
  if (static_cast<int>(data.points.size()) != totalPoints) {
    reader.fail(*pointsLineNumber, "'points:' announces a total multiplicity of " +
                                       std::to_string(totalPoints) + ", the rows add up to " +
                                       std::to_string(data.points.size()));
  }
  if (!hasType) reader.fail(header.number, "missing 'type:' in the contour");
  data.block.form = CurveFileBlock::Form::Cver;
  data.block.countLine = *pointsLineNumber;
  return data;
}

// The older curve format (`version: 1.4`, as cpfg-Ridley's profile.con): labelled lines
// contact, end, heading, up, size, points, range, dimension, type, then the rows. cpfg's curveX/Y
// use the rows as they are (Ridley's positions match only untransformed), so the placement labels
// are read and not applied; with dimension 4 the fourth number is the multiplicity.
ContourData readVersion14Curve(CurveFileReader& reader) {
  const TextLine& header = reader.take("'version:'");
  if (header.words.size() != 2 || !parseDouble(header.words[1])) {
    reader.fail(header.number, "expected 'version:' followed by a number");
  }
  ContourData data;
  std::optional<int> pointsLineNumber;
  int count = 0;
  int rows = 0;
  std::size_t dimension = 3;
  while (!reader.atEnd()) {
    const TextLine& line = reader.take("a line");
    const std::string_view label = line.words[0];
    if (startsWithNumber(line)) {
      if (!pointsLineNumber) reader.fail(line.number, "control point before 'points:'");
      if (rows == count) {
        reader.fail(line.number, "more control points than the " + std::to_string(count) +
                                     " given by 'points:'");
      }
      readContourRow(reader, line, dimension, data);
      ++rows;
    } else if (label == "contact:" || label == "end:" || label == "heading:" || label == "up:") {
      reader.numbersAfter(line, label, 3, "three coordinates");
    } else if (label == "size:") {
      reader.numbersAfter(line, "size:", 1, "a number");
    } else if (label == "range:") {
      reader.numbersAfter(line, "range:", 2, "two numbers");
    } else if (label == "dimension:") {
      const int value = reader.countAfter(line, "dimension:", "2, 3 or 4");
      if (value < 2 || value > 4)
        reader.fail(line.number, "expected 'dimension:' followed by 2, 3 or 4");
      if (rows > 0) reader.fail(line.number, "'dimension:' must come before the control points");
      dimension = static_cast<std::size_t>(value);
    } else if (label == "type:") {
      if (line.words.size() != 2 || line.words[1] != "bspline") {
        reader.fail(line.number, "expected 'type: bspline'");
      }
    } else if (label == "points:") {
      count = reader.countAfter(line, "points:", "a count");
      pointsLineNumber = line.number;
    } else {
      reader.fail(line.number, "unexpected " + quoted(label) + " in a curve");
    }
  }
  if (!pointsLineNumber) reader.fail(header.number, "missing 'points:' in the curve");
  if (rows != count) {
    reader.fail(*pointsLineNumber, "'points:' announces " + std::to_string(count) +
                                       " control points, the file has " + std::to_string(rows));
  }
  data.block.form = CurveFileBlock::Form::Version14;
  data.block.countLine = *pointsLineNumber;
  return data;
}

// cuspy v1.0: a header `n dim open|closed`, then n rows of dim coordinates.
ContourData readVersion10Contour(CurveFileReader& reader) {
  const TextLine& header = reader.take("a header");
  std::optional<int> count;
  std::optional<int> dimension;
  if (header.words.size() == 3) {
    count = parseInt(header.words[0]);
    dimension = parseInt(header.words[1]);
  }
  const bool typeKnown =
      header.words.size() == 3 && (header.words[2] == "open" || header.words[2] == "closed");
  if (!count || !dimension || *count < 1 || (*dimension != 2 && *dimension != 3) || !typeKnown) {
    reader.fail(header.number,
                "expected 'cver 1 3', 'version:' or a header 'count dimension open|closed'");
  }
  ContourData data;
  data.closed = header.words[2] == "closed";
  for (int i = 0; i < *count; ++i) {
    readContourRow(reader, reader.take("control point " + std::to_string(i + 1)),
                   static_cast<std::size_t>(*dimension), data);
  }
  expectEnd(reader, "the last control point");
  data.block.form = CurveFileBlock::Form::Version10;
  data.block.countLine = header.number;
  return data;
}

ContourData readContour(CurveFileReader& reader) {
  if (reader.atEnd()) reader.fail(1, "empty contour file");
  const std::string_view first = reader.peek().words[0];
  ContourData data;
  if (first == "cver") {
    data = readCverContour(reader);
  } else if (first == "version:") {
    data = readVersion14Curve(reader);
  } else {
    data = readVersion10Contour(reader);
  }
  const std::size_t needed = data.closed ? 3 : 4;
  if (data.points.size() < needed) {
    reader.fail(1, std::string(data.closed ? "a closed" : "an open") + " contour needs at least " +
                       std::to_string(needed) +
                       " control points (counting multiplicities), found " +
                       std::to_string(data.points.size()));
  }
  data.block.name = data.name;
  data.block.closed = data.closed;
  return data;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dx = b[0] - a[0];
  const double dy = b[1] - a[1];
  const double dz = b[2] - a[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// NaN reads as 0, everything else is clamped to [0, 1].
double clampUnit(double value) {
  if (!(value > 0.0)) return 0.0;
  return value > 1.0 ? 1.0 : value;
}

// ---------------------------------------------------------------------------------------------
// The view file.

bool isIdentifier(const std::string& word) {
  if (word.empty() || std::isdigit(static_cast<unsigned char>(word[0]))) return false;
  return std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

// The view names a file that is not there.
void requireFile(const SourceLocation& where, const std::string& kind,
                 const std::filesystem::path& path, std::string_view fileName) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw DiagnosticError(where, "cannot open " + kind + " file " + quoted(fileName) +
                                     " (looked for " + path.string() + ")");
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// FunctionCurve

FunctionCurve::FunctionCurve(std::string name, int samples,
                             std::vector<std::array<double, 2>> points)
    : name_(std::move(name)), samples_(samples), points_(std::move(points)) {
  if (samples_ > kMaxCurveSamples) throw std::invalid_argument("too many function samples");
  // cpfg: with more than 2 samples, func() interpolates linearly in a table of `samples` values at
  // x = i/(samples-1) (tools-LeafPosition: the values at 0, 1/3, 2/3, 1 are exact solutions, the
  // ones between are interpolated).
  if (samples_ > 2) {
    table_.reserve(static_cast<std::size_t>(samples_));
    for (int i = 0; i < samples_; ++i) {
      table_.push_back(solveForX(static_cast<double>(i) / (samples_ - 1)));
    }
  }
}

FunctionCurve FunctionCurve::parse(std::string_view text, const std::string& fileName,
                                   int viewSamples) {
  FunctionData data = readFunctionText(text, fileName, viewSamples);
  return FunctionCurve(std::move(data.name), data.samples, std::move(data.points));
}

std::vector<FunctionCurve> FunctionCurve::parseSet(std::string_view text,
                                                   const std::string& fileName) {
  std::vector<FunctionCurve> functions;
  for (FunctionData& data : readFunctionSetText(text, fileName)) {
    functions.push_back(FunctionCurve(std::move(data.name), data.samples, std::move(data.points)));
  }
  return functions;
}

FunctionCurve FunctionCurve::load(const std::filesystem::path& file, int viewSamples) {
  return parse(readFile(file, "function"), file.string(), viewSamples);
}

std::vector<FunctionCurve> FunctionCurve::loadSet(const std::filesystem::path& fset) {
  return parseSet(readFile(fset, "function set"), fset.string());
}

// cpfg (reference/cpfg-functions.md §2.4): the clamped cubic B-spline of the K control points,
// knots U_j = 0 (j < 4), K − 3 (j > K − 1), j − 3 otherwise, at u = m·(K − 3), each basis function
// N_{k,4} by the Cox–de Boor recursion (a term whose knot difference is 0 left out) and the sum
// accumulated from k = 0 upward. The intervals are half-open, so P(1) = (0, 0) as in cpfg; the
// bisection below never asks for it unless the curve does not span x.
std::array<double, 2> FunctionCurve::pointAt(double m) const {
  const int count = static_cast<int>(points_.size());
  const double u = m * (count - 3);
  const auto knot = [count](int j) -> double {
    if (j < 4) return 0.0;
    if (j > count - 1) return count - 3;
    return j - 3;
  };
  // basis[k] holds N_{k,r}(u) for k = 0 … count + 3 − r, order r = 1 … 4 in turn.
  constexpr int kOnStack = 64;
  std::array<double, kOnStack> onStack;
  std::vector<double> onHeap;
  double* basis = onStack.data();
  if (count + 3 > kOnStack) {
    onHeap.resize(static_cast<std::size_t>(count + 3));
    basis = onHeap.data();
  }
  for (int k = 0; k < count + 3; ++k) basis[k] = knot(k) <= u && u < knot(k + 1) ? 1.0 : 0.0;
  for (int r = 2; r <= 4; ++r) {
    for (int k = 0; k < count + 4 - r; ++k) {
      double value = 0.0;
      const double left = knot(k + r - 1) - knot(k);
      if (left != 0.0) value = (u - knot(k)) / left * basis[k];
      const double right = knot(k + r) - knot(k + 1);
      if (right != 0.0) value += (knot(k + r) - u) / right * basis[k + 1];
      basis[k] = value;
    }
  }
  std::array<double, 2> p{0.0, 0.0};
  for (int k = 0; k < count; ++k) {
    p[0] += points_[k][0] * basis[k];
    p[1] += points_[k][1] * basis[k];
  }
  return p;
}

// cpfg (§2.4): bisection on the curve parameter, starting at its middle, until x(m) is within
// kTolerance of x; y there is the value. The answer is therefore off by up to the tolerance even
// at the ends (func(1,1) of tools-LeafRandom's internode is 1.00316, the last point 1.003176).
// cpfg loops forever when x is out of reach (a curve not spanning [0, 1]); here the bisection
// ends where the parameter interval stops shrinking, at the nearest end.
double FunctionCurve::solveForX(double x) const {
  constexpr int kMaxSteps = 80;  // enough to exhaust a double's precision on [0, 1]
  double low = 0.0;
  double high = 1.0;
  std::array<double, 2> p{};
  for (int step = 0; step < kMaxSteps; ++step) {
    const double m = (low + high) / 2.0;
    p = pointAt(m);
    if (std::fabs(p[0] - x) <= kTolerance) break;
    if (p[0] > x) {
      high = m;
    } else {
      low = m;
    }
  }
  return p[1];
}

// cpfg (§2.5): the table entries around index = x·(S − 1), weighted (1 − index + i) and
// (index − i), in that order.
double FunctionCurve::evaluate(double x) const {
  x = clampUnit(x);
  if (table_.empty()) return solveForX(x);
  const double index = x * (samples_ - 1);
  const int i = static_cast<int>(std::floor(index));
  if (i >= samples_ - 1) return table_.back();
  const double below = (1.0 - index) + i;
  const double above = index - i;
  return below * table_[i] + above * table_[i + 1];
}

// ---------------------------------------------------------------------------------------------
// ContourCurve

ContourCurve::ContourCurve(std::string name, bool closed, std::vector<std::array<double, 3>> points,
                           int samples)
    : name_(std::move(name)), closed_(closed), points_(std::move(points)), samples_(samples) {
  if (samples_ < 2 || samples_ > kMaxCurveSamples) {
    throw std::invalid_argument("a curve needs 2 to kMaxCurveSamples samples");
  }
  // cpfg (reference/cpfg-functions.md §3.4): the curve is sampled at t_i = i/(S − 1), the 3-D
  // chord lengths summed; curveGAL is that polyline's length and the table is normalised by it
  // (cpfg-Ridley: with 100 samples the 495 primordia land where cpfg put them, with 99 or 101
  // they do not).
  std::vector<double> running;
  running.reserve(static_cast<std::size_t>(samples_));
  running.push_back(0.0);
  std::array<double, 3> previous = pointAtParameter(0.0);
  for (int i = 1; i < samples_; ++i) {
    const std::array<double, 3> current = pointAtParameter(static_cast<double>(i) / (samples_ - 1));
    running.push_back(running.back() + distance(previous, current));
    previous = current;
  }
  length_ = running.back();
  lengthFraction_.reserve(running.size());
  // A curve of coinciding points has no length; its table stays 0 (cpfg divides by 0).
  for (const double l : running) lengthFraction_.push_back(length_ > 0.0 ? l / length_ : 0.0);
}

ContourCurve ContourCurve::parse(std::string_view text, const std::string& fileName, int samples) {
  CurveFileReader reader(text, fileName);
  ContourData data = readContour(reader);
  return ContourCurve(std::move(data.name), data.closed, std::move(data.points), samples);
}

ContourCurve ContourCurve::load(const std::filesystem::path& file, int samples) {
  return parse(readFile(file, "contour"), file.string(), samples);
}

// cpfg (§3.2, §3.3): a closed curve is its points followed by the first three again, so
// n = N + 3; the parameter t ∈ [0, 1] maps to u = 3 + t·(n − 3.000001) on integer knots, the
// constant keeping the segment index in range at t = 1 (so t = 1 is at local parameter 0.999999
// of the last segment). Each of the segment's four basis functions comes from the Cox–de Boor
// recursion, and the terms are summed left to right.
std::array<double, 3> ContourCurve::pointAtParameter(double t) const {
  const int distinct = static_cast<int>(points_.size());
  const int count = closed_ ? distinct + 3 : distinct;
  const double scale = count - 3.000001;
  const int segment = std::clamp(3 + static_cast<int>(t * scale), 3, count - 1);
  const double u = 3 + t * scale;
  // basis[j] is B_{segment−3+j, r}(u), j = 0 … 6 − (r − 1), for r = 1 … 4 in turn.
  std::array<double, 7> basis{};
  for (int j = 0; j < 7; ++j) {
    const double knot = segment - 3 + j;
    basis[j] = knot <= u && u < knot + 1 ? 1.0 : 0.0;
  }
  for (int r = 2; r <= 4; ++r) {
    for (int j = 0; j + r <= 7; ++j) {
      const double knot = segment - 3 + j;
      basis[j] = (u - knot) / (r - 1) * basis[j] + (knot + r - u) / (r - 1) * basis[j + 1];
    }
  }
  std::array<double, 3> p{0.0, 0.0, 0.0};
  for (int j = 0; j < 4; ++j) {
    const std::array<double, 3>& control = points_[(segment - 3 + j) % distinct];
    for (int k = 0; k < 3; ++k) p[k] += control[k] * basis[j];
  }
  return p;
}

// cpfg (§3.5): t is located in the normalised length table by bisection (λ_lo ≤ t < λ_hi, the
// last interval at t = 1), the curve parameter interpolated linearly between the two samples,
// and the spline evaluated exactly there. (Interpolating the sampled positions instead leaves
// cpfg-Ridley's primordia up to 1e-4 off along the curve.)
std::array<double, 3> ContourCurve::point(double t) const {
  t = clampUnit(t);
  int low = 0;
  int high = samples_ - 1;
  while (high - low > 1) {
    const int middle = (low + high) / 2;
    if (lengthFraction_[middle] > t) {
      high = middle;
    } else {
      low = middle;
    }
  }
  const double chord = lengthFraction_[high] - lengthFraction_[low];
  // A zero-length chord divides by 0 in cpfg; here it reads as the sample itself.
  const double fraction = chord != 0.0 ? (t - lengthFraction_[low]) / chord : 0.0;
  return pointAtParameter((low + fraction) / (samples_ - 1));
}

// ---------------------------------------------------------------------------------------------
// CurveFile

namespace {

// The line with word `index` (0-based, blank-separated) replaced by `value`, the blanks kept.
std::string withWord(const std::string& line, std::size_t index, const std::string& value) {
  std::size_t position = 0;
  for (std::size_t word = 0;; ++word) {
    position = line.find_first_not_of(" \t\r", position);
    if (position == std::string::npos) return line;
    const std::size_t end = std::min(line.find_first_of(" \t\r", position), line.size());
    if (word == index) return line.substr(0, position) + value + line.substr(end);
    position = end;
  }
}

}  // namespace

CurveFile CurveFile::parse(std::string_view text, const std::string& fileName, Kind kind) {
  CurveFile file(kind, fileName);
  file.reread(EditedText::split(text));  // with no text yet, a broken one throws
  return file;
}

CurveFile CurveFile::load(const std::filesystem::path& file, Kind kind) {
  return parse(readFile(file, kind == Kind::Contour ? "contour" : "function"), file.string(), kind);
}

// Reads `edited` with the readers; on success it becomes the file's text. A broken text throws
// the first time (no text yet) and is refused with its message afterwards.
std::string CurveFile::reread(EditedText edited) {
  const std::string text = edited.joined();
  std::vector<CurveFileBlock> blocks;
  try {
    if (kind_ == Kind::Function) {
      blocks.push_back(readFunctionText(text, fileName_, 0).block);
    } else if (kind_ == Kind::FunctionSet) {
      for (FunctionData& data : readFunctionSetText(text, fileName_))
        blocks.push_back(std::move(data.block));
    } else {
      CurveFileReader reader(text, fileName_);
      blocks.push_back(readContour(reader).block);
    }
  } catch (const DiagnosticError& error) {
    if (text_.lines.empty()) throw;
    return error.diagnostic().text();
  }
  text_ = std::move(edited);
  blocks_ = std::move(blocks);
  return std::string();
}

std::string CurveFile::rowText(const CurveFileBlock& block, const CurveFileRow& row) const {
  // funcedit and cuspy write "%f"; a value with more digits keeps them (edited_text.h).
  const int coordinates =
      block.form == CurveFileBlock::Form::Function ? 2 : std::min(block.columns, 3);
  std::string text;
  for (int i = 0; i < coordinates; ++i) {
    if (i > 0) text += ' ';
    text += formatFixed(row.point[static_cast<std::size_t>(i)], 6);
  }
  if (row.multiplicityWritten) text += ' ' + std::to_string(row.multiplicity);
  return text;
}

std::string CurveFile::functionRule(std::size_t block, std::size_t row, double x,
                                    bool inserting) const {
  if (kind_ == Kind::Contour) return std::string();
  const std::vector<CurveFileRow>& rows = blocks_[block].rows;
  if (!(x >= 0.0 && x <= 1.0)) return "a function's x lies in [0, 1]";
  if (!inserting && (row == 0 || row + 1 == rows.size()) && x != rows[row].point[0]) {
    return "the first and last points of a function keep their x (the curve spans [0, 1])";
  }
  const double low = row == 0 ? 0.0 : rows[row - 1].point[0];
  const std::size_t next = inserting ? row : row + 1;
  const double high = next < rows.size() ? rows[next].point[0] : 1.0;
  if (inserting && (row == 0 || row == rows.size()))
    return "a new point goes between two points of the function";
  if (x < low || x > high) {
    return "x must stay between its neighbours' (" + formatFixed(low, 1) + " to " +
           formatFixed(high, 1) + "), so that y(x) stays a function";
  }
  return std::string();
}

std::string CurveFile::setPoint(std::size_t block, std::size_t row, std::array<double, 3> point) {
  if (block >= blocks_.size() || row >= blocks_[block].rows.size()) return "no such point";
  if (std::string rule = functionRule(block, row, point[0], false); !rule.empty()) return rule;
  const CurveFileBlock& edited = blocks_[block];
  CurveFileRow changed = edited.rows[row];
  if (edited.form == CurveFileBlock::Form::Function || edited.columns == 2) point[2] = 0.0;
  changed.point = point;
  EditedText text = text_;
  text.lines[static_cast<std::size_t>(changed.line - 1)] = rowText(edited, changed);
  return reread(std::move(text));
}

namespace {

// The count line of `block` with `rows` rows of `total` multiplicity.
std::string countLineText(const CurveFileBlock& block, const std::string& line, int rows,
                          int total) {
  switch (block.form) {
    case CurveFileBlock::Form::Cver:
      return withWord(withWord(line, 1, std::to_string(rows)), 2, std::to_string(total));
    case CurveFileBlock::Form::Version10:
      return withWord(line, 0, std::to_string(rows));
    default:
      return withWord(line, 1, std::to_string(rows));
  }
}

int totalMultiplicity(const CurveFileBlock& block) {
  int total = 0;
  for (const CurveFileRow& row : block.rows) total += row.multiplicity;
  return total;
}

}  // namespace

std::string CurveFile::insertPoint(std::size_t block, std::size_t row,
                                   std::array<double, 3> point) {
  if (block >= blocks_.size() || row > blocks_[block].rows.size()) return "no such point";
  if (std::string rule = functionRule(block, row, point[0], true); !rule.empty()) return rule;
  const CurveFileBlock& edited = blocks_[block];
  const int rows = static_cast<int>(edited.rows.size());
  CurveFileRow added;
  added.point = point;
  if (edited.form == CurveFileBlock::Form::Function || edited.columns == 2) added.point[2] = 0.0;
  // The new row takes the multiplicity column its neighbour has.
  const CurveFileRow& neighbour = edited.rows[std::min<std::size_t>(row, edited.rows.size() - 1)];
  added.multiplicityWritten = neighbour.multiplicityWritten;
  // Inserted after the line of the row before it, or before the first row's line.
  const std::size_t at = row == 0 ? static_cast<std::size_t>(edited.rows[0].line - 1)
                                  : static_cast<std::size_t>(edited.rows[row - 1].line);
  EditedText text = text_;
  std::string& count = text.lines[static_cast<std::size_t>(edited.countLine - 1)];
  count = countLineText(edited, count, rows + 1, totalMultiplicity(edited) + 1);
  text.lines.insert(text.lines.begin() + static_cast<std::ptrdiff_t>(at), rowText(edited, added));
  return reread(std::move(text));
}

std::string CurveFile::removePoint(std::size_t block, std::size_t row) {
  if (block >= blocks_.size() || row >= blocks_[block].rows.size()) return "no such point";
  const CurveFileBlock& edited = blocks_[block];
  if (kind_ != Kind::Contour && (row == 0 || row + 1 == edited.rows.size()))
    return "the first and last points of a function stay (the curve spans [0, 1])";
  const int rows = static_cast<int>(edited.rows.size());
  EditedText text = text_;
  std::string& count = text.lines[static_cast<std::size_t>(edited.countLine - 1)];
  count = countLineText(edited, count, rows - 1,
                        totalMultiplicity(edited) - edited.rows[row].multiplicity);
  text.lines.erase(text.lines.begin() + edited.rows[row].line - 1);
  return reread(std::move(text));
}

FunctionCurve CurveFile::function(std::size_t block, int viewSamples) const {
  if (kind_ == Kind::FunctionSet) return FunctionCurve::parseSet(text(), fileName_).at(block);
  return FunctionCurve::parse(text(), fileName_, viewSamples);
}

ContourCurve CurveFile::contour(int samples) const {
  return ContourCurve::parse(text(), fileName_, samples);
}

// ---------------------------------------------------------------------------------------------
// readViewFunctions

ViewFunctions readViewFunctions(const std::string& preprocessedViewText,
                                const std::filesystem::path& viewFile) {
  ViewFunctions out;
  const std::filesystem::path folder = viewFile.parent_path();
  for (const ViewFileLine& line : viewFileLines(preprocessedViewText, viewFile)) {
    const bool isFunction = line.label == "function:";
    const bool isFunctionSet = line.label == "function set:";
    const bool isCurve = line.label == "curve:";
    if (!isFunction && !isFunctionSet && !isCurve) continue;

    const std::vector<ViewWord> arguments = viewWords(line);
    if (arguments.empty()) {
      throw DiagnosticError(line.where, "expected a file name after " + quoted(line.label));
    }
    const auto argumentAt = [&line](const ViewWord& word) {
      return SourceLocation{line.where.file, line.where.line, word.column};
    };
    const std::string_view fileName = arguments[0].text;
    const SourceLocation fileAt = argumentAt(arguments[0]);
    std::optional<int> samples;
    if (isFunctionSet == false && arguments.size() > 1) {
      samples = parseInt(arguments[1].text);
      if (!samples) {
        throw DiagnosticError(
            argumentAt(arguments[1]),
            "expected a sample count after the file name, found " + quoted(arguments[1].text));
      }
      if (*samples > kMaxCurveSamples) {
        throw DiagnosticError(argumentAt(arguments[1]),
                              "at most " + std::to_string(kMaxCurveSamples) + " samples, found " +
                                  std::to_string(*samples));
      }
    }
    // The file must stay beneath the view file's folder (model_folder.h).
    const ModelFolder modelFolder(folder);
    const std::string refused = modelFolder.refusal(std::string(fileName));
    if (!refused.empty())
      throw DiagnosticError(fileAt, "cannot open " + quoted(fileName) + ": " + refused);
    const std::filesystem::path path = modelFolder.pathOf(std::string(fileName));

    requireFile(fileAt,
                isFunction      ? "function"
                : isFunctionSet ? "function set"
                                : "curve",
                path, fileName);
    if (isFunction) {
      try {
        out.functions.push_back(FunctionCurve::load(path, samples.value_or(0)));
        out.functionFiles.push_back(path);
        out.functionSamples.push_back(samples.value_or(0));
      } catch (const DiagnosticError& error) {
        rethrowAtViewLine(fileAt, "function", fileName, error);
      }
    } else if (isFunctionSet) {
      // cpfg: `function set:` replaces the function list; its names become preprocessor macros.
      try {
        out.functions = FunctionCurve::loadSet(path);
        out.functionFiles = {path};
        out.functionSamples = {0};
      } catch (const DiagnosticError& error) {
        rethrowAtViewLine(fileAt, "function set", fileName, error);
      }
      out.macroDefinitions.clear();
      for (std::size_t i = 0; i < out.functions.size(); ++i) {
        // A name that is no identifier (`leaf-length`) cannot be a macro; it is left out rather
        // than handed to the preprocessor as a broken -D.
        if (isIdentifier(out.functions[i].name())) {
          out.macroDefinitions.emplace_back(out.functions[i].name(), std::to_string(i + 1));
        }
      }
    } else {
      const int curveSamples = samples.value_or(ContourCurve::kDefaultSamples);
      if (curveSamples < 2) {
        throw DiagnosticError(argumentAt(arguments[1]), "a curve needs at least 2 samples, found " +
                                                            std::to_string(curveSamples));
      }
      try {
        out.curves.push_back(ContourCurve::load(path, curveSamples));
        out.curveFiles.push_back(path);
      } catch (const DiagnosticError& error) {
        rethrowAtViewLine(fileAt, "curve", fileName, error);
      }
    }
  }
  return out;
}

}  // namespace hirsute
