// Template hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.2; DESIGN.md, "Template hairs"):
// each `hair:` L-system of the view file becomes polylines of turtle positions in the hair's
// frame, x along the first segment. Fixtures in tests/fixtures/hairs.
#include "hirsute/hairs/plant/hair_templates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "hairs";
constexpr float kTolerance = 1e-5f;

std::vector<HairTemplate> templatesOf(const std::string& view) {
  Diagnostics diagnostics;
  const ModelResources resources = loadModelResources(kFixtures / view, {}, diagnostics);
  return loadHairTemplates(resources, diagnostics);
}

void expectPolyline(const std::vector<glm::vec3>& actual, const std::vector<glm::vec3>& expected,
                    float tolerance = kTolerance) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].x, expected[i].x, tolerance) << "vertex " << i;
    EXPECT_NEAR(actual[i].y, expected[i].y, tolerance) << "vertex " << i;
    EXPECT_NEAR(actual[i].z, expected[i].z, tolerance) << "vertex " << i;
  }
}

TEST(HairTemplates, EachHairLineBecomesATemplateInOrder) {
  const std::vector<HairTemplate> templates = templatesOf("templates.v");
  ASSERT_EQ(templates.size(), 4u);
  const char* names[] = {"straight.l", "bent.l", "turned.l", "broken.l"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(fs::path(templates[i].file).filename(), names[i]);
  }
}

TEST(HairTemplates, StraightTemplateRunsAlongX) {
  const HairTemplate straight = templatesOf("templates.v").at(0);
  ASSERT_EQ(straight.polylines.size(), 1u);
  expectPolyline(straight.polylines[0], {{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0}});
  EXPECT_NEAR(straight.extent, 1, kTolerance);
  EXPECT_EQ(straight.segmentCount(), 2u);
}

// A left turn (+) turns the heading toward the turtle's left, the hair frame's y.
TEST(HairTemplates, TurnsBecomeTheHairFramesSecondAxis) {
  const HairTemplate bent = templatesOf("templates.v").at(1);
  ASSERT_EQ(bent.polylines.size(), 1u);
  expectPolyline(bent.polylines[0], {{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0.5f, 0}});
  EXPECT_NEAR(bent.extent, std::sqrt(0.5f), kTolerance);
}

// The frame's x is the first segment's direction, not the turtle's initial heading.
TEST(HairTemplates, FirstSegmentDefinesTheHairDirection) {
  const HairTemplate turned = templatesOf("templates.v").at(2);
  ASSERT_EQ(turned.polylines.size(), 1u);
  const float h = std::sqrt(0.5f);
  expectPolyline(turned.polylines[0], {{0, 0, 0}, {1, 0, 0}, {1 + h, -h, 0}});
}

// Sec. 3.2: hair curvature comes from functions. A template reads the plant's function set,
// its names defined, as the plant does: turns of 90·ramp(i/4) = 36°, 54°, 72° (the function is
// a sampled B-spline: within 1e-3).
TEST(HairTemplates, TemplateCurvesWithThePlantsFunctions) {
  const std::vector<HairTemplate> templates = templatesOf("function_template.v");
  ASSERT_EQ(templates.size(), 1u);
  ASSERT_EQ(templates[0].polylines.size(), 1u);
  std::vector<glm::vec3> expected{{0, 0, 0}, {0.25f, 0, 0}};
  float heading = 0;
  for (float turn : {36.0f, 54.0f, 72.0f}) {
    heading += glm::radians(turn);
    expected.push_back(expected.back() + 0.25f * glm::vec3(std::cos(heading), std::sin(heading), 0));
  }
  expectPolyline(templates[0].polylines[0], expected, 1e-3f);
}

TEST(HairTemplates, MoveWithoutDrawingStartsANewPolyline) {
  const HairTemplate broken = templatesOf("templates.v").at(3);
  ASSERT_EQ(broken.polylines.size(), 2u);
  expectPolyline(broken.polylines[0], {{0, 0, 0}, {1, 0, 0}});
  expectPolyline(broken.polylines[1], {{2, 0, 0}, {3, 0, 0}});
  EXPECT_EQ(broken.segmentCount(), 2u);
  EXPECT_NEAR(broken.extent, 3, kTolerance);
}

TEST(HairTemplates, TemplateThatDrawsNothingIsAnErrorNamingItsFile) {
  try {
    templatesOf("draws_nothing.v");
    FAIL() << "a template that draws nothing was accepted";
  } catch (const DiagnosticError& e) {
    // At the view file's `hair:` line (line 4), naming the template's file.
    const Diagnostic& d = e.diagnostic();
    EXPECT_EQ(fs::path(d.where.fileName()).filename(), "draws_nothing.v") << d.text();
    EXPECT_EQ(d.where.line, 4) << d.text();
    EXPECT_NE(d.message.find("draws_nothing.l"), std::string::npos) << d.text();
    EXPECT_NE(d.message.find("draws nothing"), std::string::npos) << d.text();
  }
}

TEST(HairTemplates, ViewWithoutHairLinesHasNoTemplates) {
  EXPECT_TRUE(templatesOf("cylinder.v").empty());
}

}  // namespace
}  // namespace hirsute
