// glTF 2.0 (gltf_writer.h) read back by Assimp's importer: the meshes with their vertices and
// normals, the materials' base colours in linear light, the view's camera where it looks from;
// `hirsute export --gltf` of the herb as .gltf with its buffer beside it and as .glb, and a name
// of neither kind refused on the command line.
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "hirsute/viewer/export/gltf_writer.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using testing::readText;

class GltfExportTest : public testing::TemporaryFolderTest {
 protected:
  GltfExportTest() : TemporaryFolderTest("hirsute_gltf_") {}
};

Material colour(float r, float g, float b) {
  Material m;
  m.ambient = m.diffuse = glm::vec3(r, g, b);
  return m;
}

// A quad in material 1, a half-transparent triangle in material 2, a sphere in material 1 (a
// mesh of its own after them) and a line, which glTF leaves out.
Scene handBuiltScene() {
  Scene scene;
  scene.materials = {colour(0.1f, 0.2f, 0.4f), colour(0.9f, 0.1f, 0.5f), colour(1, 1, 1)};
  scene.materials[2].transparency = 0.5f;
  TriangleMesh& quad = scene.meshFor(1);
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  TriangleMesh& triangle = scene.meshFor(2);
  triangle.positions = {{2, 0, 0}, {3, 0, 0}, {2, 0, -1}};
  triangle.indices = {0, 1, 2};
  scene.spheres = {{{3, 3, 3}, 0.5f, 1}};
  scene.lines = {{{0, 0, 0}, {0, 1, 0}, 1, 1, 1}};
  return scene;
}

float linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

const aiMaterial* materialNamed(const aiScene& scene, const char* name) {
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    aiString found;
    if (scene.mMaterials[i]->Get(AI_MATKEY_NAME, found) == AI_SUCCESS && found == aiString(name))
      return scene.mMaterials[i];
  }
  return nullptr;
}

void expectReadsBack(const fs::path& file) {
  SCOPED_TRACE(file.string());
  const Scene scene = handBuiltScene();
  GltfOptions options;
  options.width = 400;
  options.height = 300;
  const GltfExportStats stats = writeGltf(scene, options, file);
  EXPECT_EQ(stats.meshes, 3u);
  EXPECT_EQ(stats.vertices, 7u + 62u);  // the sphere: two poles and 5 rings of 12
  EXPECT_EQ(stats.triangles, 3u + 120u);

  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile(file.string(), 0);
  ASSERT_NE(read, nullptr) << importer.GetErrorString();
  ASSERT_EQ(read->mNumMeshes, 3u);
  EXPECT_EQ(read->mMeshes[0]->mNumVertices, 4u);
  EXPECT_EQ(read->mMeshes[0]->mNumFaces, 2u);
  ASSERT_TRUE(read->mMeshes[0]->HasNormals());
  EXPECT_FLOAT_EQ(read->mMeshes[0]->mNormals[2].z, 1.0f);
  EXPECT_EQ(read->mMeshes[1]->mNumVertices, 3u);
  EXPECT_EQ(read->mMeshes[1]->mNumFaces, 1u);
  EXPECT_FLOAT_EQ(read->mMeshes[1]->mVertices[2].z, -1.0f);
  EXPECT_EQ(read->mMeshes[2]->mNumVertices, 62u);
  EXPECT_EQ(read->mMeshes[2]->mNumFaces, 120u);
  ASSERT_TRUE(read->mMeshes[2]->HasNormals());
  EXPECT_NEAR(read->mMeshes[2]->mVertices[0].y, 3.5f, 1e-6);  // the north pole

  // Base colours in linear light, the transparent material's alpha 1 - its transparency.
  const aiMaterial* pink = materialNamed(*read, "m1");
  const aiMaterial* white = materialNamed(*read, "m2");
  ASSERT_NE(pink, nullptr);
  ASSERT_NE(white, nullptr);
  aiColor4D base;
  ASSERT_EQ(pink->Get(AI_MATKEY_BASE_COLOR, base), AI_SUCCESS);
  EXPECT_NEAR(base.r, linear(0.9f), 1e-5);
  EXPECT_NEAR(base.g, linear(0.1f), 1e-5);
  EXPECT_NEAR(base.b, linear(0.5f), 1e-5);
  EXPECT_NEAR(base.a, 1.0f, 1e-6);
  ASSERT_EQ(white->Get(AI_MATKEY_BASE_COLOR, base), AI_SUCCESS);
  EXPECT_NEAR(base.r, 1.0f, 1e-6);
  EXPECT_NEAR(base.a, 0.5f, 1e-6);
  EXPECT_EQ(read->mMaterials[read->mMeshes[0]->mMaterialIndex], pink);
  EXPECT_EQ(read->mMaterials[read->mMeshes[1]->mMaterialIndex], white);
  EXPECT_EQ(read->mMaterials[read->mMeshes[2]->mMaterialIndex], pink);

  // The camera: on the fitted camera's line of sight, looking along it.
  ASSERT_EQ(read->mNumCameras, 1u);
  const aiNode* node = read->mRootNode->FindNode(read->mCameras[0]->mName);
  ASSERT_NE(node, nullptr);
  aiMatrix4x4 world = node->mTransformation;
  for (const aiNode* up = node->mParent; up != nullptr; up = up->mParent)
    world = up->mTransformation * world;
  const Camera fitted =
      fitCamera(options.view, scene.bounds(), glm::ivec2(options.width, options.height));
  const glm::vec3 at(world.a4, world.b4, world.c4);
  const glm::vec3 looks = -glm::normalize(glm::vec3(world.a3, world.b3, world.c3));
  EXPECT_NEAR(glm::dot(looks, fitted.forward), 1.0f, 1e-5);
  EXPECT_LT(glm::length(glm::cross(at - fitted.eye, fitted.forward)), 1e-4f);
  EXPECT_NEAR(read->mCameras[0]->mAspect, 400.0f / 300.0f, 1e-5);
}

TEST_F(GltfExportTest, TextGltfReadsBackWithItsBuffer) {
  expectReadsBack(file("scene.gltf"));
  EXPECT_TRUE(fs::is_regular_file(file("scene.bin")));
  // The JSON names its buffer by the file beside it, nothing of the writer's.
  EXPECT_NE(readText(file("scene.gltf")).find("\"scene.bin\""), std::string::npos);
}

TEST_F(GltfExportTest, BinaryGlbReadsBackAlone) {
  expectReadsBack(file("scene.glb"));
  EXPECT_FALSE(fs::exists(file("scene.bin")));
  EXPECT_EQ(readText(file("scene.glb")).substr(0, 4), "glTF");
}

TEST_F(GltfExportTest, ABufferNameIsWrittenAsAUri) {
  writeGltf(handBuiltScene(), GltfOptions{}, file("a plant#1.gltf"));
  // (Assimp 5.2's importer does not decode a URI's percents; Blender's does.)
  EXPECT_NE(readText(file("a plant#1.gltf")).find("\"a%20plant%231.bin\""), std::string::npos);
  EXPECT_TRUE(fs::is_regular_file(file("a plant#1.bin")));
}

TEST_F(GltfExportTest, ACoordinateNotANumberWritesNothing) {
  Scene scene = handBuiltScene();
  scene.meshes[0].positions[1].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(writeGltf(scene, GltfOptions{}, file("scene.glb")), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(folder_));
}

int run(const std::string& arguments, const fs::path& log) {
  const std::string command =
      std::string("'") + HIRSUTE_BINARY + "' " + arguments + " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The herb through the command line, with an OBJ in the same run: every file in place, no
// temporary one left, and Assimp reads from the glTF the OBJ's meshes and spheres.
TEST_F(GltfExportTest, TheHerbExportsAsGltfAndGlb) {
  const std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/herb";
  ASSERT_EQ(run("export '" + herb + ".l' '" + herb + ".v' --size 64x48 --gltf '" +
                    file("herb.gltf").string() + "' --obj '" + file("herb.obj").string() + "'",
                file("log")),
            0)
      << readText(file("log"));
  ASSERT_EQ(run("export '" + herb + ".l' '" + herb + ".v' --size 64x48 --gltf '" +
                    file("herb.glb").string() + "'",
                file("log")),
            0)
      << readText(file("log"));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(folder_)) {
    (void)entry;
    ++files;
  }
  // herb.gltf, herb.bin, herb.obj, herb.mtl, herb.glb and the log.
  EXPECT_EQ(files, 6u);
  for (const char* name : {"herb.gltf", "herb.glb"}) {
    Assimp::Importer importer;
    const aiScene* read = importer.ReadFile(file(name).string(), 0);
    ASSERT_NE(read, nullptr) << name << ": " << importer.GetErrorString();
    // The OBJ's two meshes and its spheres, all of one colour: one mesh more.
    EXPECT_EQ(read->mNumMeshes, 3u) << name;
    EXPECT_EQ(read->mNumCameras, 1u) << name;
    // Assimp's exporter joins identical vertices (its glTF exporter asks for that step), so
    // the triangles are counted: the OBJ's of its meshes, those before its spheres, and 120 for
    // each of its spheres of 224 (16 slices and 8 stacks in the OBJ, 12 and 6 in the glTF).
    unsigned triangles = 0;
    for (unsigned i = 0; i < read->mNumMeshes; ++i) triangles += read->mMeshes[i]->mNumFaces;
    const std::string obj = readText(file("herb.obj"));
    const std::size_t spheres = obj.find("\no spheres\n");
    ASSERT_NE(spheres, std::string::npos);
    const std::size_t meshTriangles = testing::countLinesStarting(obj.substr(0, spheres), "f ");
    const std::size_t sphereTriangles = testing::countLinesStarting(obj.substr(spheres), "f ");
    EXPECT_EQ(sphereTriangles % 224, 0u);
    EXPECT_GT(sphereTriangles, 0u);
    EXPECT_EQ(triangles, meshTriangles + sphereTriangles / 224 * 120) << name;
  }
}

TEST_F(GltfExportTest, ANameNeitherGltfNorGlbIsACommandLineError) {
  const std::string herb = std::string(HIRSUTE_SOURCE_DIR) + "/models/herb/herb";
  EXPECT_EQ(
      run("export '" + herb + ".l' '" + herb + ".v' --gltf '" + file("herb.obj").string() + "'",
          file("log")),
      2);
  EXPECT_NE(readText(file("log")).find("a glTF file's name ends in .gltf or .glb"),
            std::string::npos)
      << readText(file("log"));
  EXPECT_FALSE(fs::exists(file("herb.obj")));
}

}  // namespace
}  // namespace hirsute
