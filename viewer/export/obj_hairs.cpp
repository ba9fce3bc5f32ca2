// Plant hairs in the OBJ file (DESIGN.md, "Plant hairs"): each polyline of a hair's template,
// placed, one `l` element under `o hairs`, grouped by the template's material. The rest of the
// file is obj_writer.cpp; other organs add their own file beside this one.
#include <algorithm>
#include <glm/gtc/quaternion.hpp>
#include <vector>

#include "hirsute/viewer/export/obj_writer.h"

namespace hirsute {

void ObjWriter::hairs(const std::vector<HairTemplate>& templates, const std::vector<Hair>& hairs) {
  finishPolyline();
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
      if (shape.material != material || shape.segmentCount() == 0 || first[t] == first[t + 1])
        continue;
      group("hairs");
      useMaterial(material, -1);
      for (std::size_t k = first[t]; k < first[t + 1]; ++k) {
        const Hair& h = hairs[order[k]];
        glm::mat3 rotation = glm::mat3_cast(h.rotation());
        for (const auto& polyline : shape.polylines) {
          if (polyline.size() < 2) continue;
          for (const glm::vec3& p : polyline) {
            vertex(h.root + h.length * (rotation * p));
            polyline_.push_back(stats_.vertices);
          }
          finishPolyline();
        }
        ++stats_.hairs;
        advance();
      }
    }
  }
}

}  // namespace hirsute
