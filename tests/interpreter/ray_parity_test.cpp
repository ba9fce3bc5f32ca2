// Ray parity: for every model of the conformance set (../shared/conformance) with cpfg's own
// geometry (expected.ray.gz, cpfg's `-ray` rayshade output), our turtle must draw the same number
// of primitives of each kind, and a bounding box within 0.1% of cpfg's diagonal.
//
// How cpfg's rayshade primitives map onto our Scene:
//   cylinder, cone          F and G segments (Turtle::counts().segments): Scene::lines in pixel
//                           and polygon line styles, one open cylinder mesh each in cylinder style
//   poly, polygon           { } polygons (Turtle::counts().polygons), triangulated in meshes
//   triangle                generalized-cylinder triangles (Scene::cylinderSegments' indices)
//   sphere                  Scene::spheres (@O)
//   disc                    Scene::discs (@o, @c)
//   background scene        the view's `background scene:` files (BackgroundScene::counts)
//   object X + transforms   a ~X surface instance (Turtle::counts().surfaces); its triangles are
//                           the triangleuv of the definition `name X … end`, once per instance
// Bounding boxes: cpfg's is that of its primitives: cylinders and cones with their radii in
// cylinder line style (our meshes have them), by their end points otherwise (our lines are drawn
// in pixels or as screen-facing ribbons); spheres and discs with their radii; triangles and
// polygons by their vertices; surface instances by their definition's vertices transformed.
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// Primitive counts by kind, ours or cpfg's.
struct KindCounts {
  std::size_t segments = 0, polygons = 0, tubeTriangles = 0, spheres = 0, discs = 0, surfaces = 0,
              surfaceTriangles = 0;
  bool operator==(const KindCounts&) const = default;
};

struct Box {
  glm::dvec3 min{1e300}, max{-1e300};
  bool empty() const { return min.x > max.x; }
  void add(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  double diagonal() const { return empty() ? 0 : glm::length(max - min); }
};

// ---- cpfg's rayshade output ----------------------------------------------------------------

std::string readGzip(const fs::path& file) {
  gzFile in = gzopen(file.c_str(), "rb");
  if (in == nullptr) return {};
  std::string text;
  char buffer[1 << 16];
  int n;
  while ((n = gzread(in, buffer, sizeof buffer)) > 0)
    text.append(buffer, static_cast<std::size_t>(n));
  gzclose(in);
  return text;
}

bool isNumber(const std::string& token, double& value) {
  char* end = nullptr;
  value = std::strtod(token.c_str(), &end);
  return !token.empty() && end == token.c_str() + token.size();
}

// A rayshade transformation as an affine map of row vectors (rayshade applies `scale`,
// `transform`, `translate` in the order written).
struct Affine {
  glm::dmat3 linear{1.0};
  glm::dvec3 offset{0.0};
  glm::dvec3 apply(const glm::dvec3& p) const { return linear * p + offset; }
  Affine then(const Affine& next) const { return Affine{next.linear * linear, next.apply(offset)}; }
};

struct RayInstance {
  std::string name;
  Affine transform;
};

// One `name X … end` block (or the top level).
struct RayDefinition {
  KindCounts counts;
  std::size_t surfaceTriangles = 0;  // triangleuv written directly in it
  std::vector<glm::dvec3> points;    // for the bounding box
  std::vector<RayInstance> instances;
};

struct RayScene {
  KindCounts counts;
  Box box;
};

class RayReader {
 public:
  RayReader(const std::string& text, bool cylinderExtents) : cylinderExtents_(cylinderExtents) {
    // Only the geometry after `#else` of the `#ifdef BBOX` block: surfaces and headers come first.
    std::size_t start = text.find("\n#else");
    std::istringstream lines(start == std::string::npos ? text : text.substr(start + 1));
    std::string line;
    while (std::getline(lines, line)) {
      if (!line.empty() && line[0] == '#') continue;  // preprocessor lines
      std::istringstream words(line);
      std::string word;
      while (words >> word) tokens_.push_back(word);
    }
  }

  RayScene read() {
    definitions_[""];
    std::vector<std::string> open{""};
    while (at_ < tokens_.size()) {
      const std::string word = tokens_[at_++];
      RayDefinition& current = definitions_[open.back()];
      if (word == "name" && at_ < tokens_.size()) {
        open.push_back(tokens_[at_++]);
        definitions_[open.back()];
      } else if (word == "end") {
        if (open.size() > 1) open.pop_back();
      } else if (word == "object" && at_ < tokens_.size()) {
        RayInstance instance{tokens_[at_++], {}};
        readTransforms(instance.transform);
        current.instances.push_back(instance);
      } else if (word == "cylinder" || word == "cone") {
        skipSurfaceName();
        const std::vector<double> v = numbers();
        if (v.size() < 7) continue;
        const bool cone = word == "cone";
        const glm::dvec3 a(v[1], v[2], v[3]);
        const double r1 = v[0], r2 = cone && v.size() >= 8 ? v[4] : r1;
        const glm::dvec3 b =
            cone && v.size() >= 8 ? glm::dvec3(v[5], v[6], v[7]) : glm::dvec3(v[4], v[5], v[6]);
        ++current.counts.segments;
        addSegment(current, a, b, r1, r2);
      } else if (word == "sphere") {
        skipSurfaceName();
        const std::vector<double> v = numbers();
        if (v.size() < 4) continue;
        ++current.counts.spheres;
        const glm::dvec3 c(v[1], v[2], v[3]);
        current.points.push_back(c - glm::dvec3(v[0]));
        current.points.push_back(c + glm::dvec3(v[0]));
      } else if (word == "disc") {
        skipSurfaceName();
        const std::vector<double> v = numbers();
        if (v.size() < 7) continue;
        ++current.counts.discs;
        addDisc(current, glm::dvec3(v[1], v[2], v[3]), glm::dvec3(v[4], v[5], v[6]), v[0]);
      } else if (word == "triangle" || word == "triangleuv" || word == "poly" ||
                 word == "polygon") {
        skipSurfaceName();
        const std::vector<double> v = numbers();
        // Vertices: x y z (poly, plain triangle), x y z n n n (triangle with normals), or
        // x y z n n n u v (triangleuv).
        std::size_t stride = 3;
        if (word == "triangleuv") stride = 8;
        if (word == "triangle" && v.size() == 18) stride = 6;
        for (std::size_t i = 0; i + 2 < v.size(); i += stride)
          current.points.emplace_back(v[i], v[i + 1], v[i + 2]);
        if (word == "triangleuv") ++current.surfaceTriangles;
        if (word == "triangle") ++current.counts.tubeTriangles;
        if (word == "poly" || word == "polygon") ++current.counts.polygons;
      }
    }
    RayScene scene;
    expand("", Affine{}, scene, 0, true);
    return scene;
  }

 private:
  void skipSurfaceName() {
    double value;
    if (at_ < tokens_.size() && !isNumber(tokens_[at_], value) && !isKeyword(tokens_[at_])) ++at_;
  }

  static bool isKeyword(const std::string& word) {
    static const char* const kKeywords[] = {
        "name", "end",      "object",     "cylinder",  "cone",    "sphere",
        "disc", "triangle", "triangleuv", "poly",      "polygon", "applysurf",
        "grid", "scale",    "transform",  "translate", "rotate"};
    return std::find(std::begin(kKeywords), std::end(kKeywords), word) != std::end(kKeywords);
  }

  std::vector<double> numbers() {
    std::vector<double> v;
    double value;
    while (at_ < tokens_.size() && isNumber(tokens_[at_], value)) {
      v.push_back(value);
      ++at_;
    }
    return v;
  }

  void readTransforms(Affine& transform) {
    while (at_ < tokens_.size()) {
      const std::string& word = tokens_[at_];
      if (word != "scale" && word != "transform" && word != "translate") return;
      ++at_;
      const std::vector<double> v = numbers();
      Affine step;
      if (word == "scale" && v.size() >= 3) {
        step.linear =
            glm::dmat3(glm::dvec3(v[0], 0, 0), glm::dvec3(0, v[1], 0), glm::dvec3(0, 0, v[2]));
      } else if (word == "transform" && v.size() >= 9) {
        // Rayshade multiplies row vectors: row i of the matrix is the image of axis i.
        step.linear = glm::dmat3(glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]),
                                 glm::dvec3(v[6], v[7], v[8]));
        if (v.size() >= 12) step.offset = glm::dvec3(v[9], v[10], v[11]);
      } else if (word == "translate" && v.size() >= 3) {
        step.offset = glm::dvec3(v[0], v[1], v[2]);
      }
      transform = transform.then(step);
    }
  }

  void addSegment(RayDefinition& d, const glm::dvec3& a, const glm::dvec3& b, double r1,
                  double r2) {
    if (!cylinderExtents_) {
      d.points.push_back(a);
      d.points.push_back(b);
      return;
    }
    // A circle of radius r about axis direction n reaches r·sqrt(1 − n_i²) along axis i.
    const glm::dvec3 axis = b - a;
    const double length = glm::length(axis);
    const glm::dvec3 n = length > 0 ? axis / length : glm::dvec3(0.0);
    const glm::dvec3 reach = glm::sqrt(glm::max(glm::dvec3(1.0) - n * n, glm::dvec3(0.0)));
    d.points.push_back(a - reach * r1);
    d.points.push_back(a + reach * r1);
    d.points.push_back(b - reach * r2);
    d.points.push_back(b + reach * r2);
  }

  static void addDisc(RayDefinition& d, const glm::dvec3& c, const glm::dvec3& normal, double r) {
    const double length = glm::length(normal);
    const glm::dvec3 n = length > 0 ? normal / length : glm::dvec3(0.0);
    const glm::dvec3 reach = glm::sqrt(glm::max(glm::dvec3(1.0) - n * n, glm::dvec3(0.0))) * r;
    d.points.push_back(c - reach);
    d.points.push_back(c + reach);
  }

  // Adds definition `name` under `transform`; `topLevel`: the file's own primitives, not a
  // surface definition that only its instances draw.
  void expand(const std::string& name, const Affine& transform, RayScene& scene, int depth,
              bool topLevel) {
    auto found = definitions_.find(name);
    if (found == definitions_.end() || depth > 8) return;
    const RayDefinition& d = found->second;
    if (!topLevel || name.empty()) {
      KindCounts& c = scene.counts;
      c.segments += d.counts.segments;
      c.polygons += d.counts.polygons;
      c.tubeTriangles += d.counts.tubeTriangles;
      c.spheres += d.counts.spheres;
      c.discs += d.counts.discs;
      for (const glm::dvec3& p : d.points) scene.box.add(transform.apply(p));
    }
    for (const RayInstance& instance : d.instances) {
      // The file's last line instances the whole scene (`object NAME.ray`); every other object
      // is a ~X surface.
      const bool wholeScene = name.empty() && instance.name.size() > 4 &&
                              instance.name.compare(instance.name.size() - 4, 4, ".ray") == 0;
      if (!wholeScene) {
        ++scene.counts.surfaces;
        scene.counts.surfaceTriangles += definitions_[instance.name].surfaceTriangles;
      }
      expand(instance.name, instance.transform.then(transform), scene, depth + 1, false);
    }
  }

  bool cylinderExtents_;
  std::vector<std::string> tokens_;
  std::size_t at_ = 0;
  std::map<std::string, RayDefinition> definitions_;
};

// ---- our side ------------------------------------------------------------------------------

struct Row {
  std::string id, lfile, vfile, colors, environment;
  int steps = 0;
  std::string notes;
};

std::vector<Row> readIndex(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, '\t')) cells.push_back(cell);
    if (cells.size() < 7) continue;
    rows.push_back(Row{cells[0], cells[1], cells[2], cells[4], cells[6], std::stoi(cells[5]),
                       cells.size() > 8 ? cells[8] : ""});
  }
  return rows;
}

// cpfg's colour options: `-M file`, `-m file`, `-m2 file`, …
ColorFiles colorFiles(const fs::path& folder, const std::string& options) {
  ColorFiles files;
  std::istringstream words(options);
  std::string option, file;
  while (words >> option >> file) {
    const bool materials = option.rfind("-M", 0) == 0;
    const int bank = option.size() > 2 ? std::atoi(option.c_str() + 2) : 1;
    (materials ? files.materials : files.colormaps).push_back({bank, folder / file});
  }
  return files;
}

struct Ours {
  KindCounts counts;
  Box box;
};

Ours interpretModel(const fs::path& folder, const Row& row, ModelResources& resources) {
  Diagnostics diagnostics;
  std::optional<fs::path> view;
  if (row.vfile != "-") view = folder / row.vfile;
  // cpfg wrote these files in its batch mode (-g), which reads the .l before the .v: the
  // function-set names were undefined (as in the conformance runner).
  ModelOptions modelOptions;
  modelOptions.defineFunctionSetNames =
      row.notes.find("-g reads .l before .v") == std::string::npos;
  Model model = loadModel(folder / row.lfile, view, diagnostics, modelOptions);
  resources = loadModelResources(view, colorFiles(folder, row.colors), diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = row.steps;
  Derivation derivation(model.program, evaluator, diagnostics, options);
  installQueryPass(derivation, resources, diagnostics);
  derivation.run();

  Scene scene;
  Turtle turtle(resources, &scene, diagnostics);
  turtle.setSourceString(&derivation.mutableString());
  derivation.emit(turtle, true);
  turtle.finish();

  Ours ours;
  ours.counts.segments = turtle.counts().segments;
  ours.counts.polygons = turtle.counts().polygons;
  ours.counts.surfaces = turtle.counts().surfaces;
  ours.counts.surfaceTriangles = turtle.counts().surfaceTriangles;
  for (const CylinderSegment& s : scene.cylinderSegments)
    ours.counts.tubeTriangles += s.indexCount / 3;
  ours.counts.spheres = scene.spheres.size();
  ours.counts.discs = scene.discs.size();
  // The view's background scenes (drawn after the string, as interpret() does), counted in cpfg's
  // rayshade primitives: cylinders and cones with their end discs, spheres, triangles.
  for (const BackgroundScene& background : resources.backgroundScenes) {
    appendBackgroundScene(background, scene);
    ours.counts.segments += background.counts.cylinders;
    ours.counts.discs += background.counts.discs;
    ours.counts.spheres += background.counts.spheres;
    ours.counts.tubeTriangles += background.counts.triangles;
  }
  for (const TriangleMesh& mesh : scene.meshes) {
    for (const glm::vec3& p : mesh.positions) ours.box.add(glm::dvec3(p));
  }
  for (const LineSegment& l : scene.lines) {
    ours.box.add(glm::dvec3(l.from));
    ours.box.add(glm::dvec3(l.to));
  }
  for (const Sphere& s : scene.spheres) {
    ours.box.add(glm::dvec3(s.center) - glm::dvec3(s.radius));
    ours.box.add(glm::dvec3(s.center) + glm::dvec3(s.radius));
  }
  // Screen-aligned discs (@o) face the viewer, as cpfg writes them.
  glm::dvec3 toViewer =
      glm::dvec3(resources.view.viewpoint) - glm::dvec3(resources.view.viewReference);
  toViewer = glm::length(toViewer) > 0 ? glm::normalize(toViewer) : glm::dvec3(0, 0, 1);
  for (const Disc& d : scene.discs) {
    const glm::dvec3 n =
        glm::length(d.normal) > 0 ? glm::normalize(glm::dvec3(d.normal)) : toViewer;
    const glm::dvec3 reach =
        glm::sqrt(glm::max(glm::dvec3(1.0) - n * n, glm::dvec3(0.0))) * double(d.radius);
    ours.box.add(glm::dvec3(d.center) - reach);
    ours.box.add(glm::dvec3(d.center) + reach);
  }
  return ours;
}

// The largest difference of a box coordinate, relative to cpfg's diagonal.
double boxDifference(const Box& ours, const Box& cpfg) {
  if (ours.empty() || cpfg.empty()) return ours.empty() == cpfg.empty() ? 0 : 1;
  const double diagonal = std::max(cpfg.diagonal(), 1e-12);
  const glm::dvec3 low = glm::abs(ours.min - cpfg.min), high = glm::abs(ours.max - cpfg.max);
  return std::max({low.x, low.y, low.z, high.x, high.y, high.z}) / diagonal;
}

std::string text(const Box& box) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "(%g %g %g) to (%g %g %g)", box.min.x, box.min.y, box.min.z,
                box.max.x, box.max.y, box.max.z);
  return buffer;
}

constexpr double kBoxTolerance = 0.001;  // 0.1% of the diagonal

// Models whose geometry differs from cpfg's for a reason understood, not (yet) reproduced.
struct KnownDifference {
  const char* id;
  const char* reason;
};
constexpr KnownDifference kKnownDifferences[] = {
    {"cpfg-RandomMoss",
     "the rayshade file comes from another run of this stochastic model than expected.str "
     "(index.tsv: "
     "\"str_gui DIFFERS from -g string\"); our string is cpfg's expected.str"},
};

const char* knownDifference(const std::string& id) {
  for (const KnownDifference& k : kKnownDifferences) {
    if (id == k.id) return k.reason;
  }
  return nullptr;
}

std::string pair(std::size_t ours, std::size_t cpfg) {
  return ours == cpfg ? std::to_string(ours) : std::to_string(ours) + "/" + std::to_string(cpfg);
}

TEST(RayParity, ConformanceModelsDrawWhatCpfgDraws) {
  const fs::path root = fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";
  if (!fs::exists(root / "index.tsv")) GTEST_SKIP() << root << " is absent";
  std::ostringstream table;
  table << std::left << std::setw(40) << "model"
        << " segments  polygons  tube-tri  spheres  discs  surfaces  surf-tri  "
        << "bbox-diff  result\n";
  int passed = 0, failed = 0, known = 0;
  for (const Row& row : readIndex(root / "index.tsv")) {
    const fs::path folder = root / row.id;
    if (!fs::exists(folder / "expected.ray.gz")) continue;
    std::string result, boxes;
    KindCounts ours, cpfg;
    double difference = 1;
    const char* excuse = knownDifference(row.id);
    if (row.environment == "yes") {
      result = "skipped: needs cpfg's environment program (-e)";
    } else {
      try {
        ModelResources resources;
        const Ours drawn = interpretModel(folder, row, resources);
        const bool cylinders = resources.view.lineStyle == LineStyle::Cylinder;
        const RayScene ray = RayReader(readGzip(folder / "expected.ray.gz"), cylinders).read();
        ours = drawn.counts;
        cpfg = ray.counts;
        difference = boxDifference(drawn.box, ray.box);
        const bool same = ours == cpfg && difference <= kBoxTolerance;
        if (difference > 1e-4)
          boxes = "    box ours " + text(drawn.box) + "\n    box cpfg " + text(ray.box) + "\n";
        if (same) {
          result = excuse ? "match (listed as a known difference: remove it)" : "match";
        } else {
          result = excuse ? std::string("known difference: ") + excuse : "DIFFERS";
        }
        if (same)
          ++passed;
        else if (excuse)
          ++known;
        else
          ++failed;
        EXPECT_TRUE(same || excuse != nullptr) << row.id << " differs from cpfg's rayshade output";
      } catch (const DiagnosticError& e) {
        result = (excuse ? "known difference: " : "ERROR: ") + e.diagnostic().text();
        if (excuse)
          ++known;
        else
          ++failed;
        EXPECT_NE(excuse, nullptr) << row.id << ": " << e.diagnostic().text();
      }
    }
    char bbox[32];
    std::snprintf(bbox, sizeof bbox, "%.2e", difference);
    table << std::left << std::setw(40) << row.id << ' ' << std::setw(9)
          << pair(ours.segments, cpfg.segments) << ' ' << std::setw(9)
          << pair(ours.polygons, cpfg.polygons) << ' ' << std::setw(9)
          << pair(ours.tubeTriangles, cpfg.tubeTriangles) << ' ' << std::setw(8)
          << pair(ours.spheres, cpfg.spheres) << ' ' << std::setw(6) << pair(ours.discs, cpfg.discs)
          << ' ' << std::setw(9) << pair(ours.surfaces, cpfg.surfaces) << ' ' << std::setw(9)
          << pair(ours.surfaceTriangles, cpfg.surfaceTriangles) << ' ' << std::setw(10) << bbox
          << ' ' << result << '\n'
          << boxes;
  }
  table << passed << " match, " << failed << " differ, " << known << " known differences\n";
  std::cout << "ours/cpfg where they differ; bbox-diff: largest box coordinate difference / cpfg's "
               "diagonal\n"
            << table.str();
}

}  // namespace
}  // namespace hirsute
