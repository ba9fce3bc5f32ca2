// Every export format is one printer class driven by the same walk over the Scene (PlantGL's
// lesson, STYLE.md): printScene() visits the elements in one fixed order and a printer turns
// each into its format's text. Adding a format is adding a printer; it reads the Scene and
// nothing else (and, for formats that carry a camera, the view it is given).
#pragma once

#include <cstddef>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/core/progress.h"

namespace hirsute {

class ScenePrinter {
 public:
  virtual ~ScenePrinter() = default;

  // Before any element: the whole scene, for what a format declares up front (materials used,
  // bounds, precision).
  virtual void beginScene(const Scene& scene) = 0;
  virtual void mesh(const TriangleMesh& mesh) = 0;
  // Lines come in scene order; `style` says how their widths are meant (Scene::lineStyle).
  virtual void line(const LineSegment& line, LineStyle style) = 0;
  virtual void sphere(const Sphere& sphere) = 0;
  virtual void disc(const Disc& disc) = 0;
  virtual void label(const Label& label) = 0;
  // Plant hairs, after the labels, once, when the scene has any: the templates and the placed
  // hairs, which are instances of them (a hair's templateIndex may name no template: such a hair
  // is left out). All of them at once, because formats group them (by template, material, size).
  virtual void hairs(const std::vector<HairTemplate>& templates,
                     const std::vector<Hair>& hairs) = 0;
  // Feathers, after the hairs, once, when the scene has any: the whole scene, because each
  // feather is built from its types (hirsute/hairs/feathers/feather_instances.h) and formats
  // group them.
  virtual void feathers(const Scene& scene) = 0;
  // Fur, after the feathers, once, when the scene has fur surfaces: as explicit strands
  // (hirsute/hairs/fur/fur_strands.h), since no format draws shells.
  virtual void fur(const Scene& scene) = 0;
  // After the last element: close what is open and commit the files.
  virtual void endScene() = 0;

 protected:
  // A printer whose one call writes many items (hairs() a hair at a time) calls this after each,
  // so that the progress line moves while it runs.
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
  double done_ = 0;  // items written: triangles, lines, spheres, discs, labels, hairs, feathers
};

// Visits meshes, lines, spheres, discs, labels, hairs and feathers, in that order and each in scene
// order. Meshes without triangles are skipped. With `progress`, shows `STAGE: N%` of the items
// written (a mesh counts its triangles).
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
