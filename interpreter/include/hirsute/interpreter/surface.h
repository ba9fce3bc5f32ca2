// Predefined surfaces drawn by `~X`: cpfg's bicubic `.s` files (bezieredit), declared in the view
// file with `surface: X file.s size …` (cpfg-features.md, "Bicubic surface .s").
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/edited_text.h"
#include "hirsute/interpreter/mesh_file.h"

namespace hirsute {

struct BezierPatch {
  std::string name;
  std::array<glm::dvec3, 16> points;  // 4 rows of 4 control points, as in the file
  int topColor = 0, bottomColor = 0;  // 0: the turtle's colour
  double topDiffuse = 0, bottomDiffuse = 0;
  // Neighbours by name for normal averaging (AL A AR L R BL B BR; empty: none).
  std::array<std::string, 8> neighbours;
};

// cpfg's tessellation of a patch when neither the file (PRECISION) nor the view's `surface:`
// line gives one: S_COUNT/2 = 5 quads each way, as cpfg's rayshade output of cpfg-Sedge shows
// (50 triangles per patch).
inline constexpr int kDefaultSurfacePrecision = 5;

// cpfg reads at most this many patches per surface; Hirsute reads more and warns.
inline constexpr int kCpfgMaxPatches = 65;

struct Surface {
  char id = 0;
  std::string file;
  glm::dvec3 contact{0.0}, endPoint{0.0}, heading{0, 1, 0}, up{0, 0, 1};  // as in the file
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};  // the first line: xmin xmax ymin ymax zmin zmax
  double fileSize = 1;                        // SIZE: in the file
  double viewSize = 1;                        // size: in the view file's `surface:` line
  // Quads per patch along s and t: the view's `surface:` line, else the file's PRECISION, else
  // kDefaultSurfacePrecision. Never 0 once loaded.
  int sPrecision = kDefaultSurfacePrecision, tPrecision = kDefaultSurfacePrecision;
  int texture = 0;  // 1-based, 0 none (the view's `surface:` line)
  std::vector<BezierPatch> patches;
  // A mesh file's triangles instead of patches (mesh_file.h): its contact and end points are the
  // file's origin, its heading +y and its up +z, SIZE 1.
  std::shared_ptr<const SurfaceMeshData> mesh;
  std::optional<glm::dvec3> flow;  // a mesh's `mesh flow:`, in the file's coordinates
};

// Reads a `.s` file. Throws DiagnosticError at the broken line.
Surface loadSurface(const std::string& file);

}  // namespace hirsute

namespace hirsute {

// A `.s` file as the viewer's surface editor changes it (docs/viewer.md, "Surfaces"): its lines
// as written and the lines of each patch's rows of control points. Moving a point rewrites its
// row and reads the whole text again with the reader above, so that the editor shows and saves
// exactly what cpfg will read; every other byte stays as it was.
class SurfaceFile {
 public:
  // Throws DiagnosticError at the broken line.
  static SurfaceFile parse(std::string_view text, const std::string& fileName);
  static SurfaceFile load(const std::string& file);

  const Surface& surface() const { return surface_; }
  const std::string& fileName() const { return fileName_; }
  std::string text() const { return text_.joined(); }

  // Point `index` (row-major, 0 to 15) of patch `patch`, in the file's coordinates. Returns an
  // empty string when made, else why not (the file left as it was).
  std::string setPoint(std::size_t patch, std::size_t index, glm::dvec3 point);

 private:
  std::string fileName_;
  EditedText text_;
  Surface surface_;
  std::vector<std::array<int, 4>> rowLines_;  // 1-based lines of each patch's rows
};

}  // namespace hirsute
