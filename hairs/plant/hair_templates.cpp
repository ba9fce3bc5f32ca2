// Template hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.2): each `hair:` file is an
// independent L-system, derived and interpreted by the plant's turtle; the hair is the polyline
// of the turtle's positions, and the triangles of the polygons it fills, kept once in the hair's
// own frame.
#include "hirsute/hairs/plant/hair_templates.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

// Consecutive segments whose ends meet closer than this (relative to the template's size) are
// one polyline.
constexpr float kJoinTolerance = 1e-5f;

}  // namespace

HairTemplate hairTemplateFromScene(const Scene& scene, const std::string& file,
                                   const SourceLocation& where) {
  std::vector<const LineSegment*> segments;
  for (const LineSegment& line : scene.lines) {
    if (glm::length(line.to - line.from) > 0.0f) segments.push_back(&line);
  }
  if (segments.empty()) {
    throw DiagnosticError(
        where.file ? where : SourceLocation{std::make_shared<const std::string>(file), 0, 0},
        "the template hair " + file +
            " draws nothing: it needs F modules (a hair is the polyline of the "
            "turtle's positions)");
  }
  // The hair frame: x along the first segment, y the turtle's initial left (-x in cpfg's frame)
  // made orthogonal to it, or its initial up when the first segment runs along the left.
  const glm::vec3 origin = segments.front()->from;
  const glm::vec3 x = glm::normalize(segments.front()->to - origin);
  glm::vec3 y = glm::vec3(-1, 0, 0) - x * glm::dot(glm::vec3(-1, 0, 0), x);
  if (glm::length(y) < 1e-4f) y = glm::vec3(0, 0, -1) - x * glm::dot(glm::vec3(0, 0, -1), x);
  y = glm::normalize(y);
  const glm::vec3 z = glm::cross(x, y);
  auto local = [&](const glm::vec3& p) {
    const glm::vec3 d = p - origin;
    return glm::vec3(glm::dot(d, x), glm::dot(d, y), glm::dot(d, z));
  };

  HairTemplate hair;
  hair.file = file;
  hair.material = segments.front()->material;
  float size = 0;
  for (const LineSegment* s : segments)
    size = std::max({size, glm::length(s->from - origin), glm::length(s->to - origin)});
  const float tolerance = kJoinTolerance * std::max(size, 1e-6f);
  for (const LineSegment* s : segments) {
    const glm::vec3 from = local(s->from), to = local(s->to);
    if (hair.polylines.empty() || glm::length(hair.polylines.back().back() - from) > tolerance) {
      hair.polylines.push_back({from});
    }
    hair.polylines.back().push_back(to);
  }
  // A closed outline the template wraps in `{ }` is filled, as cpfg fills a polygon: the
  // interpreter has triangulated it into the scene's meshes.
  for (const TriangleMesh& mesh : scene.meshes) {
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      for (std::size_t k = 0; k < 3; ++k)
        hair.triangles.push_back(local(mesh.positions.at(mesh.indices[i + k])));
    }
  }
  for (const auto& polyline : hair.polylines) {
    for (const glm::vec3& p : polyline) hair.extent = std::max(hair.extent, glm::length(p));
  }
  for (const glm::vec3& p : hair.triangles) hair.extent = std::max(hair.extent, glm::length(p));
  return hair;
}

std::vector<HairTemplate> loadHairTemplates(const ModelResources& resources,
                                            Diagnostics& diagnostics) {
  std::vector<HairTemplate> templates;
  const std::vector<HairTemplateDeclaration>& declared =
      resources.view.organ<HairSettings>().templates;
  if (declared.empty()) return templates;
  // The plant's settings (angle increment, colours, contours), but lines drawn as lines: a hair
  // is its turtle's positions.
  ModelResources own = resources;
  own.view.lineStyle = LineStyle::Pixel;
  own.view.organ<HairSettings>().templates.clear();
  own.backgroundScenes.clear();
  for (const HairTemplateDeclaration& declaration : declared) {
    const std::string& file = declaration.file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
      throw DiagnosticError(declaration.where, "cannot open the template hair " + file);
    }
    // Sec. 3.2: hair curvature is controlled with functions; a template reads the plant's
    // function set (`func(id, x)`, the set's names defined) as the plant does.
    Model model = loadModel(file, resources.viewFile, diagnostics);
    Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, std::cerr);
    DerivationOptions options;
    options.maxModules = 1'000'000;  // a hair is a few segments
    Derivation derivation(model.program, evaluator, diagnostics, options);
    derivation.run();
    Scene scene;
    interpret(derivation, own, scene, diagnostics);
    templates.push_back(hairTemplateFromScene(scene, file, declaration.where));
  }
  return templates;
}

}  // namespace hirsute
