// Plant hairs as a table: one CSV row per placed hair (`hirsute export --hairs hairs.csv`), for
// analysis and for other renderers. Reads the Scene's hairs and nothing else. docs/export.md
// describes the columns.
#pragma once

#include <cstdint>
#include <filesystem>

#include "hirsute/core/output_target.h"
#include "hirsute/core/progress.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

struct HairCsvStats {
  std::uint64_t bytes = 0;
  std::uint64_t rows = 0;  // hairs, the header not counted
};

// The columns, as the header names them: root x,y,z, the unit direction x,y,z (the template's
// first segment, Hair::direction), the template index, length, radius, and the side of the
// surface the hair grows on (front, back, edge). Numbers are the shortest text that reads back
// as the same float.
inline constexpr const char* kHairCsvHeader =
    "root_x,root_y,root_z,direction_x,direction_y,direction_z,template,length,radius,side";

// "front", "back" or "edge".
const char* hairSideName(HairSide side);

// Writes a row for every hair of `scene` to `target`, through a temporary file renamed into place;
// shows its progress on `progress` when given; commits with `group` when given. Throws
// std::runtime_error when the file cannot be written, std::invalid_argument for a value that is
// not finite.
HairCsvStats writeHairCsv(const Scene& scene, const std::filesystem::path& target,
                          Progress* progress = nullptr, OutputGroup* group = nullptr);

}  // namespace hirsute
