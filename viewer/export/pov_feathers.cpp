// Feathers in the POV-Ray scene (DESIGN.md, "Feathers"; docs/export.md, "Feathers"): built at the
// level of detail of their size in the scene's image (--width, --height), as the GL renderer
// builds them (feather_buffers.h), one level finer, the shafts one opaque mesh2, the barbs another
// whose vertices carry their colour and a transparency that fades to the barb tips (and, on
// strips, to their edges), interpolated across each triangle as POV-Ray does for a face with three
// texture indices. Polyline barbs become thin ribbons facing the feather's front, since POV-Ray
// has no lines. Textures are not exported (the colour is the type's).
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {
namespace {

constexpr float kRibbonShare = 0.3f;  // a polyline barb's ribbon: this share of the spacing
constexpr char kLitFinish[] = "ambient 0.2 diffuse 0.7";

}  // namespace

void PovWriter::feathers(const Scene& scene) {
  closeRun();
  if (scene.feathers.empty()) return;
  // A still is looked at closer than a preview: one level finer than the camera asks for.
  std::vector<std::uint8_t> levels = featherDetailLevels(scene, camera_);
  for (std::uint8_t& level : levels) level = static_cast<std::uint8_t>(std::min(level + 1, 7));
  FeatherBuffers b = buildFeatherBuffers(scene, levels);

  // Polyline barbs as ribbons: each segment (i, j) a quad across the barb in the vane plane.
  std::vector<std::uint32_t> triangles;
  std::vector<glm::vec3> positions = b.barbPositions;
  std::vector<glm::vec4> colours = b.barbColors;
  for (const FeatherBuffers::Part& part : b.parts) {
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      const auto begin = b.vaneIndices.begin() + vane.first;
      if (vane.primitiveSize == 3) {
        triangles.insert(triangles.end(), begin, begin + vane.count);
        continue;
      }
      for (std::uint32_t k = 0; k + 1 < vane.count; k += 2) {
        const std::uint32_t i = begin[k], j = begin[k + 1];
        const glm::vec3 along = positions[j] - positions[i];
        glm::vec3 across = glm::cross(along, glm::cross(part.left, along));
        const float length = glm::length(across);
        if (!(length > 0)) continue;
        across *= kRibbonShare * 0.5f * glm::length(along) / length;
        const auto base = static_cast<std::uint32_t>(positions.size());
        for (std::uint32_t v : {i, j}) {
          positions.push_back(positions[v] + across);
          positions.push_back(positions[v] - across);
          colours.push_back(colours[v]);
          colours.push_back(colours[v]);
        }
        triangles.insert(triangles.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
      }
    }
  }

  if (!b.shaftIndices.empty()) {
    std::vector<Shade> shades;
    shades.reserve(b.shaftColors.size());
    for (const glm::vec3& c : b.shaftColors) shades.push_back(shadeOf(c, 1));
    writeShadedMesh("feather shafts", b.shaftPositions, shades, b.shaftIndices, kLitFinish);
  }
  if (!triangles.empty()) {
    std::vector<Shade> shades;
    shades.reserve(colours.size());
    for (const glm::vec4& c : colours) shades.push_back(shadeOf(glm::vec3(c), c.a));
    writeShadedMesh("feather barbs", positions, shades, triangles, kLitFinish);
  }
  stats_.feathers += scene.feathers.size();
}

PovWriter::Shade PovWriter::shadeOf(const glm::vec3& c, float alpha) {
  auto q = [](float v) { return static_cast<int>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  return {q(c.r), q(c.g), q(c.b),
          static_cast<int>(std::lround(std::clamp(alpha, 0.0f, 1.0f) * kShadeAlphaLevels))};
}

void PovWriter::writeShadedMesh(std::string_view comment, const std::vector<glm::vec3>& points,
                                const std::vector<Shade>& shades,
                                const std::vector<std::uint32_t>& faces, std::string_view finish) {
  std::map<Shade, int> textureOf;
  for (const Shade& s : shades) textureOf.emplace(s, 0);
  int n = 0;
  for (auto& [shade, index] : textureOf) index = n++;
  out_.put("\n// ");
  out_.put(comment);
  out_.put("\nmesh2{\nvertex_vectors{");
  out_.putInteger(static_cast<std::int64_t>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    out_.put(i % 4 == 0 ? ",\n" : ",");
    vector(points[i], position_);
  }
  out_.put("}\ntexture_list{");
  out_.putInteger(n);
  for (const auto& [shade, index] : textureOf) {
    out_.put(",\ntexture{pigment{rgbt<");
    number(shade.r / 255.0, colour_);
    out_.put(',');
    number(shade.g / 255.0, colour_);
    out_.put(',');
    number(shade.b / 255.0, colour_);
    out_.put(',');
    number(1.0 - static_cast<double>(shade.a) / kShadeAlphaLevels, colour_);
    out_.put(">}finish{");
    out_.put(finish);
    out_.put("}}");
  }
  out_.put("}\nface_indices{");
  out_.putInteger(static_cast<std::int64_t>(faces.size() / 3));
  for (std::size_t t = 0; t + 2 < faces.size(); t += 3) {
    out_.put(t % 12 == 0 ? ",\n<" : ",<");
    for (int c = 0; c < 3; ++c) {
      if (c > 0) out_.put(',');
      out_.putInteger(faces[t + static_cast<std::size_t>(c)]);
    }
    out_.put('>');
    for (int c = 0; c < 3; ++c) {
      out_.put(',');
      out_.putInteger(textureOf[shades[faces[t + static_cast<std::size_t>(c)]]]);
    }
  }
  out_.put("}\n}\n");
  stats_.triangles += faces.size() / 3;
}

}  // namespace hirsute
