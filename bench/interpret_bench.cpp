// hirsute_interpret_bench: how fast the turtle turns a derived string into the Scene.
//
// docs/design.md, "Benchmarks": figures printed, never asserted. For each model the string is
// derived first (not timed), then, in turn and repeated (the fastest run is reported):
//   homomorphism  the string after the homomorphism, recorded into a ModuleString: what
//                 `interpret()` feeds the turtle (for a model without one, a copy of the string);
//   turtle        the turtle alone on that recorded string into a fresh Scene: modules per second
//                 into the Scene, triangles per second, and generalized-cylinder triangles (those
//                 of @Gs … @Gc … @Ge tubes) per second;
//   interpret     `interpret()` as `hirsute render` and `export` run it: the two together.
// The turtle's Scene is checked against interpret()'s (the same triangles, lines, spheres and
// discs), so that the split measures the real work.
//
// Models: models/bench/branching.l, fewer steps than the derivation benchmark's (pixel lines as
// it ships, and as cylinders with tubes.v's view); models/bench/tubes.l, 2048 tubes of ten
// four-strip segments of twelve sides (~2 million tube triangles); and, when the conformance set
// (../shared/conformance) is present, tools-FernLeaf (generalized-cylinder leaves) and
// cpfg-Lilac (cylinders and surfaces) with the index's colour options and steps.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace {

namespace fs = std::filesystem;

// A model as the benchmark runs it: files, colour files, steps.
struct BenchCase {
  std::string name;
  fs::path lsystem;
  std::optional<fs::path> view;
  hirsute::ColorFiles colors;
  std::optional<int> steps;
  std::string exercises;
};

// Collects the modules the turtle would receive, in the string's own encoding.
class RecordingSink : public hirsute::ModuleSink {
 public:
  explicit RecordingSink(hirsute::ModuleString& out) : out_(out) {}
  void module(char symbol, const float* parameters, std::size_t count) override {
    out_.append(symbol, std::span<const float>(parameters, count));
  }
  void module(hirsute::ModuleRef m) override { out_.append(m); }

 private:
  hirsute::ModuleString& out_;
};

struct SceneCounts {
  std::size_t triangles = 0, tubeTriangles = 0, lines = 0, spheres = 0, discs = 0;
  std::size_t bytes = 0;  // held by the Scene's arrays
  bool operator==(const SceneCounts&) const = default;
};

SceneCounts countScene(const hirsute::Scene& scene) {
  SceneCounts c;
  c.triangles = scene.triangleCount();
  for (const hirsute::CylinderSegment& s : scene.cylinderSegments)
    c.tubeTriangles += s.indexCount / 3;
  c.lines = scene.lines.size();
  c.spheres = scene.spheres.size();
  c.discs = scene.discs.size();
  for (const hirsute::TriangleMesh& m : scene.meshes) {
    c.bytes +=
        m.positions.capacity() * sizeof(glm::vec3) + m.normals.capacity() * sizeof(glm::vec3) +
        m.texcoords.capacity() * sizeof(glm::vec2) + m.indices.capacity() * sizeof(std::uint32_t);
  }
  c.bytes += scene.lines.capacity() * sizeof(hirsute::LineSegment) +
             scene.spheres.capacity() * sizeof(hirsute::Sphere) +
             scene.discs.capacity() * sizeof(hirsute::Disc);
  for (const hirsute::CylinderSegment& s : scene.cylinderSegments) {
    c.bytes += sizeof s + s.rings.capacity() * sizeof(hirsute::CylinderRing) +
               (s.contourStart.capacity() + s.contourEnd.capacity()) * sizeof(glm::vec2);
  }
  return c;
}

struct Figures {
  std::size_t derivedModules = 0;  // the string as derived
  std::size_t modules = 0;         // what the turtle receives (after the homomorphism)
  SceneCounts scene;
  double homomorphismSeconds = 1e300, turtleSeconds = 1e300, interpretSeconds = 1e300;
  int runs = 0;
  bool sameScene = true;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Derives the model, then times the homomorphism, the turtle and interpret() `repeat` times, or,
// when `repeat` is 0, until a second has gone by (at least three runs).
Figures measure(const BenchCase& c, int repeat) {
  hirsute::Diagnostics diagnostics(&std::cerr);
  hirsute::ModelResources resources = hirsute::loadModelResources(c.view, c.colors, diagnostics);
  hirsute::Model model = hirsute::loadModel(c.lsystem, c.view, diagnostics);
  hirsute::Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder,
                               std::cerr);
  hirsute::DerivationOptions options;
  options.steps = c.steps;
  hirsute::Derivation derivation(model.program, evaluator, diagnostics, options);
  hirsute::installQueryPass(derivation, resources, diagnostics);
  derivation.run();

  Figures f;
  f.derivedModules = derivation.string().moduleCount();
  auto benchStart = std::chrono::steady_clock::now();
  for (int run = 0; repeat > 0 ? run < repeat : (run < 3 || secondsSince(benchStart) < 1.0);
       ++run) {
    hirsute::ModuleString recorded;
    auto start = std::chrono::steady_clock::now();
    {
      RecordingSink sink(recorded);
      derivation.emit(sink, true);
    }
    f.homomorphismSeconds = std::min(f.homomorphismSeconds, secondsSince(start));
    f.modules = recorded.moduleCount();

    SceneCounts turtleCounts;
    {
      hirsute::Scene scene;
      start = std::chrono::steady_clock::now();
      hirsute::Turtle turtle(resources, &scene, diagnostics);
      turtle.setSourceString(&recorded);
      turtle.modules(recorded, recorded.begin(), recorded.end());
      turtle.finish();
      f.turtleSeconds = std::min(f.turtleSeconds, secondsSince(start));
      turtleCounts = countScene(scene);
    }
    {
      hirsute::Scene scene;
      start = std::chrono::steady_clock::now();
      hirsute::interpret(derivation, resources, scene, diagnostics);
      f.interpretSeconds = std::min(f.interpretSeconds, secondsSince(start));
      f.scene = countScene(scene);
    }
    SceneCounts a = turtleCounts, b = f.scene;
    a.bytes = b.bytes = 0;  // capacities may differ; the geometry may not
    f.sameScene = f.sameScene && a == b;
    f.runs = run + 1;
  }
  return f;
}

// One row of the conformance index: the model's files, colour options and steps.
std::optional<BenchCase> conformanceCase(const fs::path& root, const std::string& id,
                                         const std::string& exercises) {
  std::ifstream in(root / "index.tsv");
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, '\t');) cells.push_back(cell);
    if (cells.size() < 6 || cells[0] != id) continue;
    fs::path folder = root / id;
    BenchCase c{id, folder / cells[1], std::nullopt, {}, std::stoi(cells[5]), exercises};
    if (cells[2] != "-") c.view = folder / cells[2];
    // cpfg's -m/-M FILE (bank 1) and -mN/-MN FILE (bank N).
    std::istringstream options(cells[4]);
    for (std::string flag, file; options >> flag >> file;) {
      int bank = flag.size() > 2 ? std::stoi(flag.substr(2)) : 1;
      auto& list = flag[1] == 'm' ? c.colors.colormaps : c.colors.materials;
      list.push_back({bank, folder / file});
    }
    return c;
  }
  return std::nullopt;
}

std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string perSecond(std::size_t count, double seconds) {
  if (count == 0) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", static_cast<double>(count) / seconds);
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Interpretation benchmark: modules and triangles per second into the Scene"};
  std::string only;
  int repeat = 0;
  int branchingSteps = 16;
  std::string modelFolder = HIRSUTE_BENCH_MODEL_DIR;
  std::string conformanceFolder = HIRSUTE_CONFORMANCE_DIR;
  app.add_option("--model", only, "Run only this model (a name from the table)");
  app.add_option("--repeat", repeat,
                 "Runs per model, the fastest reported (default: as many as fit in a second, at "
                 "least 3)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--branching-steps", branchingSteps,
                 "Derivation steps of branching.l (default 16: about a million modules)")
      ->check(CLI::Range(1, 19));
  app.add_option("--models", modelFolder, "The folder of the benchmark models")
      ->check(CLI::ExistingDirectory);
  app.add_option("--conformance", conformanceFolder,
                 "The conformance set (its FernLeaf and Lilac rows are skipped when absent)");
  CLI11_PARSE(app, argc, argv);

  const fs::path models = modelFolder;
  std::vector<BenchCase> cases = {
      {"branching",
       models / "branching.l",
       std::nullopt,
       {},
       branchingSteps,
       "branching.l as it ships: pixel lines, no view file"},
      {"branching-cyl",
       models / "branching.l",
       models / "tubes.v",
       {},
       branchingSteps,
       "branching.l with tubes.v: every F an open cylinder of 12 sides"},
      {"tubes",
       models / "tubes.l",
       models / "tubes.v",
       {},
       std::nullopt,
       "2048 generalized cylinders, 10 segments of 4 strips, 12 sides"},
  };
  const fs::path conformance = conformanceFolder;
  bool conformancePresent = fs::exists(conformance / "index.tsv");
  if (conformancePresent) {
    for (auto [id, exercises] :
         {std::pair{"tools-FernLeaf", "generalized-cylinder leaflets, homomorphism"},
          std::pair{"cpfg-Lilac", "cylinders, ~p ~c surfaces, tropism, homomorphism"}}) {
      if (auto c = conformanceCase(conformance, id, exercises)) cases.push_back(*c);
    }
  }
  std::erase_if(cases, [&](const BenchCase& c) { return !only.empty() && c.name != only; });
  if (cases.empty()) {
    std::cerr << "hirsute_interpret_bench: no model named '" << only << "'\n";
    return 2;
  }

  std::printf("%-15s %5s %10s %10s %9s %10s %10s %8s %8s %8s %5s %11s %11s %11s %8s\n", "model",
              "steps", "derived", "to turtle", "lines", "triangles", "tube tri", "homo s",
              "turtle s", "interp s", "runs", "modules/s", "tri/s", "tube tri/s", "scene MiB");
  int failures = 0;
  for (const BenchCase& c : cases) {
    Figures f;
    try {
      f = measure(c, repeat);
    } catch (const hirsute::DiagnosticError& e) {
      std::cerr << c.name << ": " << e.diagnostic().text() << '\n';
      ++failures;
      continue;
    }
    std::printf("%-15s %5s %10s %10s %9s %10s %10s %8.4f %8.4f %8.4f %5d %11s %11s %11s %8.1f\n",
                c.name.c_str(), c.steps ? std::to_string(*c.steps).c_str() : "file",
                grouped(f.derivedModules).c_str(), grouped(f.modules).c_str(),
                grouped(f.scene.lines).c_str(), grouped(f.scene.triangles).c_str(),
                grouped(f.scene.tubeTriangles).c_str(), f.homomorphismSeconds, f.turtleSeconds,
                f.interpretSeconds, f.runs, perSecond(f.modules, f.turtleSeconds).c_str(),
                perSecond(f.scene.triangles, f.turtleSeconds).c_str(),
                perSecond(f.scene.tubeTriangles, f.turtleSeconds).c_str(),
                static_cast<double>(f.scene.bytes) / (1024.0 * 1024.0));
    if (!f.sameScene) {
      std::printf(
          "  %s: the turtle alone drew a different Scene from interpret(): its figures "
          "are not the real work\n",
          c.name.c_str());
      ++failures;
    }
    std::fflush(stdout);
  }
  std::printf(
      "\nderived: modules of the derived string; to turtle: after the homomorphism; lines: "
      "pixel-style segments\n(segments shorter than ~0.003 are not drawn, as in cpfg). homo s: "
      "recording the string after the\nhomomorphism; turtle s: the turtle alone on it into a "
      "fresh Scene; interp s: interpret(), both\ntogether. modules/s, tri/s and tube tri/s are "
      "over turtle s (tube tri: triangles of @Gs…@Ge tubes).\nscene MiB: the Scene's arrays. "
      "Fastest of `runs` runs; the derivation is not timed.\n");
  for (const BenchCase& c : cases) std::printf("  %-15s %s\n", c.name.c_str(), c.exercises.c_str());
  if (!conformancePresent) {
    std::printf("(%s is absent: tools-FernLeaf and cpfg-Lilac are left out)\n",
                conformance.c_str());
  }
  return failures ? 1 : 0;
}
