// Barb length from silhouette boundary points (Streit & Heidrich 2002, Sec. 4.1, 4.2.2).
#pragma once

#include <span>

#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// The length at `position` along the rachis: linear between neighbouring points, the first
// (last) point's length before (after) them. Where two points share a position (a
// discontinuity), the barb exactly there takes the second; `fromBelow` asks for the first (the
// limit from below). Points must be sorted by position and not empty.
float silhouetteLength(std::span<const SilhouettePoint> points, float position,
                       bool fromBelow = false);

// The barb length of a vane at `position`: its silhouette, or its constant length without one.
float vaneBarbLength(const Vane& vane, float position);

}  // namespace hirsute
