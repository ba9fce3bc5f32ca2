// Feathers in the GL renderer (Streit & Heidrich 2002, Sec. 4.3): the shafts as lit tubes, the
// barbs as alpha-blended lines or strips fading to their tips, textured in the type's mapping,
// each feather at the level of detail of its size on the screen, its barbs thinned where the
// picture cannot show them all, and its vanes in the order the camera asks for
// (feather_buffers.h). Feathers are instances (FeatherInstances): each template's geometry is
// built once, and every frame streams the feathers through one buffer, each feather its template
// placed by its transform, in the Scene's order (a coat from the bottom feather up, so that
// blending stays right), a draw for up to kStreamVertices vertices: llvmpipe pays some 85 µs a
// draw, which a draw per feather made the larger part of a coat's time. Memory follows the
// templates and the stream, not the feathers: a full stream is rasterised before the next is
// filled. The renderer makes one by featherDrawing() (organ_drawing.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/gl/organ_drawing.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/view/feather_buffers.h"

namespace hirsute {

class FeatherDrawing : public OrganDrawing {
 public:
  // Compiles the feather programs; the renderer's context must be current.
  explicit FeatherDrawing(const GlFunctions& gl);
  ~FeatherDrawing() override;
  FeatherDrawing(const FeatherDrawing&) = delete;
  FeatherDrawing& operator=(const FeatherDrawing&) = delete;

  // Keeps what the feathers are made of; the geometry is built on the first draw, for its camera.
  // `textures` are the renderer's GL textures by Scene texture index (0: none).
  void upload(const OrganUpload& upload) override { take(upload.scene, upload.textures); }
  // The feathers and their poses again, as upload() takes them.
  void update(const Scene& scene, const std::vector<GLuint>& textures) override {
    take(scene, textures);
  }
  void release() override;
  // Draws the shafts (opaque) and then the barbs (blended, without depth writes), rebuilding the
  // geometry when the camera asks for other levels of detail. `light` is the direction towards
  // the light the shafts are lit by.
  void draw(const Camera& camera, const glm::vec3& light, float detail) override;

  std::size_t instances() const override { return scene_.organ<FeatherPart>().feathers.size(); }
  // The barb and shaft triangles and segments drawn for the last camera, every instance's.
  std::size_t primitives() const override;
  const FeatherInstances& builtInstances() const { return instances_; }

 private:
  void take(const Scene& scene, const std::vector<GLuint>& textures);
  void build(const std::vector<std::uint8_t>& levels);

  const GlFunctions& gl_;
  GLuint shaftProgram_ = 0, barbProgram_ = 0;
  GLint shaftViewProjection_ = -1, shaftLight_ = -1;
  GLint barbViewProjection_ = -1, barbTextured_ = -1, barbTexture_ = -1;
  Scene scene_;  // the feathers, their types and the materials (no other geometry)
  std::vector<GLuint> textures_;
  FeatherInstances instances_;
  bool built_ = false;
  GLuint shaftArray_ = 0, barbArray_ = 0;
  GLuint vertexBuffers_[7] = {};  // shaft positions, normals, colours, indices; barb positions,
                                  // colours, texture coordinates
  GLuint barbIndices_ = 0;
  // The stream: placed vertices and indices of the feathers drawn next (FeatherBuffers' layout).
  FeatherBuffers stream_;
  std::vector<FeatherDrawRun> runs_;
  // The levels whose geometry passed the vertex limit, and the error it gave (empty: none).
  std::vector<std::uint8_t> failedLevels_;
  std::string failure_;
};

// The feathers' drawing, registered as "feathers".
const OrganDrawingType& featherDrawing();

}  // namespace hirsute
