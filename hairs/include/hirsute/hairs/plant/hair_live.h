// The plant hairs in the interactive viewer (live_organ.h): shown and hidden with H; nothing of
// theirs moves between builds.
#pragma once

#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {

const LiveOrganType& plantHairLive();

}  // namespace hirsute
