// cpfg's background scenes (manual §8.3, view command `background scene:`): extra objects drawn
// after the string, read from a preprocessed text of OpenGL-like commands: primitives (polygon,
// polygonuv, rectangle, mesh, box, cone, cylinder, sphere), `material` and the modelview matrix
// commands. Loaded once per model with the other resources; appended to every Scene built from it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/lsys/preprocessor.h"

namespace hirsute {

// What a background scene holds in cpfg's own primitives, as its rayshade output (-ray) writes
// them: a cylinder or cone with a disc on each end, a sphere, and polygons as triangles.
struct BackgroundPrimitiveCounts {
  std::size_t triangles = 0;
  std::size_t spheres = 0;
  std::size_t cylinders = 0;  // cylinders and cones
  std::size_t discs = 0;      // their end caps (radius > 0)
};

// One background file, in world coordinates. Materials are the file's `material` commands in
// order (entry 0 is OpenGL's default material, used before the first); the meshes' and spheres'
// `material` fields index this list.
struct BackgroundScene {
  std::vector<Material> materials;
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  BackgroundPrimitiveCounts counts;
};

// Reads a background file through the C preprocessor, as cpfg does, with `preprocessing`'s
// limits. Errors are thrown as DiagnosticError at `file:line`.
BackgroundScene loadBackgroundScene(const std::filesystem::path& file, Diagnostics& diagnostics,
                                    const PreprocessorOptions& preprocessing = {});

// Appends the background's materials to scene.materials (at new indices after the palette) and
// its meshes and spheres, drawn with them.
void appendBackgroundScene(const BackgroundScene& background, Scene& scene);

}  // namespace hirsute
