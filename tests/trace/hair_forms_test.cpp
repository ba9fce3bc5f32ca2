// Hairs seen small are traced in a coarser form of their template (plant_hair_tracer.h): the
// forms and how far they stray, and the form the tracer picks by a hair's size in the picture.
#include <gtest/gtest.h>

#include <cmath>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/plant_hair_tracer.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/viewer/trace/trace_scene.h"

namespace {

using namespace hirsute;

// A hair of length 1 bent into a quarter of a circle, as five points.
HairTemplate bentHair() {
  HairTemplate hair;
  std::vector<glm::vec3> polyline;
  const float radius = 2 / static_cast<float>(M_PI);  // a quarter circle of length 1
  for (int i = 0; i <= 4; ++i) {
    const float a = static_cast<float>(M_PI) / 2 * static_cast<float>(i) / 4;
    polyline.emplace_back(radius * std::sin(a), radius * (1 - std::cos(a)), 0.0f);
  }
  hair.polylines.push_back(polyline);
  return hair;
}

TEST(HairForms, EachFormKeepsEveryOtherVertexOfTheOneBefore) {
  EXPECT_EQ(keptVertices(5, 0), (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(keptVertices(5, 1), (std::vector<std::size_t>{0, 2, 4}));
  EXPECT_EQ(keptVertices(5, 2), (std::vector<std::size_t>{0, 4}));
  EXPECT_EQ(keptVertices(4, 1), (std::vector<std::size_t>{0, 2, 3}));  // the last is always kept
  EXPECT_EQ(keptVertices(2, 3), (std::vector<std::size_t>{0, 1}));
}

TEST(HairForms, TheStrayIsTheFarthestDroppedVertexFromTheCoarserPolyline) {
  const HairForms forms = hairFormsOf(bentHair());
  ASSERT_EQ(forms.stray.size(), 3u);  // the template, two segments, one
  EXPECT_EQ(forms.stray[0], 0.0f);
  // A chord of angle θ on a circle of radius r passes r (1 - cos(θ/2)) from the arc's middle.
  const double r = 2 / M_PI;
  EXPECT_NEAR(forms.stray[1], r * (1 - std::cos(M_PI / 8)), 1e-5);
  EXPECT_NEAR(forms.stray[2], r * (1 - std::cos(M_PI / 4)), 1e-5);
  // The coarsest form within the tolerance.
  EXPECT_EQ(hairFormFor(forms, 1.0f, 0.01f), 0u);
  EXPECT_EQ(hairFormFor(forms, 1.0f, 0.05f), 1u);
  EXPECT_EQ(hairFormFor(forms, 0.1f, 0.05f), 2u);
  EXPECT_EQ(hairFormFor(forms, 1.0f, 0.0f), 0u);  // behind the eye: the template itself
}

// Ten bent hairs of length `length` about the origin, traced through a parallel camera whose
// pixels are `pixel` wide: the curve segments the tracer made.
std::size_t tracedSegments(float length, float pixel) {
  Scene scene;
  HairPart& part = scene.organ<HairPart>();
  part.templates.push_back(bentHair());
  for (int i = 0; i < 10; ++i) {
    Hair hair;
    hair.root = glm::vec3(0.1f * static_cast<float>(i), 0, 0);
    hair.length = length;
    hair.radius = 0.001f;
    part.hairs.push_back(hair);
  }
  Camera camera;
  camera.viewport = {100, 100};
  camera.halfHeight = camera.halfWidth = 50 * pixel;
  trace::TraceScene traced(TraceSettings{});
  plantHairTracer().addTo(scene, camera, traced);
  return traced.curveSegments();
}

TEST(HairForms, TheTracerTracesHairsSeenSmallInTheirCoarserForms) {
  // A quarter of a pixel against the strays of a hair of length 1, 0.0485 and 0.186.
  EXPECT_EQ(tracedSegments(1.0f, 0.01f), 40u);  // 0.0025: the template, four segments a hair
  EXPECT_EQ(tracedSegments(1.0f, 0.3f), 20u);   // 0.075: two segments a hair
  EXPECT_EQ(tracedSegments(0.01f, 0.1f), 10u);  // a hundredth of the length: one
}

// A filled template (a scale: its outline and the polygon inside, HairTemplate::triangles) is
// traced as its outline's curves and its triangles, placed with each hair, as a thin surface of
// the template's colour: it passes light (docs/trace.md), where an outline alone is a ring.
TEST(HairForms, AFilledTemplateIsTracedAsASurfaceInsideItsOutline) {
  Scene scene;
  scene.materials.resize(2);
  scene.materials[1].diffuse = glm::vec3(0.5f, 0.4f, 0.2f);
  HairPart& part = scene.organ<HairPart>();
  HairTemplate scale;
  scale.polylines = {{{0, 0, 0}, {1, 0.5f, 0}, {2, 0, 0}, {1, -0.5f, 0}, {0, 0, 0}}};
  scale.triangles = {{0, 0, 0}, {1, -0.5f, 0}, {2, 0, 0}, {0, 0, 0}, {2, 0, 0}, {1, 0.5f, 0}};
  scale.material = 1;
  scale.extent = 2;
  part.templates.push_back(scale);
  for (int i = 0; i < 3; ++i) {
    Hair hair;
    hair.root = glm::vec3(static_cast<float>(i), 0, 0);
    hair.length = 0.5f;
    hair.radius = 0.01f;
    part.hairs.push_back(hair);
  }
  Camera camera;
  camera.viewport = {100, 100};
  camera.halfHeight = camera.halfWidth = 5;
  trace::TraceScene traced(TraceSettings{});
  plantHairTracer().addTo(scene, camera, traced);
  EXPECT_EQ(traced.curveSegments(), 3u * 4);
  ASSERT_EQ(traced.triangleCount(), 3u * 2);
  // The triangles' material: the template's colour, reflected and, as a thin sheet, passed on.
  traced.commit();
  bool found = false;
  for (unsigned g = 0; g < 2; ++g) {
    const trace::TraceShape& shape = traced.shape(g);
    if (shape.curve) continue;
    found = true;
    const trace::TraceMaterial& m = traced.material(shape.material);
    EXPECT_FALSE(m.hair);
    EXPECT_NEAR(m.surface.reflectance.r, trace::linearColour(glm::vec3(0.5f)).r, 1e-5f);
    EXPECT_GT(m.surface.transmittance.g, 0.0f);
  }
  EXPECT_TRUE(found);
}

}  // namespace
