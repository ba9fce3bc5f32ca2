// POV-Ray 3.7 export: a self-contained scene file (camera, lights and background from the view
// file, the camera framed as the PNG is, by fitCamera; one declared texture per material used; each
// triangle mesh a declared `mesh2` with its normals, placed by an `object`; lines as cylinders and
// cones; spheres; discs), written compactly because POV-Ray's parse time grows with the length of
// the text. docs/export.md describes the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"
#include "hirsute/viewer/export/export_file.h"
#include "hirsute/viewer/export/scene_writer.h"
#include "hirsute/viewer/view/camera.h"

namespace hirsute {

struct PovOptions {
  ViewSettings view;          // camera and lights (cpfg's view file)
  bool materialMode = false;  // the background is material 0's emission, else colour 0
  bool colorMapFile = false;  // the colours are a colour map file's (litPaletteOffset)
  // The image the camera is fitted for (as the PNG of the same size) and the size of a pixel for
  // pixel-wide lines. Rendered at another aspect, the image shows at least the same window.
  int width = 800, height = 600;
  // The box the camera is fitted to and the lights placed by; absent: the scene's. The frames of
  // a simulation share the first frame's, so that the camera stays where it was.
  std::optional<Bounds> fitBounds;
  // The outputs this scene is committed with (output_target.h); none: on its own.
  OutputGroup* group = nullptr;
  // The folder the scene is written into under a name Hirsute made itself (the frames of
  // `simulate -o DIR`): the scene is `target`'s file name in it, created there as the side files
  // are (output_folder.h). None: `target` is the name the user typed (output_target.h), and the
  // side files go into the folder it is in.
  const OutputFolder* folder = nullptr;
  // The path tracer's light set-up instead of the view's GL lights (docs/export.md, "The
  // tracer's lights"): its spherical light as an area light, its sky as an emitting dome seen
  // by radiosity, and the view file's `translucency:` as backside diffuse.
  bool traceLights = false;
};

struct PovExportStats {
  std::uint64_t bytes = 0;
  std::size_t triangles = 0, cylinders = 0, cones = 0, spheres = 0, discs = 0, objects = 0;
  std::size_t linesSkipped = 0;  // zero length or zero width at the file's precision
  // What the organs' writers wrote, by the names they count under (PovWriter::count).
  std::map<std::string, std::size_t, std::less<>> organs;
  std::size_t organ(std::string_view what) const {
    const auto found = organs.find(what);
    return found == organs.end() ? 0 : found->second;
  }
};

class PovWriter : public ScenePrinter {
 public:
  PovWriter(std::filesystem::path target, PovOptions options);
  ~PovWriter() override;

  void beginScene(const Scene& scene, std::span<const OrganWriter* const> organs) override;
  void mesh(const TriangleMesh& mesh) override;
  void line(const LineSegment& line, LineStyle style) override;
  void sphere(const Sphere& sphere) override;
  void disc(const Disc& disc) override;
  void label(const Label& label) override;
  // Closes the run of primitives and hands the writer to the organ (organ_writer.h).
  void organ(const OrganWriter& organ, const Scene& scene) override;
  void endScene() override;

  // Declared objects and their instances: a mesh is written once as `#declare NAME=mesh2{…}`
  // and placed by `object{NAME …}` as often as needed, each placement with its own material and
  // transform (an organ's template, placed once an instance). Returns NAME. Both are
  // called between beginScene() and endScene().
  std::string declareMesh(const TriangleMesh& mesh);
  // `transform` null: in place. Otherwise the affine map of the instance (its last row unused).
  void placeObject(std::string_view name, int material, int texture,
                   const glm::mat4* transform = nullptr);

  const Camera& camera() const { return camera_; }
  // The world size of a pixel at the fitted image size, at the point looked at.
  float worldPerPixel() const { return worldPerPixel_; }
  const PovExportStats& stats() const { return stats_; }

  // What the organs' writers draw with (organ_writer.h), between beginScene() and endScene().
  const PovOptions& options() const { return options_; }
  ExportFile& out() { return out_; }
  // The format of positions: the scene's, which a writer may change for a mesh in other units
  // and must set back.
  NumberFormat& positionFormat() { return position_; }
  void number(double value, NumberFormat format) { out_.putFixed(value, format); }
  // Adds `count` to what the organ's writers wrote of `what` (PovExportStats::organs), and
  // `triangles` to the triangles written.
  void count(std::string_view what, std::size_t count, std::size_t triangles = 0);
  // A colour and an opacity per vertex, quantized so that a mesh2's texture_list stays short.
  // The colour is a display (sRGB) colour, as GL draws it; writeShadedMesh writes it in linear
  // light, as every colour of the scene (assumed_gamma 1).
  struct Shade {
    int r, g, b, a;  // display colour in 1/255, alpha in 1/kShadeAlphaLevels
    auto key() const { return std::tie(r, g, b, a); }
    bool operator<(const Shade& o) const { return key() < o.key(); }
  };
  static constexpr int kShadeAlphaLevels = 16;
  static Shade shadeOf(const glm::vec3& colour, float alpha);
  // A mesh2 whose vertices carry their shades (interpolated across each face), with `finish`;
  // with a `declaredName`, declared under it (`#declare NAME=mesh2{…}`) for objects to place.
  void writeShadedMesh(std::string_view comment, const std::vector<glm::vec3>& points,
                       const std::vector<Shade>& shades, const std::vector<std::uint32_t>& faces,
                       std::string_view finish, std::string_view declaredName = {});
  // `#declare NAME=mesh2{…}` of `mesh` at the present position format.
  void writeMesh2(std::string_view name, const TriangleMesh& mesh);
  // The declared texture of a material (and texture image), declared on first use.
  const std::string& useTexture(int material, int texture);

 private:
  void writeHeader(const Scene& scene, std::span<const OrganWriter* const> organs);
  void writeCamera();
  void writeLights(const Bounds& bounds);
  void writeMaterial(std::string_view name, int index, const Material& material, int texture);
  void writeTraceLights(const Bounds& bounds);
  std::string textureName(int material, int texture) const;
  // A line, sphere or disc, held back while it may be the only member of a union.
  struct Primitive {
    enum Kind { Cylinder, Cone, Sphere, Disc } kind;
    glm::vec3 a, b;  // ends; centre and (disc) normal
    float radiusA, radiusB;
  };
  void emit(int material, const Primitive& primitive);
  // The palette entry a surface of colour `material` is written with: a `lit` one (a mesh,
  // sphere or disc) the entry GL gives it in full light (litPaletteEntry, view_lighting.h), as
  // the path tracer does; lines and hairs, unlit in GL, their own.
  int shownMaterial(int material, bool lit) const;
  void closeRun();
  void writePrimitive(const Primitive& primitive, const std::string* texture);
  void vector(const glm::vec3& v, NumberFormat format);

  // The folder of the side files (texture images), opened when the first is written.
  const OutputFolder& sideFolder();

  std::filesystem::path target_;
  PovOptions options_;
  ExportFile out_;
  std::optional<OutputFolder> sideFolder_;
  const Scene* scene_ = nullptr;
  Camera camera_;
  float worldPerPixel_ = 0;
  NumberFormat position_{4, false};
  NumberFormat normal_{3, false};
  NumberFormat texcoord_{4, false};
  NumberFormat colour_{3, false};
  std::vector<int> texturesWritten_;
  std::set<std::pair<int, int>> declaredTextures_;  // (material, texture)
  int lastMaterial_ = 0, lastTexture_ = -2;
  std::string lastName_;
  // The run of primitives of one material being written: its length, and its first primitive.
  int runMaterial_ = 0;
  std::size_t runLength_ = 0;
  Primitive pending_{};
  int meshesDeclared_ = 0;
  PovExportStats stats_;
};

// Writes `scene` to `target` (textures beside it, see texture_file.h) and returns the figures;
// shows its progress on `progress` when given.
PovExportStats writePov(const Scene& scene, const PovOptions& options,
                        const std::filesystem::path& target, Progress* progress = nullptr);

}  // namespace hirsute
