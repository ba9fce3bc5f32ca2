// The shape editors without a window (shape_workbench.h): the script's `function`, `contour` and
// `surface` commands parsed and checked, then run on copies of a shipped model's files: each
// change written at once as asked, undo and redo, refusals that leave the file as it was.
#include "hirsute/viewer/interaction/shape_workbench.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/viewer/interaction/view_script.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string scriptError(const std::string& script) {
  try {
    parseViewScript(script, "--commands");
  } catch (const DiagnosticError& error) {
    return error.diagnostic().text();
  }
  return "";
}

TEST(ShapeWorkbench, TheScriptsCommandsAreCheckedBeforeTheWindowOpens) {
  EXPECT_EQ(parseViewScript("function leafsize point 2 0.5 0.7; contour leaf add 3 0 0 1; "
                            "surface l point 5 0.1 0.2 0.3; function leafsize undo",
                            "--commands")
                .size(),
            4u);
  EXPECT_NE(scriptError("function leafsize bend 2")
                .find("--commands:1:1: error: unknown function action 'bend'"),
            std::string::npos);
  EXPECT_NE(scriptError("step; contour leaf point 1 2")
                .find("--commands:1:7: error: expected 'contour NAME point I X Y [Z]'"),
            std::string::npos);
  EXPECT_NE(scriptError("surface l remove 2").find("unknown surface action 'remove'"),
            std::string::npos);
  EXPECT_NE(scriptError("function leafsize").find("'function' takes 2 to 6 arguments"),
            std::string::npos);
  EXPECT_NE(scriptError("function leafsize point two 0 0").find("expected a number, found 'two'"),
            std::string::npos);
}

class ShapeWorkbenchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("hirsute_workbench_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
    const fs::path models = fs::path(HIRSUTE_SOURCE_DIR) / "models";
    fs::copy_file(models / "herb" / "herb.fset", folder_ / "herb.fset");
    fs::copy_file(models / "herb" / "leaf.s", folder_ / "leaf.s");
    fs::copy_file(models / "hairy-leaf" / "leaf.con", folder_ / "leaf.con");
    model_.functionFiles = {folder_ / "herb.fset"};
    ContourDeclaration contour;
    contour.id = 1;
    contour.file = (folder_ / "leaf.con").string();
    model_.view.contours = {contour};
    SurfaceDeclaration surface;
    surface.id = 'l';
    surface.file = (folder_ / "leaf.s").string();
    model_.view.surfaces = {surface};
    workbench_.follow(model_, folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  std::string run(const std::string& command) {
    return workbench_.run(parseViewScript(command, "--commands").front());
  }

  fs::path folder_;
  ViewerModel model_;
  ShapeWorkbench workbench_;
};

TEST_F(ShapeWorkbenchTest, EachChangeIsWrittenAtOnceAndUndoWritesItBack) {
  const std::string function = readText(folder_ / "herb.fset");
  const std::string contour = readText(folder_ / "leaf.con");
  const std::string surface = readText(folder_ / "leaf.s");
  EXPECT_EQ(run("function leafsize point 2 0.25 0.5"), "");
  EXPECT_NE(readText(folder_ / "herb.fset").find("\n0.250000 0.500000 1\n"), std::string::npos);
  EXPECT_EQ(run("contour leaf.con point 1 -1 0.5"), "");
  EXPECT_NE(readText(folder_ / "leaf.con").find("\n-1.000000 0.500000 0.000000 3\n"),
            std::string::npos);
  EXPECT_EQ(run("surface l point 16 0.25 1 0.2"), "");
  EXPECT_NE(readText(folder_ / "leaf.s").find("0.25 1.00 0.20  \n"), std::string::npos);
  EXPECT_EQ(workbench_.takeWritten().size(), 3u);

  EXPECT_EQ(run("function herb undo"), "");
  EXPECT_EQ(run("contour leaf undo"), "");
  EXPECT_EQ(run("surface leaf.s undo"), "");
  EXPECT_EQ(readText(folder_ / "herb.fset"), function);
  EXPECT_EQ(readText(folder_ / "leaf.con"), contour);
  EXPECT_EQ(readText(folder_ / "leaf.s"), surface);
  EXPECT_EQ(run("surface l undo"), "nothing to undo in leaf.s");
  EXPECT_EQ(run("surface l redo"), "");
  EXPECT_NE(readText(folder_ / "leaf.s"), surface);
}

TEST_F(ShapeWorkbenchTest, RefusedChangesLeaveTheFile) {
  const std::string function = readText(folder_ / "herb.fset");
  EXPECT_EQ(run("function leafsize point 9 0.5 0.5"), "no point 9: the points are numbered 1 to 5");
  EXPECT_EQ(run("function leafsize remove 1"),
            "the first and last points of a function stay (the curve spans [0, 1])");
  EXPECT_EQ(run("function leafsize add 1.5 0.5"), "a function's x lies in [0, 1]");
  EXPECT_EQ(run("function stem point 1 0 0"),
            "the model has no function 'stem' (its functions: herb.fset, leafsize)");
  EXPECT_EQ(readText(folder_ / "herb.fset"), function);
  EXPECT_TRUE(workbench_.takeWritten().empty());
}

TEST_F(ShapeWorkbenchTest, AFileChangedElsewhereIsReadAgain) {
  EXPECT_EQ(run("function leafsize point 2 0.25 0.5"), "");
  std::string edited = readText(folder_ / "herb.fset");
  edited.replace(edited.find("0.750000 1.000000"), 17, "0.750000 0.900000");
  std::ofstream(folder_ / "herb.fset", std::ios::binary | std::ios::trunc) << edited;
  workbench_.follow(model_, folder_);
  const CurveDocument& document = workbench_.functions().front();
  EXPECT_EQ(document.history.current().text(), edited);
  EXPECT_FALSE(document.history.canUndo()) << "its history starts anew";
}

// A file beneath another folder than the model's is never written, whatever names it.
TEST_F(ShapeWorkbenchTest, NothingIsWrittenOutsideTheModelsFolder) {
  fs::create_directories(folder_ / "model");
  workbench_.follow(model_, folder_ / "model");
  const std::string function = readText(folder_ / "herb.fset");
  const std::string refused = run("function leafsize point 2 0.25 0.5");
  EXPECT_NE(refused.find("cannot write"), std::string::npos) << refused;
  EXPECT_NE(refused.find("leaves the model's folder"), std::string::npos) << refused;
  EXPECT_EQ(readText(folder_ / "herb.fset"), function);
  EXPECT_TRUE(workbench_.takeWritten().empty());
}

// A version 0 function takes its table's size from the view file's `function:` line: the editor
// draws it through the same table.
TEST_F(ShapeWorkbenchTest, AVersion0FunctionKeepsTheViewsSampleCount) {
  const std::string text = "range: 0.0 1.0\npoints: 4\n0.0 0.0\n0.2 0.9\n0.5 0.1\n1.0 1.0\n";
  std::ofstream(folder_ / "wave.func", std::ios::binary) << text;
  model_.functionFiles = {folder_ / "wave.func"};
  model_.functionSamples = {4};
  workbench_.follow(model_, folder_);
  ASSERT_EQ(workbench_.functions().size(), 1u);
  const CurveDocument& document = workbench_.functions().front();
  EXPECT_EQ(document.viewSamples, 4);
  const FunctionCurve shown = document.history.current().function(0, document.viewSamples);
  const FunctionCurve derived = FunctionCurve::parse(text, "wave.func", 4);
  for (double x : {0.1, 0.4, 0.55, 0.9}) EXPECT_EQ(shown.evaluate(x), derived.evaluate(x));
  EXPECT_NE(shown.evaluate(0.55), FunctionCurve::parse(text, "wave.func", 0).evaluate(0.55));
}

}  // namespace
}  // namespace hirsute
