// Plant hairs in the OBJ file (docs/design.md, "Plant hairs"): each polyline of a hair's template,
// placed, one `l` element under `o hairs`, and its filled polygons as faces, grouped by the
// template's material. The rest of the
// file is obj_writer.cpp.
#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hair_writer.h"
#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {

void PlantHairWriter::writeObj(const Scene& scene, ObjWriter& obj) const {
  const std::vector<HairTemplate>& templates = scene.organ<HairPart>().templates;
  const std::vector<Hair>& hairs = scene.organ<HairPart>().hairs;
  std::uint64_t written = 0;
  // Hairs by template (a counting sort), templates by material in order of first use: one
  // `usemtl` a material.
  std::vector<std::size_t> first(templates.size() + 1, 0);
  for (const Hair& h : hairs) {
    if (h.templateIndex < templates.size()) ++first[h.templateIndex + 1];
  }
  for (std::size_t t = 0; t < templates.size(); ++t) first[t + 1] += first[t];
  std::vector<std::size_t> order(first.back());
  {
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < hairs.size(); ++i) {
      if (hairs[i].templateIndex < templates.size()) order[next[hairs[i].templateIndex]++] = i;
    }
  }
  std::vector<int> materials;
  for (const HairTemplate& t : templates) {
    if (std::find(materials.begin(), materials.end(), t.material) == materials.end())
      materials.push_back(t.material);
  }
  for (int material : materials) {
    for (std::size_t t = 0; t < templates.size(); ++t) {
      const HairTemplate& shape = templates[t];
      if (shape.material != material || (shape.segmentCount() == 0 && shape.triangles.empty()) ||
          first[t] == first[t + 1])
        continue;
      obj.group("hairs");
      obj.useMaterial(material, -1);
      for (std::size_t k = first[t]; k < first[t + 1]; ++k) {
        const Hair& h = hairs[order[k]];
        glm::mat3 rotation = glm::mat3_cast(h.rotation());
        for (const auto& polyline : shape.polylines) {
          if (polyline.size() < 2) continue;
          for (const glm::vec3& p : polyline) {
            obj.vertex(h.root + h.length * (rotation * p));
            obj.polyline().push_back(obj.stats().vertices);
          }
          obj.finishPolyline();
        }
        // The template's filled polygons, as faces.
        for (std::size_t v = 0; v + 2 < shape.triangles.size(); v += 3) {
          for (std::size_t c = 0; c < 3; ++c)
            obj.vertex(h.root + h.length * (rotation * shape.triangles[v + c]));
          const std::uint64_t last = obj.stats().vertices;
          obj.face({last - 2, last - 1, last});
        }
        ++written;
        obj.advance();
      }
    }
  }
  obj.count("hairs", written);
}

}  // namespace hirsute
