// The organs in the interactive viewer (live_organ.h), registered (organ_list.h), in the order of
// their drawings.
#include "hirsute/viewer/interaction/live_organ.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name) const LiveOrganType& name##Live();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

std::span<const LiveOrganType* const> liveOrgans() {
#define HIRSUTE_LIVE(folder, name) &name##Live(),
  static const LiveOrganType* const organs[] = {HIRSUTE_ORGANS(HIRSUTE_LIVE)};
#undef HIRSUTE_LIVE
  return organs;
}

}  // namespace hirsute
