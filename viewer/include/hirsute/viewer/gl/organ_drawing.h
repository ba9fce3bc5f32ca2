// An organ's drawing in the GL renderer (docs/design.md, "Organs"): each renderer makes one
// of every organ of organDrawings(), uploads the scene to it, and draws it after the lines and
// before the transparent surfaces, with the light the surfaces have. The drawings live in the
// organs' folders (hairs/NAME/gl/), over the GL helpers of gl_objects.h; the renderer never names
// an organ, and reaches one by the name it registers ("hairs").
//
// Adding an organ's drawing: a class derived from OrganDrawing and an OrganDrawingType that makes
// it (OrganDrawingTypeOf), in the organ's folder, returned by its nameDrawing(); the organ's line
// in hairs/organs/organ_list.h registers it, and the list's order is the order they are drawn in.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

// What a drawing uploads from.
struct OrganUpload {
  const Scene& scene;
  const ViewSettings& view;
  const std::vector<GLuint>&
      textures;  // the renderer's GL textures by Scene texture index (0: none)
  const std::vector<Material>& palette;  // the renderer's materials, never empty
};

class OrganDrawing {
 public:
  virtual ~OrganDrawing() = default;

  // Replaces what was uploaded. The renderer's context is current in every call.
  virtual void upload(const OrganUpload& upload) = 0;
  // Takes from `scene` again what the viewer moves (poses, strands, wetness); the rest stays as
  // uploaded. `textures` as in OrganUpload.
  virtual void update(const Scene& scene, const std::vector<GLuint>& textures) = 0;
  virtual void release() = 0;
  // Draws, lit by the directional light `light` (towards it); `detail` in [0, 1] is the share of
  // the instances drawn while the camera moves, for an organ that can draw a uniform part.
  virtual void draw(const Camera& camera, const glm::vec3& light, float detail) = 0;
  // Whether it draws only `detail` of its instances (the others draw all whatever the detail).
  virtual bool thins() const { return false; }
  // Instances uploaded, and the primitives they are drawn with (at detail 1).
  virtual std::size_t instances() const = 0;
  virtual std::size_t primitives() const = 0;
};

class OrganDrawingType {
 public:
  virtual ~OrganDrawingType() = default;
  // The name the viewer reaches the drawing by ("hairs").
  virtual const char* name() const = 0;
  // A drawing for the renderer whose context `gl` was resolved for (current now).
  virtual std::unique_ptr<OrganDrawing> make(const GlFunctions& gl) const = 0;
};

// The type of a drawing class constructed from the GL functions alone.
template <class Drawing>
class OrganDrawingTypeOf : public OrganDrawingType {
 public:
  explicit OrganDrawingTypeOf(const char* name) : name_(name) {}
  const char* name() const override { return name_; }
  std::unique_ptr<OrganDrawing> make(const GlFunctions& gl) const override {
    return std::make_unique<Drawing>(gl);
  }

 private:
  const char* name_;
};

// Every organ's drawing, in the order they are drawn (hairs/organs/organ_list.h).
std::span<const OrganDrawingType* const> organDrawings();

}  // namespace hirsute
