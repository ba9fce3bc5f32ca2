// What every organ's attribute record shares (DESIGN.md, "Organs: one placement engine, one
// Scene, several organ types"): the value form of its modules, and the indices by which the
// turtle carries the records. Each organ keeps its records in a Scene vector of its own; the
// turtle state holds an index into each, copied on write, so `[` and `]` save and restore them
// and generalized-cylinder segments record them at their two ends.
#pragma once

namespace hirsute {

// One attribute of an organ module in the value form `v[,rng[,fun[,loc]]]` (Fuhrer et al. 2004,
// Table 1): value ± a uniform offset up to `range` per instance, times function `function` of
// the model's function set evaluated at the girth position s in [0, 1] (0: none).
struct OrganValue {
  float value = 0;
  float range = 0;
  int function = 0;

  bool operator==(const OrganValue&) const = default;
};

// The organs' attribute records where the turtle is: per organ, an index into its Scene vector
// (-1: the organ's defaults, switched off). An organ adds its field here and its table to the
// list in organ_modules.cpp.
struct OrganAttributeIndices {
  int hair = -1;     // HairPart::attributes (hair_part.h)
  int feather = -1;  // FeatherPart::attributes (feather_part.h)
  int fur = -1;      // FurPart::attributes (fur_part.h)

  bool operator==(const OrganAttributeIndices&) const = default;
};

}  // namespace hirsute
