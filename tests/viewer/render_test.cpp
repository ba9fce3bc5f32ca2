// Render smoke tests: hand-built scenes through the headless path (OSMesa), checked pixel by
// pixel against where cpfg's camera puts them.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/gtc/constants.hpp>
#include <string>

#include "hirsute/viewer/view/camera.h"
#include "hirsute/viewer/gl/gl_renderer.h"
#include "hirsute/viewer/gl/offscreen.h"

namespace hirsute {
namespace {

const glm::vec3 kBackground{0.2f, 0.4f, 0.6f};
const glm::u8vec4 kBackgroundPixel{51, 102, 153, 255};
constexpr int kRed = 1, kGreen = 2, kBlue = 3, kGrey = 4;

// A colour-map palette: the background, red, green, blue, mid grey.
Scene paletteScene() {
  Scene scene;
  for (glm::vec3 c :
       {kBackground, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(0.5f)}) {
    Material m;
    m.ambient = m.diffuse = c;
    scene.materials.push_back(m);
  }
  return scene;
}

// A flat polygon (a fan from its first corner) with its face normal.
void addPolygon(Scene& scene, int material, std::initializer_list<glm::vec3> corners,
                bool twoSided = true) {
  TriangleMesh& mesh = scene.meshFor(material);
  mesh.twoSided = twoSided;
  std::vector<glm::vec3> p(corners);
  glm::vec3 normal = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (const glm::vec3& q : p) {
    mesh.positions.push_back(q);
    mesh.normals.push_back(normal);
  }
  for (std::uint32_t i = 1; i + 1 < p.size(); ++i) {
    mesh.indices.insert(mesh.indices.end(), {first, first + i, first + i + 1});
  }
}

RgbaImage render(const Scene& scene, const ViewSettings& view, int width, int height,
                 int samples = 1, bool materialMode = false) {
  return renderOffscreen(scene, view, materialMode, {width, height, samples});
}

// Lit as a material file is: GL lighting from the view's lights.
RgbaImage renderMaterials(const Scene& scene, const ViewSettings& view) {
  return renderOffscreen(scene, view, true, {20, 20, 1});
}

bool same(glm::u8vec4 a, glm::u8vec4 b, int tolerance = 1) {
  for (int i = 0; i < 3; ++i) {
    if (std::abs(int(a[i]) - int(b[i])) > tolerance) return false;
  }
  return true;
}

// Shows pixels as r,g,b in failure messages.
std::string text(glm::u8vec4 p) {
  return std::to_string(p.r) + "," + std::to_string(p.g) + "," + std::to_string(p.b);
}

int countPixels(const RgbaImage& image, const std::function<bool(glm::u8vec4)>& test) {
  int n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) n += test(image.pixel(x, y)) ? 1 : 0;
  }
  return n;
}

int countColor(const RgbaImage& image, glm::u8vec4 color) {
  return countPixels(image, [&](glm::u8vec4 p) { return same(p, color); });
}

// The extent in pixels of a colour along one row or column.
int runLength(const RgbaImage& image, glm::u8vec4 color, bool row, int index) {
  int n = 0;
  int length = row ? image.width : image.height;
  for (int i = 0; i < length; ++i) {
    n += same(row ? image.pixel(i, index) : image.pixel(index, i), color) ? 1 : 0;
  }
  return n;
}

const glm::u8vec4 kRedPixel{255, 0, 0, 255}, kGreenPixel{0, 255, 0, 255},
    kBluePixel{0, 0, 255, 255};

TEST(OffscreenTest, ContextIsCoreProfile33OrLater) {
  OsMesaContext context;
  GLint major = 0, minor = 0, profile = 0;
  context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
  context.gl().GetIntegerv(GL_MINOR_VERSION, &minor);
  context.gl().GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 33) << context.description();
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT) << context.description();
}

TEST(RenderTest, ImageHasTheRequestedSize) {
  Scene scene = paletteScene();
  RgbaImage image = render(scene, ViewSettings{}, 123, 45);
  EXPECT_EQ(image.width, 123);
  EXPECT_EQ(image.height, 45);
  EXPECT_EQ(image.rgba.size(), 123u * 45u * 4u);
}

TEST(RenderTest, BackgroundIsPaletteEntryZero) {
  Scene scene = paletteScene();
  RgbaImage image = render(scene, ViewSettings{}, 40, 30);
  EXPECT_EQ(countColor(image, kBackgroundPixel), 40 * 30);
  // From a material file cpfg takes the emission of material 0.
  scene.materials[0].emission = {1, 0.5f, 0};
  image = render(scene, ViewSettings{}, 40, 30, 1, true);
  EXPECT_EQ(countColor(image, {255, 128, 0, 255}), 40 * 30);
}

TEST(RenderTest, RedTriangleLiesWhereTheCameraPutsIt) {
  Scene scene = paletteScene();
  glm::vec3 a(0, 0, 0), b(2, 0, 0), c(1, 2, 0);
  addPolygon(scene, kRed, {a, b, c});
  ViewSettings view;
  RgbaImage image = render(scene, view, 200, 100);
  Camera camera = fitCamera(view, scene.bounds(), {200, 100});
  glm::vec2 pa(camera.toPixels(a)), pb(camera.toPixels(b)), pc(camera.toPixels(c));
  // The fit: the triangle fills the image's height, centred; its apex is at the top.
  EXPECT_NEAR(pc.y, 0, 1e-3);
  EXPECT_NEAR(pa.y, 100, 1e-3);
  EXPECT_NEAR((pa.x + pb.x) / 2, 100, 1e-3);

  auto inside = [&](glm::vec2 p, float margin) {
    auto edge = [&](glm::vec2 u, glm::vec2 v) {
      glm::vec2 d = glm::normalize(v - u);
      return (p.x - u.x) * d.y - (p.y - u.y) * d.x;  // distance inside the edge, in pixels
    };
    return edge(pa, pb) > -margin && edge(pb, pc) > -margin && edge(pc, pa) > -margin;
  };
  int red = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      glm::vec2 centre(x + 0.5f, y + 0.5f);
      if (same(image.pixel(x, y), kRedPixel)) {
        ++red;
        EXPECT_TRUE(inside(centre, 1.0f)) << "red pixel outside the triangle at " << x << "," << y;
      } else {
        EXPECT_TRUE(same(image.pixel(x, y), kBackgroundPixel));
        EXPECT_FALSE(inside(centre, -1.0f)) << "no red inside the triangle at " << x << "," << y;
      }
    }
  }
  EXPECT_NEAR(red, 100 * 100 / 2, 100);
}

TEST(RenderTest, PixelLineIsItsWidthInPixels) {
  Scene scene = paletteScene();
  scene.lines.push_back({{0, 0, 0}, {10, 0, 0}, 3, 3, kGreen});
  RgbaImage image = render(scene, ViewSettings{}, 200, 101);
  // The line runs across the image through its middle row, three pixels thick, in its colour.
  EXPECT_EQ(runLength(image, kGreenPixel, false, 100), 3);
  EXPECT_TRUE(same(image.pixel(100, 50), kGreenPixel));
  EXPECT_TRUE(same(image.pixel(100, 49), kGreenPixel));
  EXPECT_TRUE(same(image.pixel(100, 51), kGreenPixel));
  EXPECT_NEAR(runLength(image, kGreenPixel, true, 50), 200, 1);
  // Twice the image, the same width in pixels.
  image = render(scene, ViewSettings{}, 400, 201);
  EXPECT_EQ(runLength(image, kGreenPixel, false, 200), 3);
}

TEST(RenderTest, ThinPixelLinesAreOnePixelAsCpfgDrawsThem) {
  Scene scene = paletteScene();
  // Widths of a pixel or less are GL lines of one pixel (glLineWidth below 1 draws 1).
  scene.lines.push_back({{0, 0, 0}, {10, 0, 0}, 1, 1, kGreen});
  scene.lines.push_back({{0, 1, 0}, {10, 1, 0}, 0.25f, 0.25f, kBlue});
  scene.lines.push_back({{0, -1, 0}, {10, -1, 0}, 5, 5, kRed});  // a wide one among them
  ViewSettings view;
  view.scaleFactor = 0.5f;
  RgbaImage image = render(scene, view, 201, 101);
  EXPECT_EQ(runLength(image, kGreenPixel, false, 100), 1);
  EXPECT_EQ(runLength(image, kBluePixel, false, 100), 1);
  EXPECT_EQ(runLength(image, kRedPixel, false, 100), 5);
  EXPECT_NEAR(runLength(image, kGreenPixel, true, 50), 100, 1);
}

TEST(RenderTest, TaperedPixelLineNarrowsTowardsItsEnd) {
  Scene scene = paletteScene();
  scene.lines.push_back({{0, 0, 0}, {10, 0, 0}, 9, 1, kGreen});
  RgbaImage image = render(scene, ViewSettings{}, 200, 101);
  int nearStart = runLength(image, kGreenPixel, false, 10);
  int nearEnd = runLength(image, kGreenPixel, false, 190);
  EXPECT_NEAR(nearStart, 9 - 8 * 10.5 / 200, 1);
  EXPECT_LE(nearEnd, 2);
}

TEST(RenderTest, PolygonLineIsARibbonInWorldUnits) {
  Scene scene = paletteScene();
  scene.lineStyle = LineStyle::Polygon;
  scene.lines.push_back({{0, 0, 0}, {10, 0, 0}, 1, 1, kBlue});
  // The fit spans 10 units over 200 pixels: the ribbon is 20 pixels wide.
  RgbaImage image = render(scene, ViewSettings{}, 200, 101);
  EXPECT_NEAR(runLength(image, kBluePixel, false, 100), 20, 1);
  image = render(scene, ViewSettings{}, 400, 201);
  EXPECT_NEAR(runLength(image, kBluePixel, false, 200), 40, 1);
}

TEST(RenderTest, SphereHasARoundSilhouette) {
  Scene scene = paletteScene();
  scene.spheres.push_back({{0, 0, 0}, 1, kRed});
  ViewSettings view;
  view.contourSides = 64;
  RgbaImage image = render(scene, view, 201, 201);
  float radius = 100.5f;  // the sphere's bounds fill the image
  EXPECT_NEAR(countColor(image, kRedPixel), glm::pi<float>() * radius * radius, 0.02 * 31730);
  EXPECT_TRUE(same(image.pixel(100, 100), kRedPixel));
  for (float angle = 0; angle < 6.28f; angle += 0.3f) {
    glm::vec2 dir(std::cos(angle), std::sin(angle));
    glm::ivec2 in(glm::vec2(100.5f) + dir * radius * 0.95f);
    glm::ivec2 out(glm::vec2(100.5f) + dir * radius * 1.05f);
    EXPECT_TRUE(same(image.pixel(in.x, in.y), kRedPixel)) << angle;
    if (out.x >= 0 && out.x < 201 && out.y >= 0 && out.y < 201) {
      EXPECT_TRUE(same(image.pixel(out.x, out.y), kBackgroundPixel)) << angle;
    }
  }
}

TEST(RenderTest, SphereSidesFollowContourSides) {
  EXPECT_EQ(sphereSides(8), 8);
  EXPECT_EQ(sphereSides(9), 16);
  EXPECT_EQ(sphereSides(3), 4);
  // Coarse spheres have polygonal silhouettes: a square seen along the axis of a 4-sided one
  // covers less than the circle.
  Scene scene = paletteScene();
  scene.spheres.push_back({{0, 0, 0}, 1, kRed});
  ViewSettings view;
  view.contourSides = 4;
  RgbaImage coarse = render(scene, view, 101, 101);
  view.contourSides = 64;
  RgbaImage fine = render(scene, view, 101, 101);
  EXPECT_LT(countColor(coarse, kRedPixel), 0.8 * countColor(fine, kRedPixel));
}

TEST(RenderTest, ParallelKeepsSizesAndPerspectiveShrinksTheFar) {
  Scene scene = paletteScene();
  addPolygon(scene, kRed, {{-3, -0.5f, 0}, {-2, -0.5f, 0}, {-2, 0.5f, 0}, {-3, 0.5f, 0}});
  addPolygon(scene, kBlue, {{2, -0.5f, -5}, {3, -0.5f, -5}, {3, 0.5f, -5}, {2, 0.5f, -5}});
  ViewSettings view;
  view.viewpoint = {0, 0, 10};
  RgbaImage parallel = render(scene, view, 400, 300);
  int red = runLength(parallel, kRedPixel, true, 150);
  int blue = runLength(parallel, kBluePixel, true, 150);
  EXPECT_GT(red, 20);
  EXPECT_NEAR(red, blue, 1);

  view.projection = Projection::Perspective;
  RgbaImage perspective = render(scene, view, 400, 300);
  red = runLength(perspective, kRedPixel, true, 150);
  blue = runLength(perspective, kBluePixel, true, 150);
  // Eye at 10: the red square is 10 away, the blue 15. Half height at 10 is 10·tan 22.5°.
  EXPECT_NEAR(red, 300 / (2 * 10 * std::tan(glm::radians(22.5f))), 1.5);
  EXPECT_NEAR(static_cast<float>(blue) / static_cast<float>(red), 10.0f / 15.0f, 0.04);
}

TEST(RenderTest, ShadedModeLightsFromTheViewsLights) {
  Scene scene = paletteScene();
  scene.materials[kGrey].ambient = glm::vec3(0);
  // One square facing the viewer, one (one-sided) facing away, one two-sided facing away.
  addPolygon(scene, kGrey, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  Scene away = paletteScene();
  away.materials[kGrey].ambient = glm::vec3(0);
  addPolygon(away, kGrey, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, false);
  Scene awayTwoSided = paletteScene();
  awayTwoSided.materials[kGrey].ambient = glm::vec3(0);
  addPolygon(awayTwoSided, kGrey, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, true);

  ViewSettings view;
  view.renderMode = RenderMode::Shaded;
  LightSource light;
  light.vector = {0, 0, 1};
  light.diffuse = glm::vec3(1);
  view.lights.push_back(light);
  EXPECT_TRUE(same(renderMaterials(scene, view).pixel(10, 10), {128, 128, 128, 255}));
  EXPECT_TRUE(same(renderMaterials(away, view).pixel(10, 10), {0, 0, 0, 255}));
  EXPECT_TRUE(same(renderMaterials(awayTwoSided, view).pixel(10, 10), {128, 128, 128, 255}));

  // A light at 60° from the normal gives half the diffuse light.
  view.lights[0].vector = {0, std::sin(glm::radians(60.0f)), 0.5f};
  EXPECT_TRUE(same(renderMaterials(scene, view).pixel(10, 10), {64, 64, 64, 255}));
}

TEST(RenderTest, DefaultMaterialLightShinesFromTheEye) {
  // OpenGL's light 0: no ambient, white diffuse and specular, along the line of sight.
  Scene front = paletteScene();
  front.materials[kGrey].ambient = glm::vec3(0.1f);
  addPolygon(front, kGrey, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  Scene side = paletteScene();
  side.materials[kGrey].ambient = glm::vec3(0.1f);
  addPolygon(side, kGrey, {{0, 0, 0}, {0, 1, 0}, {0, 1, -1}, {0, 0, -1}});  // facing +x
  ViewSettings view;
  view.renderMode = RenderMode::Shaded;
  // 0.2 · 0.1 global ambient + 0.5 diffuse
  glm::u8vec4 p = renderMaterials(front, view).pixel(10, 10);
  EXPECT_TRUE(same(p, {133, 133, 133, 255})) << text(p);
  view.viewpoint = {1, 0, 0};
  p = renderMaterials(side, view).pixel(10, 10);
  EXPECT_TRUE(same(p, {133, 133, 133, 255})) << text(p);
}

TEST(RenderTest, ColorMapShadingMovesAlongThePalette) {
  Scene scene = paletteScene();
  scene.materials.resize(512);
  for (int i = 0; i < 512; ++i) {
    scene.materials[static_cast<std::size_t>(i)].diffuse =
        glm::vec3(static_cast<float>(i % 256) / 255);
  }
  addPolygon(scene, 110, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  ViewSettings view;
  view.renderMode = RenderMode::Shaded;
  auto shade = [&](const Scene& s) { return render(s, view, 20, 20).pixel(10, 10); };
  // cpfg-manual §8.1.3: col + i·N·L with i = `diffuse reflection:` (10).
  view.lightDirection = {0, 0, 1};
  EXPECT_TRUE(same(shade(scene), {120, 120, 120, 255})) << text(shade(scene));
  view.lightDirection = {1, 0, 0};
  EXPECT_TRUE(same(shade(scene), {110, 110, 110, 255})) << text(shade(scene));
  view.lightDirection = {0, 0, -3};
  EXPECT_TRUE(same(shade(scene), {100, 100, 100, 255})) << text(shade(scene));
  view.lightDirection = {0, 0, 1};
  view.diffuseReflection = 5;
  EXPECT_TRUE(same(shade(scene), {115, 115, 115, 255})) << text(shade(scene));
  // The shade stays within the colour's bank of 256.
  view.diffuseReflection = 10;
  scene.meshes[0].material = 256 + 250;
  EXPECT_TRUE(same(shade(scene), {255, 255, 255, 255})) << text(shade(scene));
  // `filled` draws the colour itself.
  view.renderMode = RenderMode::Filled;
  EXPECT_TRUE(same(shade(scene), {250, 250, 250, 255})) << text(shade(scene));
}

TEST(RenderTest, MaterialSpecularAndEmissionAddUp) {
  Scene scene = paletteScene();
  Material& m = scene.materials[kGrey];
  m.ambient = glm::vec3(0);
  m.diffuse = glm::vec3(0.25f);
  m.specular = glm::vec3(0.5f);
  m.shininess = 10;
  m.emission = {0.1f, 0, 0};
  addPolygon(scene, kGrey, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  ViewSettings view;
  view.renderMode = RenderMode::Shaded;
  LightSource light;
  light.vector = {0, 0, 1};  // along the normal: the half vector too, so specular is full
  view.lights.push_back(light);
  light.ambient = glm::vec3(0);
  view.lights.back() = light;
  glm::u8vec4 p = renderMaterials(scene, view).pixel(10, 10);
  EXPECT_TRUE(same(p, {217, 191, 191, 255})) << text(p);
}

TEST(RenderTest, FlatModeUsesOneNormalPerPolygon) {
  Scene scene = paletteScene();
  scene.materials[kGrey].ambient = glm::vec3(0);
  addPolygon(scene, kGrey, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  // Vertex normals tilted away from the light: smooth shading follows them, flat ignores them.
  for (glm::vec3& n : scene.meshes[0].normals) n = glm::normalize(glm::vec3(0, 1, 1));
  ViewSettings view;
  LightSource light;
  light.vector = {0, 0, 1};
  view.lights.push_back(light);
  view.renderMode = RenderMode::Shaded;
  EXPECT_TRUE(same(renderMaterials(scene, view).pixel(10, 10), {90, 90, 90, 255}, 2));
  view.renderMode = RenderMode::Flat;
  EXPECT_TRUE(same(renderMaterials(scene, view).pixel(10, 10), {128, 128, 128, 255}));
}

TEST(RenderTest, FilledModeDrawsTheDiffuseColourUnlit) {
  Scene scene = paletteScene();
  scene.materials[kGrey].diffuse = {0.2f, 0.6f, 1.0f};
  addPolygon(scene, kGrey, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  ViewSettings view;  // render mode: filled is cpfg's default
  LightSource light;
  light.vector = {0, 0, -1};
  view.lights.push_back(light);
  EXPECT_TRUE(same(render(scene, view, 20, 20).pixel(10, 10), {51, 153, 255, 255}));
}

TEST(RenderTest, ZBufferHidesTheFartherSurface) {
  Scene scene = paletteScene();
  // The nearer blue square is drawn first.
  addPolygon(scene, kBlue, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  addPolygon(scene, kRed, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  ViewSettings view;
  EXPECT_TRUE(same(render(scene, view, 20, 20).pixel(10, 10), kBluePixel));
  view.zBuffer = false;  // cpfg: the last object drawn is visible
  EXPECT_TRUE(same(render(scene, view, 20, 20).pixel(10, 10), kRedPixel));
}

TEST(RenderTest, MultisamplingSmoothsEdges) {
  Scene scene = paletteScene();
  addPolygon(scene, kRed, {{0, 0, 0}, {2, 0, 0}, {1, 2, 0}});
  auto mixed = [](const RgbaImage& image) {
    return countPixels(
        image, [](glm::u8vec4 p) { return !same(p, kRedPixel) && !same(p, kBackgroundPixel); });
  };
  EXPECT_EQ(mixed(render(scene, ViewSettings{}, 200, 100, 1)), 0);
  EXPECT_GT(mixed(render(scene, ViewSettings{}, 200, 100, 4)), 100);
}

TEST(RenderTest, WireframeModeDrawsOnlyEdges) {
  Scene scene = paletteScene();
  addPolygon(scene, kRed, {{0, 0, 0}, {2, 0, 0}, {1, 2, 0}});
  ViewSettings view;
  view.renderMode = RenderMode::Wireframe;
  view.scaleFactor = 0.9f;  // keeps the base off the image's edge
  RgbaImage image = render(scene, view, 200, 100);
  EXPECT_TRUE(same(image.pixel(100, 65), kBackgroundPixel));
  EXPECT_GT(countColor(image, kRedPixel), 200);
  EXPECT_LT(countColor(image, kRedPixel), 600);
}

TEST(RenderTest, ScreenAlignedDiscFacesTheViewer) {
  Scene scene = paletteScene();
  scene.discs.push_back({{0, 0, 0}, {0, 0, 0}, 1, kGreen});
  ViewSettings view;
  view.viewpoint = {3, 2, 1};
  view.contourSides = 64;
  RgbaImage image = render(scene, view, 201, 201);
  int across = runLength(image, kGreenPixel, true, 100);
  int down = runLength(image, kGreenPixel, false, 100);
  EXPECT_GT(across, 50);
  EXPECT_NEAR(across, down, 2);
}

TEST(RenderTest, OrientedDiscIsForeshortened) {
  Scene scene = paletteScene();
  scene.discs.push_back({{0, 0, 0}, {0, 0, 1}, 1, kGreen});
  ViewSettings view;
  view.viewpoint = {1, 0, 1};  // 45° about y: the disc's width shrinks by cos 45°
  view.contourSides = 64;
  RgbaImage image = render(scene, view, 301, 301);
  int across = runLength(image, kGreenPixel, true, 150);
  int down = runLength(image, kGreenPixel, false, 150);
  EXPECT_NEAR(static_cast<float>(across) / static_cast<float>(down), std::cos(glm::radians(45.0f)),
              0.03);
}

TEST(RenderTest, TransparentMaterialBlendsWithWhatIsBehind) {
  Scene scene = paletteScene();
  scene.materials[kRed].transparency = 0.5f;
  addPolygon(scene, kRed, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}});
  addPolygon(scene, kBlue, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  glm::u8vec4 p = render(scene, ViewSettings{}, 20, 20).pixel(10, 10);
  EXPECT_TRUE(same(p, {128, 0, 128, 255}, 2)) << int(p.r) << " " << int(p.g) << " " << int(p.b);
}

TEST(RenderTest, TextureModulatesTheColourRightSideUp) {
  Scene scene = paletteScene();
  Texture texture;
  texture.width = texture.height = 2;
  // Rows top first: red green / blue white.
  texture.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  scene.textures.push_back(texture);
  scene.materials[kGrey].diffuse = glm::vec3(1);
  TriangleMesh& mesh = scene.meshFor(kGrey, 0);
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals.assign(4, {0, 0, 1});
  mesh.texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  RgbaImage image = render(scene, ViewSettings{}, 40, 40);
  // Pixels near the texel centres (linear filtering blends a little of the neighbours).
  EXPECT_TRUE(same(image.pixel(10, 10), kRedPixel, 16)) << text(image.pixel(10, 10));
  EXPECT_TRUE(same(image.pixel(30, 10), kGreenPixel, 16)) << text(image.pixel(30, 10));
  EXPECT_TRUE(same(image.pixel(10, 30), kBluePixel, 16)) << text(image.pixel(10, 30));
  EXPECT_TRUE(same(image.pixel(30, 30), {255, 255, 255, 255}, 16)) << text(image.pixel(30, 30));
}

TEST(RenderTest, MaterialIndexOutsideThePaletteDrawsTheLastEntry) {
  Scene scene = paletteScene();
  addPolygon(scene, 300, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  EXPECT_TRUE(same(render(scene, ViewSettings{}, 20, 20).pixel(10, 10), {128, 128, 128, 255}));
}

TEST(RenderTest, RendererCountsWhatItUploads) {
  OsMesaContext context;
  GlRenderer renderer(context.gl());
  Scene scene = paletteScene();
  addPolygon(scene, kRed, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  scene.lines.push_back({{0, 0, 0}, {1, 1, 1}, 1, 1, kGreen});
  scene.spheres.push_back({{0, 0, 0}, 1, kRed});
  ViewSettings view;
  view.contourSides = 8;  // an 8 × 4 sphere: 8 + 8 pole triangles and 2 × 8 × 2 between
  renderer.upload(scene, view, false);
  EXPECT_EQ(renderer.triangleCount(), 2u + 48u);
  EXPECT_EQ(renderer.lineCount(), 1u);
  // Uploading again replaces the scene.
  renderer.upload(paletteScene(), view, false);
  EXPECT_EQ(renderer.triangleCount(), 0u);
  EXPECT_EQ(renderer.lineCount(), 0u);
}

TEST(RenderTest, OversizedImageIsRefused) {
  EXPECT_THROW(render(paletteScene(), ViewSettings{}, 100000, 10), std::runtime_error);
}

// cpfg's @L: screen-aligned text of a fixed pixel size whose top left corner is the label's
// projected position, in the label's colour, over the model.
TEST(RenderTest, LabelIsDrawnAtItsProjectedPosition) {
  Scene scene = paletteScene();
  addPolygon(scene, kBlue,
             {glm::vec3(0, 0, 0), glm::vec3(4, 0, 0), glm::vec3(4, 4, 0), glm::vec3(0, 4, 0)});
  scene.labels.push_back(Label{glm::vec3(1, 3, 0), "Hi 42", kGreen});
  ViewSettings view;
  RgbaImage image = render(scene, view, 200, 200);
  Camera camera = fitCamera(view, scene.bounds(), {200, 200});
  glm::vec2 anchor(camera.toPixels(glm::vec3(1, 3, 0)));
  int near = 0, far = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!same(image.pixel(x, y), kGreenPixel)) continue;
      // Five characters of stb_easy_font, about 6 by 7 pixels each at twice their size.
      bool inside = x >= anchor.x - 1 && x <= anchor.x + 5 * 6 * 2 + 1 && y >= anchor.y - 1 &&
                    y <= anchor.y + 12 * 2 + 1;
      ++(inside ? near : far);
    }
  }
  EXPECT_GT(near, 40);
  EXPECT_EQ(far, 0);
  // The text is drawn over the polygon, which still shows around it.
  EXPECT_GT(countColor(image, kBluePixel), 1000);
}

}  // namespace
}  // namespace hirsute
