// The name a user most likely meant: for "did you mean …?" hints on a misspelt keyword, command
// or option.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace hirsute {

// Edits that turn `a` into `b`: a letter inserted, removed, replaced, or two neighbours swapped
// (the optimal string alignment distance), ignoring the case of letters.
std::size_t editDistance(std::string_view a, std::string_view b);

// The candidate nearest `word` when it lies within `maxDistance` edits and no other candidate is
// as near; empty otherwise (an exact match is returned as well).
std::string nearestName(std::string_view word, const std::vector<std::string>& candidates,
                        std::size_t maxDistance);

// The edits a slip of the hand may make in a name of `length` letters: one in a short name,
// two from eight letters on.
inline std::size_t typoDistance(std::size_t length) { return length >= 8 ? 2 : 1; }

}  // namespace hirsute
