#include "hirsute/hairs/plant/hair_csv_writer.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hair_writer.h"
#include "hirsute/viewer/export/export_file.h"

namespace hirsute {

const char* hairSideName(HairSide side) {
  switch (side) {
    case HairSide::Front:
      return "front";
    case HairSide::Back:
      return "back";
    case HairSide::Edge:
      return "edge";
  }
  return "front";
}

HairCsvStats writeHairCsv(const Scene& scene, const std::filesystem::path& target,
                          Progress* progress, OutputGroup* group) {
  ExportFile out(target, group);
  auto number = [&out](float value) {
    if (!std::isfinite(value))
      throw std::invalid_argument("a hair's position or size is not a finite number");
    // The shortest decimal that reads back as the same float (std::to_chars' guarantee).
    char text[32];
    auto result = std::to_chars(text, text + sizeof text, value);
    out.put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
  };
  if (progress != nullptr) {
    progress->begin("writing hairs", Progress::Unit::Percent,
                    static_cast<double>(scene.organ<HairPart>().hairs.size()));
  }
  out.put(kHairCsvHeader);
  out.put('\n');
  HairCsvStats stats;
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    glm::vec3 direction = h.direction();
    for (int k = 0; k < 3; ++k) {
      number(h.root[k]);
      out.put(',');
    }
    for (int k = 0; k < 3; ++k) {
      number(direction[k]);
      out.put(',');
    }
    out.putInteger(h.templateIndex);
    out.put(',');
    number(h.length);
    out.put(',');
    number(h.radius);
    out.put(',');
    out.put(hairSideName(h.side));
    out.put('\n');
    ++stats.rows;
    if (progress != nullptr) progress->tick(static_cast<double>(stats.rows));
  }
  out.commit();
  stats.bytes = out.bytesWritten();
  return stats;
}

std::optional<OrganTable> PlantHairWriter::table() const {
  return OrganTable{
      "--hairs",
      "Write the placed hairs to FILE (.csv): one row per hair (root, direction, template, "
      "length, radius, side)",
      [](const Scene& scene, const std::filesystem::path& target, Progress* progress,
         OutputGroup* group) { return writeHairCsv(scene, target, progress, group).rows; }};
}

const OrganWriter& plantHairWriter() {
  static const PlantHairWriter writer;
  return writer;
}

}  // namespace hirsute
