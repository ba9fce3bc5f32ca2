// Feathers in the GL renderer (Streit & Heidrich 2002, Sec. 4.3): the shafts as lit tubes, the
// barbs as alpha-blended lines or strips fading to their tips, textured in the type's mapping,
// each feather at the level of detail of its size on the screen and its vanes in the order the
// camera asks for (feather_buffers.h). GlRenderer owns one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/view/feather_buffers.h"
#include "hirsute/viewer/gl/gl_functions.h"

namespace hirsute {

class FeatherDrawing {
 public:
  // Compiles the feather programs; the renderer's context must be current.
  explicit FeatherDrawing(const GlFunctions& gl);
  ~FeatherDrawing();
  FeatherDrawing(const FeatherDrawing&) = delete;
  FeatherDrawing& operator=(const FeatherDrawing&) = delete;

  // Keeps what the feathers are made of; the geometry is built on the first draw, for its camera.
  // `textures` are the renderer's GL textures by Scene texture index (0: none).
  void upload(const Scene& scene, const std::vector<GLuint>& textures);
  void release();
  // Draws the shafts (opaque) and then the barbs (blended, without depth writes), rebuilding the
  // geometry when the camera asks for other levels of detail. `light` is the direction towards
  // the light the shafts are lit by.
  void draw(const Camera& camera, const glm::vec3& light);

  std::size_t featherCount() const { return scene_.feathers.size(); }
  const FeatherBuffers& buffers() const { return buffers_; }

 private:
  void build(const std::vector<std::uint8_t>& levels);

  const GlFunctions& gl_;
  GLuint shaftProgram_ = 0, barbProgram_ = 0;
  GLint shaftViewProjection_ = -1, shaftLight_ = -1;
  GLint barbViewProjection_ = -1, barbTextured_ = -1, barbTexture_ = -1;
  Scene scene_;  // the feathers, their types and the materials (no other geometry)
  std::vector<GLuint> textures_;
  FeatherBuffers buffers_;
  bool built_ = false;
  GLuint shaftArray_ = 0, barbArray_ = 0;
  GLuint vertexBuffers_[7] = {};  // shaft positions, normals, colours, indices; barb positions,
                                  // colours, texture coordinates
  GLuint barbIndices_ = 0;
  std::vector<std::uint32_t> order_;
  std::vector<FeatherDrawRun> runs_;
  std::vector<char> nearSides_;  // the vane order the barb indices were last built for
};

}  // namespace hirsute
