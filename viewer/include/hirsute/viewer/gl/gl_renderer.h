// The GL renderer shared by the window and the headless path: uploads a Scene and draws it with
// GL 3.3 core-profile shaders as cpfg would show it (cpfg-manual §8.1.3–8.1.5).
//
// Render modes: `filled` (cpfg's default), `interpolated`, `fast` and `wireframe` draw each
// colour as it is; `flat` and `shaded` (and `shadows`, without the shadows) shade. With a colour
// map the shading moves along the palette as cpfg's does (`light direction:`, `diffuse
// reflection:`); with materials it lights them with the view's `light:` lines, or without any
// with OpenGL's default light 0, which shines from the eye (view_lighting.h, shared with the
// exporters). Polygons are lit on both sides when
// their mesh is two-sided. Lines and hairs are drawn in their colour, unlit.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/view/view_lighting.h"  // backgroundColor, the lights of a view

namespace hirsute {

// Sides of the polygon that stands for a sphere's circumference: cpfg uses the power of two at
// or above `contour sides:` (manual §8.1.5).
int sphereSides(int contourSides);

class GlRenderer {
 public:
  static constexpr int kMaxLights = 8;  // as OpenGL's fixed pipeline

  // Compiles the shaders. The context `gl` was resolved for must be current whenever the
  // renderer is used, and outlive it.
  explicit GlRenderer(const GlFunctions& gl);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Uploads the scene's geometry, materials and textures, replacing what was there. Spheres and
  // discs are tessellated with the view's `contour sides:`; the render mode, lights and z buffer
  // setting are kept for draw().
  void upload(const Scene& scene, const ViewSettings& view, bool materialMode);

  // Clears the bound framebuffer's viewport to the background and draws the scene.
  void draw(const Camera& camera);

  std::size_t triangleCount() const { return triangles_; }
  std::size_t lineCount() const { return lines_; }

  // Plant hairs (DESIGN.md, "Plant hairs"): instances of their template's segments, drawn as
  // antialiased (multisampled) GL lines in the template material's colour, unlit, one instanced
  // draw per template. Each template's hairs are ordered at upload by a hash of their index (dealt
  // into 64 random levels, each kept in placement order), so that any prefix of them is a
  // spatially uniform subset: the fraction draws that prefix of every template (level of detail
  // while the camera moves). Both settings outlast upload().
  void setHairsVisible(bool visible) { hairsVisible_ = visible; }
  void setHairFraction(float fraction);  // clamped to 0..1
  bool hairsVisible() const { return hairsVisible_; }
  float hairFraction() const { return hairFraction_; }
  // Hairs uploaded (those whose template has segments), and their segments, at fraction 1.
  std::size_t hairCount() const { return hairs_; }
  std::size_t hairSegmentCount() const { return hairSegments_; }

  // Feathers (DESIGN.md, "Feathers"; docs/feathers.md): shafts lit, barbs blended in the order
  // the camera asks for, each feather at the level of detail of its size on the screen. The
  // setting outlasts upload(); updateFeathers() takes the feathers (and their poses, bent by the
  // dynamics) of `scene` again, the rest of the model as it was uploaded.
  void setFeathersVisible(bool visible) { feathersVisible_ = visible; }
  void updateFeathers(const Scene& scene);
  bool feathersVisible() const { return feathersVisible_; }
  std::size_t featherCount() const { return feathers_; }

  // Shell fur (DESIGN.md, "Fur"; docs/fur.md): the fur surfaces as layers over their base
  // surface. The setting outlasts upload(); updateFur() uploads the strands' particles and the
  // wetness masks again after the viewer moved or wetted them.
  void setFurVisible(bool visible) { furVisible_ = visible; }
  bool furVisible() const { return furVisible_; }
  void updateFur(const Scene& scene);
  std::size_t furSurfaceCount() const;

  // The viewer's wireframe switch: every polygon drawn as its edges, whatever the render mode
  // (as cpfg's `render mode: wireframe`). Outlasts upload().
  void setWireframe(bool wireframe) { wireframe_ = wireframe; }
  bool wireframe() const { return wireframe_; }

 private:
  struct Mesh;
  struct Program;
  struct Resources;

  void release();
  const Program& surfaceProgram(int geometry, int shading, bool textured);
  void useSurfaceProgram(const Program& program, const Camera& camera);
  void useLineProgram(const Program& program, const Camera& camera);
  void drawMeshes(const Camera& camera, std::vector<Mesh>::const_iterator begin,
                  std::vector<Mesh>::const_iterator end);
  void drawMesh(const Program& program, const Mesh& mesh);

  const GlFunctions& gl_;
  std::unique_ptr<Resources> resources_;
  std::size_t triangles_ = 0, lines_ = 0;
  std::size_t hairs_ = 0, hairSegments_ = 0;
  bool hairsVisible_ = true;
  bool feathersVisible_ = true;
  bool furVisible_ = true;
  std::size_t feathers_ = 0;
  float hairFraction_ = 1.0f;
  bool wireframe_ = false;
};

}  // namespace hirsute
