// The shipped mesh models (docs/meshes.md) through every output from the command line: the leaf
// mesh's hairs in the CSV table, the OBJ and the POV-Ray scene (rendered by POV-Ray where it is
// installed), the furry body through the path tracer.
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

}  // namespace
