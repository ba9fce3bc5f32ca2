// hirsute_point_diffusion_bench: the point-diffusion texture's quality and cost per fill
// (docs/design.md, "Placement"; docs/hairs.md). For each fill, over seeds 1..20 of a 100 × 100
// texture: the relative radius ρ (Lagae & Dutré 2008; the design asks ≥ 0.65), the point count
// against fill·W·H (within 2%), and the generation time.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "hirsute/hairs/placement/point_diffusion.h"
#include "hirsute/hairs/placement/point_spacing.h"

int main() {
  constexpr int kSeeds = 20;
  constexpr double kFills[] = {0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3};
  std::printf("100x100 texture, seeds 1..%d\n", kSeeds);
  std::printf("%6s %8s %8s %8s %9s %9s %10s\n", "fill", "rho min", "rho mean", "target",
              "count min", "count max", "ms / tex");
  for (double fill : kFills) {
    double rhoMin = 1e9, rhoSum = 0, seconds = 0;
    std::size_t countMin = static_cast<std::size_t>(-1), countMax = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const auto start = std::chrono::steady_clock::now();
      const hirsute::PointDiffusionTexture texture = hirsute::PointDiffusionTexture::generate(
          {100, 100, fill, static_cast<std::uint64_t>(seed)});
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double rho = hirsute::relativeRadius(texture.positions());
      rhoMin = std::min(rhoMin, rho);
      rhoSum += rho;
      countMin = std::min(countMin, texture.points().size());
      countMax = std::max(countMax, texture.points().size());
    }
    std::printf("%6.3f %8.3f %8.3f %8.0f %9zu %9zu %10.2f\n", fill, rhoMin, rhoSum / kSeeds,
                fill * 100 * 100, countMin, countMax, 1e3 * seconds / kSeeds);
  }
  return 0;
}
