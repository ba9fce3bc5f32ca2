// The plant hairs' writers (organ_writer.h): POV-Ray (export/pov_hairs.cpp), OBJ
// (export/obj_hairs.cpp) and the table of `export --hairs` (export/hair_csv_writer.cpp).
#pragma once

#include <string>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/export/organ_writer.h"

namespace hirsute {

class PlantHairWriter : public OrganWriter {
 public:
  // Sides of a hair's POV-Ray tube, and the step of the radius/length buckets: a hair's tube
  // radius is within 1% of its own radius.
  static constexpr int kTubeSides = 5;
  static constexpr double kBucketStep = 1.02;

  std::size_t items(const Scene& scene) const override {
    return scene.organ<HairPart>().hairs.size();
  }
  // Hairs as instances (docs/design.md, "Plant hairs"): a tube of the hair radius around each
  // template is declared once per template and bucket of radius/length (the tube is in the
  // template's frame, which length scales), and each hair is an `object` of it with its matrix;
  // the hairs of a material are one union carrying the material's texture. docs/export.md has
  // the figures. Counts "hairs", "hair meshes" (tubes declared) and "hairs skipped" (no template
  // with segments, zero radius or length).
  void writePov(const Scene& scene, PovWriter& pov) const override;
  // Hairs as polylines: each polyline of a hair's template, placed, one `l` element, under
  // `o hairs`, grouped by their template's material (one `usemtl` each). Counts "hairs".
  void writeObj(const Scene& scene, ObjWriter& obj) const override;
  // Each template's hairs one curve group (blender_hairs.cpp). Counts "hairs".
  void writeBlender(const Scene& scene, BlenderWriter& blender) const override;
  // "N hairs".
  std::string povSummary(const Scene& scene) const override {
    return std::to_string(scene.organ<HairPart>().hairs.size()) + " hairs";
  }
  // `--hairs FILE`: writeHairCsv (hair_csv_writer.h).
  std::optional<OrganTable> table() const override;
};

const OrganWriter& plantHairWriter();

}  // namespace hirsute
