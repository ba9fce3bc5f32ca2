// Plant hairs in every output (docs/design.md, "Plant hairs"), on hand-built scenes whose hairs are
// placed directly: the GL renderer draws them where root, orientation and length put them and
// nowhere else, hides them, and draws a uniform fraction of them; the POV-Ray scene declares one
// tube per template and radius bucket and places one object per hair (and POV-Ray renders it
// without a warning); the OBJ has one polyline per placed template polyline; the CSV has one row
// per hair whose numbers read back exactly; `hirsute export --hairs` writes it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_stage.h"
#include "hirsute/hairs/plant/hair_csv_writer.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/viewer/export/obj_writer.h"
#include "hirsute/viewer/export/pov_writer.h"
#include "hirsute/viewer/export/povray_runner.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "hirsute/viewer/gl/organ_drawing.h"
#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/view/feather_buffers.h"
#include "hirsute/viewer/view/png_image.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

constexpr int kRed = 1, kGreen = 2, kBlue = 3;

Material colour(float r, float g, float b) {
  Material m;
  m.ambient = m.diffuse = glm::vec3(r, g, b);
  return m;
}

// Palette: 0 background (dark blue), 1 red, 2 green, 3 blue.
Scene paletteScene() {
  Scene scene;
  scene.materials = {colour(0.1f, 0.2f, 0.4f), colour(1, 0, 0), colour(0, 1, 0), colour(0, 0, 1)};
  return scene;
}

// A straight hair along its own x axis, one unit long, in three vertices.
HairTemplate straightTemplate(int material) {
  HairTemplate t;
  t.file = "straight.l";
  t.polylines = {{{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}}};
  t.material = material;
  t.extent = 1;
  return t;
}

// A bent hair of two polylines (a branch): 3 + 2 vertices, 3 segments.
HairTemplate branchedTemplate(int material) {
  HairTemplate t;
  t.file = "branched.l";
  t.polylines = {{{0, 0, 0}, {0.5f, 0, 0}, {0.8f, 0.3f, 0}}, {{0.5f, 0, 0}, {0.6f, 0, 0.3f}}};
  t.material = material;
  t.extent = glm::length(glm::vec3(0.8f, 0.3f, 0));
  return t;
}

Hair hair(glm::vec3 root, glm::quat rotation, float length, float radius, int templateIndex,
          HairSide side = HairSide::Front) {
  Hair h;
  h.root = root;
  h.setRotation(rotation);
  h.length = length;
  h.radius = radius;
  h.templateIndex = static_cast<std::uint8_t>(templateIndex);
  h.side = side;
  return h;
}

// The rotation that turns the template's x axis (the hair direction) onto `direction`: the
// quaternion (1 + x·d, x × d), normalised.
glm::quat pointing(glm::vec3 direction) {
  glm::vec3 x(1, 0, 0), d = glm::normalize(direction);
  glm::vec3 axis = glm::cross(x, d);
  return glm::normalize(glm::quat(1 + glm::dot(x, d), axis.x, axis.y, axis.z));
}

// ---- The GL renderer ----

struct Frame {
  RgbaImage image;
  Camera camera;
  std::size_t hairs = 0, segments = 0;
};

// Renders through the headless path with one sample a pixel (exact coverage), after `configure`
// has set the renderer's hair settings.
Frame renderHairs(const Scene& scene, int width, int height,
                  const std::function<void(GlRenderer&)>& configure = {}) {
  OsMesaContext context;
  OffscreenFramebuffer framebuffer(context.gl(), width, height, 1);
  GlRenderer renderer(context.gl());
  renderer.upload(scene, ViewSettings{}, false);
  if (configure) configure(renderer);
  framebuffer.bind();
  Frame frame;
  frame.camera = fitCamera(ViewSettings{}, scene.bounds(), {width, height});
  renderer.draw(frame.camera);
  frame.image = framebuffer.read();
  frame.hairs = renderer.organInstances("hairs");
  frame.segments = renderer.organPrimitives("hairs");
  return frame;
}

// The renderer reaches each organ's drawing by the name it registers (organ_drawing.h), in the
// registered order; a name no organ registers is a mistake of the caller, not a silent no-op.
TEST(OrganDrawings, TheRendererReachesEachOrganByItsName) {
  std::vector<std::string> names;
  for (const OrganDrawingType* type : organDrawings()) names.emplace_back(type->name());
  EXPECT_EQ(names, (std::vector<std::string>{"hairs", "feathers", "fur"}));
  OsMesaContext context;
  GlRenderer renderer(context.gl());
  renderer.upload(Scene{}, ViewSettings{}, false);
  for (const std::string& name : names) {
    EXPECT_TRUE(renderer.organVisible(name));
    renderer.setOrganVisible(name, false);
    EXPECT_FALSE(renderer.organVisible(name));
    EXPECT_EQ(renderer.organInstances(name), 0u);
  }
  EXPECT_THROW(renderer.setOrganVisible("petals", false), std::invalid_argument);
  EXPECT_THROW(renderer.updateOrgan("petals", Scene{}), std::invalid_argument);
}

bool isRed(glm::u8vec4 p) {
  return p.r > 200 && p.g < 50 && p.b < 50;
}

glm::ivec2 pixelOf(const Camera& camera, glm::vec3 world) {
  glm::vec3 p = camera.toPixels(world);
  return {static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y))};
}

// Whether any pixel within `radius` of `at` passes `test`.
bool anyNear(const RgbaImage& image, glm::ivec2 at, int radius,
             const std::function<bool(glm::u8vec4)>& test) {
  for (int y = at.y - radius; y <= at.y + radius; ++y) {
    for (int x = at.x - radius; x <= at.x + radius; ++x) {
      if (x >= 0 && y >= 0 && x < image.width && y < image.height && test(image.pixel(x, y)))
        return true;
    }
  }
  return false;
}

// The distance in pixels from the centre of pixel (x, y) to the segment a–b on the screen.
float screenDistance(int x, int y, glm::vec2 a, glm::vec2 b) {
  glm::vec2 p(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
  glm::vec2 d = b - a;
  float t = glm::dot(d, d) > 0 ? std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0f, 1.0f) : 0;
  return glm::distance(p, a + t * d);
}

TEST(HairRenderTest, HairsChangeThePixelsWhereTheyLieAndNoOthers) {
  Scene scene = paletteScene();
  // A green square behind the hairs: hairs draw over it, and leave the rest of it alone.
  TriangleMesh& quad = scene.meshFor(kGreen);
  quad.positions = {{-3, -3, -1}, {3, -3, -1}, {3, 3, -1}, {-3, 3, -1}};
  quad.normals.assign(4, {0, 0, 1});
  quad.indices = {0, 1, 2, 0, 2, 3};
  scene.organ<HairPart>().templates = {straightTemplate(kRed), branchedTemplate(kBlue)};
  scene.organ<HairPart>().hairs = {hair({-2, -2, 0}, pointing({1, 1, 0}), 2, 0.01f, 0),
                                   hair({1, -2.5f, 0}, pointing({0, 1, 0}), 3, 0.01f, 0),
                                   hair({-2, 1, 0}, pointing({1, 0, 0}), 2, 0.01f, 1)};
  Frame with = renderHairs(scene, 120, 120);
  Frame without =
      renderHairs(scene, 120, 120, [](GlRenderer& r) { r.setOrganVisible("hairs", false); });
  EXPECT_EQ(with.hairs, 3u);
  EXPECT_EQ(with.segments, 2u + 2u + 3u);

  // The screen segments of every placed hair.
  std::vector<std::pair<glm::vec2, glm::vec2>> segments;
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    for (const auto& polyline : scene.organ<HairPart>().templates[h.templateIndex].polylines) {
      for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        segments.emplace_back(glm::vec2(with.camera.toPixels(h.place(polyline[i]))),
                              glm::vec2(with.camera.toPixels(h.place(polyline[i + 1]))));
      }
    }
  }
  int changed = 0;
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 120; ++x) {
      if (with.image.pixel(x, y) == without.image.pixel(x, y)) continue;
      ++changed;
      float nearest = 1e9f;
      for (const auto& [a, b] : segments) nearest = std::min(nearest, screenDistance(x, y, a, b));
      EXPECT_LE(nearest, 1.0f) << "pixel " << x << "," << y << " changed away from every hair";
    }
  }
  EXPECT_GT(changed, 50);
  // Every segment's middle is drawn, in its template's colour.
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    const HairTemplate& t = scene.organ<HairPart>().templates[h.templateIndex];
    for (const auto& polyline : t.polylines) {
      for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        glm::ivec2 at = pixelOf(with.camera, h.place((polyline[i] + polyline[i + 1]) * 0.5f));
        EXPECT_TRUE(anyNear(with.image, at, 1,
                            [&](glm::u8vec4 p) {
                              return t.material == kRed ? isRed(p)
                                                        : (p.b > 200 && p.r < 50 && p.g < 50);
                            }))
            << "segment " << i << " of a hair at " << h.root.x << "," << h.root.y;
      }
    }
  }
  // Hidden, or drawn at fraction 0, no pixel is a hair's.
  Frame zero = renderHairs(scene, 120, 120, [](GlRenderer& r) { r.setDetail(0); });
  EXPECT_EQ(zero.image.rgba, without.image.rgba);
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 120; ++x) EXPECT_FALSE(isRed(without.image.pixel(x, y))) << x << "," << y;
  }
}

TEST(HairRenderTest, HairFollowsRootOrientationAndLength) {
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed)};
  // Rooted at (1, -1, 0), turned from +x to +y, two units long: the tip is at (1, 1, 0).
  scene.organ<HairPart>().hairs = {
      hair({1, -1, 0}, glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1)), 2, 0.01f, 0)};
  Frame frame = renderHairs(scene, 100, 100);
  const Camera& camera = frame.camera;
  glm::ivec2 root = pixelOf(camera, {1, -1, 0}), tip = pixelOf(camera, {1, 1, 0});
  ASSERT_LT(tip.y, root.y) << "+y is up on the screen";
  // The red column: from the root's row to the tip's, in the root's column.
  int top = 1 << 20, bottom = -1;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      if (!isRed(frame.image.pixel(x, y))) continue;
      EXPECT_LE(std::abs(x - root.x), 1) << "a red pixel off the hair at " << x << "," << y;
      top = std::min(top, y);
      bottom = std::max(bottom, y);
    }
  }
  EXPECT_NEAR(top, tip.y, 1.0);
  EXPECT_NEAR(bottom, root.y, 1.0);
  EXPECT_TRUE(anyNear(frame.image, pixelOf(camera, {1, 0, 0}), 1, isRed));
  // Not where the template would lie unturned (+x from the root) or unscaled (ending at y = 0).
  EXPECT_FALSE(anyNear(frame.image, pixelOf(camera, {2.5f, -1, 0}), 1, isRed));
  EXPECT_TRUE(anyNear(frame.image, pixelOf(camera, {1, 0.8f, 0}), 1, isRed));
}

// A grid of 40 × 25 short hairs, one unit apart, each along +x: none overlaps another.
Scene hairGrid() {
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed)};
  for (int j = 0; j < 25; ++j) {
    for (int i = 0; i < 40; ++i) {
      scene.organ<HairPart>().hairs.push_back(
          hair({static_cast<float>(i), static_cast<float>(j), 0}, glm::quat(1, 0, 0, 0), 0.5f,
               0.01f, 0));
    }
  }
  return scene;
}

// Which hairs of the grid are drawn: the middle of each hair shows red.
std::vector<bool> drawnHairs(const Scene& scene, float fraction, bool visible = true) {
  Frame frame = renderHairs(scene, 400, 250, [&](GlRenderer& r) {
    r.setDetail(fraction);
    r.setOrganVisible("hairs", visible);
  });
  std::vector<bool> drawn;
  for (const Hair& h : scene.organ<HairPart>().hairs) {
    drawn.push_back(anyNear(frame.image, pixelOf(frame.camera, h.place({0.5f, 0, 0})), 1, isRed));
  }
  return drawn;
}

TEST(HairRenderTest, HiddenHairsAndFractionZeroDrawNothing) {
  Scene scene = hairGrid();
  auto all = drawnHairs(scene, 1.0f);
  EXPECT_EQ(std::count(all.begin(), all.end(), true), 1000);
  auto none = drawnHairs(scene, 0.0f);
  EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
  auto hidden = drawnHairs(scene, 1.0f, false);
  EXPECT_EQ(std::count(hidden.begin(), hidden.end(), true), 0);
}

TEST(HairRenderTest, AFractionDrawsThatShareSpreadOverThePlant) {
  Scene scene = hairGrid();
  auto half = drawnHairs(scene, 0.5f);
  EXPECT_NEAR(std::count(half.begin(), half.end(), true), 500, 2);
  // Spread: each quadrant of the grid shows about half of its hairs (the hairs' index order runs
  // row by row, so a prefix in that order would fill the lower rows and leave the upper empty).
  for (int qy = 0; qy < 2; ++qy) {
    for (int qx = 0; qx < 2; ++qx) {
      int shown = 0, total = 0;
      for (std::size_t k = 0; k < scene.organ<HairPart>().hairs.size(); ++k) {
        int i = static_cast<int>(k % 40), j = static_cast<int>(k / 40);
        if ((i < 20) == (qx == 0) && (j < 12) == (qy == 0)) {
          ++total;
          shown += half[k] ? 1 : 0;
        }
      }
      EXPECT_GT(shown, total * 2 / 5) << "quadrant " << qx << "," << qy;
      EXPECT_LT(shown, total * 3 / 5) << "quadrant " << qx << "," << qy;
    }
  }
  // A smaller fraction is a prefix of the same order: its hairs are among those of the larger.
  auto quarter = drawnHairs(scene, 0.25f);
  EXPECT_NEAR(std::count(quarter.begin(), quarter.end(), true), 250, 2);
  for (std::size_t k = 0; k < half.size(); ++k) {
    if (quarter[k]) {
      EXPECT_TRUE(half[k]) << "hair " << k;
    }
  }
}

// ---- Export files ----

class HairExportTest : public testing::TemporaryFolderTest {
 protected:
  HairExportTest() : TemporaryFolderTest("hirsute_hairs_") {}
};

using testing::countLinesStarting;
using testing::countOccurrences;
using testing::linesOf;
using testing::readText;

// Template 0 straight and red, template 1 branched and green. Template 0's hairs come in two
// radius/length ratios (0.01 twice, 0.02 once), template 1's in one; one hair has no radius and
// one names a template that does not exist: both are left out of the POV-Ray scene.
Scene exportScene() {
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed), branchedTemplate(kGreen)};
  scene.organ<HairPart>().hairs = {hair({1, 2, 3}, glm::quat(1, 0, 0, 0), 2, 0.02f, 0),
                                   hair({0, 0, 0}, pointing({0, 1, 0}), 1, 0.01f, 0),
                                   hair({0.5f, 0, 0}, pointing({0, 1, 1}), 1.5f, 0.03f, 0),
                                   hair({0, 0, 1}, pointing({1, 1, 0}), 1, 0.05f, 1),
                                   hair({0, 1, 1}, pointing({-1, 1, 0}), 0.5f, 0.025f, 1),
                                   hair({0, 1, 2}, pointing({0, 1, 0}), 1, 0, 0),
                                   hair({0, 2, 2}, pointing({0, 1, 0}), 1, 0.01f, 7)};
  return scene;
}

TEST_F(HairExportTest, PovDeclaresOneTubePerTemplateAndRadiusBucket) {
  Scene scene = exportScene();
  PovExportStats stats = writePov(scene, PovOptions{}, file("hairs.pov"));
  std::string text = readText(file("hairs.pov"));
  EXPECT_EQ(stats.organ("hair meshes"), 3u);
  EXPECT_EQ(countOccurrences(text, "=mesh2{"), 3u) << text;
  EXPECT_EQ(countOccurrences(text, "#declare H"), 3u);
  // A tube: sides × segments × 2 triangles.
  EXPECT_EQ(stats.triangles, 5u * 2 * 2 * 2 + 5u * 3 * 2);
  EXPECT_EQ(stats.organ("hairs"), 5u);
  EXPECT_EQ(stats.organ("hairs skipped"), 2u);
}

TEST_F(HairExportTest, PovPlacesOneObjectPerHairInAUnionPerMaterial) {
  Scene scene = exportScene();
  writePov(scene, PovOptions{}, file("hairs.pov"));
  std::string text = readText(file("hairs.pov"));
  EXPECT_EQ(countOccurrences(text, "object{H"), 5u) << text;
  // The hairs of each material share the union's texture: no object carries its own.
  EXPECT_EQ(countOccurrences(text, "union{"), 2u);
  EXPECT_EQ(countOccurrences(text, "texture{M1}}"), 1u);
  EXPECT_EQ(countOccurrences(text, "texture{M2}}"), 1u);
  EXPECT_EQ(countOccurrences(text, " texture{"), 0u);
  // The unturned hair of length 2 at (1, 2, 3): the template scaled by 2, moved to its root.
  EXPECT_NE(text.find("matrix<2,0,0,0,2,0,0,0,2,1,2,3>"), std::string::npos) << text;
  // Its tube is declared at radius 0.02 / 2 = 0.01 in the template's frame, as is the second
  // hair's (0.01 / 1): both use the same mesh.
  std::size_t first = text.find("object{H"), second = text.find("object{H", first + 1);
  ASSERT_NE(second, std::string::npos);
  auto nameAt = [&](std::size_t at) {
    std::size_t end = text.find(' ', at);
    return text.substr(at + 7, end - at - 7);
  };
  EXPECT_EQ(nameAt(first), nameAt(second));
  EXPECT_NE(nameAt(first), nameAt(text.find("object{H", second + 1)));
}

TEST_F(HairExportTest, PovLoneHairCarriesItsTexture) {
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed)};
  scene.organ<HairPart>().hairs = {hair({0, 0, 0}, pointing({0, 1, 0}), 1, 0.01f, 0)};
  writePov(scene, PovOptions{}, file("hair.pov"));
  std::string text = readText(file("hair.pov"));
  EXPECT_EQ(countOccurrences(text, "union{"), 0u) << "POV-Ray warns about a union of one";
  EXPECT_EQ(countOccurrences(text, "object{H0 texture{M1} matrix<"), 1u) << text;
}

#define SKIP_WITHOUT_POVRAY() \
  if (!povrayAvailable()) GTEST_SKIP() << "povray is not installed (apt install povray)"

TEST_F(HairExportTest, PovrayRendersHairsWhereTheyStand) {
  SKIP_WITHOUT_POVRAY();
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed), branchedTemplate(kGreen)};
  // Three thick red hairs standing up in a row, and green ones to the right.
  for (float x : {-1.0f, 0.0f, 1.0f}) {
    scene.organ<HairPart>().hairs.push_back(hair({x, -1, 0}, pointing({0, 1, 0}), 2, 0.15f, 0));
  }
  scene.organ<HairPart>().hairs.push_back(hair({2, -1, 0}, pointing({0, 1, 0}), 1.5f, 0.1f, 1));
  scene.organ<HairPart>().hairs.push_back(hair({2.5f, -1, 0}, pointing({0, 1, 0}), 1.5f, 0.1f, 1));
  PovOptions options;
  options.width = 64;
  options.height = 48;
  LightSource front;
  front.directional = true;
  front.vector = {0, 0, 1};
  front.ambient = glm::vec3(0.0f);
  options.view.lights = {front};
  PovWriter writer(file("hairs.pov"), options);
  printScene(scene, writer);
  PovrayRun run = runPovray(file("hairs.pov"), file("hairs.png"), 64, 48, false);
  ASSERT_EQ(run.exitStatus, 0) << run.messages;
  EXPECT_EQ(run.messages, "") << "POV-Ray warned on\n" << readText(file("hairs.pov"));
  RgbaImage image = readPng(file("hairs.png"));
  ASSERT_EQ(image.width, 64);
  const Camera& camera = writer.camera();
  for (float x : {-1.0f, 0.0f, 1.0f}) {
    glm::ivec2 at = pixelOf(camera, {x, 0, 0});
    glm::u8vec4 p = image.pixel(at.x, at.y);
    EXPECT_GT(p.r, 150) << "hair at x = " << x;
    EXPECT_LT(p.g, 80);
  }
  // Between two hairs, and above them: the background.
  for (glm::vec3 empty : {glm::vec3(-0.5f, 0, 0), glm::vec3(0, 1.5f, 0)}) {
    glm::ivec2 at = pixelOf(camera, empty);
    glm::u8vec4 p = image.pixel(at.x, at.y);
    EXPECT_LT(p.r, 60) << empty.x << "," << empty.y;
  }
}

TEST_F(HairExportTest, ObjHasOnePolylinePerPlacedTemplatePolyline) {
  Scene scene = exportScene();
  ObjExportStats stats = writeObj(scene, file("hairs.obj"));
  std::string text = readText(file("hairs.obj"));
  // Template 0: one polyline of 3 vertices, 4 hairs (its radius does not matter to OBJ);
  // template 1: 3 + 2 vertices, 2 hairs; the hair of template 7 is left out.
  EXPECT_EQ(testing::objPolylines(text).size(), 4u * 1 + 2u * 2) << text;
  EXPECT_EQ(countLinesStarting(text, "l "), 4u * 2 + 2u * (2 + 1));  // one a segment
  EXPECT_EQ(countLinesStarting(text, "v "), 4u * 3 + 2u * 5);
  EXPECT_EQ(stats.organ("hairs"), 6u);
  EXPECT_EQ(countLinesStarting(text, "o hairs"), 1u);
  EXPECT_EQ(countLinesStarting(text, "usemtl "), 2u);
  EXPECT_EQ(countLinesStarting(readText(file("hairs.mtl")), "newmtl "), 2u);
  // Every `l` names vertices already written; the first hair's are its template placed.
  std::vector<std::string> lines = linesOf(text);
  std::size_t vertices = 0;
  for (const std::string& line : lines) {
    if (line.rfind("v ", 0) == 0) ++vertices;
    if (line.rfind("l ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    for (std::size_t index; in >> index;) {
      EXPECT_GE(index, 1u);
      EXPECT_LE(index, vertices);
    }
  }
  auto first = std::find_if(lines.begin(), lines.end(),
                            [](const std::string& l) { return l.rfind("v ", 0) == 0; });
  ASSERT_NE(first, lines.end());
  EXPECT_EQ(*first, "v 1 2 3");
  EXPECT_EQ(*(first + 2), "v 3 2 3");
}

TEST_F(HairExportTest, CsvHasOneRowPerHairThatReadsBack) {
  Scene scene = paletteScene();
  scene.organ<HairPart>().templates = {straightTemplate(kRed), branchedTemplate(kGreen)};
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1, 1);
  for (int i = 0; i < 500; ++i) {
    scene.organ<HairPart>().hairs.push_back(
        hair({unit(random) * 100, unit(random), unit(random) * 1e-3f},
             pointing({unit(random), unit(random), unit(random) + 1.5f}), 1 + unit(random) * 0.5f,
             0.01f * (2 + unit(random)), i % 2, static_cast<HairSide>(1 + i % 3)));
  }
  HairCsvStats stats = writeHairCsv(scene, file("hairs.csv"));
  EXPECT_EQ(stats.rows, 500u);
  std::vector<std::string> rows = linesOf(readText(file("hairs.csv")));
  ASSERT_EQ(rows.size(), 501u);
  EXPECT_EQ(rows[0], kHairCsvHeader);
  EXPECT_EQ(rows[0],
            "root_x,root_y,root_z,direction_x,direction_y,direction_z,template,length,radius,side");
  const char* sides[] = {"", "front", "back", "edge"};
  for (std::size_t i = 0; i < scene.organ<HairPart>().hairs.size(); ++i) {
    const Hair& h = scene.organ<HairPart>().hairs[i];
    std::vector<std::string> cells;
    std::istringstream in(rows[i + 1]);
    for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 10u) << rows[i + 1];
    auto read = [](const std::string& cell) {
      float value = 0;
      auto result = std::from_chars(cell.data(), cell.data() + cell.size(), value);
      EXPECT_EQ(result.ptr, cell.data() + cell.size()) << cell;
      return value;
    };
    glm::vec3 direction = h.direction();
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(read(cells[static_cast<std::size_t>(k)]), h.root[k]) << "row " << i;
      EXPECT_EQ(read(cells[static_cast<std::size_t>(3 + k)]), direction[k]) << "row " << i;
    }
    EXPECT_NEAR(glm::length(direction), 1.0f, 1e-5f);
    EXPECT_EQ(cells[6], std::to_string(h.templateIndex));
    EXPECT_EQ(read(cells[7]), h.length);
    EXPECT_EQ(read(cells[8]), h.radius);
    EXPECT_EQ(cells[9], sides[static_cast<int>(h.side)]);
  }
}

TEST_F(HairExportTest, CsvOfASceneWithoutHairsIsItsHeader) {
  Scene scene = paletteScene();
  writeHairCsv(scene, file("none.csv"));
  EXPECT_EQ(readText(file("none.csv")), std::string(kHairCsvHeader) + "\n");
}

int runHirsute(const std::string& arguments, const fs::path& log) {
  std::string command =
      std::string("'") + HIRSUTE_BINARY + "' " + arguments + " > '" + log.string() + "' 2>&1";
  int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST_F(HairExportTest, CommandWritesTheHairsCsvAlone) {
  std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/herb";
  fs::path csv = file("herb.csv");
  ASSERT_EQ(runHirsute("export '" + herb + ".l' '" + herb + ".v' --hairs '" + csv.string() + "'",
                       file("log")),
            0)
      << readText(file("log"));
  std::vector<std::string> rows = linesOf(readText(csv));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], kHairCsvHeader);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(std::count(rows[i].begin(), rows[i].end(), ','), 9) << rows[i];
  }
}

// A textured feather type's barbs reach POV-Ray in its texture's colours (times the type's), as
// GL's barb shader draws them: the peacock feather's eye gives its barbs hundreds of colours,
// where an untextured type (feather-types' first) gives them one.
TEST_F(HairExportTest, FeatherTexturesReachPovRay) {
  auto barbColours = [&](const std::string& model, const std::string& name) {
    const std::string base = std::string(HIRSUTE_SOURCE_DIR) + "/models/" + model;
    const fs::path pov = file(name + ".pov");
    EXPECT_EQ(runHirsute("export '" + base + "/" + name + ".l' '" + base + "/" + name +
                             ".v' --pov '" + pov.string() + "' --size 200x200",
                         file("log")),
              0)
        << readText(file("log"));
    const std::string text = readText(pov);
    const std::size_t barbs = text.find("// feather barbs");
    EXPECT_NE(barbs, std::string::npos);
    std::set<std::string> colours;
    for (std::size_t at = text.find("rgbt<", barbs); at != std::string::npos;
         at = text.find("rgbt<", at + 1)) {
      const std::size_t end = text.find('>', at);
      const std::string rgbt = text.substr(at + 5, end - at - 5);
      colours.insert(rgbt.substr(0, rgbt.rfind(',')));  // without the transparency
    }
    return colours.size();
  };
  EXPECT_GT(barbColours("peacock-feather", "peacock-feather"), 100u);
  EXPECT_LE(barbColours("feather-interpolation", "feather-interpolation"), 8u);
}

// The mean colour of the pixels of `image` that differ from its corner (the background) by
// more than 30 levels in all, and how many there are.
struct Foreground {
  glm::dvec3 mean{0.0};
  int pixels = 0;
};

Foreground foregroundOf(const RgbaImage& image) {
  Foreground f;
  const glm::ivec3 background(glm::u8vec3(image.pixel(0, 0)));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::ivec3 p(glm::u8vec3(image.pixel(x, y)));
      const glm::ivec3 d = glm::abs(p - background);
      if (d.x + d.y + d.z <= 30) continue;
      f.mean += glm::dvec3(p);
      ++f.pixels;
    }
  }
  if (f.pixels > 0) f.mean /= f.pixels;
  return f;
}

// Fur strands through POV-Ray show the preview's colours: the strands' shades (display colours,
// emitted) are written in linear light for the scene's `assumed_gamma 1`, as every surface colour
// is, so the fur of models/fur-square has GL's mean colour within 10 levels (ribbons a strand
// wide stand for the shells, and the square shows between them a little differently: 153/119/80
// for GL's 161/125/83; written as display values, POV-Ray showed it washed out, 201/179/148).
TEST_F(HairExportTest, FurThroughPovRayHasThePreviewsColour) {
  SKIP_WITHOUT_POVRAY();
  const std::string base = std::string(HIRSUTE_SOURCE_DIR) + "/models/fur-square/square";
  const std::string model = "'" + base + ".l' '" + base + ".v'";
  ASSERT_EQ(runHirsute("render " + model + " --size 64x48 -o '" + file("gl.png").string() + "'",
                       file("log")),
            0)
      << readText(file("log"));
  ASSERT_EQ(runHirsute("export " + model + " --pov '" + file("fur.pov").string() +
                           "' --size 64x48 --render",
                       file("log")),
            0)
      << readText(file("log"));
  const Foreground gl = foregroundOf(readPng(file("gl.png")));
  const Foreground pov = foregroundOf(readPng(file("fur.png")));
  ASSERT_GT(gl.pixels, 500);
  EXPECT_NEAR(pov.pixels, gl.pixels, 0.1 * gl.pixels);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(pov.mean[c], gl.mean[c], 10.0)
        << "channel " << c << ": POV-Ray " << pov.mean.x << "/" << pov.mean.y << "/" << pov.mean.z
        << ", GL " << gl.mean.x << "/" << gl.mean.y << "/" << gl.mean.z;
  }
}

// The numbers of every `rgbt<r,g,b,t>` in `text` after `from`, without the transparency.
std::vector<glm::dvec3> rgbtColours(const std::string& text, std::size_t from) {
  std::vector<glm::dvec3> colours;
  for (std::size_t at = text.find("rgbt<", from); at != std::string::npos;
       at = text.find("rgbt<", at + 1)) {
    std::istringstream numbers(text.substr(at + 5, text.find('>', at) - at - 5));
    glm::dvec3 c;
    char comma = 0;
    numbers >> c.x >> comma >> c.y >> comma >> c.z;
    colours.push_back(c);
  }
  return colours;
}

// A feather's barbs are lit by POV-Ray from its type's colour as a surface of that colour is:
// decoded from sRGB to linear light. The base feather's colour 0.42 0.29 0.17
// (models/feather-parameters, every barb of angles.l) is written as 0.147 0.0685 0.0242, not
// as the display values.
TEST_F(HairExportTest, FeatherBarbColoursAreWrittenInLinearLight) {
  const std::string base = std::string(HIRSUTE_SOURCE_DIR) + "/models/feather-parameters/";
  ASSERT_EQ(runHirsute("export '" + base + "angles.l' '" + base + "angles.v' --pov '" +
                           file("angles.pov").string() + "' --size 160x120",
                       file("log")),
            0)
      << readText(file("log"));
  const std::string text = readText(file("angles.pov"));
  const std::size_t feathers = text.find("// feather barbs");
  ASSERT_NE(feathers, std::string::npos);
  auto linear = [](double display) {
    const double level = std::round(display * 255) / 255;  // the shades' quantization
    return level <= 0.04045 ? level / 12.92 : std::pow((level + 0.055) / 1.055, 2.4);
  };
  const glm::dvec3 expected(linear(0.42), linear(0.29), linear(0.17));
  int barbs = 0, display = 0;
  for (const glm::dvec3& c : rgbtColours(text, feathers)) {
    if (glm::length(c - expected) < 2e-4) ++barbs;
    if (glm::length(c - glm::dvec3(0.42, 0.29, 0.17)) < 3e-3) ++display;
  }
  EXPECT_GT(barbs, 0) << "no barb of the type's colour in linear light";
  EXPECT_EQ(display, 0) << "barbs written in display values";
}

// A template hair's closed outline between { and } is filled (tests/fixtures/hairs/filled.l, a
// square on a stalk): the OBJ export gives every hair its outline's polyline and the square's
// faces, three triangles a hair.
TEST_F(HairExportTest, AFilledTemplateGivesEachHairItsFaces) {
  const std::string fixtures = std::string(HIRSUTE_SOURCE_DIR) + "/tests/fixtures/hairs/";
  ASSERT_EQ(runHirsute("export '" + fixtures + "filled_hairs.l' '" + fixtures +
                           "filled_template.v' --obj '" + file("hairs.obj").string() + "'",
                       file("log")),
            0)
      << readText(file("log"));
  std::istringstream lines(readText(file("hairs.obj")));
  bool hairs = false;
  std::size_t faces = 0;
  std::string hairLines;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("o ", 0) == 0) hairs = line == "o hairs";
    if (!hairs) continue;
    if (line.rfind("f ", 0) == 0) ++faces;
    if (line.rfind("l ", 0) == 0) hairLines += line + "\n";
  }
  const std::size_t polylines = testing::objPolylines(hairLines).size();
  EXPECT_GT(polylines, 100u);
  EXPECT_EQ(faces, 3 * polylines);
}

// The OBJ export's barbs take a material of their type's colour and texture: the hawk's and the
// budgie's vanes (models/feather-types) a map_Kd of their image, written beside the OBJ, and
// their faces and polylines texture coordinates that exist; untextured types a plain Kd.
TEST_F(HairExportTest, FeatherTexturesAndColoursReachTheObj) {
  const std::string base = std::string(HIRSUTE_SOURCE_DIR) + "/models/feather-types/feather-types";
  const fs::path obj = file("types.obj");
  ASSERT_EQ(runHirsute("export '" + base + ".l' '" + base + ".v' --obj '" + obj.string() + "'",
                       file("log")),
            0)
      << readText(file("log"));
  const std::vector<std::string> library = linesOf(readText(file("types.mtl")));
  std::size_t textured = 0, plain = 0;
  for (std::size_t k = 0; k < library.size(); ++k) {
    if (library[k].rfind("newmtl feather_", 0) != 0) continue;
    ASSERT_LT(k + 1, library.size());
    EXPECT_EQ(library[k + 1].rfind("Kd ", 0), 0u) << library[k + 1];
    if (library[k].find("_T") != std::string::npos) {
      ++textured;
      ASSERT_LT(k + 3, library.size());
      ASSERT_EQ(library[k + 3].rfind("map_Kd ", 0), 0u) << library[k + 3];
      EXPECT_TRUE(fs::exists(file(library[k + 3].substr(7)))) << library[k + 3];
    } else {
      ++plain;
    }
  }
  EXPECT_EQ(textured, 2u);  // the hawk and the budgie
  EXPECT_GT(plain, 0u);
  // Texture coordinates: every one referred to exists, and textured barbs refer to them.
  std::uint64_t texcoords = 0, referred = 0, largest = 0;
  bool inTextured = false;
  for (const std::string& line : linesOf(readText(obj))) {
    if (line.rfind("vt ", 0) == 0) ++texcoords;
    if (line.rfind("usemtl ", 0) == 0) inTextured = line.find("_T") != std::string::npos;
    if (!inTextured || (line.rfind("f ", 0) != 0 && line.rfind("l ", 0) != 0)) continue;
    std::istringstream words(line.substr(2));
    for (std::string word; words >> word;) {
      const std::size_t slash = word.find('/');
      ASSERT_NE(slash, std::string::npos) << line;
      largest = std::max<std::uint64_t>(largest, std::stoull(word.substr(slash + 1)));
      ++referred;
    }
  }
  EXPECT_GT(referred, 1000u);
  EXPECT_GT(texcoords, 0u);
  EXPECT_LE(largest, texcoords);
}

// The OBJ export writes a cross-fade as vertex colours (`v x y z r g b`) under a white material:
// the blended feathers of hawk-to-budgie.l have them, each colour in [0, 1], and the two ends'
// pure types keep their textured materials.
TEST_F(HairExportTest, CrossFadedFeathersGiveTheObjVertexColours) {
  const std::string folder = std::string(HIRSUTE_SOURCE_DIR) + "/models/feather-types/";
  const fs::path obj = file("row.obj");
  ASSERT_EQ(runHirsute("export '" + folder + "hawk-to-budgie.l' '" + folder +
                           "feather-types.v' --obj '" + obj.string() + "'",
                       file("log")),
            0)
      << readText(file("log"));
  std::size_t coloured = 0, plain = 0;
  std::set<std::string> materials;
  for (const std::string& line : linesOf(readText(obj))) {
    if (line.rfind("usemtl ", 0) == 0) materials.insert(line.substr(7));
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    std::vector<double> numbers;
    for (double x; words >> x;) numbers.push_back(x);
    if (numbers.size() == 3) {
      ++plain;
      continue;
    }
    ASSERT_EQ(numbers.size(), 6u) << line;
    for (std::size_t k = 3; k < 6; ++k) {
      EXPECT_GE(numbers[k], 0.0);
      EXPECT_LE(numbers[k], 1.0);
    }
    ++coloured;
  }
  EXPECT_GT(coloured, 1000u);
  EXPECT_GT(plain, 0u);  // shafts and the two unblended ends
  EXPECT_TRUE(materials.count("feather_ffffff")) << "the cross-fades' white material";
  EXPECT_EQ(std::count_if(materials.begin(), materials.end(),
                          [](const std::string& m) { return m.find("_T") != std::string::npos; }),
            2);
}

// A blended type cross-fades its key types' textures with its shape: along the row of
// models/feather-types/hawk-to-budgie.l (@Fi from the barred hawk feather to the green budgie
// feather in eight steps) the barbs' mean colour moves by even steps (each about a seventh of
// the way from the hawk to the budgie, none a quarter); a blend taking the nearer type's texture
// jumps by 0.58 of it at t = 0.5.
TEST(FeatherTextures, BlendedTexturesCrossFadeAlongARow) {
  const fs::path folder = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "feather-types";
  Diagnostics diagnostics;
  const ModelResources resources = loadModelResources(folder / "feather-types.v", {}, diagnostics);
  const Model model =
      loadModel(folder / "hawk-to-budgie.l", folder / "feather-types.v", diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  Derivation derivation(model.program, evaluator, diagnostics);
  derivation.run();
  Scene scene;
  interpret(derivation, resources, scene, diagnostics);
  FeatherStageOptions options;
  options.lsystemFile = (folder / "hawk-to-budgie.l").string();
  growFeathers(scene, resources, model.functions, options, diagnostics);
  const std::size_t count = scene.organ<FeatherPart>().feathers.size();
  ASSERT_EQ(count, 9u);
  ASSERT_EQ(scene.textures.size(), 2u);

  const FeatherBuffers buffers = buildFeatherBuffers(scene, std::vector<std::uint8_t>(count, 5));
  const std::vector<glm::vec4> colours = texturedBarbColours(scene, buffers);
  ASSERT_EQ(buffers.parts.size(), count);  // neither type has an afterfeather
  std::vector<glm::vec3> means;
  for (const FeatherBuffers::Part& part : buffers.parts) {
    std::set<std::uint32_t> vertices;
    for (const FeatherBuffers::Vane& vane : part.vanes) {
      for (std::uint32_t k = 0; k < vane.count; ++k)
        vertices.insert(buffers.vaneIndices[vane.first + k]);
    }
    glm::vec3 sum(0.0f);
    float weight = 0;
    for (std::uint32_t v : vertices) {
      sum += glm::vec3(colours[v]) * colours[v].a;  // as drawn: faded towards the tips
      weight += colours[v].a;
    }
    ASSERT_GT(weight, 0);
    means.push_back(sum / weight);
  }
  const float whole = glm::length(means.back() - means.front());
  EXPECT_GT(whole, 0.15f);  // the hawk's brown and the budgie's green differ
  float largest = 0;
  for (std::size_t i = 0; i + 1 < means.size(); ++i) {
    largest = std::max(largest, glm::length(means[i + 1] - means[i]));
  }
  EXPECT_LT(largest, whole / 4) << "largest step " << largest << " of " << whole;
}

}  // namespace
}  // namespace hirsute
