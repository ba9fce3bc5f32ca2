// hirsute_export_bench: export figures (docs/design.md, "Benchmarks").
//
// POV-Ray export of one million triangles: the seconds the writer takes and the bytes it writes,
// and, when povray is installed, the seconds POV-Ray takes to parse the file (parse time grows
// with the text, which is why the writer is compact). The scene is made like a plant's: tubes of
// eight-sided rings with a repeated seam vertex, as generalized cylinders are meshed, in eight
// materials. Beside it, for reference: the same scene as OBJ, and one million line segments (hairs
// drawn as lines) as POV-Ray cylinders and cones.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"

namespace {

namespace fs = std::filesystem;
using hirsute::Scene;

constexpr int kSides = 8;            // contour sides: cpfg's default
constexpr int kStripsPerTube = 125;  // 125 strips × 16 triangles: 2000 triangles a tube
constexpr int kMaterials = 8;

// Tubes rising from the ground on a spiral, bending slightly, thinning towards their tips.
Scene tubeScene(std::size_t triangles, unsigned seed) {
  Scene scene;
  for (int m = 0; m < kMaterials + 1; ++m) {
    hirsute::Material material;
    material.diffuse = material.ambient = glm::vec3(0.2f + 0.08f * m, 0.6f, 0.3f);
    scene.materials.push_back(material);
  }
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  std::size_t perTube = static_cast<std::size_t>(kStripsPerTube) * kSides * 2;
  std::size_t tubes = (triangles + perTube - 1) / perTube;
  for (std::size_t t = 0; t < tubes; ++t) {
    hirsute::TriangleMesh& mesh = scene.meshFor(1 + static_cast<int>(t % kMaterials));
    float angle = static_cast<float>(t) * 2.39996f;  // the golden angle
    float distance = 40.0f * std::sqrt(static_cast<float>(t) / static_cast<float>(tubes));
    glm::vec3 base(distance * std::cos(angle), 0, distance * std::sin(angle));
    glm::vec3 lean(jitter(random) * 0.3f, 1, jitter(random) * 0.3f);
    lean = glm::normalize(lean);
    glm::vec3 side = glm::normalize(glm::cross(lean, glm::vec3(0, 0, 1)));
    glm::vec3 other = glm::cross(side, lean);
    float radius = 0.4f + 0.2f * jitter(random);
    for (int ring = 0; ring <= kStripsPerTube; ++ring) {
      float along = static_cast<float>(ring) * 0.5f;
      glm::vec3 centre = base + lean * along + side * (0.002f * along * along);
      float r = radius * (1.0f - 0.8f * static_cast<float>(ring) / kStripsPerTube);
      for (int j = 0; j <= kSides; ++j) {
        float a = 2.0f * 3.14159265f * static_cast<float>(j % kSides) / kSides;
        glm::vec3 normal = std::cos(a) * side + std::sin(a) * other;
        mesh.positions.push_back(centre + r * normal);
        mesh.normals.push_back(normal);
      }
    }
    auto first = static_cast<std::uint32_t>(
        mesh.positions.size() - static_cast<std::size_t>((kStripsPerTube + 1) * (kSides + 1)));
    for (int ring = 0; ring < kStripsPerTube; ++ring) {
      for (int j = 0; j < kSides; ++j) {
        std::uint32_t a = first + static_cast<std::uint32_t>(ring * (kSides + 1) + j);
        std::uint32_t b = a + kSides + 1;
        mesh.indices.insert(mesh.indices.end(), {a, a + 1, b + 1, a, b + 1, b});
      }
    }
  }
  return scene;
}

// Hairs drawn as lines: polylines of ten tapering segments, in one material.
Scene hairScene(std::size_t segments, unsigned seed) {
  Scene scene;
  scene.materials.resize(2);
  scene.lineStyle = hirsute::LineStyle::Polygon;
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  glm::vec3 p(0.0f);
  for (std::size_t i = 0; i < segments; ++i) {
    if (i % 10 == 0) p = glm::vec3(jitter(random), jitter(random), jitter(random)) * 20.0f;
    glm::vec3 q = p + glm::vec3(jitter(random), 1, jitter(random)) * 0.1f;
    float w = 0.02f * (1.0f - static_cast<float>(i % 10) / 10.0f);
    scene.lines.push_back({p, q, w, w * 0.9f, 1});
    p = q;
  }
  return scene;
}

template <typename F>
double bestSeconds(int runs, F&& run) {
  double best = 1e30;
  for (int i = 0; i < runs; ++i) {
    auto start = std::chrono::steady_clock::now();
    run();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Export figures: POV-Ray export of a million triangles, and POV-Ray's parse time for it"};
  std::size_t triangles = 1'000'000;
  std::size_t segments = 1'000'000;
  int runs = 3;
  bool parse = true;
  std::string folderOption;
  app.add_option("--triangles", triangles, "Triangles in the mesh scene (default 1000000)");
  app.add_option("--segments", segments, "Line segments in the hair scene (default 1000000)");
  app.add_option("--runs", runs, "Timed runs of each export; the best is reported (default 3)")
      ->check(CLI::Range(1, 100));
  app.add_flag("!--no-povray", parse, "Do not run POV-Ray for its parse time");
  app.add_option("--folder", folderOption,
                 "Where the files are written (default: a temporary folder, removed)");
  CLI11_PARSE(app, argc, argv);

  fs::path folder = folderOption.empty() ? fs::temp_directory_path() /
                                               ("hirsute_export_bench_" + std::to_string(getpid()))
                                         : fs::path(folderOption);
  fs::create_directories(folder);
  try {
    Scene scene = tubeScene(triangles, 1);
    std::printf("scene: %zu triangles in %zu meshes, %zu vertices\n", scene.triangleCount(),
                scene.meshes.size(), [&] {
                  std::size_t n = 0;
                  for (const auto& m : scene.meshes) n += m.positions.size();
                  return n;
                }());

    hirsute::PovExportStats pov;
    double povSeconds = bestSeconds(
        runs, [&] { pov = hirsute::writePov(scene, hirsute::PovOptions{}, folder / "mesh.pov"); });
    double million = static_cast<double>(pov.triangles) / 1e6;
    std::printf(
        "POV-Ray export, mesh:  %.3f s  %llu bytes  (%.1f bytes/triangle, %.3f s and %.1f MB per "
        "million triangles, %.0f MB/s)\n",
        povSeconds, static_cast<unsigned long long>(pov.bytes),
        static_cast<double>(pov.bytes) / static_cast<double>(pov.triangles), povSeconds / million,
        static_cast<double>(pov.bytes) / 1e6 / million,
        static_cast<double>(pov.bytes) / 1e6 / povSeconds);

    hirsute::ObjExportStats obj;
    double objSeconds =
        bestSeconds(runs, [&] { obj = hirsute::writeObj(scene, folder / "mesh.obj"); });
    std::printf("OBJ export, mesh:      %.3f s  %llu bytes  (%.1f bytes/triangle)\n", objSeconds,
                static_cast<unsigned long long>(obj.bytes),
                static_cast<double>(obj.bytes) / static_cast<double>(obj.faces));

    Scene hairs = hairScene(segments, 2);
    hirsute::PovExportStats lines;
    double lineSeconds = bestSeconds(runs, [&] {
      lines = hirsute::writePov(hairs, hirsute::PovOptions{}, folder / "lines.pov");
    });
    std::printf(
        "POV-Ray export, lines: %.3f s  %llu bytes  (%zu cylinders and cones, %.1f bytes each; "
        "%.3f s per million)\n",
        lineSeconds, static_cast<unsigned long long>(lines.bytes), lines.cylinders + lines.cones,
        static_cast<double>(lines.bytes) / static_cast<double>(lines.cylinders + lines.cones),
        lineSeconds / (static_cast<double>(lines.cylinders + lines.cones) / 1e6));

    if (parse && hirsute::povrayAvailable()) {
      for (const char* name : {"mesh.pov", "lines.pov"}) {
        auto start = std::chrono::steady_clock::now();
        hirsute::PovrayRun run =
            hirsute::runPovray(folder / name, folder / "parse.png", 32, 24, false);
        double wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (run.exitStatus != 0 || run.parseSeconds < 0) {
          std::printf("POV-Ray on %s failed (exit %d):\n%s", name, run.exitStatus,
                      run.messages.c_str());
          continue;
        }
        std::printf("POV-Ray parse, %-9s %.3f s (whole run at 32x24: %.3f s)%s\n", name,
                    run.parseSeconds, wall, run.messages.empty() ? "" : "  with warnings:");
        if (!run.messages.empty()) std::printf("%s", run.messages.c_str());
      }
    } else if (parse) {
      std::printf("POV-Ray parse: povray is not installed\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hirsute_export_bench: %s\n", e.what());
    if (folderOption.empty()) fs::remove_all(folder);
    return 1;
  }
  if (folderOption.empty()) fs::remove_all(folder);
  return 0;
}
