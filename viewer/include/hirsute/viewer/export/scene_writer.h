// Every export format is one printer class driven by the same walk over the Scene (PlantGL's
// lesson): printScene() visits the Scene's own elements in one fixed order and a printer turns
// each into its format's text, then hands itself to each organ's writer (organ_writer.h), which
// draws the organ through the printer's public calls. A printer reads the Scene's own elements
// (and, for formats that carry a camera, the view it is given) and names no organ; adding a
// format is adding a printer and, in each organ's folder, its writer for the format.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "hirsute/core/progress.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/export/organ_writer.h"

namespace hirsute {

class ScenePrinter {
 public:
  virtual ~ScenePrinter() = default;

  // Before any element: the whole scene, for what a format declares up front (materials used,
  // bounds, precision).
  // `organs` are the organs' writers printScene() visits after the scene's own elements.
  virtual void beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) = 0;
  virtual void mesh(const TriangleMesh& mesh) = 0;
  // Lines come in scene order; `style` says how their widths are meant (Scene::lineStyle).
  virtual void line(const LineSegment& line, LineStyle style) = 0;
  virtual void sphere(const Sphere& sphere) = 0;
  virtual void disc(const Disc& disc) = 0;
  virtual void label(const Label& label) = 0;
  // After the labels, each organ of organWriters() that the scene has, once: the printer hands
  // itself to the organ's writer for its format (organ_writer.h).
  virtual void organ(const OrganWriter& organ, const Scene& scene) = 0;
  // After the last element: close what is open and commit the files.
  virtual void endScene() = 0;

  // A printer or an organ's writer whose one call writes many items (instance by instance)
  // calls this after each, so that the progress line moves while it runs.
  void advance(double items = 1) {
    if (progress_ == nullptr) return;
    done_ += items;
    // A big step (a mesh of many triangles) is worth a look at the clock; small ones count down.
    if (items >= 64) {
      progress_->update(done_);
    } else {
      progress_->tick(done_);
    }
  }

 private:
  friend void printScene(const Scene&, ScenePrinter&, Progress*, const char*);
  Progress* progress_ = nullptr;
  double done_ = 0;  // items written: triangles, lines, spheres, discs, labels, organs' items
};

// Visits meshes, lines, spheres, discs and labels, in that order and each in scene order, then the
// organs of organWriters() (in the export library, not the formats'). Meshes without triangles are
// skipped. With `progress`, shows `STAGE: N%` of the items written (a mesh counts its triangles).
void printScene(const Scene& scene, ScenePrinter& printer, Progress* progress = nullptr,
                const char* stage = "writing");

// Whether `mesh` is drawn with its texture image: it names a texture of the scene that has pixels,
// and has one texture coordinate per vertex. As in the GL renderer, a texture that could not be
// read leaves its meshes untextured.
bool drawnTextured(const Scene& scene, const TriangleMesh& mesh);

// The normals a mesh is written with: its own, normalised; where one is zero or not finite, the
// normalised sum of the normals of the faces around the vertex (POV-Ray rejects a zero normal,
// OBJ readers shade it black). Only a mesh that needs them pays for the face normals.
class VertexNormals {
 public:
  explicit VertexNormals(const TriangleMesh& mesh) : mesh_(mesh) {}
  glm::vec3 operator[](std::size_t vertex);

 private:
  const TriangleMesh& mesh_;
  std::vector<glm::vec3> faceSums_;
};

// The distance below which two printed coordinates may be read back equal, relative to the
// scene's size: one millionth of the bounding-box diagonal (far below a pixel at any usable
// resolution, above float's own precision), and the decimals that resolve it.
int positionDecimals(const Bounds& bounds);

}  // namespace hirsute
