// The GL renderer shared by the window and the headless path: uploads a Scene and draws it with
// GL 3.3 core-profile shaders as cpfg would show it (cpfg-manual §8.1.3–8.1.5).
//
// Render modes: `filled` (cpfg's default), `interpolated`, `fast` and `wireframe` draw each
// colour as it is; `flat` and `shaded` (and `shadows`, without the shadows) shade. With a colour
// map the shading moves along the palette as cpfg's does (`light direction:`, `diffuse
// reflection:`); with materials it lights them with the view's `light:` lines, or without any
// with OpenGL's default light 0, which shines from the eye (view_lighting.h, shared with the
// exporters). Polygons are lit on both sides when
// their mesh is two-sided. Lines are drawn in their colour, unlit; each organ draws itself
// (organ_drawing.h).
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/gl/gl_functions.h"
#include "hirsute/viewer/view/camera.h"
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

  // The organs' drawings (organ_drawing.h), by the name each registers; an unknown name throws
  // std::invalid_argument. Whether an organ is drawn outlasts upload(); updateOrgan() takes
  // again from `scene` what the viewer moves (poses, strands, wetness), the rest of the model as
  // it was uploaded.
  void setOrganVisible(std::string_view organ, bool visible);
  bool organVisible(std::string_view organ) const;
  void updateOrgan(std::string_view organ, const Scene& scene);
  // Instances uploaded, and the primitives they are drawn with.
  std::size_t organInstances(std::string_view organ) const;
  std::size_t organPrimitives(std::string_view organ) const;
  // Whether the organ draws only the detail's share of its instances; the instances of all
  // those that do (what a level of detail thins).
  bool organThins(std::string_view organ) const;
  std::size_t thinnedInstances() const;
  // The share of each organ's instances drawn, 0 to 1 (level of detail while the camera
  // moves; an organ that cannot draw part of itself draws all). Outlasts upload().
  void setDetail(float fraction);
  float detail() const { return detail_; }

  // The viewer's wireframe switch: every polygon drawn as its edges, whatever the render mode
  // (as cpfg's `render mode: wireframe`). Outlasts upload().
  void setWireframe(bool wireframe) { wireframe_ = wireframe; }
  bool wireframe() const { return wireframe_; }

 private:
  struct Mesh;
  struct Program;
  struct Resources;

  void release();
  std::size_t organIndex(std::string_view organ) const;
  const Program& surfaceProgram(int geometry, int shading, bool textured);
  void useSurfaceProgram(const Program& program, const Camera& camera);
  void useLineProgram(const Program& program, const Camera& camera);
  void drawMeshes(const Camera& camera, std::vector<Mesh>::const_iterator begin,
                  std::vector<Mesh>::const_iterator end);
  void drawMesh(const Program& program, const Mesh& mesh);

  const GlFunctions& gl_;
  std::unique_ptr<Resources> resources_;
  std::size_t triangles_ = 0, lines_ = 0;
  std::vector<bool> hidden_;  // by organDrawings()
  float detail_ = 1.0f;
  bool wireframe_ = false;
};

}  // namespace hirsute
