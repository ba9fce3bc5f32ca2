// The POV-Ray and OBJ exporters on hand-built scenes: what the files contain, counted and parsed
// back, and the POV-Ray scene rendered by the installed povray (skipped when it is absent), which
// must parse and render it without a warning and show each object where the camera puts it; and
// `hirsute export` on the shipped herb model.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/viewer/export/export_file.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"
#include "hirsute/viewer/view/png_image.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// A fresh, empty folder per test, removed afterwards.
class ExportTest : public testing::TemporaryFolderTest {
 protected:
  ExportTest() : TemporaryFolderTest("hirsute_export_") {}
};

using testing::countLinesStarting;
using testing::countOccurrences;
using testing::linesOf;
using testing::readText;

std::string formatted(double value, int decimals, bool leadingZero) {
  char buffer[ExportFile::kMaxNumberLength];
  return std::string(buffer, formatFixed(value, NumberFormat{decimals, leadingZero}, buffer));
}

Material colour(float r, float g, float b) {
  Material m;
  m.ambient = m.diffuse = glm::vec3(r, g, b);  // as a colour map gives them
  return m;
}

// Palette: 0 background (dark blue), 1 red, 2 green, 3 blue, 4 yellow, 5 unused.
Scene paletteScene() {
  Scene scene;
  scene.materials = {colour(0.1f, 0.2f, 0.4f), colour(0.9f, 0.1f, 0.1f), colour(0.1f, 0.9f, 0.1f),
                     colour(0.1f, 0.1f, 0.9f), colour(0.9f, 0.9f, 0.1f), colour(0.5f, 0.5f, 0.5f)};
  return scene;
}

// A square facing +z, counter-clockwise seen from +z.
void addQuad(Scene& scene, int material, glm::vec2 centre, float half, bool normals = true) {
  TriangleMesh& mesh = scene.meshFor(material);
  auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (glm::vec2 corner :
       {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    mesh.positions.push_back(glm::vec3(centre + corner * half, 0));
    if (normals) mesh.normals.push_back({0, 0, 1});
  }
  mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// Two meshes, three line segments (two of them one polyline), a sphere and a disc.
Scene mixedScene() {
  Scene scene = paletteScene();
  addQuad(scene, 1, {0, 0}, 0.5f);
  TriangleMesh& plain = scene.meshFor(2);  // no normals
  plain.positions = {{2, 0, 0}, {3, 0, 0}, {2, 1, 0}};
  plain.indices = {0, 1, 2};
  scene.lines.push_back({{0, 0, 1}, {0, 1, 1}, 2, 2, 3});
  scene.lines.push_back({{0, 1, 1}, {0, 2, 1}, 2, 2, 3});
  scene.lines.push_back({{1, 0, 1}, {1, 1, 1}, 2, 2, 3});
  scene.spheres.push_back({{-2, 0, 0}, 0.5f, 4});
  scene.discs.push_back({{-2, 2, 0}, {0, 0, 1}, 0.5f, 1});
  return scene;
}

TEST(NumberFormat, FixedPointIsShortAndRounded) {
  EXPECT_EQ(formatted(2.0, 4, false), "2");
  EXPECT_EQ(formatted(-1.25, 4, false), "-1.25");
  EXPECT_EQ(formatted(0.5, 4, false), ".5");
  EXPECT_EQ(formatted(0.5, 4, true), "0.5");
  EXPECT_EQ(formatted(-0.5, 3, false), "-.5");
  EXPECT_EQ(formatted(-0.00004, 4, false), "0");
  EXPECT_EQ(formatted(123.45678, 3, true), "123.457");
  EXPECT_EQ(formatted(0.000123, 6, true), "0.000123");
  EXPECT_EQ(formatted(7.0, 0, true), "7");
  EXPECT_EQ(formatted(1e20, 4, true), "1e+20");
  EXPECT_THROW(formatted(std::nan(""), 4, true), std::invalid_argument);
}

TEST_F(ExportTest, FileAppearsOnlyWhenCommitted) {
  fs::path target = file("scene.txt");
  {
    ExportFile out(target);
    out.put("first ");
    out.putInteger(-42);
    EXPECT_FALSE(fs::exists(target));
    out.commit();
  }
  EXPECT_EQ(readText(target), "first -42");
  {
    ExportFile out(target);  // abandoned: the old file stays and no temporary is left
    out.put("second");
  }
  EXPECT_EQ(readText(target), "first -42");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()), 1);
}

TEST_F(ExportTest, FileInAMissingFolderIsAnError) {
  EXPECT_THROW(ExportFile(file("no/such/folder/scene.pov")), std::runtime_error);
}

TEST_F(ExportTest, LargeOutputPassesThroughTheBuffer) {
  fs::path target = file("big.txt");
  ExportFile out(target);
  std::string block(3000, 'x');
  for (int i = 0; i < 1000; ++i) out.put(block);
  out.commit();
  EXPECT_EQ(fs::file_size(target), 3'000'000u);
  EXPECT_EQ(out.bytesWritten(), 3'000'000u);
}

TEST_F(ExportTest, ObjCountsVerticesFacesLinesAndMaterials) {
  Scene scene = mixedScene();
  ObjExportStats stats = writeObj(scene, file("plant.obj"));
  std::string obj = readText(file("plant.obj"));
  std::string mtl = readText(file("plant.mtl"));
  ObjOptions o;
  std::size_t spherePoints = 2 + static_cast<std::size_t>((o.sphereStacks - 1) * o.sphereSlices);
  std::size_t sphereFaces = static_cast<std::size_t>(2 * o.sphereSlices * (o.sphereStacks - 1));
  std::size_t discPoints = 1 + static_cast<std::size_t>(o.discSegments);
  // quad 4, triangle 3, polylines 3 + 2, sphere, disc
  EXPECT_EQ(countLinesStarting(obj, "v "), 4 + 3 + 5 + spherePoints + discPoints);
  EXPECT_EQ(countLinesStarting(obj, "vn "), 4 + spherePoints + 1);
  EXPECT_EQ(countLinesStarting(obj, "vt "), 0u);
  EXPECT_EQ(countLinesStarting(obj, "f "),
            2 + 1 + sphereFaces + static_cast<std::size_t>(o.discSegments));
  // The polylines of 3 and 2 vertices: one `l` element a segment.
  EXPECT_EQ(countLinesStarting(obj, "l "), 3u);
  EXPECT_EQ(testing::objPolylines(obj).size(), 2u);
  EXPECT_EQ(countLinesStarting(obj, "mtllib plant.mtl"), 1u);
  EXPECT_EQ(countLinesStarting(obj, "usemtl "), 5u);  // m1 m2 m3 m4 m1
  EXPECT_EQ(countLinesStarting(mtl, "newmtl "), 4u);
  EXPECT_EQ(mtl.find("newmtl m5"), std::string::npos) << "an unused material is not written";
  EXPECT_NE(mtl.find("newmtl m1\nKa 0.9 0.1 0.1\nKd 0.9 0.1 0.1\nKs 0 0 0\nNs 0\nd 1\nillum 2\n"),
            std::string::npos)
      << mtl;
  EXPECT_EQ(stats.vertices, countLinesStarting(obj, "v "));
  EXPECT_EQ(stats.faces, countLinesStarting(obj, "f "));
  EXPECT_EQ(stats.lineElements, 3u);
  EXPECT_EQ(stats.polylines, 2u);
  EXPECT_EQ(stats.materials, 4u);
  EXPECT_EQ(stats.bytes, obj.size());
  EXPECT_EQ(stats.mtlBytes, mtl.size());
}

TEST_F(ExportTest, ObjElementsReferToWrittenVertices) {
  Scene scene = mixedScene();
  writeObj(scene, file("plant.obj"));
  std::size_t vertices = 0, normals = 0, faces = 0, segments = 0;
  for (const std::string& line : linesOf(readText(file("plant.obj")))) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "v") ++vertices;
    if (key == "vn") ++normals;
    if (key == "f") {
      ++faces;
      int corners = 0;
      for (std::string corner; in >> corner; ++corners) {
        std::size_t v = std::stoul(corner);
        EXPECT_GE(v, 1u);
        EXPECT_LE(v, vertices) << line;
        std::size_t slashes = corner.rfind("//");
        if (slashes != std::string::npos) {
          EXPECT_LE(std::stoul(corner.substr(slashes + 2)), normals) << line;
        }
      }
      EXPECT_EQ(corners, 3) << line;
    }
    if (key == "l") {
      std::size_t ends = 0;
      for (std::size_t v; in >> v; ++ends) EXPECT_LE(v, vertices);
      // Blender's default OBJ importer keeps only the first segment of a longer element.
      EXPECT_EQ(ends, 2u) << line;
      ++segments;
    }
  }
  EXPECT_GT(faces, 0u);
  EXPECT_EQ(segments, 3u);
  const auto polylines = testing::objPolylines(readText(file("plant.obj")));
  ASSERT_FALSE(polylines.empty());
  const std::vector<std::uint64_t>& firstPolyline = polylines.front();
  ASSERT_EQ(firstPolyline.size(), 3u) << "two segments that continue each other are one polyline";
  EXPECT_EQ(firstPolyline[1], firstPolyline[0] + 1);
}

TEST_F(ExportTest, ObjTexturedMeshHasTexcoordsAndItsImage) {
  Scene scene = paletteScene();
  scene.textures.push_back({"bark.png", 2, 1, {255, 0, 0, 255, 0, 255, 0, 255}});
  TriangleMesh& mesh = scene.meshFor(1, 0);
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.texcoords = {{0, 0}, {1, 0}, {0, 0.25f}};
  mesh.indices = {0, 1, 2};
  writeObj(scene, file("plant.obj"));
  std::string obj = readText(file("plant.obj"));
  EXPECT_EQ(countLinesStarting(obj, "vt "), 3u);
  EXPECT_NE(obj.find("vt 0 0.25\n"), std::string::npos) << obj;
  EXPECT_NE(obj.find("f 1/1/1 2/2/2 3/3/3\n"), std::string::npos) << obj;
  EXPECT_NE(readText(file("plant.mtl")).find("newmtl m1_t1\n"), std::string::npos);
  EXPECT_NE(readText(file("plant.mtl")).find("map_Kd plant_texture1.png\n"), std::string::npos);
  RgbaImage image = readPng(file("plant_texture1.png"));
  ASSERT_EQ(image.width, 2);
  EXPECT_EQ(image.pixel(1, 0), glm::u8vec4(0, 255, 0, 255));
}

// The files a writer names beside its target (the .mtl, the texture images) are its own: a link
// planted at such a name is replaced, never written through (output_folder.h).
TEST_F(ExportTest, SideFilesReplaceLinksPlantedAtTheirNames) {
  Scene scene = paletteScene();
  scene.textures.push_back({"bark.png", 2, 1, {255, 0, 0, 255, 0, 255, 0, 255}});
  TriangleMesh& mesh = scene.meshFor(1, 0);
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.texcoords = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  fs::create_directories(file("outside"));
  std::ofstream(file("outside/profile"), std::ios::binary) << "the user's own file\n";
  for (const char* name : {"plant.mtl", "plant_texture1.png", "scene_texture1.png"})
    fs::create_symlink(file("outside/profile"), file(name));
  writeObj(scene, file("plant.obj"));
  writePov(scene, PovOptions{}, file("scene.pov"));
  EXPECT_EQ(readText(file("outside/profile")), "the user's own file\n");
  for (const char* name : {"plant.mtl", "plant_texture1.png", "scene_texture1.png"})
    EXPECT_FALSE(fs::is_symlink(file(name))) << name;
  EXPECT_NE(readText(file("plant.mtl")).find("map_Kd plant_texture1.png\n"), std::string::npos);
  EXPECT_EQ(readPng(file("plant_texture1.png")).width, 2);
  EXPECT_EQ(readPng(file("scene_texture1.png")).width, 2);
}

// A scene written under a name the program made (simulate's frames) is created in its folder as
// its side files are.
TEST_F(ExportTest, AFrameInAnOutputFolderReplacesALinkAtItsName) {
  Scene scene = paletteScene();
  addQuad(scene, 1, {0, 0}, 1);
  fs::create_directories(file("outside"));
  std::ofstream(file("outside/profile"), std::ios::binary) << "the user's own file\n";
  fs::create_symlink(file("outside/profile"), file("frame-0001.pov"));
  fs::create_symlink(file("outside/profile"), file("frame-0001.obj"));
  const OutputFolder folder(folder_);
  PovOptions pov;
  pov.folder = &folder;
  writePov(scene, pov, file("frame-0001.pov"));
  ObjOptions obj;
  obj.folder = &folder;
  writeObj(scene, file("frame-0001.obj"), obj);
  EXPECT_EQ(readText(file("outside/profile")), "the user's own file\n");
  EXPECT_EQ(readText(file("frame-0001.pov")).rfind("// Hirsute", 0), 0u);
  EXPECT_EQ(readText(file("frame-0001.obj")).rfind("# Hirsute", 0), 0u);
  EXPECT_FALSE(fs::is_symlink(file("frame-0001.pov")));
}

TEST_F(ExportTest, PovSceneHasCameraLightsMaterialsAndPrimitives) {
  Scene scene = mixedScene();
  PovExportStats stats = writePov(scene, PovOptions{}, file("plant.pov"));
  std::string pov = readText(file("plant.pov"));
  std::vector<std::string> lines = linesOf(pov);
  auto firstCode = std::find_if(lines.begin(), lines.end(),
                                [](const std::string& l) { return l.rfind("//", 0) != 0; });
  ASSERT_NE(firstCode, lines.end());
  EXPECT_EQ(*firstCode, "#version 3.7;");
  EXPECT_EQ(countOccurrences(pov, "camera{orthographic "), 1u);
  EXPECT_EQ(countOccurrences(pov, "light_source{"), 1u);
  EXPECT_EQ(countOccurrences(pov, "background{rgb<"), 1u);
  EXPECT_EQ(countOccurrences(pov, "=texture{"), 4u) << "materials 1 to 4, declared once each";
  EXPECT_EQ(countOccurrences(pov, "#declare M5="), 0u);
  EXPECT_EQ(countOccurrences(pov, "=mesh2{"), 2u);
  EXPECT_EQ(countOccurrences(pov, "vertex_vectors{4,"), 1u);
  EXPECT_EQ(countOccurrences(pov, "normal_vectors{4,"), 1u);
  EXPECT_EQ(countOccurrences(pov, "normal_vectors{"), 1u) << "the mesh without normals has none";
  EXPECT_EQ(countOccurrences(pov, "face_indices{2,"), 1u);
  EXPECT_EQ(countOccurrences(pov, "face_indices{1,"), 1u);
  EXPECT_EQ(countOccurrences(pov, "object{Mesh"), 2u);
  EXPECT_EQ(countOccurrences(pov, "cylinder{"), 3u);
  EXPECT_EQ(countOccurrences(pov, "\nsphere{<-2,0,0>,.5 texture{M4}}\n"), 1u);
  EXPECT_EQ(countOccurrences(pov, "\ndisc{<-2,2,0>,<0,0,1>,.5 texture{M1}}\n"), 1u);
  // The three segments of material 3 share one texture statement; a lone sphere or disc is no
  // union (POV-Ray warns about a union of one).
  EXPECT_EQ(countOccurrences(pov, "union{"), 1u);
  EXPECT_EQ(countOccurrences(pov, "\nunion{cylinder{"), 1u);
  EXPECT_EQ(countOccurrences(pov, "}\ntexture{M3}}\n"), 1u);
  EXPECT_EQ(countOccurrences(pov, "texture{M3}"), 1u);
  // Every material is declared before its first use.
  for (int m = 1; m <= 4; ++m) {
    std::string name = "M" + std::to_string(m);
    EXPECT_LT(pov.find("#declare " + name + "="), pov.find("texture{" + name + "}")) << name;
  }
  EXPECT_EQ(stats.triangles, 3u);
  EXPECT_EQ(stats.cylinders, 3u);
  EXPECT_EQ(stats.bytes, pov.size());
}

// With a colour map file in a shaded render mode, GL shades a surface of colour c along the
// palette up to c + d in full light; POV-Ray's light does the shading, so meshes, spheres and discs
// take entry c + d (kept in the palette), as the path tracer does, and lines keep their own.
TEST_F(ExportTest, PovShadedColourMapSurfacesTakeTheirFullyLitEntry) {
  Scene scene = mixedScene();
  PovOptions options;
  options.view.renderMode = RenderMode::Shaded;
  options.view.diffuseReflection = 1;
  options.colorMapFile = true;
  writePov(scene, options, file("plant.pov"));
  const std::string pov = readText(file("plant.pov"));
  EXPECT_EQ(countOccurrences(pov, "\nsphere{<-2,0,0>,.5 texture{M5}}\n"), 1u) << "4 + 1";
  EXPECT_EQ(countOccurrences(pov, "\ndisc{<-2,2,0>,<0,0,1>,.5 texture{M2}}\n"), 1u) << "1 + 1";
  EXPECT_EQ(countOccurrences(pov, "}\ntexture{M3}}\n"), 1u) << "the lines keep theirs";
  EXPECT_EQ(countOccurrences(pov, "texture{M2}"), 2u) << "the red quad's mesh and the disc";
  EXPECT_EQ(countOccurrences(pov, "texture{M1}"), 0u);
  // Past the palette's end an entry stays at its last colour; unlit modes keep every entry.
  options.view.diffuseReflection = 7;
  writePov(scene, options, file("far.pov"));
  const std::string far = readText(file("far.pov"));
  EXPECT_EQ(countOccurrences(far, "=texture{"), 2u) << "the lines' M3 and the last entry, M5";
  EXPECT_EQ(countOccurrences(far, "#declare M5="), 1u);
  options.view.renderMode = RenderMode::Filled;
  writePov(scene, options, file("filled.pov"));
  EXPECT_EQ(countOccurrences(readText(file("filled.pov")), "\nsphere{<-2,0,0>,.5 texture{M4}}\n"),
            1u);
  // The default palette's neighbours are other colours, not the colour lit: entry c is kept.
  options.view.renderMode = RenderMode::Shaded;
  options.colorMapFile = false;
  writePov(scene, options, file("default.pov"));
  EXPECT_EQ(countOccurrences(readText(file("default.pov")), "\nsphere{<-2,0,0>,.5 texture{M4}}\n"),
            1u);
}

TEST_F(ExportTest, PovPixelWidthsBecomeWorldRadii) {
  // Bounds 0..2 in y: the parallel camera is fitted 2 units high, so at 600 pixels a pixel is
  // 1/300 unit, and widths 10 and 4 pixels are radii 1/60 and 1/150.
  Scene scene = paletteScene();
  scene.lines.push_back({{0, 0, 0}, {0, 2, 0}, 10, 4, 3});
  PovWriter writer(file("lines.pov"), PovOptions{});
  printScene(scene, writer);
  EXPECT_NEAR(writer.worldPerPixel(), 2.0f / 600, 1e-7f);
  std::string pov = readText(file("lines.pov"));
  EXPECT_NE(pov.find("\ncone{<0,0,0>,.016667,<0,2,0>,.006667 texture{M3}}\n"), std::string::npos)
      << pov;

  scene.lineStyle = LineStyle::Polygon;  // widths in world units
  scene.lines[0].widthFrom = scene.lines[0].widthTo = 0.1f;
  writePov(scene, PovOptions{}, file("lines.pov"));
  pov = readText(file("lines.pov"));
  EXPECT_NE(pov.find("\ncylinder{<0,0,0>,<0,2,0>,.05 texture{M3}}\n"), std::string::npos) << pov;
}

TEST_F(ExportTest, PovSkipsLinesThatWouldBeDegenerate) {
  Scene scene = paletteScene();
  scene.lines.push_back({{0, 0, 0}, {0, 1, 0}, 1, 1, 1});
  scene.lines.push_back({{0, 1, 0}, {0, 1, 0}, 1, 1, 1});  // zero length
  scene.lines.push_back({{0, 0, 0}, {1, 0, 0}, 0, 0, 1});  // zero width
  PovExportStats stats = writePov(scene, PovOptions{}, file("lines.pov"));
  EXPECT_EQ(stats.cylinders, 1u);
  EXPECT_EQ(stats.linesSkipped, 2u);
  EXPECT_EQ(countOccurrences(readText(file("lines.pov")), "cylinder{"), 1u);
}

TEST_F(ExportTest, PovZeroNormalTakesItsFacesNormal) {
  Scene scene = paletteScene();
  addQuad(scene, 1, {0, 0}, 1);
  scene.meshes[0].normals[2] = glm::vec3(0.0f);
  writePov(scene, PovOptions{}, file("normals.pov"));
  std::string pov = readText(file("normals.pov"));
  std::size_t start = pov.find("normal_vectors{4,");
  ASSERT_NE(start, std::string::npos);
  std::string normals = pov.substr(start, pov.find('}', start) - start);
  EXPECT_EQ(countOccurrences(normals, "<0,0,1>"), 4u) << normals;
}

TEST_F(ExportTest, UnreadableTextureLeavesItsMeshUntextured) {
  Scene scene = paletteScene();
  scene.textures.push_back({"missing.png", 0, 0, {}});  // as a texture that could not be read
  TriangleMesh& mesh = scene.meshFor(1, 0);
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.texcoords = {{0, 0}, {1, 0}, {0, 1}};
  mesh.indices = {0, 1, 2};
  writePov(scene, PovOptions{}, file("plant.pov"));
  writeObj(scene, file("plant.obj"));
  std::string pov = readText(file("plant.pov"));
  EXPECT_EQ(pov.find("uv_vectors"), std::string::npos);
  EXPECT_NE(pov.find("object{Mesh0 texture{M1}}"), std::string::npos) << pov;
  EXPECT_EQ(countLinesStarting(readText(file("plant.obj")), "vt "), 0u);
  EXPECT_EQ(readText(file("plant.mtl")).find("map_Kd"), std::string::npos);
  EXPECT_FALSE(fs::exists(file("plant_texture1.png")));
}

TEST_F(ExportTest, PovMeshOutOfRangeIndexIsAnError) {
  Scene scene = paletteScene();
  addQuad(scene, 1, {0, 0}, 1);
  scene.meshes[0].indices[4] = 99;
  EXPECT_THROW(writePov(scene, PovOptions{}, file("bad.pov")), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file("bad.pov")));
}

// ---- POV-Ray renders the files ----

#define SKIP_WITHOUT_POVRAY() \
  if (!povrayAvailable()) GTEST_SKIP() << "povray is not installed (apt install povray)"

constexpr int kWidth = 64, kHeight = 48;

// The image size of the renders, and a white directional light from +z (the viewer's side in
// the default view), without ambient light of its own.
PovOptions renderOptions() {
  PovOptions options;
  options.width = kWidth;
  options.height = kHeight;
  LightSource front;
  front.directional = true;
  front.vector = {0, 0, 1};
  front.ambient = glm::vec3(0.0f);
  front.diffuse = glm::vec3(1.0f);
  options.view.lights = {front};
  return options;
}

// POV-Ray's render of `pov`, which must pass without a message, but for one that says
// `experimental` (backside diffuse is one of POV-Ray 3.7's experimental features) when allowed.
RgbaImage renderClean(const fs::path& pov, const fs::path& png, bool experimental = false) {
  PovrayRun run = runPovray(pov, png, kWidth, kHeight, false);
  EXPECT_EQ(run.exitStatus, 0) << run.messages;
  std::string messages = run.messages;
  if (experimental && messages.find("uses the following experimental feature(s):\n backside "
                                    "illumination.") != std::string::npos) {
    messages.clear();
  }
  EXPECT_EQ(messages, "") << "POV-Ray warned or failed on\n" << readText(pov);
  if (run.exitStatus != 0) return {};
  RgbaImage image = readPng(png);
  EXPECT_EQ(image.width, kWidth);
  EXPECT_EQ(image.height, kHeight);
  return image;
}

glm::ivec3 pixelAt(const RgbaImage& image, const Camera& camera, const glm::vec3& world) {
  glm::vec3 p = camera.toPixels(world);
  int x = std::clamp(static_cast<int>(p.x), 0, image.width - 1);
  int y = std::clamp(static_cast<int>(p.y), 0, image.height - 1);
  glm::u8vec4 c = image.pixel(x, y);
  return {c.r, c.g, c.b};
}

// The channel that clearly dominates, or -1.
int dominant(glm::ivec3 c) {
  for (int i = 0; i < 3; ++i) {
    if (c[i] > 100 && c[i] > 2 * c[(i + 1) % 3] && c[i] > 2 * c[(i + 2) % 3]) return i;
  }
  return -1;
}

TEST_F(ExportTest, PovrayRendersTheSceneWhereTheCameraPutsIt) {
  SKIP_WITHOUT_POVRAY();
  Scene scene = paletteScene();
  addQuad(scene, 1, {-2, 0}, 0.6f);                                // red, left
  scene.spheres.push_back({{2, 0, 0}, 0.6f, 2});                   // green, right
  scene.lines.push_back({{0, -1.5f, 0}, {0, 1.5f, 0}, 6, 6, 3});   // blue, 6 pixels wide at 64×48
  scene.lines.push_back({{0, -1.5f, 0}, {0, -1.5f, 0}, 6, 6, 3});  // degenerate: left out
  scene.discs.push_back({{0, 1.8f, 0}, {0, 0, 0}, 0.3f, 4});       // yellow, facing the camera
  PovOptions options = renderOptions();
  PovWriter writer(file("scene.pov"), options);
  printScene(scene, writer);
  RgbaImage image = renderClean(file("scene.pov"), file("scene.png"));
  if (image.width == 0) return;
  const Camera& camera = writer.camera();
  EXPECT_EQ(dominant(pixelAt(image, camera, {-2, 0, 0})), 0);
  EXPECT_EQ(dominant(pixelAt(image, camera, {2, 0, 0})), 1) << "+x is on the right, as in the PNG";
  EXPECT_EQ(dominant(pixelAt(image, camera, {0, -0.5f, 0})), 2);
  glm::ivec3 disc = pixelAt(image, camera, {0, 1.8f, 0});
  EXPECT_GT(disc.r, 150);
  EXPECT_GT(disc.g, 150);
  EXPECT_LT(disc.b, 100);
  // The background is colour 0 of the palette, unchanged by POV-Ray's gamma handling.
  glm::u8vec4 corner = image.pixel(0, 0);
  EXPECT_NEAR(corner.r, 0.1 * 255, 1.5);
  EXPECT_NEAR(corner.g, 0.2 * 255, 1.5);
  EXPECT_NEAR(corner.b, 0.4 * 255, 1.5);
}

TEST_F(ExportTest, PovrayPerspectiveAndTwistFollowTheCamera) {
  SKIP_WITHOUT_POVRAY();
  Scene scene = paletteScene();
  scene.spheres.push_back({{1.5f, 0, 0}, 0.4f, 1});  // red on +x
  scene.spheres.push_back({{0, 1.5f, 0}, 0.4f, 2});  // green on +y
  scene.spheres.push_back({{0, 0, 0}, 0.2f, 3});     // blue at the centre
  PovOptions options = renderOptions();
  options.view.projection = Projection::Perspective;
  options.view.viewpoint = {1, 1, 8};
  options.view.viewReference = {0, 0, 0};
  options.view.viewingAngle = 40;
  options.view.twistDegrees = 30;
  PovWriter writer(file("perspective.pov"), options);
  printScene(scene, writer);
  RgbaImage image = renderClean(file("perspective.pov"), file("perspective.png"));
  if (image.width == 0) return;
  const Camera& camera = writer.camera();
  EXPECT_EQ(dominant(pixelAt(image, camera, {1.5f, 0, 0})), 0);
  EXPECT_EQ(dominant(pixelAt(image, camera, {0, 1.5f, 0})), 1);
  EXPECT_EQ(dominant(pixelAt(image, camera, {0, 0, 0})), 2);
}

TEST_F(ExportTest, PovrayShowsTextureRowsAsTheGlRendererDoes) {
  SKIP_WITHOUT_POVRAY();
  Scene scene = paletteScene();
  scene.materials[5] = colour(1, 1, 1);
  // Row 0, the top of the image: red, green; row 1: blue, white. t = 0 is the bottom row, as
  // the GL renderer uploads the image.
  scene.textures.push_back(
      {"check.png", 2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}});
  TriangleMesh& mesh = scene.meshFor(5, 0);
  mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  mesh.normals.assign(4, {0, 0, 1});
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  PovOptions options = renderOptions();
  PovWriter writer(file("textured.pov"), options);
  printScene(scene, writer);
  EXPECT_TRUE(fs::exists(file("textured_texture1.png")));
  RgbaImage image = renderClean(file("textured.pov"), file("textured.png"));
  if (image.width == 0) return;
  const Camera& camera = writer.camera();
  EXPECT_EQ(dominant(pixelAt(image, camera, {-0.5f, 0.5f, 0})), 0);   // s .25, t .75: red
  EXPECT_EQ(dominant(pixelAt(image, camera, {0.5f, 0.5f, 0})), 1);    // s .75, t .75: green
  EXPECT_EQ(dominant(pixelAt(image, camera, {-0.5f, -0.5f, 0})), 2);  // s .25, t .25: blue
  glm::ivec3 white = pixelAt(image, camera, {0.5f, -0.5f, 0});        // s .75, t .25
  EXPECT_GT(std::min({white.r, white.g, white.b}), 200);
}

TEST_F(ExportTest, PovrayDrawsEveryInstanceOfADeclaredMesh) {
  SKIP_WITHOUT_POVRAY();
  Scene scene = paletteScene();
  scene.spheres.push_back({{-3, -1, 0}, 0.01f, 3});  // extends the bounds the camera frames
  scene.spheres.push_back({{3, 1, 0}, 0.01f, 3});
  Scene templateScene;
  addQuad(templateScene, 0, {0, 0}, 0.5f);
  PovOptions options = renderOptions();
  PovWriter writer(file("instances.pov"), options);
  writer.beginScene(scene, {});
  std::string name = writer.declareMesh(templateScene.meshes[0]);
  glm::mat4 left = glm::translate(glm::mat4(1.0f), glm::vec3(-2, 0, 0));
  glm::mat4 right =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)), 0.5f, glm::vec3(0, 0, 1));
  writer.placeObject(name, 1, -1, &left);
  writer.placeObject(name, 2, -1, &right);
  writer.endScene();
  std::string pov = readText(file("instances.pov"));
  EXPECT_EQ(countOccurrences(pov, "=mesh2{"), 1u);
  EXPECT_EQ(countOccurrences(pov, "object{" + name + " texture{M"), 2u);
  EXPECT_EQ(countOccurrences(pov, " matrix<"), 2u);
  RgbaImage image = renderClean(file("instances.pov"), file("instances.png"));
  if (image.width == 0) return;
  EXPECT_EQ(dominant(pixelAt(image, writer.camera(), {-2, 0, 0})), 0);
  EXPECT_EQ(dominant(pixelAt(image, writer.camera(), {2, 0, 0})), 1);
  glm::ivec3 between = pixelAt(image, writer.camera(), {0, 0, 0});
  EXPECT_NEAR(between.b, 0.4 * 255, 1.5) << "nothing between them: the background";
  EXPECT_NEAR(between.r, 0.1 * 255, 1.5);
}

TEST_F(ExportTest, PovrayLightsAMaterialSceneFromItsLightLines) {
  SKIP_WITHOUT_POVRAY();
  Scene scene;
  Material grey;
  grey.ambient = glm::vec3(0.1f);
  grey.diffuse = glm::vec3(0.8f);
  grey.specular = glm::vec3(0.5f);
  grey.shininess = 40;
  Material glowing;
  glowing.diffuse = glm::vec3(0.0f);
  glowing.emission = {0, 0.8f, 0};
  scene.materials = {Material{}, grey, glowing};
  addQuad(scene, 1, {-1.2f, 0}, 1);
  addQuad(scene, 2, {1.2f, 0}, 1);
  PovOptions options = renderOptions();
  options.materialMode = true;
  LightSource facing;  // from the viewer's side: the grey quad is lit
  facing.vector = {0, 0, 1};
  facing.ambient = glm::vec3(0.0f);
  facing.diffuse = glm::vec3(1.0f);
  LightSource spot;
  spot.directional = false;
  spot.vector = {-1.2f, 0, 3};
  spot.spot = true;
  spot.spotDirection = {0, 0, -1};
  spot.spotCutoff = 20;
  spot.spotExponent = 2;
  spot.ambient = glm::vec3(0.0f);
  spot.diffuse = glm::vec3(1.0f);
  options.view.lights = {facing, spot};
  PovWriter writer(file("lit.pov"), options);
  printScene(scene, writer);
  std::string pov = readText(file("lit.pov"));
  EXPECT_EQ(countOccurrences(pov, "light_source{"), 2u);
  EXPECT_EQ(countOccurrences(pov, " spotlight "), 1u);
  RgbaImage image = renderClean(file("lit.pov"), file("lit.png"));
  if (image.width == 0) return;
  glm::ivec3 lit = pixelAt(image, writer.camera(), {-1.2f, -0.5f, 0});
  EXPECT_GT(lit.r, 180) << "diffuse 0.8 under a light along the normal";
  EXPECT_EQ(lit.r, lit.g);
  EXPECT_EQ(dominant(pixelAt(image, writer.camera(), {1.2f, 0, 0})), 1)
      << "a black surface that glows green";
  glm::u8vec4 corner = image.pixel(0, 0);
  EXPECT_EQ(corner.r + corner.g + corner.b, 0) << "material 0's emission (none) is the background";
}

// `--trace-lights`: the tracer's set-up in POV-Ray. Two white squares, the left one passing half
// its light through (translucency: 1 0.5). Lit from behind, only the translucent one shows, at
// half the light's value; lit from the front, both, the translucent one at the half it
// reflects; under the sky alone (by radiosity), the sky's radiance. A light of irradiance π
// gives a white surface facing it the value 1, as in the tracer.
TEST_F(ExportTest, PovrayWithTheTracersLightsPassesLightThroughTranslucentColours) {
  SKIP_WITHOUT_POVRAY();
  Scene scene;
  scene.materials = {colour(0, 0, 0), colour(1, 1, 1), colour(1, 1, 1)};
  addQuad(scene, 1, {-1.2f, 0}, 1);
  addQuad(scene, 2, {1.2f, 0}, 1);
  auto render = [&](const char* name, glm::vec3 towardsLight, float irradiance, float sky) {
    PovOptions options = renderOptions();
    options.traceLights = true;
    options.view.trace.lightDirection = towardsLight;
    options.view.trace.lightIrradiance = glm::vec3(irradiance);
    options.view.trace.sky = glm::vec3(sky);
    options.view.trace.up = glm::vec3(0, 0, 1);
    options.view.trace.translucent = {{1, 0.5f}};
    PovWriter writer(file(std::string(name) + ".pov"), options);
    printScene(scene, writer);
    const std::string pov = readText(file(std::string(name) + ".pov"));
    EXPECT_EQ(countOccurrences(pov, "area_light"), irradiance > 0 ? 1u : 0u);
    EXPECT_EQ(countOccurrences(pov, "radiosity{"), 1u);
    EXPECT_EQ(countOccurrences(pov, "diffuse .5,.5"), 1u) << pov;
    EXPECT_EQ(countOccurrences(pov, "no_image"), sky > 0 ? 1u : 0u);
    const RgbaImage image =
        renderClean(file(std::string(name) + ".pov"), file(std::string(name) + ".png"), true);
    if (image.width == 0) return std::pair{glm::ivec3(-1), glm::ivec3(-1)};
    return std::pair{pixelAt(image, writer.camera(), {-1.2f, 0.3f, 0}),
                     pixelAt(image, writer.camera(), {1.2f, 0.3f, 0})};
  };
  constexpr float kPi = 3.14159265f;
  // Half the light in linear values is 188 of 255 in sRGB.
  const auto [behindTranslucent, behindOpaque] = render("behind", {0, 0, -1}, kPi, 0);
  EXPECT_NEAR(behindTranslucent.g, 188, 12);
  EXPECT_LT(behindOpaque.g, 10);
  const auto [frontTranslucent, frontOpaque] = render("front", {0, 0, 1}, kPi, 0);
  EXPECT_NEAR(frontTranslucent.g, 188, 12);
  EXPECT_GT(frontOpaque.g, 245);
  // The sky's display value 0.5 is its radiance; a white square facing it returns it.
  const auto [skyTranslucent, skyOpaque] = render("sky", {0, 0, 1}, 0, 0.5f);
  EXPECT_NEAR(skyOpaque.g, 128, 15);
  EXPECT_NEAR(skyTranslucent.g, 90, 15);  // half of it reflected: 0.107 linear
}

// Without `light:` lines a material scene is lit as the GL renderer lights it (view_lighting.h):
// by OpenGL's light 0 from the eye, not from `light direction:`, which only colour maps use.
TEST_F(ExportTest, PovrayLightsAMaterialSceneWithoutLightLinesFromTheEye) {
  SKIP_WITHOUT_POVRAY();
  Scene scene;
  Material grey;
  grey.ambient = glm::vec3(0.0f);
  grey.diffuse = glm::vec3(0.8f);
  scene.materials = {Material{}, grey};
  addQuad(scene, 1, {0, 0}, 1);  // facing +z, the default view's eye
  PovOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.materialMode = true;
  options.view.lightDirection = {1, 0, 0};  // edge-on to the quad: it would leave it dark
  PovWriter writer(file("headlight.pov"), options);
  printScene(scene, writer);
  const std::string pov = readText(file("headlight.pov"));
  EXPECT_EQ(countOccurrences(pov, "light_source{"), 1u);
  RgbaImage image = renderClean(file("headlight.pov"), file("headlight.png"));
  if (image.width == 0) return;
  glm::ivec3 lit = pixelAt(image, writer.camera(), {0, 0, 0});
  EXPECT_GT(lit.r, 180) << "diffuse 0.8 under the light from the eye";
}

// ---- POV-Ray runs confined ----

const fs::path kHostileScenes =
    fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "render_frames";

TEST_F(ExportTest, PovrayRunPassesNoNameAsAnOption) {
  SKIP_WITHOUT_POVRAY();
  const fs::path scene = file("x\" +GAinjected.log +I\"x.pov");
  fs::copy_file(kHostileScenes / "sphere.pov", scene);
  std::ofstream(file("x.pov")) << "#version 3.7;\n#error \"the other scene was rendered\"\n";
  const PovrayRun run = runPovray(scene, file("image.png"), 32, 24, false);
  EXPECT_EQ(run.exitStatus, 0) << run.messages;
  EXPECT_FALSE(fs::exists(file("injected.log")));
  const RgbaImage image = readPng(file("image.png"));
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  for (const auto& entry : fs::directory_iterator(file("")))
    EXPECT_NE(entry.path().filename().string().front(), '.') << "the work folder is removed";
}

TEST_F(ExportTest, PovrayRunReadsAndWritesNothingOutsideTheScenesFolder) {
  SKIP_WITHOUT_POVRAY();
  fs::create_directory(file("scene"));
  fs::copy_file(kHostileScenes / "fopen_outside.pov", file("scene/writes.pov"));
  PovrayRun run = runPovray(file("scene/writes.pov"), file("scene/writes.png"), 32, 24, false);
  EXPECT_NE(run.exitStatus, 0) << run.messages;
  EXPECT_FALSE(fs::exists(file("written-outside.txt")));
  EXPECT_FALSE(fs::exists(file("scene/writes.png"))) << "no image from a failed run";

  fs::copy_file(kHostileScenes / "include_passwd.pov", file("scene/reads.pov"));
  run = runPovray(file("scene/reads.pov"), file("scene/reads.png"), 32, 24, false);
  EXPECT_NE(run.exitStatus, 0) << run.messages;
  EXPECT_EQ(run.messages.find("root:"), std::string::npos) << run.messages;

  fs::copy_file(kHostileScenes / "include_outside.pov", file("scene/link.pov"));
  fs::copy_file(kHostileScenes / "secret.inc", file("secret.inc"));
  fs::create_symlink(file("secret.inc"), file("scene/secret.inc"));
  run = runPovray(file("scene/link.pov"), file("scene/link.png"), 32, 24, false);
  EXPECT_NE(run.exitStatus, 0) << run.messages;
  EXPECT_FALSE(fs::exists(file("scene/link.png")));
}

TEST_F(ExportTest, PovrayRunStopsAtItsTimeLimit) {
  SKIP_WITHOUT_POVRAY();
  fs::copy_file(kHostileScenes / "endless.pov", file("endless.pov"));
  const auto start = std::chrono::steady_clock::now();
  const PovrayRun run =
      runPovray(file("endless.pov"), file("endless.png"), 32, 24, false, std::chrono::seconds(1));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(run.timedOut);
  EXPECT_NE(run.exitStatus, 0);
  EXPECT_LT(seconds, 5.0);
  EXPECT_FALSE(fs::exists(file("endless.png")));
}

// Stopped while it renders, POV-Ray has reported no problem: nothing of its output (its banner,
// its options, a progress line for every few pixels) is handed on; the caller says it stopped.
TEST_F(ExportTest, PovrayStoppedWhileRenderingHandsOnNoneOfItsProgress) {
  SKIP_WITHOUT_POVRAY();
  fs::copy_file(kHostileScenes / "slow-render.pov", file("slow.pov"));
  const PovrayRun run =
      runPovray(file("slow.pov"), file("slow.png"), 800, 600, false, std::chrono::seconds(2));
  EXPECT_TRUE(run.timedOut) << run.exitStatus;
  EXPECT_EQ(run.messages.find("Rendered"), std::string::npos);
  EXPECT_LT(run.messages.size(), 1000u) << run.messages.substr(0, 1000);
}

// ---- `hirsute export` ----

// Runs the hirsute binary with `arguments` (each quoted), its output to `log`; the exit status.
int runHirsute(const std::string& arguments, const fs::path& log) {
  std::string command =
      std::string("'") + HIRSUTE_BINARY + "' " + arguments + " > '" + log.string() + "' 2>&1";
  int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The progress line reads POV-Ray's reports of its render: the last whole one, past a part cut
// off at the end of what has come so far.
TEST(PovrayProgress, TheLastWholeReportOfPixelsRenderedCounts) {
  EXPECT_FALSE(lastPixelsRendered("==== [Parsing...] ====\nParse Warning: …\n"));
  const auto first =
      lastPixelsRendered("==== [Rendering...] ===\nRendered 1024 of 307200 pixels (0%)\r");
  ASSERT_TRUE(first);
  EXPECT_EQ(first->done, 1024);
  EXPECT_EQ(first->total, 307200);
  const auto later = lastPixelsRendered(
      "Rendered 1024 of 307200 pixels (0%)\rRendered 153600 of 307200 pixels (50%)\rRendered 15");
  ASSERT_TRUE(later);
  EXPECT_EQ(later->done, 153600);
  EXPECT_FALSE(lastPixelsRendered("Rendered many of 307200 pixels"));
}

TEST_F(ExportTest, CommandWritesPovAndObjForAModel) {
  std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/herb";
  fs::path pov = file("herb.pov"), obj = file("herb.obj");
  std::string render = povrayAvailable() ? " --render --size 80x60" : "";
  ASSERT_EQ(runHirsute("export '" + herb + ".l' '" + herb + ".v' --pov '" + pov.string() +
                           "' --obj '" + obj.string() + "'" + render,
                       file("log")),
            0)
      << readText(file("log"));
  std::string povText = readText(pov);
  EXPECT_NE(povText.find("camera{orthographic"), std::string::npos);
  // The herb draws its internodes as cylinder-style tubes (meshes) and its leaves as surfaces.
  EXPECT_GT(countOccurrences(povText, "mesh2{"), 0u);
  std::string objText = readText(obj);
  EXPECT_GT(countLinesStarting(objText, "f "), 1000u);
  EXPECT_GT(countLinesStarting(objText, "v "), 1000u);
  EXPECT_GT(countLinesStarting(readText(file("herb.mtl")), "newmtl "), 0u);
  if (povrayAvailable()) {
    EXPECT_EQ(readText(file("log")).find("Warning"), std::string::npos) << readText(file("log"));
    RgbaImage image = readPng(file("herb.png"));
    EXPECT_EQ(image.width, 80);
    EXPECT_EQ(image.height, 60);
  }
}

TEST_F(ExportTest, CommandNeedsAnOutput) {
  std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/herb";
  EXPECT_EQ(runHirsute("export '" + herb + ".l' '" + herb + ".v'", file("log")), 2);
  EXPECT_NE(readText(file("log")).find("--pov FILE or --obj FILE"), std::string::npos)
      << readText(file("log"));
  EXPECT_EQ(runHirsute("export '" + herb + ".l' --obj '" + file("x.obj").string() + "' --render",
                       file("log")),
            2);
  EXPECT_FALSE(fs::exists(file("x.obj")));
}

}  // namespace
}  // namespace hirsute
