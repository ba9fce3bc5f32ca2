// Predefined surfaces drawn by `~X`: cpfg's bicubic `.s` files (bezieredit), declared in the view
// file with `surface: X file.s size …` (cpfg-features.md, "Bicubic surface .s").
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hirsute {

struct BezierPatch {
  std::string name;
  std::array<glm::dvec3, 16> points;  // 4 rows of 4 control points, as in the file
  int topColor = 0, bottomColor = 0;  // 0: the turtle's colour
  double topDiffuse = 0, bottomDiffuse = 0;
  // Neighbours by name for normal averaging (AL A AR L R BL B BR; empty: none).
  std::array<std::string, 8> neighbours;
};

struct Surface {
  char id = 0;
  std::string file;
  glm::dvec3 contact{0.0}, endPoint{0.0}, heading{0, 1, 0}, up{0, 0, 1};
  double fileSize = 1;   // SIZE: in the file
  double viewSize = 1;   // size: in the view file's `surface:` line
  int sPrecision = 0, tPrecision = 0;
  int texture = 0;
  std::vector<BezierPatch> patches;
};

// Reads a `.s` file. Throws DiagnosticError at the broken line.
Surface loadSurface(const std::string& file);

}  // namespace hirsute
