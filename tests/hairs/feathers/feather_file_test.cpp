// The feather file (.fea, docs/feathers.md): every keyword read into FeatherType, the defaults,
// and each broken line reported at its file:line:col. Fixtures in tests/fixtures/feathers.
#include "hirsute/hairs/feathers/feather_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <glm/geometric.hpp>
#include <string>

#include "support/diagnostic_of.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using testing::diagnosticOf;

const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "feathers";

FeatherType load(const std::string& name) {
  Diagnostics diagnostics;
  return loadFeatherType(kFixtures / name, diagnostics);
}

// The error of a broken fixture: at `line`:`column` of `file` (default: the fixture itself),
// its message containing `message`.
void expectError(const std::string& fixture, int line, int column, const std::string& message,
                 const std::string& file = "") {
  const Diagnostic error = diagnosticOf([&] { load(fixture); });
  EXPECT_EQ(error.severity, Severity::Error);
  EXPECT_EQ(fs::path(error.where.fileName()).filename(), file.empty() ? fixture : file);
  EXPECT_EQ(error.where.line, line) << error.text();
  EXPECT_EQ(error.where.column, column) << error.text();
  EXPECT_NE(error.message.find(message), std::string::npos) << error.text();
}

TEST(FeatherFile, ReadsEveryKeyword) {
  const FeatherType type = load("contour.fea");
  EXPECT_FLOAT_EQ(type.calamusLength, 0.15f);
  EXPECT_FLOAT_EQ(type.calamusWidthRatio, 0.8f);
  EXPECT_FLOAT_EQ(type.rachisLength, 1.2f);
  EXPECT_FLOAT_EQ(type.rachisWidth, 0.03f);
  EXPECT_FLOAT_EQ(type.rachisSideCurvature, 0.1f);
  EXPECT_FLOAT_EQ(type.rachisFrontCurvature, -0.05f);
  EXPECT_FLOAT_EQ(type.barbSpacingBase, 0.02f);
  EXPECT_FLOAT_EQ(type.barbSpacingTip, 0.01f);
  EXPECT_FLOAT_EQ(type.left.baseAngle, 110);
  EXPECT_FLOAT_EQ(type.left.tipAngle, 155);
  EXPECT_FLOAT_EQ(type.right.baseAngle, 115);
  EXPECT_FLOAT_EQ(type.right.tipAngle, 150);
  EXPECT_FLOAT_EQ(type.left.barbLength, 0.35f);
  EXPECT_FLOAT_EQ(type.right.barbLength, 0.35f);
  ASSERT_EQ(type.left.silhouette.size(), 4u);
  EXPECT_EQ(type.left.silhouette[1], (SilhouettePoint{0.3f, 0.4f}));
  EXPECT_TRUE(type.right.silhouette.empty());

  ASSERT_EQ(type.keyBarbs.size(), 2u);
  const KeyBarb& both = type.keyBarbs[0];
  EXPECT_EQ(both.side, BarbSide::Both);
  EXPECT_FLOAT_EQ(both.position, 0.4f);
  ASSERT_EQ(both.vertices.size(), 4u);
  EXPECT_EQ(both.vertices[0], glm::vec3(0, 0, 0));  // 2D vertices have z = 0
  EXPECT_EQ(both.vertices[1], glm::vec3(0.3f, 0.1f, 0.02f));
  EXPECT_FALSE(both.angle.has_value());
  EXPECT_EQ(both.where.line, 15);
  const KeyBarb& right = type.keyBarbs[1];
  EXPECT_EQ(right.side, BarbSide::Right);
  ASSERT_TRUE(right.angle.has_value());
  EXPECT_FLOAT_EQ(*right.angle, 160);
  EXPECT_EQ(right.vertices.size(), 2u);

  EXPECT_EQ(type.appearance.drawing, BarbStyle::Strips);
  EXPECT_FLOAT_EQ(type.appearance.stripWidth, 0.004f);
  EXPECT_EQ(type.appearance.colourKind, FeatherColourKind::Rgb);
  EXPECT_EQ(type.appearance.colour, glm::vec3(0.6f, 0.4f, 0.2f));
  EXPECT_EQ(fs::path(type.appearance.texture), kFixtures / "pattern.png");
  EXPECT_EQ(type.appearance.textureMapping, FeatherTextureMapping::Vane);
  EXPECT_EQ(type.seed, 7u);
}

TEST(FeatherFile, AfterfeatherIsLoadedRelativeToTheFile) {
  const FeatherType type = load("contour.fea");
  ASSERT_TRUE(type.afterfeather);
  EXPECT_FLOAT_EQ(type.afterfeatherSize, 0.4f);
  EXPECT_EQ(fs::path(type.afterfeather->file).filename(), "down.fea");
  EXPECT_FLOAT_EQ(type.afterfeather->rachisLength, 0.3f);
  EXPECT_TRUE(type.afterfeather->keyBarbs.empty());
  EXPECT_EQ(type.afterfeather->appearance.colourKind, FeatherColourKind::ColourIndex);
  EXPECT_EQ(type.afterfeather->appearance.colourIndex, 3);
  EXPECT_EQ(type.afterfeather->seed, 11u);
}

TEST(FeatherFile, EmptyFileGivesTheDefaults) {
  Diagnostics diagnostics;
  const FeatherType type =
      parseFeatherType("# nothing but a comment\n\n", "empty.fea", diagnostics);
  const FeatherType defaults;
  EXPECT_EQ(type.rachisLength, defaults.rachisLength);
  EXPECT_EQ(type.calamusLength, defaults.calamusLength);
  EXPECT_EQ(type.left, defaults.left);
  EXPECT_EQ(type.right, defaults.right);
  EXPECT_TRUE(type.keyBarbs.empty());
  EXPECT_FALSE(type.afterfeather);
  EXPECT_EQ(type.appearance, defaults.appearance);
  EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(FeatherFile, ChordLongerThanOneIsClampedWithAWarning) {
  Diagnostics diagnostics;
  const FeatherType type = loadFeatherType(kFixtures / "clamped_chord.fea", diagnostics);
  ASSERT_EQ(type.keyBarbs.size(), 1u);
  const std::vector<glm::vec3>& v = type.keyBarbs[0].vertices;
  EXPECT_FLOAT_EQ(glm::length(v.back() - v.front()), 1);
  EXPECT_FLOAT_EQ(v[1].x, 0.5f);  // scaled about cv0: the shape is kept
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0].where.line, 1);
  EXPECT_EQ(diagnostics.warnings()[0].where.column, 32);
}

TEST(FeatherFile, UnknownKeywordIsAnError) {
  expectError("unknown_keyword.fea", 2, 3, "unknown keyword 'rachis colour:'");
}

TEST(FeatherFile, WrongCountOfNumbersIsAnError) {
  expectError("wrong_count.fea", 2, 27, "unexpected '170' after the values of 'left barb angles:'");
}

TEST(FeatherFile, MissingNumberIsAnError) {
  Diagnostics diagnostics;
  const Diagnostic error =
      diagnosticOf([&] { parseFeatherType("barb spacing:\n", "missing.fea", diagnostics); });
  EXPECT_EQ(error.where.line, 1);
  EXPECT_EQ(error.where.column, 14);
  EXPECT_EQ(error.message,
            "expected the barb spacing at the rachis base after 'barb spacing:', found nothing");
}

TEST(FeatherFile, NonNumberIsAnError) {
  expectError("not_a_number.fea", 2, 15, "expected the rachis width (a number), found 'thin'");
}

TEST(FeatherFile, NegativeLengthIsAnError) {
  expectError("negative_length.fea", 1, 16, "the rachis length must be 0 or more, found -1");
}

TEST(FeatherFile, KeyBarbPositionOutsideZeroToOneIsAnError) {
  expectError("position_out_of_range.fea", 1, 16,
              "the key barb's position along the rachis must be from 0 to 1, found 1.5");
}

TEST(FeatherFile, KeyBarbWithOneVertexIsAnError) {
  expectError("one_vertex_key_barb.fea", 1, 20,
              "a key barb needs at least 2 control vertices '(x y [z])', found 1");
}

TEST(FeatherFile, VertexWithFourNumbersIsAnError) {
  expectError("vertex_count.fea", 1, 33, "a control vertex has at most 3 numbers");
}

TEST(FeatherFile, UnknownSideIsAnError) {
  expectError("bad_side.fea", 1, 11, "expected a side (left, right or both), found 'middle'");
}

TEST(FeatherFile, SilhouetteOutOfOrderIsAnError) {
  expectError("silhouette_order.fea", 1, 36,
              "silhouette points go from the rachis base to its tip: position 0.4 comes after 0.6");
}

TEST(FeatherFile, MissingAfterfeatherIsAnError) {
  expectError("missing_afterfeather.fea", 2, 15, "cannot read afterfeather file 'nowhere.fea'");
}

TEST(FeatherFile, AfterfeatherCycleIsAnError) {
  // Reported where the cycle closes: cycle_b.fea names cycle_a.fea, which is being loaded.
  expectError("cycle_a.fea", 2, 15,
              "afterfeather 'cycle_a.fea' is a cycle: cycle_a.fea -> cycle_b.fea -> cycle_a.fea",
              "cycle_b.fea");
}

TEST(FeatherFile, DuplicateKeywordIsAnError) {
  expectError("duplicate_keyword.fea", 3, 1, "'rachis length:' is given twice; the first is at");
  const Diagnostic error = diagnosticOf([&] { load("duplicate_keyword.fea"); });
  EXPECT_NE(error.message.find("duplicate_keyword.fea:1:1"), std::string::npos) << error.text();
}

TEST(FeatherFile, LineWithoutColonIsAnError) {
  expectError("missing_colon.fea", 1, 1, "expected 'keyword: values', found 'rachis length 1'");
}

TEST(FeatherFile, ColourAndMaterialTogetherAreAnError) {
  expectError("colour_and_material.fea", 2, 1, "a feather has one colour or one material");
}

TEST(FeatherFile, MissingFileIsAnError) {
  const Diagnostic error = diagnosticOf([&] { load("no_such_feather.fea"); });
  EXPECT_NE(error.message.find("cannot read feather file"), std::string::npos);
  EXPECT_EQ(error.where.line, 0);
}

}  // namespace
}  // namespace hirsute
