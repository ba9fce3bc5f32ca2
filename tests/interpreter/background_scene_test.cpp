// cpfg's background scene files (manual §8.3): primitives in world space, materials appended
// after the palette, the matrix commands, and errors at the file's own line.
#include "hirsute/interpreter/background_scene.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "hirsute/interpreter/model_resources.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";

Bounds boundsOf(const TriangleMesh& mesh, std::uint32_t firstIndex, std::uint32_t count) {
  Bounds b;
  for (std::uint32_t i = firstIndex; i < firstIndex + count; ++i) b.add(mesh.positions[mesh.indices[i]]);
  return b;
}

TEST(BackgroundSceneTest, EveryPrimitiveIsCountedAsCpfgWritesIt) {
  Diagnostics diagnostics;
  const BackgroundScene background =
      loadBackgroundScene(kFixtures / "background_scene.dat", diagnostics);
  // box 12, rectangle 2, mesh of 6 vertices 4, pentagon 3.
  EXPECT_EQ(background.counts.triangles, 21u);
  EXPECT_EQ(background.counts.spheres, 2u);
  EXPECT_EQ(background.counts.cylinders, 2u);
  // The cone's tip (radius 0) has no disc.
  EXPECT_EQ(background.counts.discs, 3u);
}

TEST(BackgroundSceneTest, MaterialTakesItsOpacityFromTheDiffuseAlpha) {
  Diagnostics diagnostics;
  const BackgroundScene background =
      loadBackgroundScene(kFixtures / "background_scene.dat", diagnostics);
  ASSERT_EQ(background.materials.size(), 2u);  // OpenGL's default, then the file's
  const Material& m = background.materials[1];
  EXPECT_FLOAT_EQ(m.ambient.r, 0.1f);  // the macro OPAQUE expanded
  EXPECT_FLOAT_EQ(m.diffuse.b, 0.6f);
  EXPECT_FLOAT_EQ(m.specular.g, 0.5f);
  EXPECT_FLOAT_EQ(m.shininess, 32.0f);
  EXPECT_FLOAT_EQ(m.transparency, 0.75f);
  for (const TriangleMesh& mesh : background.meshes) EXPECT_EQ(mesh.material, 1);
}

TEST(BackgroundSceneTest, TransformsPlaceThePrimitives) {
  Diagnostics diagnostics;
  const BackgroundScene background =
      loadBackgroundScene(kFixtures / "background_scene.dat", diagnostics);
  // The uniformly scaled sphere stays a sphere: centre translated, radius scaled.
  ASSERT_EQ(background.spheres.size(), 1u);
  EXPECT_EQ(background.spheres[0].center, glm::vec3(0, 5, 0));
  EXPECT_FLOAT_EQ(background.spheres[0].radius, 3.0f);

  ASSERT_EQ(background.meshes.size(), 1u);
  const TriangleMesh& mesh = background.meshes[0];
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  // The box comes first: its 12 triangles span (10,0,0) to (11,2,3).
  const Bounds box = boundsOf(mesh, 0, 36);
  EXPECT_EQ(box.min, glm::vec3(10, 0, 0));
  EXPECT_EQ(box.max, glm::vec3(11, 2, 3));
  // Everything after `multmatrix` lies in the plane z = -7, the last pentagon's normal is +z.
  const std::size_t last = mesh.positions.size() - 1;
  EXPECT_FLOAT_EQ(mesh.positions[last].z, -7.0f);
  EXPECT_EQ(mesh.positions[last], glm::vec3(-1, 0.5f, -7));
  EXPECT_EQ(mesh.normals[last], glm::vec3(0, 0, 1));
  // The ellipsoid `scale 2 1 1; sphere 1` reaches x = ±2, y = ±1.
  const Bounds all = [&] {
    Bounds b;
    for (const glm::vec3& p : mesh.positions) b.add(p);
    return b;
  }();
  EXPECT_NEAR(all.min.x, -2.0f, 1e-5f);
  EXPECT_NEAR(all.min.y, -1.0f, 1e-5f);
  EXPECT_NEAR(all.max.y, 4.0f, 1e-5f);  // the cylinder's top
}

TEST(BackgroundSceneTest, AppendedMaterialsFollowThePalette) {
  Diagnostics diagnostics;
  const BackgroundScene background =
      loadBackgroundScene(kFixtures / "background_scene.dat", diagnostics);
  Scene scene;
  scene.materials.resize(256);
  appendBackgroundScene(background, scene);
  ASSERT_EQ(scene.materials.size(), 258u);
  EXPECT_FLOAT_EQ(scene.materials[257].transparency, 0.75f);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].material, 257);
  ASSERT_EQ(scene.spheres.size(), 1u);
  EXPECT_EQ(scene.spheres[0].material, 257);
}

TEST(BackgroundSceneTest, ErrorsPointAtTheFileAndLine) {
  Diagnostics diagnostics;
  try {
    loadBackgroundScene(kFixtures / "broken_background_scene.dat", diagnostics);
    FAIL() << "expected a DiagnosticError";
  } catch (const DiagnosticError& error) {
    EXPECT_NE(error.diagnostic().where.fileName().find("broken_background_scene.dat"),
              std::string::npos);
    EXPECT_EQ(error.diagnostic().where.line, 3);
    EXPECT_NE(error.diagnostic().message.find("'sphere' takes 1"), std::string::npos);
  }
  EXPECT_THROW(loadBackgroundScene(kFixtures / "unbalanced_background_scene.dat", diagnostics),
               DiagnosticError);
}

TEST(BackgroundSceneTest, ViewFileBackgroundsAreLoadedAndMissingOnesWarned) {
  Diagnostics diagnostics;
  const ModelResources resources =
      loadModelResources(kFixtures / "background_scene.v", ColorFiles{}, diagnostics);
  ASSERT_EQ(resources.backgroundScenes.size(), 1u);
  EXPECT_EQ(resources.backgroundScenes[0].counts.spheres, 2u);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_NE(diagnostics.warnings()[0].message.find("missing_background.dat"), std::string::npos);
}

}  // namespace
}  // namespace hirsute
