#include "hirsute/hairs/feathers/feather_stage.h"

#include "hirsute/hairs/placement/mesh_sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "hirsute/hairs/feathers/feather_coats.h"
#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_instances.h"
#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/hairs/placement/placement_random.h"
#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/interpreter/texture_image.h"

namespace hirsute {
namespace {

// The lowest detail of Fig. 8 is enough to bound a feather: its vertices are points of the same
// curves at coarser steps, and the camera frames with a margin.
constexpr FeatherDetail kBoundsDetail{3, 3, 3};

void addBounds(const FeatherGeometry& geometry, const glm::mat4& toWorld, Bounds& bounds) {
  forEachFeatherPart(geometry, [&](const FeatherGeometry& part, bool) {
    for (const glm::vec3& p : part.shaft.positions)
      bounds.add(glm::vec3(toWorld * glm::vec4(p, 1)));
    for (const glm::vec3& p : part.vertices.positions)
      bounds.add(glm::vec3(toWorld * glm::vec4(p, 1)));
  });
}

// Reads the texture images of a type and its afterfeathers into the scene (each file once) and
// sets their sceneTexture. Returns the type with its afterfeathers' copies updated.
void attachTextures(FeatherType& type, Scene& scene, std::map<std::string, int>& loaded) {
  FeatherAppearance& appearance = type.appearance;
  if (!appearance.texture.empty()) {
    auto [at, inserted] = loaded.try_emplace(appearance.texture, -1);
    if (inserted) {
      scene.textures.push_back(loadTexture(appearance.texture));
      at->second = static_cast<int>(scene.textures.size()) - 1;
    }
    appearance.sceneTexture = at->second;
  }
  if (type.afterfeather) {
    auto after = std::make_shared<FeatherType>(*type.afterfeather);
    attachTextures(*after, scene, loaded);
    type.afterfeather = std::move(after);
  }
}

}  // namespace

bool hasFeathers(const Scene& scene, const ModelResources& resources) {
  return !scene.organ<FeatherPart>().feathers.empty() ||
         !resources.view.organ<FeatherSettings>().types.empty();
}

FeatherStageReport growFeathers(Scene& scene, const ModelResources& resources,
                                const ViewFunctions& functions, const FeatherStageOptions& options,
                                Diagnostics& diagnostics) {
  FeatherPart& part = scene.organ<FeatherPart>();
  FeatherStageReport report;
  part.types.clear();
  part.maxVertices = options.maxVertices;
  part.fullDetail = options.fullDetail;
  for (const FeatherTypeDeclaration& declaration : resources.view.organ<FeatherSettings>().types) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(declaration.file, error)) {
      throw DiagnosticError(declaration.where,
                            "cannot read the feather type file '" + declaration.file + "'");
    }
    part.types.push_back(loadFeatherType(declaration.file, diagnostics));
  }
  // The turtle's feathers (@Fe, @Fi) count against the limit before any coat is placed; the
  // coats count on from them.
  if (part.feathers.size() > options.maxFeathers) {
    throw DiagnosticError(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
        fmt::format("{} feathers at the turtle (@Fe, @Fi), more than {} (raise the limit with "
                    "--max-feathers)",
                    part.feathers.size(), options.maxFeathers));
  }
  std::map<std::string, int> textures;
  for (FeatherType& type : part.types) attachTextures(type, scene, textures);
  report.types = part.types.size();

  if (!part.types.empty()) {
    const ViewSettings& view = resources.view;
    FeatherCoatSettings coats;
    coats.layout = view.organ<FeatherSettings>().follicleLayout;
    // The coats lay their follicles out on the hairs' point-diffusion texture (`hair texture:`).
    const HairSettings& hairs = view.organ<HairSettings>();
    coats.texture.width = coats.texture.height = hairs.textureSize;
    coats.texture.fill = hairs.textureFill;
    // Follicles are not the hairs' points: the texture and the offsets get seeds of their own,
    // from --hair-seed when given.
    const std::uint64_t seed = options.seed != 0 ? options.seed : hairs.textureSeed;
    coats.texture.seed = placementKey(seed, 0x666f6c6cu);
    coats.seed = placementKey(seed, 0x636f6174u);
    coats.maxFeathers = options.maxFeathers;
    coats.progress = options.progress;
    const std::vector<FunctionCurve>& curves = functions.functions;
    coats.function = [&curves](int index, double x) {
      if (index < 1 || static_cast<std::size_t>(index) > curves.size()) return std::nan("");
      return curves[static_cast<std::size_t>(index) - 1].evaluate(x);
    };
    try {
      const FeatherCoatReport placed = placeFeatherCoats(scene, coats);
      report.coat = placed.feathers;
      if (placed.segmentsWithoutMesh > 0) {
        diagnostics.warn(
            SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
            fmt::format("{} feathered generalized-cylinder segments are drawn as lines and get "
                        "no coat; coats grow on cylinders drawn as triangles (`line style: "
                        "cylinder` in the view file)",
                        placed.segmentsWithoutMesh));
      }
    } catch (const FeatherLimitError& e) {
      throw DiagnosticError(
          SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0}, e.what());
    } catch (const SamplingLimitError& e) {
      throw DiagnosticError(
          SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0}, e.what());
    }
  }

  const std::size_t before = part.feathers.size();
  std::erase_if(part.feathers,
                [&](const Feather& feather) { return !hasFeatherTypes(scene, feather); });
  report.dropped = before - part.feathers.size();
  report.feathers = part.feathers.size();
  if (report.dropped > 0) {
    diagnostics.warn(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
        fmt::format("{} feathers name a feather type the view file does not declare (it declares "
                    "{} with `feather:` lines) and are left out",
                    report.dropped, report.types));
  }

  // Single feathers are bounded by their own geometry. A coat has too many feathers for that:
  // each is bounded by a box of its key types in its frame, the blend of their boxes (blends
  // interpolate the types' lengths and angles, so they stay near the blend of their boxes, and
  // growing feathers are smaller, their barbs along the rachis within the rachis and barb
  // lengths), so that a coat of small feathers next to a few large ones is framed by its own.
  part.bounds = Bounds{};
  std::vector<Bounds> typeBoxes(part.types.size());
  for (std::size_t t = 0; t < part.types.size(); ++t) {
    const FeatherType& type = part.types[t];
    addBounds(buildFeatherGeometry(type, kBoundsDetail), glm::mat4(1.0f), typeBoxes[t]);
    // Barbs inside the sheath lie along the rachis (Sec. 4.2.4): as far as the tip plus a barb.
    float barb = std::max(type.left.barbLength, type.right.barbLength);
    for (const Vane* vane : {&type.left, &type.right}) {
      for (const SilhouettePoint& p : vane->silhouette) barb = std::max(barb, p.length);
    }
    typeBoxes[t].add(glm::vec3(0, 0, type.calamusLength + type.rachisLength + barb));
  }
  // A single feather's geometry depends on its types, blend and age alone; a run of feathers
  // alike (4 095 @Fe(1) at one spot) builds it once.
  std::optional<FeatherGeometry> previous;
  const Feather* previousFeather = nullptr;
  const auto alike = [](const Feather& a, const Feather& b) {
    return a.types == b.types && a.across == b.across && a.along == b.along && a.age == b.age;
  };
  for (const Feather& feather : part.feathers) {
    const glm::mat4 toWorld = featherToWorld(feather);
    if (feather.origin == FeatherOrigin::Single) {
      if (!previous || !alike(feather, *previousFeather))
        previous = featherGeometryOf(scene, feather, kBoundsDetail);
      previousFeather = &feather;
      addBounds(*previous, toWorld, part.bounds);
      continue;
    }
    // The blend's box: the key types' boxes weighted as the feather blends them (its lengths
    // and widths are those weights' mix), widened by a tenth of the way to their union for
    // what angles and silhouettes make not quite linear.
    const std::array<float, 4> weights = {(1 - feather.along) * (1 - feather.across[0]),
                                          (1 - feather.along) * feather.across[0],
                                          feather.along * (1 - feather.across[1]),
                                          feather.along * feather.across[1]};
    Bounds all, local;
    local.min = local.max = glm::vec3(0.0f);
    for (std::size_t k = 0; k < 4; ++k) {
      const Bounds& box = typeBoxes[feather.types[k] - 1u];
      all.add(box);
      local.min += weights[k] * box.min;
      local.max += weights[k] * box.max;
    }
    local.min -= 0.1f * (local.min - all.min);
    local.max += 0.1f * (all.max - local.max);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? local.max.x : local.min.x,
                        (corner & 2) ? local.max.y : local.min.y,
                        (corner & 4) ? local.max.z : local.min.z);
      part.bounds.add(glm::vec3(toWorld * glm::vec4(p, 1)));
    }
  }
  return report;
}

}  // namespace hirsute

namespace hirsute {
namespace {

struct FeatherCommandOptions : OrganOptionsOf<FeatherCommandOptions> {
  std::size_t maxFeathers = FeatherStageOptions{}.maxFeathers;
  bool fullDetail = false;
};

class FeatherStage : public OrganStageOf<FeatherCommandOptions> {
 public:
  const char* activity() const override { return "growing feathers"; }

  bool wanted(const Scene& scene, const ModelResources& resources) const override {
    return hasFeathers(scene, resources);
  }

 protected:
  void declareOptions(CLI::App& command, FeatherCommandOptions& s) const override {
    command.add_flag("!--no-feathers", s.enabled, "Leave out the feathers (@F modules)");
    command.add_option("--max-feathers", s.maxFeathers,
                       "More feathers (@Fe, @Fi and coats) are an error (default 1000000)");
    command.add_flag("--full-feathers", s.fullDetail,
                     "Draw and export every barb of every feather, each feather built whole "
                     "(no thinning to the picture, no POV-Ray instances)");
  }
  std::string growFrom(const OrganStageRun& run,
                       const FeatherCommandOptions& chosen) const override {
    FeatherStageOptions options;
    options.lsystemFile = run.lsystemFile;
    options.seed = run.seed;
    options.maxFeathers = chosen.maxFeathers;
    options.maxVertices = run.maxVertices;
    options.fullDetail = chosen.fullDetail;
    options.progress = run.progress;
    const FeatherStageReport report =
        growFeathers(run.scene, run.resources, run.functions, options, run.diagnostics);
    return fmt::format("feathers: {} ({} in coats) of {} types", report.feathers, report.coat,
                       report.types);
  }
  // The turtle's @Fe and @Fi feathers go with the rest.
  void leaveOut(Scene& scene) const override { scene.organ<FeatherPart>().feathers.clear(); }
};

}  // namespace

const OrganStage& featherStage() {
  static const FeatherStage stage;
  return stage;
}

}  // namespace hirsute
