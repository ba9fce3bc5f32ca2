// Template hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Sec. 3.2; docs/design.md, "Plant hairs"):
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

// The area of a template's filled triangles, and of the plane polygon a closed polyline
// outlines (half the length of its vector area, the sum of p_i × p_i+1).
float filledArea(const HairTemplate& hair) {
  float area = 0;
  for (std::size_t i = 0; i + 2 < hair.triangles.size(); i += 3) {
    const glm::vec3& a = hair.triangles[i];
    area += 0.5f * glm::length(glm::cross(hair.triangles[i + 1] - a, hair.triangles[i + 2] - a));
  }
  return area;
}

float outlinedArea(const std::vector<glm::vec3>& polygon) {
  glm::vec3 twice(0.0f);
  for (std::size_t i = 0; i < polygon.size(); ++i)
    twice += glm::cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5f * glm::length(twice);
}

// A closed outline between { and } is filled, as cpfg fills a polygon: the template keeps its
// triangles beside the outline's polyline, in the same frame.
TEST(HairTemplates, PolygonOfATemplateIsFilled) {
  const std::vector<HairTemplate> templates = templatesOf("filled_template.v");
  ASSERT_EQ(templates.size(), 1u);
  const HairTemplate& filled = templates[0];
  ASSERT_EQ(filled.polylines.size(), 1u);
  expectPolyline(filled.polylines[0], {{0, 0, 0},
                                       {0.5f, 0, 0},
                                       {0.5f, 0.5f, 0},
                                       {1.5f, 0.5f, 0},
                                       {1.5f, -0.5f, 0},
                                       {0.5f, -0.5f, 0},
                                       {0.5f, 0, 0}});
  ASSERT_GE(filled.triangles.size(), 6u);
  EXPECT_EQ(filled.triangles.size() % 3, 0u);
  for (const glm::vec3& p : filled.triangles) {
    EXPECT_NEAR(p.z, 0, kTolerance);
    EXPECT_GE(p.x, 0.5f - kTolerance);
    EXPECT_LE(p.x, 1.5f + kTolerance);
  }
  EXPECT_NEAR(filledArea(filled), 1, 1e-4f);
  EXPECT_NEAR(filled.extent, glm::length(glm::vec2(1.5f, 0.5f)), kTolerance);
  // A template of lines alone has no triangles.
  for (const HairTemplate& lines : templatesOf("templates.v")) EXPECT_TRUE(lines.triangles.empty());
}

// The fern croziers' scales (models/fern-croziers, scale.l and broad.l) are filled blades, not
// rings: their triangles cover the area their outline (the polyline after the stalk) encloses.
TEST(HairTemplates, FernCrozierScalesAreFilledBlades) {
  Diagnostics diagnostics;
  const fs::path crozier = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "fern-croziers";
  const ModelResources resources = loadModelResources(crozier / "fern-croziers.v", {}, diagnostics);
  const std::vector<HairTemplate> templates = loadHairTemplates(resources, diagnostics);
  ASSERT_EQ(templates.size(), 3u);
  for (std::size_t t = 0; t < 2; ++t) {
    const HairTemplate& scale = templates[t];
    SCOPED_TRACE(scale.file);
    ASSERT_EQ(scale.polylines.size(), 1u);
    const std::vector<glm::vec3>& outline = scale.polylines[0];
    ASSERT_GT(outline.size(), 4u);
    // The stalk is the first segment; the blade's outline runs from its end back to it.
    const std::vector<glm::vec3> blade(outline.begin() + 1, outline.end() - 1);
    // Closed within 0.002 of the blade's length 1: the template gives its lengths to 0.001.
    EXPECT_NEAR(glm::distance(outline.back(), outline[1]), 0, 2e-3f) << "the outline is closed";
    ASSERT_FALSE(scale.triangles.empty());
    const float area = outlinedArea(blade);
    EXPECT_GT(area, 0.05f);
    EXPECT_NEAR(filledArea(scale), area, 1e-3f * area + 1e-5f);
  }
  EXPECT_TRUE(templates[2].triangles.empty()) << "hairlike.l is a hair";
}

TEST(HairTemplates, ViewWithoutHairLinesHasNoTemplates) {
  EXPECT_TRUE(templatesOf("cylinder.v").empty());
}

}  // namespace
}  // namespace hirsute
