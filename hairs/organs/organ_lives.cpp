// The organs in the interactive viewer (live_organ.h), registered: one line an organ, in the
// order of their drawings (organ_drawings.cpp).
#include "hirsute/hairs/feathers/feather_live.h"
#include "hirsute/hairs/fur/fur_live.h"
#include "hirsute/hairs/plant/hair_live.h"
#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {

std::span<const LiveOrganType* const> liveOrgans() {
  static const LiveOrganType* const organs[] = {
      &hairLive(),
      &featherLive(),
      &furLive(),
  };
  return organs;
}

}  // namespace hirsute
