// Organs' parts of the Scene (organ_part.h): one of each type, made on first use, copied with
// the Scene, emptied in place, and counted in its bounds; and organs' settings of the view file
// (organ_settings.h), reached the same way; and the turtle's index into each organ's records.
#include "hirsute/interpreter/organ_part.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/hairs/fur/fur_part.h"
#include "hirsute/hairs/fur/fur_settings.h"
#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {
namespace {

// A part of a test organ: a list of points it draws.
struct PointsPart : OrganPartOf<PointsPart> {
  std::vector<glm::vec3> points;
  void addBounds(Bounds& box) const override {
    for (const glm::vec3& p : points) box.add(p);
  }
};

TEST(OrganParts, APartIsMadeOnFirstUseAndReachedByItsType) {
  Scene scene;
  const Scene& reading = scene;
  // Reading a part the scene does not have makes none: it reads as empty.
  EXPECT_TRUE(reading.organ<PointsPart>().points.empty());
  EXPECT_TRUE(reading.bounds().empty());
  scene.organ<PointsPart>().points.push_back({1, 2, 3});
  scene.organ<FurPart>().attributes.emplace_back();
  EXPECT_EQ(&scene.organ<PointsPart>(), &reading.organ<PointsPart>());
  ASSERT_EQ(reading.organ<PointsPart>().points.size(), 1u);
  EXPECT_EQ(reading.organ<FurPart>().attributes.size(), 1u);
  EXPECT_EQ(reading.bounds().max, glm::vec3(1, 2, 3));
}

TEST(OrganParts, CopiesAreDeepAndClearingKeepsThePart) {
  Scene scene;
  scene.organ<PointsPart>().points.push_back({1, 0, 0});
  Scene copy = scene;
  copy.organ<PointsPart>().points.push_back({2, 0, 0});
  EXPECT_EQ(scene.organ<PointsPart>().points.size(), 1u);
  EXPECT_EQ(copy.organ<PointsPart>().points.size(), 2u);
  copy = scene;
  EXPECT_EQ(copy.organ<PointsPart>().points.size(), 1u);

  PointsPart* before = &scene.organ<PointsPart>();
  scene.clear();
  EXPECT_EQ(&scene.organ<PointsPart>(), before);
  EXPECT_TRUE(scene.organ<PointsPart>().points.empty());
  EXPECT_TRUE(scene.bounds().empty());
}

TEST(OrganParts, FurBoundsReachTheFurLength) {
  Scene scene;
  FurPart& fur = scene.organ<FurPart>();
  fur.attributes.emplace_back().length = 0.5f;
  FurSurface surface;
  surface.attributes = 0;
  surface.positions = {glm::vec3(0), glm::vec3(1, 0, 0)};
  fur.surfaces.push_back(surface);
  const Bounds b = scene.bounds();
  EXPECT_EQ(b.min, glm::vec3(-0.5f));
  EXPECT_EQ(b.max, glm::vec3(1.5f, 0.5f, 0.5f));
}

TEST(OrganParts, FeatherBoundsAreTheBoxTheStageMeasured) {
  Scene scene;
  scene.organ<FeatherPart>().bounds.add(glm::vec3(-1, 0, 2));
  scene.organ<FeatherPart>().bounds.add(glm::vec3(3, 1, 2));
  scene.lines.push_back({glm::vec3(0), glm::vec3(0, 4, 0)});
  const Bounds b = scene.bounds();
  EXPECT_EQ(b.min, glm::vec3(-1, 0, 0));
  EXPECT_EQ(b.max, glm::vec3(3, 4, 2));
}

TEST(OrganParts, HairBoundsReachEachHairsTemplate) {
  Scene scene;
  HairPart& hairs = scene.organ<HairPart>();
  HairTemplate reach;
  reach.extent = 2;
  hairs.templates.push_back(reach);
  Hair hair;
  hair.root = glm::vec3(1, 0, 0);
  hair.length = 0.5f;  // reaches 0.5 · 2 = 1 from its root
  hairs.hairs.push_back(hair);
  hair.templateIndex = 1;  // no such template: not drawn, not bounded
  hair.root = glm::vec3(100, 0, 0);
  hairs.hairs.push_back(hair);
  const Bounds b = scene.bounds();
  EXPECT_EQ(b.min, glm::vec3(0, -1, -1));
  EXPECT_EQ(b.max, glm::vec3(2, 1, 1));
}

// A test organ's settings, with a default of its own.
struct PointsSettings : OrganSettingsOf<PointsSettings> {
  int count = 7;
};

TEST(OrganSettings, TheDefaultsUntilAViewFileLineSetsThem) {
  ViewSettings view;
  const ViewSettings& reading = view;
  EXPECT_EQ(reading.organ<PointsSettings>().count, 7);
  EXPECT_EQ(reading.organ<FurSettings>().layers, 16);
  view.organ<PointsSettings>().count = 3;
  EXPECT_EQ(reading.organ<PointsSettings>().count, 3);

  // A copy of the view settings has its own copy of each organ's.
  ViewSettings copy = view;
  copy.organ<PointsSettings>().count = 4;
  EXPECT_EQ(view.organ<PointsSettings>().count, 3);
  copy = view;
  EXPECT_EQ(copy.organ<PointsSettings>().count, 3);
}

TEST(OrganSettings, AnOrgansViewFileLinesSetItsSettings) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "fur layers: 24\nfur texture: 64 9 20\nwetness mask: 32\nfur force: 0 -2 0.5\n"
      "droplet: 0.25 0.75 0.1 0.5 2\n",
      "organs.v", diagnostics);
  const FurSettings& fur = view.organ<FurSettings>();
  EXPECT_EQ(fur.layers, 24);
  EXPECT_EQ(fur.textureSize, 64);
  EXPECT_EQ(fur.textureSeed, 9u);
  EXPECT_FLOAT_EQ(fur.texelsPerLength, 20);
  EXPECT_EQ(fur.wetnessMaskSize, 32);
  EXPECT_EQ(fur.force, glm::vec3(0, -2, 0.5f));
  ASSERT_EQ(fur.droplets.size(), 1u);
  EXPECT_EQ(fur.droplets[0].centre, glm::vec2(0.25f, 0.75f));
  EXPECT_EQ(fur.droplets[0].surface, 2);
  EXPECT_EQ(fur.droplets[0].where.line, 5);
}

TEST(OrganSettings, TheCoatsDynamicsLinesAreTheFeathers) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "feather follicles: hexagonal\ndynamics gravity: 0 -2 0\ndynamics substeps: 7\n"
      "dynamics vanes: on\n",
      "organs.v", diagnostics);
  const FeatherSettings& feathers = view.organ<FeatherSettings>();
  EXPECT_EQ(feathers.follicleLayout, FollicleLayout::Hexagonal);
  EXPECT_EQ(feathers.dynamics.gravity, glm::vec3(0, -2, 0));
  EXPECT_EQ(feathers.dynamics.substeps, 7);
  EXPECT_TRUE(feathers.dynamics.vanes);
  EXPECT_FALSE(FeatherDynamicsSettings{}.vanes);  // the vanes collide only when asked
  EXPECT_FLOAT_EQ(feathers.dynamics.drag, FeatherDynamicsSettings{}.drag);
  Diagnostics wrong;
  EXPECT_THROW(parseViewFile("dynamics vanes: sometimes\n", "organs.v", wrong), DiagnosticError);
}

TEST(OrganSettings, ACoatIsShingledUnlessTheViewFileSaysOff) {
  Diagnostics diagnostics;
  EXPECT_TRUE(FeatherSettings{}.shingling);
  const ViewSettings view = parseViewFile("feather shingling: off\n", "organs.v", diagnostics);
  EXPECT_FALSE(view.organ<FeatherSettings>().shingling);
  Diagnostics wrong;
  EXPECT_THROW(parseViewFile("feather shingling: maybe\n", "organs.v", wrong), DiagnosticError);
}

TEST(OrganAttributeIndices, EachOrgansRecordHasASlotOfItsOwn) {
  OrganAttributeIndices indices;
  EXPECT_TRUE(indices.none());
  indices.of<FurAttributes>() = 3;
  EXPECT_FALSE(indices.none());
  EXPECT_EQ(indices.of<HairAttributes>(), -1);
  EXPECT_EQ(indices.of<FeatherAttributes>(), -1);
  indices.of<HairAttributes>() = 1;
  const OrganAttributeIndices& reading = indices;
  EXPECT_EQ(reading.of<FurAttributes>(), 3);
  EXPECT_EQ(reading.of<HairAttributes>(), 1);

  // Indices that differ only in organs past the last one set are equal: those have none.
  OrganAttributeIndices fur;
  fur.of<FurAttributes>() = 3;
  fur.of<FurAttributes>() = -1;
  EXPECT_TRUE(fur.none());
  EXPECT_EQ(fur, OrganAttributeIndices{});
  OrganAttributeIndices hairs;
  hairs.of<HairAttributes>() = 1;
  EXPECT_FALSE(hairs == OrganAttributeIndices{});
  OrganAttributeIndices hairsAndNoFur = hairs;
  hairsAndNoFur.of<FurAttributes>() = -1;
  EXPECT_EQ(hairsAndNoFur, hairs);

  // The slots are the organs' places in the table list, however many organs there are.
  const auto tables = organModuleTables();
  for (std::size_t k = 0; k < tables.size(); ++k) EXPECT_EQ(organSlot(tables[k]->organ()), k);
  EXPECT_THROW(organSlot('Q'), std::logic_error);
}

}  // namespace
}  // namespace hirsute

namespace hirsute {
namespace {

// A texture's colour where a vertex samples it, as GL samples it: nearest texel, repeating,
// v = 0 the image's last row; black for an empty texture and for coordinates no texel holds.
TEST(TextureColour, IsTheNearestTexelRepeatingFromTheLastRow) {
  Texture t;
  t.width = 2;
  t.height = 2;
  // Row 0 (top): red, green; row 1 (bottom): blue, white.
  t.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  EXPECT_EQ(t.colourAt({0.25f, 0.25f}), glm::vec3(0, 0, 1));
  EXPECT_EQ(t.colourAt({0.75f, 0.25f}), glm::vec3(1, 1, 1));
  EXPECT_EQ(t.colourAt({0.25f, 0.75f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(t.colourAt({1.25f, -0.25f}), glm::vec3(1, 0, 0));
  EXPECT_EQ(t.colourAt({1e30f, 0.25f}), glm::vec3(0, 0, 1));
  EXPECT_EQ(Texture{}.colourAt({0.5f, 0.5f}), glm::vec3(0.0f));
}

}  // namespace
}  // namespace hirsute
