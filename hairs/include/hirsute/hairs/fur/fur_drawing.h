// Shell fur in the GL renderer (Silva et al. 2010, Sec. 3-4; docs/design.md, "Fur"):
// after the surfaces are drawn with depth writes, each fur surface is drawn again as N layers,
// one instanced draw, layer n at h = (n + 1) / N displaced by Eq. 1 (the quadratic Bézier of the
// strand's particle plus the curl of Eq. 4) in the vertex shader; the fragment shader clumps by
// Eq. 5 and Algorithm 2 from the wetness mask, keeps the texels of the fur texture whose strand
// reaches h, and shades them by Kajiya-Kay (Eq. 6) times the shadow factor. The renderer makes one
// by furDrawing() (organ_drawing.h).
#pragma once

#include <cstddef>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/gl/organ_drawing.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

class FurDrawing : public OrganDrawing {
 public:
  // Compiles the shell program; the renderer's context must be current.
  explicit FurDrawing(const GlFunctions& gl);
  ~FurDrawing() override;
  FurDrawing(const FurDrawing&) = delete;
  FurDrawing& operator=(const FurDrawing&) = delete;

  // Uploads the fur surfaces, their fur textures and wetness masks. `textures` are the
  // renderer's GL textures by Scene texture index (0: none), `palette` its materials.
  void upload(const OrganUpload& upload) override;
  // Uploads again what moves: the strands' particles and the wetness masks.
  void update(const Scene& scene, const std::vector<GLuint>& textures) override;
  void release() override;
  // Draws every layer of every fur surface, lit by the directional light `light` (towards it).
  void draw(const Camera& camera, const glm::vec3& light, float detail) override;

  // The fur surfaces, and the shell triangles drawn a frame.
  std::size_t instances() const override;
  std::size_t primitives() const override { return shellTriangles(); }
  int layers() const { return layers_; }
  std::size_t shellTriangles() const;  // triangles drawn per frame: triangles × layers

 private:
  struct Surface;

  const GlFunctions& gl_;
  GLuint program_ = 0;
  std::vector<Surface> surfaces_;
  std::vector<GLuint> furTextures_;
  int layers_ = 16;
};

// The fur's drawing, registered as "fur".
const OrganDrawingType& furDrawing();

}  // namespace hirsute
