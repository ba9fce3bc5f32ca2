// The Scene: the single interface between interpretation and every output (GL preview,
// headless PNG, POV-Ray, OBJ). The turtle and the appendages write into it; outputs only read it.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hirsute/interpreter/organ_attributes.h"
#include "hirsute/interpreter/organ_part.h"

namespace hirsute {

// A surface appearance: from a colour map (.map: the colour as ambient and diffuse) or a
// material file (.mat). Colours are linear 0..1.
struct Material {
  glm::vec3 ambient{0.2f};
  glm::vec3 diffuse{0.8f};
  glm::vec3 specular{0.0f};
  glm::vec3 emission{0.0f};
  float shininess = 0.0f;    // 0..128
  float transparency = 0.0f; // 0 opaque .. 1 clear
};

// Triangles sharing one material (and texture). Vertices carry normals, and texture coordinates
// when `texture` >= 0. Indices are triangles (3 per face), counter-clockwise seen from the front.
struct TriangleMesh {
  int material = 0;          // index into Scene::materials
  int texture = -1;          // index into Scene::textures, -1 none
  bool twoSided = true;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> texcoords;  // empty, or one per vertex
  std::vector<std::uint32_t> indices;

  std::size_t triangleCount() const { return indices.size() / 3; }
};

// How a line segment is drawn (cpfg's `line style:`).
enum class LineStyle { Pixel, Polygon, Cylinder };

// Lines drawn as lines (pixel style: width in pixels) or flat ribbons (polygon style: width in
// world units). Cylinder-style lines are meshes instead. One entry per segment keeps tapering
// (width and colour at each end).
struct LineSegment {
  glm::vec3 from, to;
  float widthFrom = 1, widthTo = 1;
  int material = 0;
};

struct Sphere {
  glm::vec3 center;
  float radius = 1;
  int material = 0;
};

// A flat disc (cpfg's @o is screen-aligned, @c lies in the turtle's HL plane).
struct Disc {
  glm::vec3 center;
  glm::vec3 normal;   // zero for screen-aligned discs
  float radius = 1;
  int material = 0;
};

struct Label {
  glm::vec3 position;
  std::string text;
  int material = 0;
};

// One frame of a generalized cylinder: the turtle's position and orientation at a ring.
struct ControlFrame {
  glm::vec3 position{0.0f};
  glm::vec3 heading{0, 1, 0};
  glm::vec3 left{-1, 0, 0};
  glm::vec3 up{0, 0, -1};
};

// One ring of a generalized-cylinder segment (cpfg-generalized-cylinders.md §2): the centre and
// frame the contour is placed in (heading = the axis tangent there), its radius, and where it lies
// along the axis and in texture space. Appendages use the rings to map (u, v) onto the strips.
struct CylinderRing {
  ControlFrame frame;
  float radius = 0;
  float axisParameter = 0;  // the Hermite parameter t of the axis (0 at the start, 1 at the end)
  float axisDistance = 0;   // arc length from @Gs, along the polyline through the ring centres
  float textureT = 0;       // the texture coordinate t (§4)
};

// A generalized-cylinder segment between two control points, as the organs read it
// (docs/design.md): its two control frames, the contour points around each end (in the ring's
// plane, contour x along U and y along -L, already multiplied by the radius), open or closed,
// the girth (contour length) at each end and the arc length along the axis accumulated from @Gs.
struct CylinderSegment {
  ControlFrame start, end;
  float radiusStart = 0, radiusEnd = 0;
  std::vector<glm::vec2> contourStart, contourEnd;  // same count; closed contours repeat no point
  bool closed = true;
  float girthStart = 0, girthEnd = 0;
  float axisStart = 0, axisLength = 0;
  int mesh = -1;                 // the TriangleMesh holding its triangles
  std::uint32_t firstIndex = 0;  // its first triangle index within that mesh
  std::uint32_t indexCount = 0;
  int strips = 1;                // rings between the two control frames, minus one
  int tube = 0;                  // segments of one @Gs…@Ge tube share this number
  // The strips + 1 rings from start to end. When drawn as a tube, ring k's vertices are
  // firstVertex + k·(sides + 1) + j, j = 0..sides (j = sides repeats the seam of closed
  // contours), and the 2·sides triangles of strip k (rings k-1, k) follow those of strip k-1
  // in the index range.
  std::vector<CylinderRing> rings;
  int sides = 0;                 // contour samples around the ring (the @! of the first point)
  std::uint32_t firstVertex = 0;
  std::uint32_t vertexCount = 0;
  // The organ attributes at the segment's two control points (per organ an index into its
  // part of the Scene, e.g. HairPart::attributes; -1: the defaults, none). Without `hair
  // interpolation: on` the segment's hairs take the end's: values set between two @Gc apply to
  // the segment they close.
  OrganAttributeIndices organStart, organEnd;
};

// A `~` surface patch or a `{ }` polygon as organs see it (docs/design.md, "Organs": organs grow on
// bicubic surfaces and polygons in their own (u, v)): its triangles, a range of one
// mesh, the (u, v) of each of its vertices, and the organ attributes in force where the turtle
// drew it. The turtle records one only where some organ's attributes are set.
enum class OrganSurfaceKind : std::uint8_t {
  BicubicPatch,  // (u, v): the Bézier patch's parameters in [0, 1]², u along a row of control
                 // points, v across the rows (surface_mesh.h)
  Polygon,       // (u, v): world distances in the polygon's plane from its first vertex, u
                 // along its first edge, v = n × u (n its Newell normal, the front)
  Mesh,          // (u, v): a mesh file's texture coordinates (mesh_file.h), or its x and y over
                 // their bounds; organs are placed over its area, not over (u, v)
};

// A run of a mesh's triangle indices, [firstIndex, firstIndex + indexCount).
struct IndexRange {
  int mesh = -1;
  std::uint32_t firstIndex = 0;
  std::uint32_t indexCount = 0;
};

struct OrganSurface {
  OrganSurfaceKind kind = OrganSurfaceKind::Polygon;
  int mesh = -1;                  // the TriangleMesh holding its triangles
  std::uint32_t firstVertex = 0;  // its vertices, [firstVertex, firstVertex + uv.size())
  std::uint32_t firstIndex = 0;   // its triangle indices, [firstIndex, firstIndex + indexCount)
  std::uint32_t indexCount = 0;
  std::vector<glm::vec2> uv;  // one per vertex
  OrganAttributeIndices organs;
  // A mesh's (OrganSurfaceKind::Mesh): the direction its coat lies along at each vertex, in the
  // world (`mesh flow:`; empty: where v grows), and the red of its file's vertex colours, which
  // blends a coat's key feathers (empty: the file has none).
  std::vector<glm::vec3> flow;
  std::vector<float> blend;
  // A mesh's without texture coordinates that is no disc (SurfaceMeshData::atlasUv): (u, v) per
  // corner of its triangles, in the order of its indices, in an atlas of charts, and each
  // triangle's chart; the fur grows through it. Empty otherwise.
  std::vector<glm::vec2> atlasUv;
  std::vector<std::uint32_t> atlasChart;
};

struct Texture {
  std::string file;     // as named by the view file, resolved against the model's folder
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // decoded pixels, row 0 at the top

  // The colour at (u, v) as the GL renderer samples it where a model colours a vertex by its
  // texture (nearest texel, repeating; v = 0 is the image's last row, as the renderer uploads
  // it), 0..1. Black for an empty texture.
  glm::vec3 colourAt(const glm::vec2& uv) const;
};

struct Bounds {
  glm::vec3 min{1e30f}, max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void add(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void add(const Bounds& b) {
    if (!b.empty()) {
      add(b.min);
      add(b.max);
    }
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  float diagonal() const { return empty() ? 0.0f : glm::length(max - min); }
};

// Geometry is bounded like the string: a model whose interpretation would make more vertices
// than the limit (`--max-vertices`) stops with this error rather than exhausting the machine.
inline constexpr std::size_t kDefaultMaxVertices = 100'000'000;
struct GeometryLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Scene {
 public:
  std::vector<Material> materials;        // by colour index (cpfg: 256 per bank)
  std::vector<TriangleMesh> meshes;
  std::vector<LineSegment> lines;
  LineStyle lineStyle = LineStyle::Pixel; // how `lines` are drawn
  std::vector<Sphere> spheres;
  std::vector<Disc> discs;
  std::vector<Label> labels;
  std::vector<CylinderSegment> cylinderSegments;
  std::vector<OrganSurface> organSurfaces;  // surfaces and polygons with organ attributes
  // The triangles of thin surfaces, one sheet with two faces: `{ }` polygons and `~` patches
  // (the path tracer lets leaves pass light by default; docs/trace.md). Open generalized
  // cylinders are known from cylinderSegments; closed ones, cylinder-style lines and mesh files
  // are not listed.
  std::vector<IndexRange> thinSurfaces;
  std::vector<Texture> textures;

  // An organ's part (organ_part.h), made empty on first use.
  template <class Part>
  Part& organ() {
    return organs_.get<Part>();
  }
  // The part of type Part, or an empty one when the scene has none.
  template <class Part>
  const Part& organ() const {
    return organs_.get<Part>();
  }

  // The mesh for a material and texture, created on first use.
  TriangleMesh& meshFor(int material, int texture = -1);
  // Lists the triangles of `mesh` from index `firstIndex` to its end as a thin surface (joined
  // to the last range where it follows on).
  void markThin(const TriangleMesh& mesh, std::uint32_t firstIndex);
  Bounds bounds() const;
  std::size_t triangleCount() const;
  // Vertices held: mesh vertices, two per line, one per sphere, disc and label.
  std::size_t vertexCount() const;
  void clear();

 private:
  std::vector<std::array<int, 3>> meshIndex_;  // (material, texture, mesh)
  OrganParts organs_;
};

}  // namespace hirsute
