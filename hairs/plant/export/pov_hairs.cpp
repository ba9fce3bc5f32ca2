// Plant hairs in the POV-Ray scene (docs/design.md, "Plant hairs"; docs/export.md, "Hairs"): a tube
// of the hair radius around each template polyline (and the template's filled polygons),
// declared once per template and radius/length bucket, and each hair an `object` of it with its
// matrix, one union a material. The rest of the
// scene is pov_writer.cpp.
#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hair_writer.h"
#include "hirsute/viewer/export/pov_writer.h"

namespace hirsute {

namespace {

// A tube of `sides` around each polyline of a hair template, in the template's frame, with
// smooth normals: rings at the vertices, turned along the polyline by projecting the previous
// ring's frame (a discrete parallel transport), open at the ends (a hair's ends are far below a
// pixel). Fuhrer et al. 2004, Sec. 3.2: offline, "the vertices are joined by cylindrical
// primitives", of constant radius.
TriangleMesh hairTube(const HairTemplate& hair, float radius, int sides) {
  TriangleMesh tube;
  for (const auto& polyline : hair.polylines) {
    std::vector<glm::vec3> points;
    for (const glm::vec3& p : polyline) {
      if (points.empty() || glm::distance(points.back(), p) > 1e-7f * (hair.extent + 1e-30f))
        points.push_back(p);
    }
    if (points.size() < 2) continue;
    glm::vec3 normal(0.0f);
    auto first = static_cast<std::uint32_t>(tube.positions.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      glm::vec3 tangent =
          glm::normalize(points[std::min(i + 1, points.size() - 1)] - points[i == 0 ? 0 : i - 1]);
      if (i == 0) {
        glm::vec3 helper = std::fabs(tangent.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        normal = glm::normalize(glm::cross(tangent, helper));
      } else {
        glm::vec3 projected = normal - glm::dot(normal, tangent) * tangent;
        if (glm::length(projected) > 1e-6f) normal = glm::normalize(projected);
      }
      glm::vec3 binormal = glm::cross(tangent, normal);
      for (int j = 0; j < sides; ++j) {
        double a = 2 * 3.14159265358979323846 * j / sides;
        glm::vec3 across =
            static_cast<float>(std::cos(a)) * normal + static_cast<float>(std::sin(a)) * binormal;
        tube.positions.push_back(points[i] + radius * across);
        tube.normals.push_back(across);
      }
    }
    auto ring = [&](std::size_t i, int j) {
      return first + static_cast<std::uint32_t>(i * static_cast<std::size_t>(sides) +
                                                static_cast<std::size_t>(j % sides));
    };
    for (std::size_t i = 0; i + 1 < points.size(); ++i) {
      for (int j = 0; j < sides; ++j) {
        tube.indices.insert(tube.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j + 1),
                                                 ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
      }
    }
  }
  // The template's filled polygons (a scale's blade), flat, in the same mesh: POV-Ray lights
  // both sides of a triangle alike.
  for (std::size_t i = 0; i + 2 < hair.triangles.size(); i += 3) {
    const glm::vec3 a = hair.triangles[i], b = hair.triangles[i + 1], c = hair.triangles[i + 2];
    const glm::vec3 normal = glm::cross(b - a, c - a);
    if (!(glm::length(normal) > 0)) continue;
    const auto first = static_cast<std::uint32_t>(tube.positions.size());
    for (const glm::vec3& p : {a, b, c}) {
      tube.positions.push_back(p);
      tube.normals.push_back(glm::normalize(normal));
    }
    tube.indices.insert(tube.indices.end(), {first, first + 1, first + 2});
  }
  return tube;
}

}  // namespace

void PlantHairWriter::writePov(const Scene& scene, PovWriter& pov) const {
  const std::vector<HairTemplate>& templates = scene.organ<HairPart>().templates;
  const std::vector<Hair>& hairs = scene.organ<HairPart>().hairs;
  ExportFile& out = pov.out();
  std::size_t meshes = 0, skipped = 0, written = 0;
  // A hair's radius is constant while its length scales the template: its tube, in the
  // template's frame, has radius radius/length. The ratio is bucketed in steps of 2% (its
  // logarithm rounded), so that a tube's radius is within 1% of its hairs' and a model needs one
  // tube per ratio its hairs have (a hundred or so a template), declared once each.
  const double logStep = std::log(kBucketStep);
  auto bucketOf = [&](const Hair& h) {
    return static_cast<int>(
        std::lround(std::log(static_cast<double>(h.radius) / h.length) / logStep));
  };
  std::vector<bool> drawable(templates.size());
  float extent = 0;
  for (std::size_t t = 0; t < templates.size(); ++t) {
    drawable[t] = templates[t].segmentCount() > 0 || !templates[t].triangles.empty();
    if (drawable[t]) extent = std::max(extent, templates[t].extent);
  }
  auto valid = [&](const Hair& h) {
    return h.templateIndex < templates.size() && drawable[h.templateIndex] && h.radius > 0 &&
           h.length > 0 && std::isfinite(h.radius / h.length);
  };
  // Tubes: one per (template, bucket) used, declared before the unions that place them.
  std::map<std::pair<int, int>, std::string> tubes;
  for (const Hair& h : hairs) {
    if (valid(h)) tubes.emplace(std::pair<int, int>(h.templateIndex, bucketOf(h)), std::string());
  }
  for (auto& [key, name] : tubes) {
    const HairTemplate& hair = templates[static_cast<std::size_t>(key.first)];
    auto radius = static_cast<float>(std::pow(kBucketStep, key.second));
    TriangleMesh tube = hairTube(hair, radius, kTubeSides);
    if (tube.triangleCount() == 0) continue;
    // Template units: resolve a hundredth of the tube's radius and a hundred-thousandth of the
    // template's size.
    double resolution = std::min(0.01 * radius, 1e-5 * std::max(hair.extent, 1e-30f));
    NumberFormat& position = pov.positionFormat();
    const NumberFormat sceneFormat = position;
    position.decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(resolution))), 0, 12);
    name = std::to_string(meshes++);
    name.insert(name.begin(), 'H');  // (GCC 12 warns falsely about "H" + std::to_string)
    pov.writeMesh2(name, tube);
    position = sceneFormat;
  }

  // Instances, grouped by their template's material (in scene order within it), each material's
  // hairs in one union with one texture: objects without their own texture share the union's,
  // where a texture in every object would be copied for each (docs/export.md: 1.5 GB against
  // 0.85 GB for a million hairs).
  std::map<int, std::vector<std::size_t>> byMaterial;
  for (std::size_t i = 0; i < hairs.size(); ++i) {
    const Hair& h = hairs[i];
    if (!valid(h) || tubes[{h.templateIndex, bucketOf(h)}].empty()) {
      ++skipped;
      continue;
    }
    byMaterial[templates[h.templateIndex].material].push_back(i);
  }
  // The transform's 3×3 part moves a template vertex at most `extent` times its error: it is
  // written to the positions' resolution over that. Hair transforms resolve a hundred-thousandth
  // of the scene (a twenty-fifth of a pixel at 4K), one decimal less than other positions: their
  // text is most of the file, and POV-Ray's parse time follows the text.
  NumberFormat root{std::max(pov.positionFormat().decimals - 1, 0), false};
  NumberFormat linear{
      std::clamp(root.decimals + static_cast<int>(std::ceil(std::log10(std::max(extent, 1e-6f)))),
                 0, 12),
      false};
  for (const auto& [material, members] : byMaterial) {
    const std::string& texture = pov.useTexture(material, -1);
    bool alone = members.size() == 1;  // POV-Ray warns about a union of one
    if (!alone) out.put("union{\n");
    for (std::size_t i : members) {
      const Hair& h = hairs[i];
      glm::mat3 m = glm::mat3_cast(h.rotation()) * h.length;
      out.put("object{");
      out.put(tubes[{h.templateIndex, bucketOf(h)}]);
      if (alone) {
        out.put(" texture{");
        out.put(texture);
        out.put('}');
      }
      // POV-Ray's matrix is row-vector: its rows are the images of x, y, z (glm's columns), then
      // the translation.
      out.put(" matrix<");
      for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
          if (column + row > 0) out.put(',');
          pov.number(m[column][row], linear);
        }
      }
      for (int k = 0; k < 3; ++k) {
        out.put(',');
        pov.number(h.root[k], root);
      }
      out.put(">}\n");
      ++written;
      pov.advance();
    }
    if (!alone) {
      out.put("texture{");
      out.put(texture);
      out.put("}}\n");
    }
  }
  pov.count("hairs", written);
  pov.count("hair meshes", meshes);
  pov.count("hairs skipped", skipped);
}

}  // namespace hirsute
