// Feathers as a table: one CSV row per feather (`hirsute export --feathers feathers.csv`), for
// analysis. Reads the Scene's feathers and nothing else.
#pragma once

#include <cstdint>
#include <filesystem>

#include "hirsute/core/output_target.h"
#include "hirsute/interpreter/scene.h"

namespace hirsute {

struct FeatherCsvStats {
  std::uint64_t bytes = 0;
  std::uint64_t rows = 0;  // feathers, the header not counted
};

// The columns, as the header names them: the calamus base x,y,z; the frame's heading (the
// rachis direction) and up (the front) x,y,z; the four types of the bilinear blend and its
// three weights (Scene's Feather: type1 to type2 by blend12, type3 to type4 by blend34, the
// first pair to the second by blend_along; a single feather of @Fe(k) has four times k, one of
// @Fi(k1, k2, t) the pairs k1, k2 with blend t); age; size; `single` or `coat`. Numbers are the
// shortest text that reads back as the same float.
inline constexpr const char* kFeatherCsvHeader =
    "root_x,root_y,root_z,heading_x,heading_y,heading_z,up_x,up_y,up_z,type1,type2,blend12,"
    "type3,type4,blend34,blend_along,age,size,origin";

// Throws std::runtime_error when the file cannot be written, std::invalid_argument for a value
// that is not finite. Commits with `group` when given (output_target.h).
FeatherCsvStats writeFeatherCsv(const Scene& scene, const std::filesystem::path& target,
                                OutputGroup* group = nullptr);

}  // namespace hirsute
