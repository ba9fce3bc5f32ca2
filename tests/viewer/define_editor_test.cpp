// The `#define` constants the viewer's panel edits, and `--save` writing them back.
#include "hirsute/viewer/interaction/define_editor.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace hirsute {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path fixture() {
  return fs::path(HIRSUTE_SOURCE_DIR) / "tests/fixtures/viewer/constants.l";
}

TEST(DefineEditorTest, FindsNumericConstantsOnly) {
  auto constants = findDefineConstants(readText(fixture()));
  ASSERT_EQ(constants.size(), 4u);
  EXPECT_EQ(constants[0].name, "STEPS");
  EXPECT_TRUE(constants[0].integer);
  EXPECT_EQ(constants[0].line, 2);
  EXPECT_EQ(constants[1].name, "ANGLE");  // indented, with a comment after it
  EXPECT_DOUBLE_EQ(constants[1].value, 22.5);
  EXPECT_FALSE(constants[1].integer);
  EXPECT_EQ(constants[2].name, "SMALL");
  EXPECT_DOUBLE_EQ(constants[2].value, -0.01);
  EXPECT_FALSE(constants[2].integer);
  EXPECT_EQ(constants[3].name, "LAST");  // SQUARE(x), NAME and EXPR are not knobs
}

TEST(DefineEditorTest, ReplacingKeepsEverythingElse) {
  std::string text = readText(fixture());
  std::string changed = replaceDefineValues(text, {{"ANGLE", "30.0"}, {"LAST", "8"}});
  std::string expected = text;
  expected.replace(expected.find("22.5"), 4, "30.0");
  expected.replace(expected.find("LAST 7") + 5, 1, "8");
  EXPECT_EQ(changed, expected);
  EXPECT_EQ(replaceDefineValues(text, {{"NOPE", "1"}}), text);
}

TEST(DefineEditorTest, FormatsValuesAsTheyWereWritten) {
  EXPECT_EQ(formatDefineValue(6.4, true), "6");
  EXPECT_EQ(formatDefineValue(-3, true), "-3");
  EXPECT_EQ(formatDefineValue(22.5, false), "22.5");
  EXPECT_EQ(formatDefineValue(30, false), "30.0");
  EXPECT_EQ(formatDefineValue(0.1, false), "0.1");
}

TEST(DefineEditorTest, SaveWritesTheFileBack) {
  fs::path file = fs::temp_directory_path() / ("hirsute_define_" + std::to_string(getpid()) + ".l");
  fs::copy_file(fixture(), file, fs::copy_options::overwrite_existing);
  saveDefineValues(file, {{"STEPS", "9"}});
  auto constants = findDefineConstants(readText(file));
  EXPECT_EQ(constants[0].text, "9");
  EXPECT_EQ(readText(file).size(), readText(fixture()).size());
  fs::remove(file);
}

}  // namespace
}  // namespace hirsute
