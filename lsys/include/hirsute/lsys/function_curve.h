// User functions and curves of a cpfg model: the `.func`/`.fset` files behind `func(id, x)` and
// the `.con` files behind `curveX/curveY/curveZ(id, t)` and `curveGAL(id)`, as named by the
// view file's `function:`, `function set:` and `curve:` lines.
//
// The numbers these return feed module parameters, so they follow cpfg's arithmetic, not just its
// intent: both were checked against cpfg's output for tools-LeafPosition, tools-LilyLeaf and
// cpfg-Ridley in the conformance set.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hirsute/core/edited_text.h"

namespace hirsute {

// The most samples a function table or a curve may have: far above any model (cpfg's defaults
// are 100), low enough that a stray digit in a file cannot exhaust memory.
inline constexpr int kMaxCurveSamples = 1000000;

// A function y(x) on [0, 1] drawn with vlab's funcedit: a clamped uniform cubic B-spline whose
// control points have non-decreasing x.
class FunctionCurve {
 public:
  // cpfg: y(x) is found by bisection until x(u) is within this distance of x.
  static constexpr double kTolerance = 1e-3;

  // Reads a `.func` file. `viewSamples` is the count given on the view file's `function:` line
  // (0 when absent); cpfg uses it only for version 0 files, v1.01 files carry their own. More
  // than kMaxCurveSamples is a programming error (std::invalid_argument); the view reader
  // reports it first. Throws DiagnosticError at the line of the file where it is broken.
  static FunctionCurve load(const std::filesystem::path& file, int viewSamples);
  // Reads a `.fset` function gallery: the functions in file order (ids 1, 2, …).
  static std::vector<FunctionCurve> loadSet(const std::filesystem::path& fset);

  // The same from text already in memory; `fileName` is used in messages.
  static FunctionCurve parse(std::string_view text, const std::string& fileName, int viewSamples);
  static std::vector<FunctionCurve> parseSet(std::string_view text, const std::string& fileName);

  // The `name:` of the file; empty for version 0 files, which have none.
  const std::string& name() const { return name_; }
  // The number of precomputed values; evaluation interpolates them when there are more than 2.
  int samples() const { return samples_; }
  // Control points with multiplicities expanded, as cpfg stores them (float precision).
  const std::vector<std::array<double, 2>>& controlPoints() const { return points_; }

  // y at x, with x clamped to [0, 1] (NaN reads as 0).
  double evaluate(double x) const;

 private:
  FunctionCurve(std::string name, int samples, std::vector<std::array<double, 2>> points);
  std::array<double, 2> pointAt(double m) const;  // m in [0, 1] over the whole curve
  double solveForX(double x) const;

  std::string name_;
  int samples_ = 0;
  std::vector<std::array<double, 2>> points_;
  std::vector<double> table_;  // samples_ values at x = i/(samples_-1), when samples_ > 2
};

// A planar or spatial curve drawn with vlab's cuspy (`.con`), used by the view's `curve:` line:
// a uniform cubic B-spline (periodic when closed), measured by arc length.
class ContourCurve {
 public:
  static constexpr int kDefaultSamples = 100;

  // Reads a `.con` file in any of cuspy's versions (cver 1.0 to 1.3, and the older
  // `version: 1.4` curve format). `samples` is the view's count (cpfg ignores the file's); fewer
  // than 2 or more than kMaxCurveSamples is a programming error (std::invalid_argument), the
  // view reader reports it first.
  static ContourCurve load(const std::filesystem::path& file, int samples = kDefaultSamples);
  static ContourCurve parse(std::string_view text, const std::string& fileName,
                            int samples = kDefaultSamples);

  const std::string& name() const { return name_; }
  bool closed() const { return closed_; }
  // Control points with multiplicities expanded.
  const std::vector<std::array<double, 3>>& controlPoints() const { return points_; }

  // The point at arc-length fraction t of the curve, t clamped to [0, 1] (NaN reads as 0).
  std::array<double, 3> point(double t) const;
  // The length of the curve (curveGAL): the polyline through its samples.
  double length() const { return length_; }

 private:
  ContourCurve(std::string name, bool closed, std::vector<std::array<double, 3>> points,
               int samples);
  std::array<double, 3> pointAtParameter(double t) const;  // t in [0, 1], cpfg's scale

  std::string name_;
  bool closed_ = false;
  std::vector<std::array<double, 3>> points_;
  int samples_ = kDefaultSamples;
  double length_ = 0.0;
  // The polyline length up to sample i over the whole length, at samples_ parameters i/(S − 1).
  std::vector<double> lengthFraction_;
};

// The control-point rows of one function or contour as its file writes them, for the viewer's
// editors (docs/viewer.md, "Function curves", "Contours").
struct CurveFileRow {
  std::array<double, 3> point{};  // x y (z) as written, before cpfg's float rounding
  int multiplicity = 1;
  bool multiplicityWritten = false;  // the row has a multiplicity column
  int line = 0;                      // 1-based line of the file
};

struct CurveFileBlock {
  // funcedit (both versions), cuspy `cver 1 n`, the `version: 1.4` curve format, cuspy 1.0's
  // header `n dim open|closed`.
  enum class Form { Function, Cver, Version14, Version10 };
  Form form = Form::Function;
  std::string name;
  bool closed = false;  // contours
  int columns = 2;      // numbers in a contour row: x y, x y z or x y z multiplicity
  int countLine = 0;    // the line that counts the rows (`points:`, or cuspy 1.0's header)
  std::vector<CurveFileRow> rows;
};

// A `.func`, `.fset` or `.con` file as the viewer's editors change it: its lines as written and
// the rows found in them by the readers above. An edit rewrites the rows it changes (and the
// count of rows), then reads the whole text again with those readers, so that the editors show,
// evaluate and save exactly what cpfg will read; every other byte of the file stays as it was.
class CurveFile {
 public:
  enum class Kind { Function, FunctionSet, Contour };

  CurveFile() = default;  // no file (for containers)
  // Throws DiagnosticError at the line where the file is broken (as the derivation would).
  static CurveFile parse(std::string_view text, const std::string& fileName, Kind kind);
  static CurveFile load(const std::filesystem::path& file, Kind kind);

  Kind kind() const { return kind_; }
  const std::string& fileName() const { return fileName_; }
  // One block per function (a set has several) or the contour's one.
  const std::vector<CurveFileBlock>& blocks() const { return blocks_; }
  std::string text() const { return text_.joined(); }

  // The edits: each returns an empty string when made, else why not ("file:line:col: error: …"
  // when the result would not read, or the rule it breaks), the file left as it was. Functions
  // keep x within [0, 1] and in order, and their first and last x where they are (funcedit's
  // rules; cpfg's bisection needs a curve that spans [0, 1]).
  std::string setPoint(std::size_t block, std::size_t row, std::array<double, 3> point);
  // A new row before `row` (the row count: after the last), with multiplicity 1.
  std::string insertPoint(std::size_t block, std::size_t row, std::array<double, 3> point);
  std::string removePoint(std::size_t block, std::size_t row);

  // The function of `block` and the curve as the derivation evaluates them.
  FunctionCurve function(std::size_t block, int viewSamples) const;
  ContourCurve contour(int samples = ContourCurve::kDefaultSamples) const;

 private:
  CurveFile(Kind kind, std::string fileName) : kind_(kind), fileName_(std::move(fileName)) {}
  std::string rowText(const CurveFileBlock& block, const CurveFileRow& row) const;
  std::string functionRule(std::size_t block, std::size_t row, double x, bool inserting) const;
  std::string reread(EditedText edited);

  Kind kind_ = Kind::Function;
  std::string fileName_;
  EditedText text_;
  std::vector<CurveFileBlock> blocks_;
};

// What a view file declares for func() and curveX/Y/Z/GAL().
struct ViewFunctions {
  std::vector<FunctionCurve> functions;  // func id k is functions[k-1]
  std::vector<ContourCurve> curves;      // curve id k is curves[k-1]
  // `function set:` names with their ids ({"growth", "1"}), to define for the `.l` preprocessor.
  std::vector<std::pair<std::string, std::string>> macroDefinitions;
  // The files read, for the viewer's editors: the `function:` files in order, or the
  // `function set:` file; the `curve:` files in order.
  std::vector<std::filesystem::path> functionFiles, curveFiles;
  // The sample count on each `function:` line (0: none given, or a `function set:`).
  std::vector<int> functionSamples;
};

// Reads the `function:`, `function set:` and `curve:` lines of a preprocessed view file and loads
// the files they name (relative to the view file's folder). Line numbers follow the `# n "file"`
// markers of the preprocessor. Throws DiagnosticError at the view line for a missing or broken
// file.
ViewFunctions readViewFunctions(const std::string& preprocessedViewText,
                                const std::filesystem::path& viewFile);

}  // namespace hirsute
