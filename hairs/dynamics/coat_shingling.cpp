// The coat laid shingled after the feathers are placed, and its pipeline stage.
#include "hirsute/hairs/dynamics/coat_shingling.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "hirsute/hairs/dynamics/feather_poses.h"
#include "hirsute/hairs/dynamics/feather_stem.h"
#include "hirsute/hairs/dynamics/worker_pool.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"

namespace hirsute::dynamics {

ShinglingReport shingleCoat(Scene& scene, const ShinglingOptions& options) {
  FeatherPart& part = scene.organ<FeatherPart>();
  std::vector<std::size_t> coat;
  for (std::size_t i = 0; i < part.feathers.size(); ++i)
    if (part.feathers[i].origin == FeatherOrigin::Coat) coat.push_back(i);
  ShinglingReport report;
  if (coat.empty()) return report;

  // The stems are built on the pool's threads, each into its own slot (the same on any number).
  std::vector<FeatherStem> grown(coat.size()), stems;
  std::vector<StemFrame> anchors(coat.size());
  WorkerPool pool(options.threads);
  pool.forEach(coat.size(), 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      grown[c] = buildFeatherStem(scene, part.feathers[coat[c]], options.segments);
      anchors[c] = anchorFrameOf(part.feathers[coat[c]]);
    }
  });
  stems = grown;
  const DeintersectionReport laid =
      deintersectStems(stems, anchors, bodyMeshOf(scene), options.laying, options.progress);
  report.feathers = laid.stems;
  report.lifted = laid.moved;
  report.intersections = laid.intersections;
  report.unresolved = laid.unresolved;
  report.leftAsGrown = laid.leftAsGrown;
  report.largestLift = laid.largestLift * 180 / std::numbers::pi;
  report.pairTests = laid.pairTests;

  part.poses.resize(part.feathers.size());
  for (std::size_t c = 0; c < coat.size(); ++c) {
    const FeatherStem& stem = stems[c];
    if (stem.positions == grown[c].positions) continue;
    const Feather& feather = part.feathers[coat[c]];
    part.poses[coat[c]] = featherPoseOf(feather, grown[c], stem);
    // The lifted feather's box: its nodes, each widened by its widest vane on every side.
    for (std::size_t k = 0; k < stem.nodeCount(); ++k) {
      const double w =
          stem.hasVane() ? std::max(stem.vaneWidths[k][0], stem.vaneWidths[k][1]) : 0.0;
      const Eigen::Vector3d& p = stem.positions[k];
      part.bounds.add(glm::vec3(p.x() - w, p.y() - w, p.z() - w));
      part.bounds.add(glm::vec3(p.x() + w, p.y() + w, p.z() + w));
    }
  }
  return report;
}

namespace {

struct ShinglingCommandOptions : OrganOptionsOf<ShinglingCommandOptions> {};

class CoatShinglingStage : public OrganStageOf<ShinglingCommandOptions> {
 public:
  const char* activity() const override { return "shingling feathers"; }

  bool wanted(const Scene& scene, const ModelResources& resources) const override {
    if (!resources.view.organ<FeatherSettings>().shingling) return false;
    const auto& feathers = scene.organ<FeatherPart>().feathers;
    return std::any_of(feathers.begin(), feathers.end(), [](const Feather& feather) {
      return feather.origin == FeatherOrigin::Coat;
    });
  }

 protected:
  void declareOptions(CLI::App& command, ShinglingCommandOptions& s) const override {
    command.add_flag("!--no-deintersect", s.enabled,
                     "Draw the feather coat as grown, its feathers passing through one another, "
                     "instead of each laid on the layer beneath");
  }
  std::string growFrom(const OrganStageRun& run, const ShinglingCommandOptions&) const override {
    ShinglingOptions options;
    options.segments = run.resources.view.organ<FeatherSettings>().dynamics.segments;
    options.threads = run.threads;
    options.progress = run.progress;
    const ShinglingReport report = shingleCoat(run.scene, options);
    const SourceLocation where{std::make_shared<const std::string>(run.lsystemFile), 0, 0};
    if (report.leftAsGrown > 0) {
      run.diagnostics.warn(
          where,
          fmt::format("the coat's feathers crowd too closely to be laid: {} pairs of their "
                      "parts were tested (at most {}), and the {} feathers above are left as "
                      "they grew, passing through one another (fewer or sparser feathers, or "
                      "--no-deintersect)",
                      report.pairTests, options.laying.maxPairTests, report.leftAsGrown));
    } else if (report.intersections > 0) {
      run.diagnostics.warn(
          where, fmt::format("{} feathers of the coat could not be laid clear of those beneath "
                             "them: {} pairs of their stems' and vanes' parts still meet",
                             report.unresolved, report.intersections));
    }
    return fmt::format(
        "shingled coat: {} feathers, {} lifted (at most {:.1f} degrees), {} intersections left",
        report.feathers, report.lifted, report.largestLift, report.intersections);
  }
};

}  // namespace

const OrganStage& coatShinglingStage() {
  static const CoatShinglingStage stage;
  return stage;
}

}  // namespace hirsute::dynamics
