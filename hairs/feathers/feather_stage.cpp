#include "hirsute/hairs/feathers/feather_stage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "hirsute/hairs/feathers/feather_coats.h"
#include "hirsute/hairs/feathers/feather_file.h"
#include "hirsute/hairs/feathers/feather_instances.h"
#include "hirsute/hairs/placement/placement_random.h"
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
  return !scene.feathers.empty() || !resources.view.featherTypes.empty();
}

FeatherStageReport growFeathers(Scene& scene, const ModelResources& resources,
                                const ViewFunctions& functions, const FeatherStageOptions& options,
                                Diagnostics& diagnostics) {
  FeatherStageReport report;
  scene.featherTypes.clear();
  for (const FeatherTypeDeclaration& declaration : resources.view.featherTypes) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(declaration.file, error)) {
      throw DiagnosticError(declaration.where,
                            "cannot read the feather type file '" + declaration.file + "'");
    }
    scene.featherTypes.push_back(loadFeatherType(declaration.file, diagnostics));
  }
  std::map<std::string, int> textures;
  for (FeatherType& type : scene.featherTypes) attachTextures(type, scene, textures);
  report.types = scene.featherTypes.size();

  if (!scene.featherTypes.empty()) {
    const ViewSettings& view = resources.view;
    FeatherCoatSettings coats;
    coats.layout = view.follicleLayout;
    coats.texture.width = coats.texture.height = view.hairTextureSize;
    coats.texture.fill = view.hairTextureFill;
    // Follicles are not the hairs' points: the texture and the offsets get seeds of their own,
    // from --hair-seed when given.
    const std::uint64_t seed = options.seed != 0 ? options.seed : view.hairTextureSeed;
    coats.texture.seed = placementKey(seed, 0x666f6c6cu);
    coats.seed = placementKey(seed, 0x636f6174u);
    coats.maxFeathers = options.maxFeathers;
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
          SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
          e.what());
    }
  }

  const std::size_t before = scene.feathers.size();
  std::erase_if(scene.feathers,
                [&](const Feather& feather) { return !hasFeatherTypes(scene, feather); });
  report.dropped = before - scene.feathers.size();
  report.feathers = scene.feathers.size();
  if (report.dropped > 0) {
    diagnostics.warn(
        SourceLocation{std::make_shared<const std::string>(options.lsystemFile), 0, 0},
        fmt::format("{} feathers name a feather type the view file does not declare (it declares "
                    "{} with `feather:` lines) and are left out",
                    report.dropped, report.types));
  }

  scene.featherBounds = Bounds{};
  for (const Feather& feather : scene.feathers) {
    addBounds(featherGeometryOf(scene, feather, kBoundsDetail), featherToWorld(feather),
              scene.featherBounds);
  }
  return report;
}

}  // namespace hirsute
