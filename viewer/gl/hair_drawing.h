// Plant hairs in the GL renderer (DESIGN.md, "Plant hairs"): instances of their template's
// segments, drawn as antialiased (multisampled) GL lines in the template material's colour,
// unlit, one instanced draw per template. GlRenderer owns one; other organs add their drawing
// beside it in a file of their own.
#pragma once

#include <cstddef>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute {

class HairDrawing {
 public:
  // Compiles the hair program; the renderer's context must be current.
  explicit HairDrawing(const GlFunctions& gl);
  ~HairDrawing();
  HairDrawing(const HairDrawing&) = delete;
  HairDrawing& operator=(const HairDrawing&) = delete;

  // Uploads the scene's hairs, coloured from `palette` (the renderer's materials, never empty).
  void upload(const Scene& scene, const std::vector<Material>& palette);
  void release();
  // Draws `fraction` (in (0, 1]) of every template's hairs: a spatially uniform prefix.
  void draw(const Camera& camera, float fraction) const;

  // Hairs uploaded (those whose template has segments), and their segments.
  std::size_t hairCount() const { return hairs_; }
  std::size_t segmentCount() const { return segments_; }

 private:
  struct Batch;

  const GlFunctions& gl_;
  GLuint program_ = 0;
  GLint viewProjection_ = -1, color_ = -1;
  std::vector<Batch> batches_;
  GLuint instances_ = 0;         // every template's hairs, template after template, in levels
  GLuint instancesInOrder_ = 0;  // the same in placement order
  std::size_t hairs_ = 0, segments_ = 0;
};

}  // namespace hirsute
