// Plant hairs in the GL renderer (docs/design.md, "Plant hairs"): instances of their template's
// segments, drawn as antialiased (multisampled) GL lines in the template material's colour,
// unlit, one instanced draw per template (organ_drawing.h: the renderer makes one by
// plantHairDrawing()).
#pragma once

#include <cstddef>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/gl/organ_drawing.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

class HairDrawing : public OrganDrawing {
 public:
  // Compiles the hair program; the renderer's context must be current.
  explicit HairDrawing(const GlFunctions& gl);
  ~HairDrawing() override;
  HairDrawing(const HairDrawing&) = delete;
  HairDrawing& operator=(const HairDrawing&) = delete;

  // Uploads the scene's hairs, coloured from the palette.
  void upload(const OrganUpload& upload) override;
  // Hairs do not move.
  void update(const Scene&, const std::vector<GLuint>&) override {}
  void release() override;
  // Draws `fraction` (in (0, 1]) of every template's hairs: a spatially uniform prefix.
  void draw(const Camera& camera, const glm::vec3& light, float fraction) override;

  // Hairs uploaded (those whose template has segments), and their segments.
  bool thins() const override { return true; }
  std::size_t instances() const override { return hairs_; }
  std::size_t primitives() const override { return segments_; }

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

// The hairs' drawing, registered as "hairs".
const OrganDrawingType& plantHairDrawing();

}  // namespace hirsute
