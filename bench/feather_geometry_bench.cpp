// hirsute_feather_geometry_bench: what feather geometry costs (docs/design.md, "Benchmarks";
// docs/feathers.md): barbs generated per second and bytes per feather geometry, at a low, a
// middle and a high level of detail, for the fixture contour feather (key barbs, silhouette,
// strips, an afterfeather) and its down afterfeather alone (Bdf1 throughout). Each figure is the
// fastest of several runs of many builds; bytes are what the geometry's arrays hold
// (FeatherGeometry::byteSize), afterfeather included.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "hirsute/hairs/feathers/feather_blend.h"
#include "hirsute/hairs/feathers/feather_geometry.h"
#include "hirsute/hairs/feathers/feather_file.h"

namespace {

namespace fs = std::filesystem;

struct Figures {
  double barbsPerSecond = 0;
  double featherMicroseconds = 0;
  std::size_t barbs = 0;
  std::size_t bytes = 0;
};

Figures measure(const hirsute::FeatherType& type, const hirsute::FeatherDetail& detail) {
  constexpr int kRuns = 3;
  Figures best;
  const hirsute::FeatherGeometry sample = hirsute::buildFeatherGeometry(type, detail);
  best.barbs = sample.totalBarbCount();
  best.bytes = sample.byteSize();
  // About 100 000 barbs a run.
  const int builds = std::max(1, static_cast<int>(100000 / std::max<std::size_t>(best.barbs, 1)));
  for (int run = 0; run < kRuns; ++run) {
    std::size_t barbs = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < builds; ++i) {
      barbs += hirsute::buildFeatherGeometry(type, detail).totalBarbCount();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best.barbsPerSecond = std::max(best.barbsPerSecond, barbs / seconds);
  }
  best.featherMicroseconds = 1e6 * best.barbs / best.barbsPerSecond;
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path folder = argc > 1 ? fs::path(argv[1]) : fs::path(HIRSUTE_FEATHER_FIXTURES);
  hirsute::Diagnostics diagnostics;
  const hirsute::FeatherType contour =
      hirsute::loadFeatherType(folder / "contour.fea", diagnostics);
  const hirsute::FeatherType down = *contour.afterfeather;
  const hirsute::FeatherType blended = hirsute::blendFeatherTypes(contour, down, 0.5f);
  const hirsute::FeatherType growing = hirsute::grownFeatherType(contour, 0.7f);
  struct Case {
    const char* name;
    const hirsute::FeatherType* type;
  };
  const Case cases[] = {
      {"contour", &contour}, {"down", &down}, {"blend 0.5", &blended}, {"age 0.7", &growing}};
  const struct {
    const char* name;
    hirsute::FeatherDetail detail;
  } details[] = {
      {"low (3,3,3)", {3, 3, 3}}, {"mid (8,6,6)", {8, 6, 6}}, {"high (32,16,12)", {32, 16, 12}}};
  std::printf("%-10s %-16s %7s %12s %10s %10s %12s\n", "feather", "detail", "barbs", "barbs/s",
              "us/feather", "bytes", "bytes/barb");
  for (const Case& c : cases) {
    for (const auto& d : details) {
      const Figures f = measure(*c.type, d.detail);
      std::printf(
          "%-10s %-16s %7zu %12.3g %10.1f %10zu %12.1f\n", c.name, d.name, f.barbs,
          f.barbsPerSecond, f.featherMicroseconds, f.bytes,
          static_cast<double>(f.bytes) / static_cast<double>(std::max<std::size_t>(f.barbs, 1)));
    }
  }
  return 0;
}
