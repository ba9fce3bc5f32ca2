// The shipped mesh models (docs/meshes.md) through every output from the command line: the leaf
// mesh's hairs in the CSV table, the OBJ and the POV-Ray scene (rendered by POV-Ray where it is
// installed), the furry body through the path tracer. And malformed meshes, made here, that once
// crashed Assimp or took it minutes and gigabytes: each is an error at the view file's line,
// exit code 2, within seconds.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "support/run_hirsute.h"
#include "support/test_files.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The leaf's mesh is 1 248 triangles of leaf.ply; its front has hairs at density 40 and its back
// at 20, so the table has about twice as many front hairs as back ones, and the OBJ and the
// scene hold the mesh.
TEST(MeshModels, TheLeafMeshGoesToEveryExport) {
  TemporaryFolder folder;
  const fs::path obj = folder.path() / "leaf.obj", pov = folder.path() / "leaf.pov",
                 csv = folder.path() / "leaf.csv";
  const RunResult run = runHirsute(
      {"export", (kModels / "mesh-leaf" / "leaf.l").string(),
       (kModels / "mesh-leaf" / "leaf.v").string(), "--obj", obj.string(), "--pov", pov.string(),
       "--hairs", csv.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const std::string table = bytesOf(csv);
  const double front = static_cast<double>(countOccurrences(table, ",front\n"));
  const double back = static_cast<double>(countOccurrences(table, ",back\n"));
  EXPECT_GT(back, 100);
  EXPECT_NEAR(front / back, 2.0, 0.15) << front << " front, " << back << " back";
  // The blade's 1 248 triangles and the petiole's.
  EXPECT_GE(countLinesStarting(bytesOf(obj), "f "), 1248u);
  EXPECT_NE(bytesOf(pov).find("mesh2"), std::string::npos);
  if (std::system("command -v povray >/dev/null 2>&1") == 0) {
    const fs::path png = folder.path() / "leaf.png";
    const std::string command = "cd '" + folder.path().string() +
                                "' && povray +Ileaf.pov +Oleaf.png +W48 +H36 -D -V >/dev/null 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0);
    EXPECT_EQ(bytesOf(png).substr(1, 3), "PNG");
  }
}

TEST(MeshModels, TheFurryBodyMeshTraces) {
  TemporaryFolder folder;
  const fs::path png = folder.path() / "body.png";
  const RunResult run =
      runHirsute({"render", (kModels / "mesh-body" / "body.l").string(),
                  (kModels / "mesh-body" / "body.v").string(), "--trace", "--spp", "1", "--size",
                  "32x24", "-o", png.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  EXPECT_EQ(bytesOf(png).substr(1, 3), "PNG");
}

// A model of one mesh surface: `mesh.l` draws ~B, `mesh.v` names `name`, whose bytes are
// `bytes`.
struct MeshModel {
  TemporaryFolder folder;
  fs::path l, v;
  MeshModel(const std::string& name, const std::string& bytes) {
    l = folder.path() / "mesh.l";
    v = folder.path() / "mesh.v";
    std::ofstream(l) << "Lsystem: 1\nderivation length: 1\nAxiom: ~B(1)\nendlsystem\n";
    std::ofstream(v) << "surface: B " << name << " 1\n";
    std::ofstream(folder.path() / name, std::ios::binary) << bytes;
  }
  RunResult render() const {
    return runHirsute({"render", l.string(), v.string(), "--size", "16x12", "-o",
                       (folder.path() / "mesh.png").string()});
  }
};

void expectRefused(const MeshModel& model, const std::string& message) {
  const RunResult run = model.render();
  EXPECT_FALSE(run.killed);
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_EQ(run.signal, 0) << run.err;
  EXPECT_LT(run.seconds, 10.0);
  EXPECT_NE(run.err.find("mesh.v:1:12: error: surface file"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(model.folder.path() / "mesh.png"));
}

// A chain of 20 000 glTF nodes, each the child of the one before, overflowed Assimp's stack.
TEST(MalformedMeshes, AGltfChainOfTwentyThousandNodes) {
  std::string nodes;
  for (int i = 0; i < 20'000; ++i) nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
  nodes += "{}";
  const MeshModel model("chain.gltf",
                        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,"
                        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[" +
                            nodes + "]}");
  expectRefused(model, "chain.gltf: the node hierarchy is more than 256 nodes deep");
}

// COLLADA nodes nested 20 000 deep did the same.
TEST(MalformedMeshes, AColladaFileOfTwentyThousandNestedNodes) {
  std::string text =
      "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><library_visual_scenes>"
      "<visual_scene id=\"s\">\n";
  for (int i = 0; i < 20'000; ++i) text += "<node id=\"n" + std::to_string(i) + "\">\n";
  for (int i = 0; i < 20'000; ++i) text += "</node>\n";
  text +=
      "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#s\"/>"
      "</scene></COLLADA>\n";
  expectRefused(MeshModel("deep.dae", text),
                "deep.dae:256:1: the XML's elements nest more than 256 deep");
}

// 200 000 groups took Assimp over a minute and 3.4 GB.
TEST(MalformedMeshes, AnObjOfTwoHundredThousandGroups) {
  std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 200'000; ++i) text += "g g" + std::to_string(i) + "\nusemtl m\nf 1 2 3\n";
  expectRefused(MeshModel("groups.obj", text),
                "groups.obj:15004:1: more than 10000 groups, objects or materials");
}

// A crash inside Assimp that no check before it sees (a DirectX file nested deeper than its
// recursion reaches) ends the reader's child process, not the program.
TEST(MalformedMeshes, ACrashOfAssimpIsAnError) {
  std::string text = "xof 0303txt 0032\n";
  for (int i = 0; i < 200'000; ++i) text += "Frame f {\n";
  expectRefused(MeshModel("deep.x", text),
                "deep.x: the mesh reader (Assimp) crashed on this file with a segmentation fault");
}

// A vertex colour's red just below 0 is clamped to 0 with a warning at the view file's line (it
// blends the key feathers from 0 to 1).
TEST(MalformedMeshes, AVertexColourOutsideTheUnitIsClampedWithAWarning) {
  const MeshModel model("colours.ply",
                        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nproperty float red\n"
                        "property float green\nproperty float blue\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n"
                        "0 0 0 -0.0001 0 0\n1 0 0 1 0 0\n0 1 0 0.5 0 0\n3 0 1 2\n");
  const RunResult run = model.render();
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("mesh.v:1:12: warning: surface file 'colours.ply': "), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("colours.ply: 1 vertex colour outside [0, 1] clamped to it"),
            std::string::npos)
      << run.err;
}

}  // namespace
