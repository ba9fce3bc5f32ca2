// How cpfg reads integers from the float parameters of modules.
#pragma once

#include <cmath>

namespace hirsute {

// cpfg reads colour indices and counts from float parameters by truncation: `;(253.565)` is 253
// (cpfg-WeepingBirch's rayshade output uses material 253 for it).
inline int truncated(float value) {
  if (!(std::abs(value) < 2e9f)) return 0;
  return static_cast<int>(value);
}

}  // namespace hirsute
