// A text file as the viewer's editors change it (docs/viewer.md, "Editors"): its lines kept as
// written, so that saving rewrites only the lines an edit touched and every other byte (spacing,
// comments, editor marks cpfg ignores) stays as the modeller's tool left it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hirsute {

struct EditedText {
  std::vector<std::string> lines;  // without their '\n' (a '\r' before it stays in the line)
  bool finalNewline = true;        // the text ends with '\n'

  static EditedText split(std::string_view text);
  std::string joined() const;
};

// A number as the curve and surface editors write it: fixed-point with at least `minDecimals`
// and at most 6 decimals (funcedit and cuspy write "%f", bezieredit "%.2f") when one of those
// reads back as the same double, else the shortest form that does.
std::string formatFixed(double value, int minDecimals);

// A value an editor sets, rounded to the 6 decimals the formats above write, so that what is
// saved reads back as what was shown.
double roundToMicro(double value);

// Writes `text` to `file` atomically (a temporary file in its folder renamed over it, no link
// followed, output_target.h). Throws std::runtime_error "PATH: REASON".
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace hirsute
