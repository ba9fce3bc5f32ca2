#include "hirsute/hairs/feathers/feather_csv_writer.h"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_writer.h"
#include "hirsute/viewer/export/export_file.h"

namespace hirsute {

FeatherCsvStats writeFeatherCsv(const Scene& scene, const std::filesystem::path& target,
                                OutputGroup* group) {
  ExportFile out(target, group);
  auto number = [&](float value) {
    if (!std::isfinite(value))
      throw std::invalid_argument("a feather's position or frame is not a finite number");
    char text[32];
    auto result = std::to_chars(text, text + sizeof text, value);
    out.put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
    out.put(',');
  };
  out.put(kFeatherCsvHeader);
  out.put('\n');
  FeatherCsvStats stats;
  for (const Feather& f : scene.organ<FeatherPart>().feathers) {
    for (const glm::vec3& v : {f.position, f.heading, f.up}) {
      for (int k = 0; k < 3; ++k) number(v[k]);
    }
    for (int pair = 0; pair < 2; ++pair) {
      out.putInteger(f.types[static_cast<std::size_t>(2 * pair)]);
      out.put(',');
      out.putInteger(f.types[static_cast<std::size_t>(2 * pair + 1)]);
      out.put(',');
      number(f.across[static_cast<std::size_t>(pair)]);
    }
    number(f.along);
    number(f.age);
    number(f.size);
    out.put(f.origin == FeatherOrigin::Coat ? "coat\n" : "single\n");
    ++stats.rows;
  }
  out.commit();
  stats.bytes = out.bytesWritten();
  return stats;
}

std::optional<OrganTable> FeatherWriter::table() const {
  return OrganTable{
      "--feathers",
      "Write the feathers to FILE (.csv): one row per feather (root, heading, up, types and "
      "blends, age, size, single or coat)",
      [](const Scene& scene, const std::filesystem::path& target, Progress* progress,
         OutputGroup* group) {
        if (progress != nullptr) {
          progress->begin("writing feathers", Progress::Unit::None);
          progress->update(0);
        }
        return writeFeatherCsv(scene, target, group).rows;
      }};
}

const OrganWriter& featherWriter() {
  static const FeatherWriter writer;
  return writer;
}

}  // namespace hirsute
