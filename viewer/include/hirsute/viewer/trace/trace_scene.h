// The path tracer's geometry (docs/design.md, "The path tracer"): the Scene as Intel Embree 3
// holds it, with a material for each shape. The Scene's own elements go in as they are drawn in
// GL: triangles for meshes (cylinders, surfaces, polygons), spheres and discs as Embree's point
// primitives, lines as round curves. Each organ adds its own part through its OrganTracer
// (organ_tracer.h): plant hairs and fur strands as round curves of their radius, feather barbs
// as flat curves fading to their tips, into buffers Embree owns, so that nothing is held twice.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/trace/fibre_bsdf.h"
#include "hirsute/viewer/trace/hair_bsdf.h"
#include "hirsute/viewer/trace/subsurface.h"
#include "hirsute/viewer/trace/surface_bsdf.h"
#include "hirsute/viewer/trace/veins.h"

struct RTCDeviceTy;
struct RTCSceneTy;
struct RTCGeometryTy;

namespace hirsute::trace {

// What a shape is made of. A hair material shades by its tangent (hair_bsdf.h), a surface one
// by its normal (surface_bsdf.h).
struct TraceMaterial {
  bool hair = false;
  SurfaceMaterial surface;
  HairMaterial fibre;
  // A hair shaded by the fibre model (fibre_bsdf.h) rather than by `fibre`: σa fitted to
  // `fibreColour` times the shape's tint, unless melanin fixed it (`absorptionFixed`).
  bool chiang = false;
  FibreMaterial chiangFibre;
  glm::vec3 fibreColour{1.0f};
  bool absorptionFixed = false;
  glm::vec3 emission{0.0f};  // radiance the shape gives off
  float opacity = 1;         // below 1: rays pass through that share of the time
  // Veins (veins.h): the index of the material's vein maps (-1: none), the veins' colour as a
  // ratio to the surface's, how far the colour goes to it on a vein, the veins' height over
  // their width.
  int veins = -1;
  glm::vec3 veinColour{0.0f};
  float veinStrength = 1;
  float veinBump = 0;
  float veinWidth = 0;  // a share of the surface's length
  SubsurfaceMaterial subsurface;  // light that walks inside a thin sheet (subsurface.h)
};

enum class CurveShape : std::uint8_t {
  Round,  // a tube of the vertices' radius (hairs, fur strands, lines)
  Flat,   // a ribbon as wide as twice the radius, turned towards each ray (barbs)
};

// Buffers an organ fills in place (Embree owns them): `vertices` of (x, y, z, radius), one
// `segments` entry a segment (the index of its first vertex; the next is its second), and, when
// asked for, a `tint` a vertex (rgb multiplies the material's colours, a its opacity).
struct CurveBuffers {
  glm::vec4* vertices = nullptr;
  std::uint32_t* segments = nullptr;
  glm::vec4* tint = nullptr;
};

// A surface's own coordinates at a vertex, for veins: (u across, v along, the variant of the
// vein map, the surface's length in world units); a negative variant: none.
using SurfacePoint = glm::vec4;

struct TriangleBuffers {
  glm::vec3* positions = nullptr;
  glm::vec3* normals = nullptr;  // null: flat-shaded
  std::uint32_t* indices = nullptr;
  glm::vec4* tint = nullptr;
  SurfacePoint* surface = nullptr;
  glm::vec2* texcoords = nullptr;  // when the triangles have a texture
};

// How a hit shape is shaded (indexed by Embree's geometry ID), with its buffers.
struct TraceShape {
  int material = 0;
  bool curve = false;
  const glm::vec4* curveVertices = nullptr;       // curves: (x, y, z, radius)
  const std::uint32_t* curveSegments = nullptr;   // curves: a segment's first vertex
  const std::uint32_t* triangleIndices = nullptr; // triangles: three a triangle
  const glm::vec3* normals = nullptr;             // triangles: a vertex each, or null
  const glm::vec4* tint = nullptr;                // a vertex each, or null
  const glm::vec3* positions = nullptr;           // triangles
  const SurfacePoint* surface = nullptr;          // triangles: a vertex each, or null
  const glm::vec2* texcoords = nullptr;           // triangles: a vertex each, or null
  int texture = -1;                               // TraceScene::texture, with texcoords
  bool flatCurve = false;                         // curves: a ribbon turned towards each ray
};

class TraceScene {
 public:
  // `look`: the view file's translucent colours and hair shading; `threads`: those Embree may
  // build with (0: all).
  explicit TraceScene(const TraceSettings& look, int threads = 0);
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  int addMaterial(const TraceMaterial& material);
  // With a colour map, GL's shaded and flat modes shade a surface of colour c along the palette,
  // from c − d facing away from the light to c + d facing it (d: `diffuse reflection:`; manual
  // §8.1.3). The tracer's light does that shading, so a lit surface takes the colour GL gives
  // it in full light, entry c + d of c's bank: `offset` d. 0 (the default): materials, or an
  // unlit render mode, where GL draws entry c itself.
  void setLitPaletteOffset(int offset) { litPaletteOffset_ = offset; }
  // The Scene's material `index` as a surface, or as a hair of that colour (cached). A surface
  // `lit` is shaded in GL (a mesh, sphere or disc), and takes the lit palette entry; an unlit one
  // (a line, a template hair's polygon) the entry itself. A `thin` one (one sheet: a polygon, a
  // patch, an open generalized cylinder) passes light through as a leaf: `translucency:` for
  // its colour, or else kLeafTranslucency of its colour besides what it reflects.
  int surfaceMaterial(const Scene& scene, int index, bool thin = false, bool lit = true);
  // `templateNumber`: the plant hairs' template (from 1) whose `fibre:` line applies.
  int hairMaterial(const Scene& scene, int index, int templateNumber = -1);
  // A hair or a two-sided surface of the linear colour `colour` (white for shapes whose tint
  // gives their colour), shaded as the view file says hairs are: its `fibre:` line for the
  // organ and `index` (a template's number, a fur colour), or the organ's line, or the default.
  int hairOfColour(const glm::vec3& colour, FibreOrgan organ = FibreOrgan::Hairs, int index = -1);
  int surfaceOfColour(const glm::vec3& colour);
  // The view file's veins for the colour `index`, or null.
  const VeinSettings* veinsOf(int index) const;
  // The Scene's material `index` with its veins, made for surfaces of proportions `aspect`
  // (width over length) the first time it is asked for (cached).
  int veinedMaterial(const Scene& scene, int index, float aspect, bool thin = false);
  const VeinMap& veinMap(int veins, float variant) const;

  CurveBuffers addCurves(CurveShape shape, std::size_t vertices, std::size_t segments,
                         int material, bool tint);
  // `texture`: an index of addTexture whose colour modulates the material's (cpfg's default
  // texture mode, as GL draws it), read at `texcoords`; -1: none.
  TriangleBuffers addTriangles(std::size_t vertices, std::size_t triangles, int material,
                               bool normals, bool tint, bool surface = false, int texture = -1);
  // A copy of the Scene's texture `index` (cached), or -1 when it has no pixels.
  int addTexture(const Scene& scene, int index);
  const Texture& texture(int index) const { return textures_[static_cast<std::size_t>(index)]; }
  void addSpheres(const std::vector<glm::vec4>& centresAndRadii, int material);
  // Discs facing `normals` (a zero normal: facing each ray).
  void addDiscs(const std::vector<glm::vec4>& centresAndRadii,
                const std::vector<glm::vec3>& normals, int material);

  // Builds the acceleration structure; nothing may be added after.
  void commit();

  RTCSceneTy* embree() const { return scene_; }
  const TraceShape& shape(unsigned geometry) const { return shapes_[geometry]; }
  const TraceMaterial& material(int index) const {
    return materials_[static_cast<std::size_t>(index)];
  }
  RTCGeometryTy* geometry(unsigned id) const;
  bool hasTransparency() const { return transparency_; }
  std::size_t curveSegments() const { return curveSegments_; }
  std::size_t triangleCount() const { return triangles_; }
  // Bytes of the buffers handed to Embree (its hierarchy comes on top).
  std::size_t bufferBytes() const { return bufferBytes_; }

 private:
  int attach(RTCGeometryTy* geometry, const TraceShape& shape);
  // The palette entry a surface of colour `index` shows (setLitPaletteOffset).
  int shownIndex(const Scene& scene, int index, bool lit) const;

  TraceSettings look_;
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
  std::vector<TraceShape> shapes_;
  std::vector<TraceMaterial> materials_;
  std::vector<int> surfaceOf_, veinedOf_;
  std::vector<std::pair<glm::ivec2, int>> hairOf_;  // (colour, template) and its material  // surfaceOf_, veinedOf_: 4 and 2 a colour
  int litPaletteOffset_ = 0;
  std::vector<std::vector<VeinMap>> veinMaps_;               // kVeinVariants a vein line
  std::vector<std::unique_ptr<SurfacePoint[]>> surfacePoints_;  // the shapes' (not Embree's)
  std::vector<std::unique_ptr<glm::vec2[]>> texcoords_;
  std::vector<Texture> textures_;
  std::vector<int> textureOf_;  // by the Scene's texture index
  std::vector<float> through_;  // translucency by colour index
  bool transparency_ = false;
  std::size_t curveSegments_ = 0, triangles_ = 0, bufferBytes_ = 0;
};

// The share of a thin surface's colour that passes through it where the view file gives its
// colour no `translucency:` line, over what it reflects (a leaf lit from behind glows).
inline constexpr float kLeafTranslucency = 0.3f;

// A colour as the view file and colour maps give it (display values) as the reflectance the
// tracer computes with (linear light).
glm::vec3 linearColour(const glm::vec3& display);

}  // namespace hirsute::trace
