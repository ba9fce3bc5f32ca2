// Plant hairs as a table: one CSV row per placed hair (`hirsute export --hairs hairs.csv`), for
// analysis and for other renderers. The printer reads the Scene's hairs and nothing else.
// docs/export.md describes the columns.
#pragma once

#include <cstdint>
#include <filesystem>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/export/export_file.h"
#include "hirsute/viewer/export/scene_writer.h"

namespace hirsute {

struct HairCsvStats {
  std::uint64_t bytes = 0;
  std::uint64_t rows = 0;  // hairs, the header not counted
};

// The columns, as the header names them: root x,y,z, the unit direction x,y,z (the template's
// first segment, Hair::direction), the template index, length, radius, and the side of the
// surface the hair grows on (front, back, edge). Numbers are the shortest text that reads back
// as the same float.
class HairCsvWriter : public ScenePrinter {
 public:
  explicit HairCsvWriter(std::filesystem::path target, OutputGroup* group = nullptr);
  ~HairCsvWriter() override;

  static constexpr const char* kHeader =
      "root_x,root_y,root_z,direction_x,direction_y,direction_z,template,length,radius,side";

  void beginScene(const Scene& scene) override;
  // Everything but hairs has no row.
  void mesh(const TriangleMesh&) override {}
  void line(const LineSegment&, LineStyle) override {}
  void sphere(const Sphere&) override {}
  void disc(const Disc&) override {}
  void label(const Label&) override {}
  void hairs(const std::vector<HairTemplate>& templates, const std::vector<Hair>& hairs) override;
  void feathers(const Scene&) override {}  // feather_csv_writer.h has their table
  void fur(const Scene&) override {}
  void endScene() override;

  const HairCsvStats& stats() const { return stats_; }

 private:
  void number(float value);

  ExportFile out_;
  HairCsvStats stats_;
};

// "front", "back" or "edge".
const char* hairSideName(HairSide side);

// Writes a row for every hair of `scene` to `target`, through a temporary file renamed into place;
// shows its progress on `progress` when given; commits with `group` when given.
HairCsvStats writeHairCsv(const Scene& scene, const std::filesystem::path& target,
                          Progress* progress = nullptr, OutputGroup* group = nullptr);

}  // namespace hirsute
