// The models of models/ that grow against a built-in environmental program, through
// `hirsute derive -e`, against strings worked out by hand; and broken .e and .spec files,
// which end the run with exit code 2 and an error in the user's file.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>

#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

class EnvironmentModelsTest : public testing::TemporaryFolderTest {
 protected:
  EnvironmentModelsTest() : TemporaryFolderTest("hirsute_environment_models_") {}

  struct Run {
    int code = -1;
    std::string out, err;
  };

  Run derive(const fs::path& folder, const std::string& model, const std::string& more = "",
             const std::string& efile = "") {
    const fs::path e = efile.empty() ? folder / (model + ".e") : folder / efile;
    const std::string command =
        std::string("'") + HIRSUTE_BINARY + "' derive '" + (folder / (model + ".l")).string() +
        "' '" + (folder / (model + ".v")).string() + "' -e '" + e.string() + "' --format compact " +
        more + " >'" + file("out").string() + "' 2>'" + file("err").string() + "'";
    const int status = std::system(command.c_str());
    Run run;
    run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.out = testing::readText(file("out"));
    run.err = testing::readText(file("err"));
    return run;
  }

  static fs::path shipped(const std::string& model) {
    return fs::path(HIRSUTE_SOURCE_DIR) / "models" / model;
  }

  // A copy of a shipped model in the test's folder, to break.
  fs::path copyOf(const std::string& model) {
    const fs::path to = folder_ / model;
    fs::copy(shipped(model), to, fs::copy_options::recursive);
    return to;
  }
};

TEST_F(EnvironmentModelsTest, Honda81StopsTheWeakerOfTwoMeetingTips) {
  // The tips start 6 apart and close by 2 a step: 6, 4 and 2 exceed the radius 1.5, so both
  // grow in steps 1 to 3; in the pass of step 4 they meet (distance 0) and the tip of vigor 1
  // stops, while the tip of vigor 2 grows a fourth F.
  const Run run = derive(shipped("tip-collision"), "tip-collision");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out, ";(1)[+(90)f(3)-(180)FFFFA(2)?E(2)][-(90)f(3)+(180);(2)FFF@o(0.3)]\n");
}

TEST_F(EnvironmentModelsTest, EcosystemLetsTheLargerCrownWin) {
  // Crowns 1+1k and 1.5+0.5k, 6 apart: their radii sum to 2.5, 4, 5.5 and then 7 ≥ 6 in the
  // pass of step 4, where the smaller (3 against 4) is dominated.
  const Run run = derive(shipped("competing-plants"), "competing-plants");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out, "[+(90)f(3)P(5,1)?E(5)][-(90)f(3)D]\n");
}

TEST_F(EnvironmentModelsTest, CloverShadesTheCellsUnderTheLeaf) {
  // The leaf of area 4π has radius 2: 3 cells each way (int(2/100·100 + 1)), offsets -3 … 2 in
  // the ellipse u²/9 + v²/9 ≤ 1 around cell (50, 50). (2.5, 0.5) is offset (2, 0) and
  // (2.5, 2.5) is (2, 2): 8/9, shaded, 0.25. (-3.5, 0.5) is offset -4, outside; (-2.5, -2.5)
  // is (-3, -3): 2 > 1, in full light.
  Run run = derive(shipped("shaded-ground"), "shaded-ground");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out,
            "F?E(2,12.5664)[@M(2.5,0.5,0)?E(0.25)][@M(-3.5,0.5,0)?E(1)][@M(2.5,2.5,0)?E(0.25)]"
            "[@M(-2.5,-2.5,0)?E(1)]\n");
  // The second pass lifts the leaf before it answers the light queries: all in full light.
  run = derive(shipped("shaded-ground"), "shaded-ground", "-n 2");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(
      run.out,
      "F[@M(2.5,0.5,0)?E(1)][@M(-3.5,0.5,0)?E(1)][@M(2.5,2.5,0)?E(1)][@M(-2.5,-2.5,0)?E(1)]\n");
}

TEST_F(EnvironmentModelsTest, ChibaDimsTheBallInTheShadow) {
  // The ball above covers the one at the origin entirely (equal radii on one vertical), so
  // half the light passes (transmittance 0.5); the other two are in full light.
  const Run run = derive(shipped("shaded-balls"), "shaded-balls");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out, "[?E(0.5)@o(2)][@M(0,3,0)?E(1)@o(2)][@M(6,0,0)?E(1)@o(2)]\n");
}

TEST_F(EnvironmentModelsTest, DensityAnswersTheFieldAndItsGradient) {
  // The source of strength 4 three units away: 4/(1+3) = 1; the gradient -4/(3·(1+3)²)·3 =
  // -0.25 along x, which is 180 degrees and 0.25 long. The source itself gets no answer.
  const Run run = derive(shipped("density-field"), "density-field");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_EQ(run.out, ";(1)?E(4)@o(0.5)[@M(3,0,0)?E(1,180,0.25)+(180)F(1)F]\n");
}

TEST_F(EnvironmentModelsTest, BrokenCommunicationFilesEndWithAnErrorInThem) {
  const fs::path model = copyOf("tip-collision");
  std::ofstream(model / "broken.e")
      << "executable: honda81 density.spec\ncommunication type: files\n"
      << "turtle position: %d %d %d\n";
  Run run = derive(model, "tip-collision", "", "broken.e");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find((model / "broken.e").string() + ":3:18: error: "), std::string::npos)
      << run.err;
  EXPECT_TRUE(run.out.empty());
  // A specification file that is not there: the error points at its name on the executable line.
  std::ofstream(model / "broken.e") << "executable: honda81 nowhere.spec\n";
  run = derive(model, "tip-collision", "", "broken.e");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find((model / "broken.e").string() +
                         ":1:21: error: cannot read honda81's specification"),
            std::string::npos)
      << run.err;
}

TEST_F(EnvironmentModelsTest, BrokenSpecificationFilesEndWithAnErrorInThem) {
  const fs::path model = copyOf("tip-collision");
  std::ofstream(model / "density.spec") << "verbose: off\nradius: wide\n";
  Run run = derive(model, "tip-collision");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find((model / "density.spec").string() + ":2:9: error: expected a number"),
            std::string::npos)
      << run.err;
  const fs::path shade = copyOf("shaded-ground");
  std::ofstream(shade / "ground.spec") << "input image: missing.rgb\n";
  run = derive(shade, "shaded-ground");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find((shade / "ground.spec").string() + ":1:14: error: "), std::string::npos)
      << run.err;
}

TEST_F(EnvironmentModelsTest, WithoutAnExecutableTheQueriesKeepTheirValues) {
  const fs::path model = copyOf("tip-collision");
  std::ofstream(model / "none.e") << "turtle position: %f %f %f\n";
  const Run run = derive(model, "tip-collision", "", "none.e");
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.err.find("no executable: line"), std::string::npos) << run.err;
  // Nothing answers: ?E(2) matches neither production and stays; ?E(1), the vigor 1, reads as
  // "grow" every step, so that tip grows through the other.
  EXPECT_EQ(run.out, ";(1)[+(90)f(3)-(180)A(2)?E(2)][-(90)f(3)+(180);(2)FFFFA(1)?E(1)]\n");
}

}  // namespace
}  // namespace hirsute
