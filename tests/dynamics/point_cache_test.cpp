// `hirsute simulate --pc2 FILE`: the frames as one PC2 point cache over a base mesh beside it
// (point_cache.h), read back without Blender. The header announces the points and frames, the
// base mesh is one object of exactly those points, and each frame's sample is that frame's OBJ,
// vertex by vertex; a run whose frames change their points, a cache named like its base mesh and
// one past --max-output-bytes are errors that leave no cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

std::vector<float> objVertices(const fs::path& obj) {
  std::vector<float> xyz;
  std::istringstream lines(readText(obj));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    for (int k = 0; k < 3; ++k) {
      float v = 0;
      words >> v;
      xyz.push_back(v);
    }
  }
  return xyz;
}

struct Pc2 {
  char signature[12];
  std::int32_t version, points;
  float start, rate;
  std::int32_t samples;
  std::vector<float> xyz;
};

Pc2 readPc2(const fs::path& file) {
  const std::string bytes = readText(file);
  Pc2 cache{};
  EXPECT_GE(bytes.size(), 32u);
  if (bytes.size() < 32) return cache;
  std::memcpy(cache.signature, bytes.data(), 12);
  std::memcpy(&cache.version, bytes.data() + 12, 4);
  std::memcpy(&cache.points, bytes.data() + 16, 4);
  std::memcpy(&cache.start, bytes.data() + 20, 4);
  std::memcpy(&cache.rate, bytes.data() + 24, 4);
  std::memcpy(&cache.samples, bytes.data() + 28, 4);
  cache.xyz.resize((bytes.size() - 32) / 4);
  std::memcpy(cache.xyz.data(), bytes.data() + 32, cache.xyz.size() * 4);
  return cache;
}

TEST(PointCache, EverySampleIsItsFramesObjVertexByVertex) {
  TemporaryFolder folder;
  const fs::path grass = kModels / "feather-grass";
  const RunResult run =
      runHirsute({"simulate", (grass / "feather-grass.l").string(), (grass / "wind.v").string(),
                  "-o", (folder.path() / "frames").string(), "--frames", "3", "--obj", "--size",
                  "32x24", "--pc2", (folder.path() / "grass.pc2").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const Pc2 cache = readPc2(folder.path() / "grass.pc2");
  EXPECT_EQ(std::string(cache.signature, 12), std::string("POINTCACHE2\0", 12));
  EXPECT_EQ(cache.version, 1);
  EXPECT_EQ(cache.start, 1.0f);
  EXPECT_EQ(cache.rate, 1.0f);
  ASSERT_EQ(cache.samples, 3);
  ASSERT_GT(cache.points, 1000);
  ASSERT_EQ(cache.xyz.size(), 3u * 3u * static_cast<std::size_t>(cache.points));

  // The base mesh: one object (no `o` line), its vertices the cache's points.
  const std::string base = readText(folder.path() / "grass.obj");
  EXPECT_EQ(countLinesStarting(base, "o "), 0u);
  EXPECT_EQ(countLinesStarting(base, "v "), static_cast<std::size_t>(cache.points));
  EXPECT_TRUE(fs::is_regular_file(folder.path() / "grass.mtl"));

  const std::size_t n = 3 * static_cast<std::size_t>(cache.points);
  const std::vector<float> first = objVertices(folder.path() / "frames" / "frame-0001.obj");
  for (int frame = 1; frame <= 3; ++frame) {
    const std::vector<float> expected =
        objVertices(folder.path() / "frames" / ("frame-000" + std::to_string(frame) + ".obj"));
    ASSERT_EQ(expected.size(), n) << frame;
    float error = 0, moved = 0;
    for (std::size_t i = 0; i < n; ++i) {
      error = std::max(error, std::fabs(cache.xyz[(frame - 1) * n + i] - expected[i]));
      moved = std::max(moved, std::fabs(expected[i] - first[i]));
    }
    // The OBJ prints a millionth of the scene's size (a few metres of grass): 1e-5 holds it.
    EXPECT_LT(error, 1e-4f) << "frame " << frame;
    if (frame > 1) {
      EXPECT_GT(moved, 0.1f) << "frame " << frame << ": the awns move in the wind";
    }
  }
}

TEST(PointCache, FramesWhosePointsChangeAreAnErrorAndLeaveNoCache) {
  TemporaryFolder folder;
  const fs::path fur = kModels / "fur-square";
  // Droplets change the strands in number.
  const RunResult run =
      runHirsute({"simulate", (fur / "square.l").string(), (fur / "square.v").string(), "-o",
                  folder.path().string(), "--frames", "3", "--no-frames", "--drop", "2:50", "--pc2",
                  (folder.path() / "fur.pc2").string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("a point cache moves the same points every frame"), std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "fur.pc2"));
  EXPECT_FALSE(fs::exists(folder.path() / "fur.obj"));
}

TEST(PointCache, ACacheNamedLikeItsBaseMeshOrPastTheLimitIsRefused) {
  TemporaryFolder folder;
  const fs::path grass = kModels / "feather-grass";
  const std::vector<std::string> model{"simulate",
                                       (grass / "feather-grass.l").string(),
                                       (grass / "wind.v").string(),
                                       "-o",
                                       folder.path().string(),
                                       "--frames",
                                       "2",
                                       "--no-frames"};
  std::vector<std::string> named = model;
  named.insert(named.end(), {"--pc2", (folder.path() / "grass.obj").string()});
  RunResult run = runHirsute(named);
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("name the cache FILE.pc2"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "grass.obj"));

  std::vector<std::string> limited = model;
  limited.insert(limited.end(),
                 {"--pc2", (folder.path() / "grass.pc2").string(), "--max-output-bytes", "100000"});
  run = runHirsute(limited);
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("more than --max-output-bytes 100000"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "grass.pc2"));
  EXPECT_FALSE(fs::exists(folder.path() / "grass.obj"));
}

}  // namespace
