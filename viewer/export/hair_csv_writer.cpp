#include "hirsute/viewer/export/hair_csv_writer.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

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

HairCsvWriter::HairCsvWriter(std::filesystem::path target, OutputGroup* group)
    : out_(std::move(target), group) {}

HairCsvWriter::~HairCsvWriter() = default;

void HairCsvWriter::beginScene(const Scene&) {
  out_.put(kHeader);
  out_.put('\n');
}

void HairCsvWriter::number(float value) {
  if (!std::isfinite(value))
    throw std::invalid_argument("a hair's position or size is not a finite number");
  // The shortest decimal that reads back as the same float (std::to_chars' guarantee).
  char text[32];
  auto result = std::to_chars(text, text + sizeof text, value);
  out_.put(std::string_view(text, static_cast<std::size_t>(result.ptr - text)));
}

void HairCsvWriter::hairs(const std::vector<HairTemplate>&, const std::vector<Hair>& hairs) {
  for (const Hair& h : hairs) {
    glm::vec3 direction = h.direction();
    for (int k = 0; k < 3; ++k) {
      number(h.root[k]);
      out_.put(',');
    }
    for (int k = 0; k < 3; ++k) {
      number(direction[k]);
      out_.put(',');
    }
    out_.putInteger(h.templateIndex);
    out_.put(',');
    number(h.length);
    out_.put(',');
    number(h.radius);
    out_.put(',');
    out_.put(hairSideName(h.side));
    out_.put('\n');
    ++stats_.rows;
    advance();
  }
}

void HairCsvWriter::endScene() {
  out_.commit();
  stats_.bytes = out_.bytesWritten();
}

HairCsvStats writeHairCsv(const Scene& scene, const std::filesystem::path& target,
                          Progress* progress, OutputGroup* group) {
  HairCsvWriter writer(target, group);
  printScene(scene, writer, progress, "writing hairs");
  return writer.stats();
}

}  // namespace hirsute
