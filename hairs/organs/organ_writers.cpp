// The organs' writers (organ_writer.h), registered (organ_list.h), in the order the formats write
// them.
#include "hirsute/viewer/export/organ_writer.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name) const OrganWriter& name##Writer();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

std::span<const OrganWriter* const> organWriters() {
#define HIRSUTE_WRITER(folder, name) &name##Writer(),
  static const OrganWriter* const writers[] = {HIRSUTE_ORGANS(HIRSUTE_WRITER)};
#undef HIRSUTE_WRITER
  return writers;
}

}  // namespace hirsute
