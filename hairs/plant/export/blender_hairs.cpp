// Plant hairs in the scene file for Blender (blender_writer.h): the hairs of each template one
// curve group, named after the template's file, each polyline of the template placed as a curve
// of the hair's radius in the template's colour; the template's filled polygons, placed, one
// mesh beside it.
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <string>
#include <vector>

#include "hirsute/hairs/plant/plant_hair_writer.h"
#include "hirsute/viewer/export/blender_writer.h"

namespace hirsute {

void PlantHairWriter::writeBlender(const Scene& scene, BlenderWriter& blender) const {
  const std::vector<HairTemplate>& templates = scene.organ<HairPart>().templates;
  const std::vector<Hair>& hairs = scene.organ<HairPart>().hairs;
  std::uint64_t written = 0;
  for (std::size_t t = 0; t < templates.size(); ++t) {
    const HairTemplate& shape = templates[t];
    const glm::vec3 colour =
        shape.material >= 0 && static_cast<std::size_t>(shape.material) < scene.materials.size()
            ? scene.materials[static_cast<std::size_t>(shape.material)].diffuse
            : Material{}.diffuse;
    // The template's name: its file's, without the folder.
    const std::string name = std::filesystem::path(shape.file).stem().string();
    std::vector<glm::vec3> blades;
    std::vector<std::uint32_t> bladeIndices;
    bool open = false;
    for (const Hair& h : hairs) {
      if (h.templateIndex != t) continue;
      if (!open && shape.segmentCount() > 0) {
        blender.beginCurves("hairs", name,
                            blender.sceneMaterial(shape.material, BlenderWriter::Shading::Hair));
        open = true;
      }
      const glm::mat3 rotation = glm::mat3_cast(h.rotation());
      for (const auto& polyline : shape.polylines) {
        if (polyline.size() < 2) continue;
        for (const glm::vec3& p : polyline)
          blender.curvePoint(h.root + h.length * (rotation * p), h.radius, colour);
        blender.endCurve();
      }
      for (const glm::vec3& p : shape.triangles) {
        bladeIndices.push_back(static_cast<std::uint32_t>(blades.size()));
        blades.push_back(h.root + h.length * (rotation * p));
      }
      ++written;
      blender.advance();
    }
    blender.endCurves();
    if (!bladeIndices.empty()) {
      blender.triangles("hairs", name + " blades",
                        blender.sceneMaterial(shape.material, BlenderWriter::Shading::Surface),
                        blades, {}, {}, {}, bladeIndices);
    }
  }
  blender.count("hairs", written);
}

}  // namespace hirsute
