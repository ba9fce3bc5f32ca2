// Feathers between feather types and feathers that are still growing (Streit & Heidrich 2002,
// Sec. 4.2.3 and 4.2.4): both are new FeatherTypes, built from whose parameters the geometry is
// made as for any other.
#pragma once

#include "hirsute/hairs/feathers/feather_type.h"

namespace hirsute {

// Sec. 4.2.3, Fig. 5: the type t of the way from `a` (t = 0, returned exactly) to `b` (t = 1,
// exactly); t is clamped to [0, 1]. Lengths, widths, curvatures, spacings, barb angles, barb
// lengths and silhouettes interpolate linearly, (1 - t) a + t b; silhouettes are first resampled
// at the positions of both (a constant length is a flat silhouette). Key barbs interpolate per
// vane, position, control vertices (the fewer degree-elevated), angle and plumulaceous mix: the
// smaller set is inflated to the larger by pairing every key barb of the larger set with the
// nearest of the smaller in position, keeping both in order and using every key barb of the
// smaller at least once (the order-keeping pairing of least total position difference). A vane
// without key barbs (down, Bdf1 throughout) pairs every key barb of the other with a copy that is
// fully plumulaceous. RGB colours and strip widths interpolate when both have them; the rest of
// the appearance and the Bdf1 seed come from the nearer type. An afterfeather on both blends; one
// on a single side shrinks to size 0 towards the other.
FeatherType blendFeatherTypes(const FeatherType& a, const FeatherType& b, float t);

// Sec. 4.2.4, Figs. 6 and 7: `type` at `age` in [0, 1] (clamped; age 1 returns it exactly). The
// staggered schedule, as Hirsute reads it:
//   0 - 0.3   calamus and rachis length and width grow from 0 (the barb spacing with them, so the
//             barb count is the grown feather's throughout);
//   0.3 - 0.5 barb lengths and silhouettes grow from 0;
//   0.5 - 0.8 the sheath opens from tip to base: a straight key barb migrates from the rachis tip
//             to its base, with the vane's grown angle at its position;
//   0.8 - 1   rachis curvature, the barb angles and the key barbs' curvature rise to their values.
// Until 0.8 barbs lie in the sheath: the vanes' angles are 180° (along the rachis) and the key
// barbs straight (their control vertices evenly on their chords). Three extra straight key barbs
// are present until age 1: at the base and the tip with angle 180° and the migrating one. In the
// last 20% they turn into the barbs the grown feather has where they stand (its key barb there,
// or Bdf1 at the base and Bdf2 at the tip) and their angles into the grown vane's, so that
// removing them at age 1 changes nothing: growth is continuous up to the grown feather.
FeatherType grownFeatherType(const FeatherType& type, float age);

}  // namespace hirsute
