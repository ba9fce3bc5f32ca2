// The scene file for Blender (blender_writer.h) read back without Blender: its ends and index
// found by readBlenderIndex, each curve group's sizes and points and each mesh's arrays read at
// the offsets the index gives, and compared with the scene they were written from; and
// `hirsute export --blender` on the oriental poppy, whose curves are its hairs' table's rows.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/viewer/export/blender_writer.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using testing::countLinesStarting;
using testing::readText;

class BlenderExportTest : public testing::TemporaryFolderTest {
 protected:
  BlenderExportTest() : TemporaryFolderTest("hirsute_blender_") {}
};

struct CurveGroup {
  std::string organ, name;
  std::uint64_t curves, points, data, sizes;
};

struct MeshEntry {
  std::string organ, name;
  std::uint64_t vertices, triangles, positions, indices;
  bool normals;
};

// The index's entries, as the writer lays them out (one an entry, keys in a fixed order).
std::vector<CurveGroup> curveGroups(const std::string& json) {
  static const std::regex entry(
      R"re(\{"organ":"([^"]*)","name":"([^"]*)","material":\d+,"curves":(\d+),"points":(\d+),)re"
      R"re("data":(\d+),"sizes":(\d+)\})re");
  std::vector<CurveGroup> groups;
  for (auto it = std::sregex_iterator(json.begin(), json.end(), entry);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    groups.push_back(
        {m[1], m[2], std::stoull(m[3]), std::stoull(m[4]), std::stoull(m[5]), std::stoull(m[6])});
  }
  return groups;
}

std::vector<MeshEntry> meshEntries(const std::string& json) {
  static const std::regex entry(
      R"re(\{"organ":"([^"]*)","name":"([^"]*)","material":\d+,"vertices":(\d+),)re"
      R"re("triangles":(\d+),"positions":(\d+),"normals":(\d+|null),)re"
      R"re("texcoords":(?:\d+|null),"colours":(?:\d+|null),)re"
      R"re("indices":(\d+)\})re");
  std::vector<MeshEntry> meshes;
  for (auto it = std::sregex_iterator(json.begin(), json.end(), entry);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    meshes.push_back({m[1], m[2], std::stoull(m[3]), std::stoull(m[4]), std::stoull(m[5]),
                      std::stoull(m[7]), m[6] != "null"});
  }
  return meshes;
}

std::uint64_t countOf(const std::string& json, const std::string& what) {
  const std::regex count("\"" + what + "\":(\\d+)");
  std::smatch m;
  return std::regex_search(json, m, count) ? std::stoull(m[1]) : 0;
}

template <typename T>
std::vector<T> arrayAt(const std::string& bytes, std::uint64_t offset, std::size_t count) {
  std::vector<T> values(count);
  EXPECT_LE(offset + count * sizeof(T), bytes.size());
  if (offset + count * sizeof(T) <= bytes.size())
    std::memcpy(values.data(), bytes.data() + offset, count * sizeof(T));
  return values;
}

Material colour(float r, float g, float b) {
  Material m;
  m.ambient = m.diffuse = glm::vec3(r, g, b);
  return m;
}

// A quad, a polyline of two segments and a lone segment, a sphere, and three hairs of a
// template of two polylines (3 + 2 vertices).
Scene handBuiltScene() {
  Scene scene;
  scene.materials = {colour(0.1f, 0.2f, 0.4f), colour(0.9f, 0.1f, 0.1f), colour(1, 1, 1)};
  TriangleMesh& quad = scene.meshFor(1);
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  scene.lineStyle = LineStyle::Polygon;
  scene.lines = {{{0, 0, 0}, {0, 1, 0}, 0.2f, 0.1f, 1},
                 {{0, 1, 0}, {0, 2, 0}, 0.1f, 0.05f, 1},
                 {{5, 0, 0}, {6, 0, 0}, 0.2f, 0.2f, 1}};
  scene.spheres = {{{3, 3, 3}, 0.5f, 1}};
  HairTemplate branched;
  branched.file = "models/x/branched.l";
  branched.polylines = {{{0, 0, 0}, {0.5f, 0, 0}, {0.8f, 0.3f, 0}},
                        {{0.5f, 0, 0}, {0.6f, 0, 0.3f}}};
  branched.material = 2;
  branched.extent = 1;
  scene.organ<HairPart>().templates = {branched};
  for (int i = 0; i < 3; ++i) {
    Hair h;
    h.root = glm::vec3(static_cast<float>(i), 0, 0);
    h.length = 2;
    h.radius = 0.01f * static_cast<float>(i + 1);
    scene.organ<HairPart>().hairs.push_back(h);
  }
  return scene;
}

TEST_F(BlenderExportTest, ReadsBackEveryCurveAndMeshAtItsOffsets) {
  const Scene scene = handBuiltScene();
  const BlenderExportStats stats = writeBlender(scene, BlenderOptions{}, file("scene.hirsute"));
  const BlenderFileIndex index = readBlenderIndex(file("scene.hirsute"));
  EXPECT_EQ(index.version, kBlenderVersion);
  EXPECT_EQ(index.fileBytes, stats.bytes);
  const std::string bytes = readText(file("scene.hirsute"));

  // Lines: one group, the polyline one curve of 3 points, the lone segment one of 2, their
  // radii half their widths.
  const std::vector<CurveGroup> groups = curveGroups(index.json);
  ASSERT_EQ(groups.size(), 2u) << index.json;
  EXPECT_EQ(groups[0].organ, "lines");
  EXPECT_EQ(arrayAt<std::uint32_t>(bytes, groups[0].sizes, groups[0].curves),
            (std::vector<std::uint32_t>{3, 2}));
  const std::vector<float> line = arrayAt<float>(bytes, groups[0].data, 7 * groups[0].points);
  EXPECT_FLOAT_EQ(line[3], 0.1f);         // the first point's radius: width 0.2 / 2
  EXPECT_FLOAT_EQ(line[7 + 3], 0.05f);    // where the two segments meet: the first's end
  EXPECT_FLOAT_EQ(line[14 + 3], 0.025f);  // the polyline's end

  // Hairs: one group named after the template's file, 2 curves a hair of the hair's radius,
  // white (linear 1), placed at root + length · p.
  EXPECT_EQ(groups[1].organ, "hairs");
  EXPECT_EQ(groups[1].name, "branched");
  ASSERT_EQ(groups[1].curves, 6u);
  EXPECT_EQ(groups[1].points, 15u);
  EXPECT_EQ(arrayAt<std::uint32_t>(bytes, groups[1].sizes, 6),
            (std::vector<std::uint32_t>{3, 2, 3, 2, 3, 2}));
  const std::vector<float> hairs = arrayAt<float>(bytes, groups[1].data, 7 * 15);
  for (int i = 0; i < 3; ++i) {
    const float* first = &hairs[static_cast<std::size_t>(7 * 5 * i)];
    EXPECT_FLOAT_EQ(first[0], static_cast<float>(i));
    const float* tip = first + 7 * 2;  // (0.8, 0.3, 0) · 2 from the root
    EXPECT_NEAR(tip[0], static_cast<float>(i) + 1.6f, 1e-5f);
    EXPECT_NEAR(tip[1], 0.6f, 1e-5f);
    EXPECT_FLOAT_EQ(first[3], 0.01f * static_cast<float>(i + 1));
    EXPECT_FLOAT_EQ(first[4], 1.0f);
  }
  EXPECT_EQ(countOf(index.json, "hairs"), 3u);

  // Meshes: the quad with its normals, the sphere tessellated.
  const std::vector<MeshEntry> meshes = meshEntries(index.json);
  ASSERT_EQ(meshes.size(), 2u) << index.json;
  EXPECT_EQ(meshes[0].vertices, 4u);
  EXPECT_EQ(meshes[0].triangles, 2u);
  EXPECT_TRUE(meshes[0].normals);
  EXPECT_EQ(arrayAt<std::uint32_t>(bytes, meshes[0].indices, 6),
            (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(arrayAt<float>(bytes, meshes[0].positions, 12)[6], 1.0f);  // (1, 1, 0)
  EXPECT_EQ(meshes[1].name, "spheres_m1");
  EXPECT_GT(meshes[1].triangles, 20u);
  EXPECT_EQ(stats.curves, 8u);
}

TEST_F(BlenderExportTest, ATruncatedFileIsRefused) {
  writeBlender(handBuiltScene(), BlenderOptions{}, file("scene.hirsute"));
  const std::string bytes = readText(file("scene.hirsute"));
  std::ofstream(file("cut.hirsute"), std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  EXPECT_THROW(readBlenderIndex(file("cut.hirsute")), std::runtime_error);
  std::ofstream(file("other.hirsute"), std::ios::binary) << "HIRSUTEB but nothing else";
  EXPECT_THROW(readBlenderIndex(file("other.hirsute")), std::runtime_error);
}

// The poppy's hairs: each of its two templates one curve group, one curve a hair (both
// templates are one polyline), as many as the rows of `--hairs`.
TEST_F(BlenderExportTest, ThePoppysCurvesAreItsHairs) {
  const std::string poppy = std::string(HIRSUTE_SOURCE_DIR) + "/models/oriental-poppy/";
  const std::string command =
      std::string("'") + HIRSUTE_BINARY + "' export '" + poppy + "oriental-poppy.l' '" + poppy +
      "oriental-poppy.v' --blender '" + file("poppy.hirsute").string() + "' --hairs '" +
      file("poppy.csv").string() + "' --size 96x72 > '" + file("log").string() + "' 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readText(file("log"));
  const BlenderFileIndex index = readBlenderIndex(file("poppy.hirsute"));
  const std::string bytes = readText(file("poppy.hirsute"));
  const std::uint64_t rows = countLinesStarting(readText(file("poppy.csv")), "") - 1;
  EXPECT_GT(rows, 100000u);
  EXPECT_EQ(countOf(index.json, "hairs"), rows);
  std::uint64_t curves = 0;
  std::vector<std::string> templates;
  for (const CurveGroup& group : curveGroups(index.json)) {
    if (group.organ != "hairs") continue;
    templates.push_back(group.name);
    curves += group.curves;
    std::uint64_t points = 0;
    for (std::uint32_t size : arrayAt<std::uint32_t>(bytes, group.sizes, group.curves)) {
      EXPECT_GE(size, 2u);
      points += size;
    }
    EXPECT_EQ(points, group.points);
    EXPECT_EQ(group.data + 28 * group.points, group.sizes);
  }
  EXPECT_EQ(templates, (std::vector<std::string>{"straight", "curved"}));
  EXPECT_EQ(curves, rows);
  EXPECT_NE(index.json.find("\"projection\":\"orthographic\""), std::string::npos);
}

// `hirsute export --blender` of `model` (in models/) at a small size into `file`.
int exportBlender(const std::string& model, const fs::path& file, const fs::path& log) {
  const std::string base = std::string(HIRSUTE_SOURCE_DIR) + "/models/" + model;
  const std::string command = std::string("'") + HIRSUTE_BINARY + "' export '" + base + ".l' '" +
                              base + ".v' --blender '" + file.string() + "' --size 32x24 > '" +
                              log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Every point's radius and colour at the offsets the group gives: radii positive, colours in
// [0, 1]; the sizes add up to the points.
void expectWholeCurves(const std::string& bytes, const CurveGroup& group) {
  std::uint64_t points = 0;
  for (std::uint32_t size : arrayAt<std::uint32_t>(bytes, group.sizes, group.curves)) {
    EXPECT_GE(size, 2u);
    points += size;
  }
  EXPECT_EQ(points, group.points) << group.name;
  const std::vector<float> data = arrayAt<float>(bytes, group.data, 7 * group.points);
  std::size_t thin = 0;
  for (std::size_t p = 0; p < group.points; ++p) {
    thin += !(data[7 * p + 3] > 0);
    for (int k = 4; k < 7; ++k) {
      EXPECT_GE(data[7 * p + k], 0.0f);
      EXPECT_LE(data[7 * p + k], 1.0f);
    }
  }
  // A barb's radius falls to nothing where it fades out at its tip, and no further.
  EXPECT_LT(thin, group.points / 4) << group.name;
}

// The fur's strands and the feathers' barbs are curves too: one curve a strand, as many as the
// fur writer counts, and the coat's barbs with their shafts' mesh (coloured at its vertices).
TEST_F(BlenderExportTest, FurStrandsAndFeatherBarbsAreCurves) {
  ASSERT_EQ(exportBlender("fur-square/square", file("fur.hirsute"), file("log")), 0)
      << readText(file("log"));
  BlenderFileIndex index = readBlenderIndex(file("fur.hirsute"));
  std::string bytes = readText(file("fur.hirsute"));
  std::vector<CurveGroup> groups = curveGroups(index.json);
  ASSERT_EQ(groups.size(), 1u) << index.json;
  EXPECT_EQ(groups[0].organ, "fur");
  EXPECT_GT(groups[0].curves, 10000u);
  EXPECT_EQ(groups[0].curves, countOf(index.json, "fur strands"));
  expectWholeCurves(bytes, groups[0]);

  ASSERT_EQ(exportBlender("coat-bending/bending", file("coat.hirsute"), file("log")), 0)
      << readText(file("log"));
  index = readBlenderIndex(file("coat.hirsute"));
  bytes = readText(file("coat.hirsute"));
  groups = curveGroups(index.json);
  ASSERT_EQ(groups.size(), 1u) << index.json;
  EXPECT_EQ(groups[0].organ, "feathers");
  EXPECT_EQ(groups[0].name, "barbs");
  EXPECT_GT(groups[0].curves, 63u * 50);  // 63 feathers of many barbs
  EXPECT_EQ(countOf(index.json, "feathers"), 63u);
  expectWholeCurves(bytes, groups[0]);
  const std::vector<MeshEntry> meshes = meshEntries(index.json);
  ASSERT_EQ(meshes.size(), 2u) << index.json;
  EXPECT_EQ(meshes[1].name, "shafts");
  const std::regex colouredShafts(R"re("name":"shafts"[^}]*"colours":\d+)re");
  EXPECT_TRUE(std::regex_search(index.json, colouredShafts)) << "the shafts' vertex colours";
}

}  // namespace
}  // namespace hirsute
