// The view file (.v) as cpfg reads it: every command, its default, exact labels, and where broken
// lines are reported.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/interpreter/view_lines.h"
#include "hirsute/interpreter/view_settings.h"
#include "support/diagnostic_of.h"

namespace hirsute {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter";
const std::filesystem::path kConformance =
    std::filesystem::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The settings of a fixture read without the preprocessor (the fixtures have no directives).
ViewSettings parseFixture(const std::string& name, Diagnostics& diagnostics) {
  const std::filesystem::path file = kFixtures / name;
  return parseViewFile(readText(file), file, diagnostics);
}

using testing::diagnosticOf;

void expectVector(const glm::vec3& actual, float x, float y, float z) {
  EXPECT_FLOAT_EQ(actual.x, x);
  EXPECT_FLOAT_EQ(actual.y, y);
  EXPECT_FLOAT_EQ(actual.z, z);
}

TEST(ViewFileTest, EmptyFileGivesCpfgsDefaults) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile("", kFixtures / "empty.v", diagnostics);
  EXPECT_FLOAT_EQ(view.angleIncrement, 45);
  EXPECT_EQ(view.initialColor, 128);
  EXPECT_EQ(view.initialBackColor, -1);
  EXPECT_EQ(view.colorIncrement, 1);
  EXPECT_FLOAT_EQ(view.initialLineWidth, 1);
  EXPECT_FLOAT_EQ(view.lineWidthIncrement, 0);
  EXPECT_EQ(view.lineStyle, LineStyle::Pixel);
  EXPECT_TRUE(view.lineWidthInPixels);
  EXPECT_TRUE(view.taperedLines);
  EXPECT_TRUE(view.interpretationPastCut);
  EXPECT_EQ(view.contourSides, 8);
  EXPECT_FALSE(view.twistOfCylinders);
  expectVector(view.viewpoint, 0, 0, 1);
  expectVector(view.viewReference, 0, 0, 0);
  EXPECT_EQ(view.projection, Projection::Parallel);
  EXPECT_FLOAT_EQ(view.viewingAngle, 45);
  EXPECT_FLOAT_EQ(view.frontDistance, -100000);
  EXPECT_FLOAT_EQ(view.backDistance, 100000);
  EXPECT_FLOAT_EQ(view.scaleFactor, 1);
  EXPECT_FALSE(view.box.has_value());
  EXPECT_TRUE(view.zBuffer);
  EXPECT_EQ(view.renderMode, RenderMode::Filled);
  EXPECT_EQ(view.shadowMap.size, 1024);
  expectVector(view.lightDirection, 1, 0, 0);
  EXPECT_EQ(view.diffuseReflection, 10);
  EXPECT_FLOAT_EQ(view.surfaceAmbient, 0.15f);
  EXPECT_FLOAT_EQ(view.surfaceDiffuse, 0.75f);
  expectVector(view.tropismDirection, 0, 1, 0);
  EXPECT_TRUE(view.lights.empty());
  EXPECT_TRUE(view.tropisms.empty());
  EXPECT_EQ(view.organ<HairSettings>().textureSize, 100);
  EXPECT_FALSE(view.organ<HairSettings>().interpolation);
  EXPECT_TRUE(diagnostics.warnings().empty());
}

TEST(ViewFileTest, EveryCommandSetsItsField) {
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("every_command.v", diagnostics);
  for (const Diagnostic& d : diagnostics.warnings()) ADD_FAILURE() << d.text();

  EXPECT_FLOAT_EQ(view.angleIncrement, 45);  // angle factor: 8 → 360/8
  EXPECT_EQ(view.initialColor, 12);
  EXPECT_EQ(view.initialBackColor, 40);
  EXPECT_EQ(view.colorIncrement, 2);
  EXPECT_EQ(view.backColorIncrement, 3);
  EXPECT_FLOAT_EQ(view.initialLineWidth, 0.25f);
  EXPECT_EQ(view.lineStyle, LineStyle::Cylinder);  // the unit word `shaded`
  EXPECT_FALSE(view.lineWidthInPixels);
  EXPECT_FLOAT_EQ(view.lineWidthIncrement, 0.5f);
  EXPECT_FALSE(view.taperedLines);
  EXPECT_FLOAT_EQ(view.initialScale, 2);
  EXPECT_FLOAT_EQ(view.scaleMultiplier, 1.5f);
  EXPECT_FALSE(view.interpretationPastCut);
  expectVector(view.viewpoint, 1, 2, 3);
  expectVector(view.viewReference, 0.5f, 1.5f, 2.5f);
  EXPECT_FLOAT_EQ(view.twistDegrees, 12.5f);  // tenths of a degree
  EXPECT_EQ(view.projection, Projection::Perspective);
  EXPECT_FLOAT_EQ(view.viewingAngle, 30);
  EXPECT_FLOAT_EQ(view.frontDistance, 0.5f);
  EXPECT_FLOAT_EQ(view.backDistance, 250);
  EXPECT_FLOAT_EQ(view.scaleFactor, 0.8f);
  ASSERT_TRUE(view.box.has_value());
  expectVector(view.box->min, -1, 0, -3);
  expectVector(view.box->max, 1, 2, 3);
  EXPECT_FLOAT_EQ(view.minZoom, 0.1f);
  EXPECT_FLOAT_EQ(view.maxZoom, 20);
  EXPECT_FALSE(view.zBuffer);
  EXPECT_EQ(view.renderMode, RenderMode::Interpolated);
  EXPECT_EQ(view.shadowMap.size, 2048);
  expectVector(view.shadowMap.color, 0.1f, 0.2f, 0.3f);
  EXPECT_FLOAT_EQ(view.shadowMap.offsetFactor, 4);
  EXPECT_FLOAT_EQ(view.shadowMap.offsetUnits, 8);
  EXPECT_TRUE(view.antialiasing);
  EXPECT_TRUE(view.concavePolygons);
  expectVector(view.lightDirection, 0, 1, 0);
  EXPECT_EQ(view.diffuseReflection, 20);
  EXPECT_FLOAT_EQ(view.surfaceAmbient, 0.2f);
  EXPECT_FLOAT_EQ(view.surfaceDiffuse, 0.7f);

  ASSERT_EQ(view.lights.size(), 2u);
  const LightSource& point = view.lights[0];
  EXPECT_FALSE(point.directional);
  expectVector(point.vector, 1, 2, 3);
  expectVector(point.ambient, 0.1f, 0.2f, 0.3f);
  expectVector(point.diffuse, 0.4f, 0.5f, 0.6f);
  expectVector(point.specular, 0.7f, 0.8f, 0.9f);
  EXPECT_TRUE(point.spot);
  expectVector(point.spotDirection, 0, -1, 0);
  EXPECT_FLOAT_EQ(point.spotExponent, 2);
  EXPECT_FLOAT_EQ(point.spotCutoff, 45);
  EXPECT_FLOAT_EQ(point.constantAttenuation, 1);
  EXPECT_FLOAT_EQ(point.linearAttenuation, 0.5f);
  EXPECT_FLOAT_EQ(point.quadraticAttenuation, 0.25f);
  // `V:5.0` without a space, as cpfg-GeneralizedCylinder writes it; the rest are defaults.
  const LightSource& sun = view.lights[1];
  EXPECT_TRUE(sun.directional);
  expectVector(sun.vector, 5, 6, 10);
  expectVector(sun.ambient, 1, 1, 1);
  EXPECT_FALSE(sun.spot);

  EXPECT_EQ(view.contourSides, 12);
  ASSERT_EQ(view.contours.size(), 1u);
  EXPECT_EQ(view.contours[0].id, 3);
  EXPECT_EQ(view.contours[0].file, (kFixtures / "square.con").string());
  EXPECT_EQ(view.contours[0].where.line, 33);
  EXPECT_EQ(view.contours[0].where.column, 12);
  EXPECT_TRUE(view.twistOfCylinders);

  ASSERT_EQ(view.surfaces.size(), 1u);
  const SurfaceDeclaration& leaf = view.surfaces[0];
  EXPECT_EQ(leaf.id, 'l');
  EXPECT_EQ(leaf.file, (kFixtures / "leaf.s").string());
  EXPECT_FLOAT_EQ(leaf.size, 2.5f);
  EXPECT_EQ(leaf.sPrecision, 8);
  EXPECT_EQ(leaf.tPrecision, 4);
  EXPECT_EQ(leaf.texture, 1);

  ASSERT_EQ(view.textures.size(), 1u);
  const TextureDeclaration& stripes = view.textures[0];
  EXPECT_EQ(stripes.file, (kFixtures / "stripes.png").string());
  EXPECT_EQ(stripes.mode, 'd');
  EXPECT_TRUE(stripes.perSurface);
  EXPECT_FLOAT_EQ(stripes.ratio, 0.5f);
  EXPECT_TRUE(stripes.magnifyLinear);
  EXPECT_EQ(stripes.minify, "mnl");

  ASSERT_EQ(view.tropisms.size(), 2u);
  const Tropism& down = view.tropisms[0];
  EXPECT_FALSE(down.torque);
  expectVector(down.direction, 0, -1, 0);  // `T: 0,-1,0`: commas separate too
  EXPECT_FLOAT_EQ(down.angle, 90);
  EXPECT_FLOAT_EQ(down.intensity, 2);
  EXPECT_FLOAT_EQ(down.elasticity, 0.3f);
  EXPECT_FLOAT_EQ(down.elasticityStep, 0.05f);
  const Tropism& twist = view.tropisms[1];
  EXPECT_TRUE(twist.torque);
  EXPECT_FLOAT_EQ(twist.angle, 0);  // cpfg ignores A: for torques
  EXPECT_FLOAT_EQ(twist.elasticity, 0.1f);

  expectVector(view.tropismDirection, 0, -2, 0);
  EXPECT_FLOAT_EQ(view.initialElasticity, 0.02f);
  EXPECT_FLOAT_EQ(view.elasticityIncrement, 0.01f);
  ASSERT_EQ(view.backgroundScenes.size(), 2u);
  EXPECT_EQ(view.backgroundScenes[1], (kFixtures / "sky.dat").string());

  ASSERT_EQ(view.organ<HairSettings>().templates.size(), 2u);
  EXPECT_EQ(view.organ<HairSettings>().templates[0].file, (kFixtures / "straight.l").string());
  EXPECT_EQ(view.organ<HairSettings>().templates[1].file, (kFixtures / "curly.l").string());
  EXPECT_GT(view.organ<HairSettings>().templates[1].where.line,
            view.organ<HairSettings>().templates[0].where.line);
  EXPECT_EQ(view.organ<HairSettings>().textureSize, 64);
  EXPECT_EQ(view.organ<HairSettings>().textureSeed, 7u);
  EXPECT_TRUE(view.organ<HairSettings>().interpolation);
}

TEST(ViewFileTest, LegacyCommandsAreReadAsCpfgDoes) {
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("legacy.v", diagnostics);
  for (const Diagnostic& d : diagnostics.warnings()) ADD_FAILURE() << d.text();
  EXPECT_EQ(view.renderMode, RenderMode::Shaded);  // shade mode 3: Gouraud shading
  EXPECT_EQ(view.contourSides, 8);                 // polygonization level 2: 2^(2+1)
  // function:, curve: (read by lsys), line: (obsolete), font:, cue range: leave no trace here.
  EXPECT_TRUE(view.surfaces.empty());
}

TEST(ViewFileTest, InitialLineWidthUnitSetsTheLineStyle) {
  Diagnostics diagnostics;
  const auto read = [&](const std::string& text) {
    return parseViewFile(text, kFixtures / "width.v", diagnostics);
  };
  ViewSettings view = read("initial line width: 2 pixels\n");
  EXPECT_EQ(view.lineStyle, LineStyle::Pixel);
  EXPECT_TRUE(view.lineWidthInPixels);
  EXPECT_FLOAT_EQ(view.initialLineWidth, 2);
  view = read("initial line width: 0.1\n");
  EXPECT_EQ(view.lineStyle, LineStyle::Polygon);
  EXPECT_FALSE(view.lineWidthInPixels);
  view = read("initial line width: 0.1 s\n");
  EXPECT_EQ(view.lineStyle, LineStyle::Cylinder);
  // A later `line style:` overrides the unit; a bogus one keeps the previous style.
  view = read("initial line width: 3 p\nline style: cylinder\n");
  EXPECT_EQ(view.lineStyle, LineStyle::Cylinder);
  EXPECT_FALSE(view.lineWidthInPixels);
  view = read("line style: polygon\nline style: wireframe\n");
  EXPECT_EQ(view.lineStyle, LineStyle::Polygon);
  EXPECT_TRUE(diagnostics.warnings().size() == 1u);
}

TEST(ViewFileTest, RenderModesByWordAndNumber) {
  Diagnostics diagnostics;
  const auto mode = [&](const std::string& text) {
    return parseViewFile(text, kFixtures / "mode.v", diagnostics).renderMode;
  };
  EXPECT_EQ(mode("render mode: shaded\n"), RenderMode::Shaded);
  EXPECT_EQ(mode("render mode: shadows\n"), RenderMode::Shadows);
  EXPECT_EQ(mode("render mode: 1\n"), RenderMode::Wireframe);
  EXPECT_EQ(mode("render mode: 6\n"), RenderMode::Fast);
  EXPECT_EQ(mode("shade mode: 1\n"), RenderMode::Filled);
  EXPECT_EQ(mode("shade mode: 2\n"), RenderMode::Interpolated);
  EXPECT_EQ(mode("shade mode: 7\n"), RenderMode::Wireframe);
  EXPECT_TRUE(diagnostics.warnings().empty());
  EXPECT_EQ(mode("render mode: glossy\n"), RenderMode::Filled);
  EXPECT_EQ(diagnostics.warnings().size(), 1u);
}

TEST(ViewFileTest, SidesScaleAndAngleEdgeCases) {
  Diagnostics diagnostics;
  const auto read = [&](const std::string& text) {
    return parseViewFile(text, kFixtures / "edges.v", diagnostics);
  };
  EXPECT_EQ(read("contour sides: 2\n").contourSides, 3);  // cpfg: fewer than 3 read as 3
  EXPECT_EQ(read("polygonization level: 4\n").contourSides, 32);
  EXPECT_FLOAT_EQ(read("scale factor: 0\n").scaleFactor, 1);  // cpfg: 0 is full size
  EXPECT_FLOAT_EQ(read("angle factor: 12\n").angleIncrement, 30);
  EXPECT_TRUE(diagnostics.warnings().empty());
  EXPECT_FLOAT_EQ(read("angle factor: 0\n").angleIncrement, 45);
  EXPECT_EQ(read("initial color: -3\n").initialColor, 128);
  EXPECT_EQ(diagnostics.warnings().size(), 2u);
}

TEST(ViewFileTest, LabelsMustBeSpelledExactly) {
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("labels.v", diagnostics);
  // Only the first line (leading spaces are skipped) sets the angle; the capitalised label,
  // the doubled space, the tab-indented line and the space before ':' are unknown to cpfg.
  EXPECT_FLOAT_EQ(view.angleIncrement, 30);
  EXPECT_EQ(view.initialColor, 7);
  ASSERT_EQ(diagnostics.warnings().size(), 5u);
  const Diagnostic& capitalised = diagnostics.warnings()[0];
  EXPECT_EQ(capitalised.where.line, 2);
  EXPECT_EQ(capitalised.where.column, 1);
  EXPECT_NE(capitalised.message.find("exact spelling 'angle increment:'"), std::string::npos)
      << capitalised.message;
  EXPECT_EQ(diagnostics.warnings()[1].where.line, 3);
  EXPECT_NE(diagnostics.warnings()[1].message.find("exact spelling"), std::string::npos);
  EXPECT_EQ(diagnostics.warnings()[2].where.line, 4);
  EXPECT_EQ(diagnostics.warnings()[3].where.line, 5);
  const Diagnostic& noColon = diagnostics.warnings()[4];
  EXPECT_EQ(noColon.where.line, 6);
  EXPECT_NE(noColon.message.find("expected a command"), std::string::npos) << noColon.message;
}

TEST(ViewFileTest, EachOrgansLinesAreCommandsOfTheViewFile) {
  // One table of lines an organ, in the order of the module tables; every label is a command
  // of the view file: written without arguments it is read (a warning or an error about its
  // arguments), never "unknown".
  ASSERT_EQ(organViewLines().size(), organModuleTables().size());
  std::size_t labels = 0;
  for (std::span<const ViewLineCommand> lines : organViewLines()) {
    EXPECT_FALSE(lines.empty());
    for (const ViewLineCommand& line : lines) {
      ++labels;
      EXPECT_EQ(line.label.back(), ':') << line.label;
      Diagnostics diagnostics;
      const std::filesystem::path file = "organ.v";
      try {
        parseViewFile(std::string(line.label) + "\n", file, diagnostics);
      } catch (const DiagnosticError&) {
      }
      for (const Diagnostic& warning : diagnostics.warnings())
        EXPECT_EQ(warning.message.find("unknown command"), std::string::npos) << warning.message;
    }
  }
  EXPECT_GE(labels, 3u);
}

TEST(ViewFileTest, BrokenSettingIsAWarningAndKeepsTheValue) {
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("broken_settings.v", diagnostics);
  const std::string file = (kFixtures / "broken_settings.v").string();
  EXPECT_FLOAT_EQ(view.angleIncrement, 45);
  expectVector(view.viewpoint, 0, 0, 1);
  EXPECT_EQ(view.lineStyle, LineStyle::Pixel);
  EXPECT_FLOAT_EQ(view.scaleFactor, 0.9f);
  EXPECT_EQ(view.initialColor, 5);
  ASSERT_EQ(diagnostics.warnings().size(), 4u);
  EXPECT_EQ(diagnostics.warnings()[0].text(),
            file +
                ":1:18: warning: expected a number after 'angle increment:', found '?'; the "
                "line is ignored");
  // `viewpoint: 0 0 1`: cpfg's sscanf needs the commas.
  EXPECT_EQ(diagnostics.warnings()[1].where.line, 2);
  EXPECT_EQ(diagnostics.warnings()[1].where.column, 14);
  EXPECT_NE(diagnostics.warnings()[1].message.find("separated by commas"), std::string::npos);
  EXPECT_EQ(diagnostics.warnings()[2].where.line, 3);
  EXPECT_EQ(diagnostics.warnings()[3].text(),
            file + ":4:19: warning: 'extra' after the arguments of 'scale factor:' is ignored");
}

// A size past int's range was cast to int (undefined behaviour); found by view_file_fuzzer.
TEST(ViewFileTest, ShadowMapSizeOutOfRangeIsIgnoredWithAWarning) {
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("shadow_map_size.v", diagnostics);
  const std::string file = (kFixtures / "shadow_map_size.v").string();
  EXPECT_EQ(view.shadowMap.size, 4096);  // the last good line
  ASSERT_EQ(diagnostics.warnings().size(), 3u);
  EXPECT_EQ(diagnostics.warnings()[0].text(),
            file + ":2:19: warning: the shadow map size must be from 1 to 16384; the line is "
                   "ignored");
  EXPECT_EQ(diagnostics.warnings()[1].where.line, 3);
  EXPECT_EQ(diagnostics.warnings()[2].where.line, 4);
}

TEST(ViewFileTest, BrokenDeclarationIsAnErrorAtItsLine) {
  Diagnostics diagnostics;
  const auto errorOf = [&](const std::string& name) {
    return diagnosticOf([&] { parseFixture(name, diagnostics); });
  };
  Diagnostic d = errorOf("broken_light.v");
  EXPECT_EQ(d.where.fileName(), (kFixtures / "broken_light.v").string());
  EXPECT_EQ(d.where.line, 2);
  EXPECT_EQ(d.where.column, 13);
  EXPECT_EQ(d.message, "expected three coordinates after 'V:' in 'light:', found 'x'");

  d = errorOf("tropism_without_direction.v");
  EXPECT_EQ(d.where.line, 3);
  EXPECT_EQ(d.where.column, 1);  // the whole line: its label
  EXPECT_NE(d.message.find("needs a direction 'T: x y z'"), std::string::npos) << d.message;

  d = errorOf("texture_without_file.v");
  EXPECT_EQ(d.where.line, 1);
  EXPECT_NE(d.message.find("'F: file'"), std::string::npos) << d.message;

  d = errorOf("contour_without_id.v");
  EXPECT_EQ(d.where.line, 2);
  EXPECT_EQ(d.where.column, 10);
  EXPECT_EQ(d.message, "expected a contour id after 'contour:', found 'one'");

  d = errorOf("surface_without_size.v");
  EXPECT_EQ(d.where.line, 2);
  EXPECT_NE(d.message.find("expected the surface's size"), std::string::npos) << d.message;

  d = errorOf("hair_texture_zero.v");
  EXPECT_EQ(d.where.line, 1);
  EXPECT_EQ(d.where.column, 15);
  EXPECT_NE(d.message.find("from 4 to 4096"), std::string::npos) << d.message;

  d = diagnosticOf(
      [&] { parseViewFile("surface: leaf leaf.s 1\n", kFixtures / "id.v", diagnostics); });
  EXPECT_NE(d.message.find("one character"), std::string::npos) << d.message;
  d = diagnosticOf([&] { parseViewFile("light: Q: 1 2 3\n", kFixtures / "q.v", diagnostics); });
  EXPECT_EQ(d.where.column, 8);
}

TEST(ViewFileTest, LineMarkersGiveTheUsersLine) {
  // As the preprocessor leaves the text: `# 7 "plant.v"` makes the next line line 7 of plant.v.
  Diagnostics diagnostics;
  const ViewSettings view = parseFixture("preprocessed.vi", diagnostics);
  EXPECT_FLOAT_EQ(view.angleIncrement, 30);
  EXPECT_EQ(view.initialColor, 3);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0].where.fileName(), "plant.v");
  EXPECT_EQ(diagnostics.warnings()[0].where.line, 8);
  EXPECT_EQ(diagnostics.warnings()[0].where.column, 14);
}

TEST(ViewFileTest, ViewFileGoesThroughThePreprocessor) {
  Diagnostics diagnostics;
  const ModelResources resources =
      loadModelResources(kFixtures / "with_macros.v", ColorFiles{}, diagnostics);
  for (const Diagnostic& d : diagnostics.warnings()) ADD_FAILURE() << d.text();
  EXPECT_FLOAT_EQ(resources.view.angleIncrement, 22.5f);
  EXPECT_EQ(resources.view.contourSides, 6);
  // The commented-out `line style: pixel` is not read.
  EXPECT_EQ(resources.view.lineStyle, LineStyle::Cylinder);
}

TEST(ViewFileTest, EveryConformanceViewFileLoads) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kConformance)) {
    if (entry.path().extension() != ".v") continue;
    SCOPED_TRACE(entry.path().string());
    Diagnostics diagnostics;
    const ModelResources resources = loadModelResources(entry.path(), ColorFiles{}, diagnostics);
    // Every contour, surface and texture declared was found, except cpfg-Sedge's bract.s, which
    // the model library does not have either.
    std::size_t missingSurfaces = 0;
    for (const SurfaceDeclaration& s : resources.view.surfaces) {
      missingSurfaces += resources.surfaces.count(s.id) == 0 ? 1 : 0;
    }
    const bool namesBract = readText(entry.path()).find("bract.s") != std::string::npos;
    EXPECT_EQ(missingSurfaces, namesBract ? 1u : 0u);
    for (const ContourDeclaration& c : resources.view.contours)
      EXPECT_TRUE(resources.contours.has(c.id));
    for (const Texture& t : resources.textures) EXPECT_GT(t.width, 0) << t.file;
    ++loaded;
  }
  EXPECT_GE(loaded, 50);
}

TEST(ViewFileTest, ConformanceSettingsMatchTheirFiles) {
  if (!std::filesystem::is_directory(kConformance)) {
    GTEST_SKIP() << "no conformance set at " << kConformance;
  }
  Diagnostics diagnostics;
  // tools-FernLeaf writes `D 0.6 0.6 0.6` without the colon; enviro-CPFG-Ecosystem separates
  // light coordinates by commas; cpfg-Tropisms has tropisms, a torque and a contour.
  ViewSettings fern =
      loadModelResources(kConformance / "tools-FernLeaf" / "plant.v", {}, diagnostics).view;
  ASSERT_EQ(fern.lights.size(), 2u);
  expectVector(fern.lights[1].diffuse, 0.6f, 0.6f, 0.6f);
  EXPECT_EQ(fern.contourSides, 14);
  EXPECT_FLOAT_EQ(fern.angleIncrement, 20);
  ViewSettings ecosystem =
      loadModelResources(kConformance / "enviro-CPFG-Ecosystem" / "tree.v", {}, diagnostics).view;
  ASSERT_EQ(ecosystem.lights.size(), 1u);
  expectVector(ecosystem.lights[0].vector, 1.0f, 0.5f, 0.5f);
  ViewSettings tropisms =
      loadModelResources(kConformance / "cpfg-Tropisms" / "view.v", {}, diagnostics).view;
  ASSERT_EQ(tropisms.tropisms.size(), 3u);
  EXPECT_FLOAT_EQ(tropisms.tropisms[1].angle, 90);
  EXPECT_TRUE(tropisms.tropisms[2].torque);
  EXPECT_EQ(tropisms.contourSides, 16);  // polygonization level: 3
  // 01-Introduction-02-snowflake-exercise leaves the angle for the student: `angle increment: ?`.
  Diagnostics exercise;
  ViewSettings snowflake =
      loadModelResources(kConformance / "01-Introduction-02-snowflake-exercise" / "fractal.v", {},
                         exercise)
          .view;
  EXPECT_FLOAT_EQ(snowflake.angleIncrement, 45);
  ASSERT_EQ(exercise.warnings().size(), 1u);
  EXPECT_EQ(exercise.warnings()[0].where.line, 1);
}

}  // namespace
}  // namespace hirsute

namespace hirsute {
namespace {

// The path tracer's lines (docs/trace.md) set its light, sky and materials, and refuse values
// out of range at the value.
// The error a view file's text stops with, or "" when it parses.
std::string viewFileError(const std::string& text, const char* file) {
  Diagnostics d;
  try {
    parseViewFile(text, file, d);
  } catch (const DiagnosticError& e) {
    return e.diagnostic().text();
  }
  return "";
}

TEST(ViewFileTest, TheTracersLinesSetItsLightsAndMaterials) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "trace light: D: -0.3,0.6,-1 A: 6 I: 4,3.9,3.6\ntrace sky: 0.1,0.2,0.3\n"
      "trace up: 0,0,1\ntranslucency: 4 0.45\ntranslucency: 7 1\n"
      "hair shading: B: 0.25 R: 0.2 S: 0.06\n",
      "trace.v", diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty());
  const TraceSettings& t = view.trace;
  ASSERT_TRUE(t.lightDirection.has_value());
  EXPECT_EQ(*t.lightDirection, glm::vec3(-0.3f, 0.6f, -1));
  EXPECT_FLOAT_EQ(t.lightAngle, 6);
  EXPECT_EQ(t.lightIrradiance, glm::vec3(4, 3.9f, 3.6f));
  EXPECT_EQ(t.sky, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(t.up, glm::vec3(0, 0, 1));
  ASSERT_EQ(t.translucent.size(), 2u);
  EXPECT_EQ(t.translucent[0], (std::pair<int, float>(4, 0.45f)));
  EXPECT_FLOAT_EQ(t.hairBackscatter, 0.25f);
  EXPECT_FLOAT_EQ(t.hairRoughness, 0.2f);
  EXPECT_FLOAT_EQ(t.hairSpecular, 0.06f);

  auto errorOf = [](const std::string& text) { return viewFileError(text, "trace.v"); };
  EXPECT_NE(errorOf("trace light: A: 400\n").find("trace.v:1:17: error:"), std::string::npos)
      << errorOf("trace light: A: 400\n");
  EXPECT_NE(errorOf("trace light: I: 1,1,1e30\n").find("must be from 0 to 10000"),
            std::string::npos);
  EXPECT_NE(errorOf("trace light: D: 0,0,0\n").find("the light's direction is zero"),
            std::string::npos);
  EXPECT_NE(errorOf("translucency: 4 1.5\n").find("trace.v:1:17: error:"), std::string::npos)
      << errorOf("translucency: 4 1.5\n");
  EXPECT_NE(errorOf("hair shading: B: nan\n").find("trace.v:1:"), std::string::npos)
      << errorOf("hair shading: B: nan\n");
}

TEST(ViewFileTest, TheTracersSkyCameraAndSubsurfaceLines) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "subsurface: 5 M: 0.004 H: 0.03 A: 0.9,0.7,0.95\nsubsurface: 3 M: 0.01 H: 0.02\n"
      "trace sun: E: 25 A: 160 T: 4 G: 0.3 B: off\ntrace ground: 0.2,0.3,0.1\n"
      "trace exposure: 1.5\ntrace tone: filmic\ntrace filter: mitchell\ntrace aperture: 0.5\n"
      "trace focus: 12\n",
      "trace.v", diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty());
  const TraceSettings& t = view.trace;
  ASSERT_EQ(t.subsurface.size(), 2u);
  EXPECT_EQ(t.subsurface[0].colour, 5);
  EXPECT_FLOAT_EQ(t.subsurface[0].meanFreePath, 0.004f);
  EXPECT_FLOAT_EQ(t.subsurface[0].thickness, 0.03f);
  ASSERT_TRUE(t.subsurface[0].albedo.has_value());
  EXPECT_EQ(*t.subsurface[0].albedo, glm::vec3(0.9f, 0.7f, 0.95f));
  EXPECT_FALSE(t.subsurface[1].albedo.has_value());
  ASSERT_TRUE(t.sun.has_value());
  EXPECT_FLOAT_EQ(t.sun->elevation, 25);
  EXPECT_FLOAT_EQ(t.sun->azimuth, 160);
  EXPECT_FLOAT_EQ(t.sun->turbidity, 4);
  EXPECT_FLOAT_EQ(t.sun->groundAlbedo, 0.3f);
  EXPECT_FALSE(t.skySeen);
  EXPECT_EQ(t.ground, glm::vec3(0.2f, 0.3f, 0.1f));
  EXPECT_EQ(t.exposure, 1.5f);
  EXPECT_EQ(t.tone, "filmic");
  EXPECT_EQ(t.filter, "mitchell");
  EXPECT_EQ(t.aperture, 0.5f);
  EXPECT_EQ(t.focus, 12.0f);

  const ViewSettings map =
      parseViewFile("trace environment: sky.exr S: 2 R: -90\n", "trace.v", diagnostics);
  EXPECT_EQ(map.trace.environment, "sky.exr");
  EXPECT_FLOAT_EQ(map.trace.environmentScale, 2);
  EXPECT_FLOAT_EQ(map.trace.environmentRotation, -90);
  EXPECT_EQ(map.trace.environmentAt.line, 1);
  EXPECT_EQ(map.trace.environmentAt.column, 20);

  auto errorOf = [](const std::string& text) { return viewFileError(text, "trace.v"); };
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"subsurface: 5 M: 0 H: 1\n", "trace.v:1:18: error:"},
           {"subsurface: 5 M: 0.1\n", "needs a mean free path 'M:' and a thickness 'H:'"},
           {"subsurface: 5 M: 0.001 H: 1\n", "more than 100 mean free paths"},
           {"subsurface: 5 M: 0.1 H: 1 A: 1.2,1,1\n", "trace.v:1:30: error:"},
           {"trace sun: E: 95\n", "trace.v:1:15: error: the value 95"},
           {"trace sun: T: 1\n", "must be from 2 to 10"},
           {"trace sun: B: maybe\n", "expected on or off"},
           {"trace ground: 0.2,2,0.1\n", "trace.v:1:19: error:"},
           {"trace environment: /etc/passwd\n", "trace.v:1:20: error: cannot open"},
           {"trace environment: sky.exr Q: 1\n", "expected 'S: scale'"},
           {"trace exposure: 30\n", "trace.v:1:17: error: expected a number from -20 to 20"},
           {"trace tone: aces\n", "expected one of none, filmic"},
           {"trace filter: lanczos\n", "expected one of box, gaussian, mitchell"},
           {"trace focus: 0\n", "trace.v:1:14: error:"},
       }) {
    EXPECT_NE(errorOf(text).find(expected), std::string::npos) << text << errorOf(text);
  }
}

// Each colour's veins cost the tracer four maps: a view file may give veins to 64 colours.
TEST(ViewFileTest, VeinsHaveALimitOfColours) {
  std::string text;
  for (int colour = 1; colour <= 64; ++colour)
    text += "veins: " + std::to_string(colour) + " splines\n";
  Diagnostics diagnostics;
  EXPECT_EQ(parseViewFile(text, "veins.v", diagnostics).trace.veins.size(), 64u);
  const std::string error = viewFileError(text + "veins: 65 particles\n", "veins.v");
  EXPECT_NE(error.find("veins.v:65:1: error: more than 64 colours with veins"), std::string::npos)
      << error;
}

TEST(ViewFileTest, VeinsLinesSetEachColoursPattern) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "veins: 5 splines C: 0.3,0.12,0.5 W: 0.02 B: 0.8\n"
      "veins: 4 particles N: 90 K: 0.6 S: 7\n"
      "veins: 5 particles\n",  // replaces the first line's
      "veins.v", diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty());
  const std::vector<VeinSettings>& veins = view.trace.veins;
  ASSERT_EQ(veins.size(), 2u);
  EXPECT_EQ(veins[0].colour, 4);
  EXPECT_EQ(veins[0].pattern, VeinPattern::Particles);
  EXPECT_EQ(veins[0].count, 90);
  EXPECT_FLOAT_EQ(veins[0].strength, 0.6f);
  EXPECT_EQ(veins[0].seed, 7u);
  EXPECT_FALSE(veins[0].veinColour.has_value());
  EXPECT_EQ(veins[1].colour, 5);
  EXPECT_EQ(veins[1].pattern, VeinPattern::Particles);
  EXPECT_FLOAT_EQ(veins[1].width, 0.012f);  // the default, not the replaced line's

  auto errorOf = [](const std::string& text) { return viewFileError(text, "veins.v"); };
  EXPECT_NE(errorOf("veins: 5 spiral\n").find("veins.v:1:10: error: expected the pattern"),
            std::string::npos)
      << errorOf("veins: 5 spiral\n");
  EXPECT_NE(errorOf("veins: 5x splines\n").find("veins.v:1:8: error: expected a colour index"),
            std::string::npos)
      << errorOf("veins: 5x splines\n");
  EXPECT_NE(errorOf("veins: 5 splines W: 2\n").find("veins.v:1:21: error:"), std::string::npos)
      << errorOf("veins: 5 splines W: 2\n");
  EXPECT_NE(errorOf("veins: 5 splines N: 1e9\n").find("must be from 1 to 2000"), std::string::npos);
  EXPECT_NE(errorOf("veins: 5 splines Q: 1\n").find("found 'Q:'"), std::string::npos)
      << errorOf("veins: 5 splines Q: 1\n");
}

// `fibre:` lines choose the hairs' scattering model by template, fur colour or organ.
TEST(ViewFileTest, FibreLinesChooseTheModelPerKindOfHair) {
  Diagnostics diagnostics;
  const ViewSettings view = parseViewFile(
      "fibre: hairs chiang L: 0.25 A: 0.4 T: 3 E: 1.5\nfibre: hairs 2 kajiya\n"
      "fibre: fur 7 chiang M: 1.3,0.2\nfibre: feathers chiang C: 0.9,0.8,0.7\n"
      "fibre: hairs 2 chiang\n",
      "fibre.v", diagnostics);
  const std::vector<FibreSettings>& f = view.trace.fibres;
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].organ, FibreOrgan::Hairs);
  EXPECT_EQ(f[0].index, -1);
  EXPECT_FLOAT_EQ(f[0].longitudinalRoughness, 0.25f);
  EXPECT_FLOAT_EQ(f[0].azimuthalRoughness, 0.4f);
  EXPECT_FLOAT_EQ(f[0].tiltDegrees, 3);
  EXPECT_FLOAT_EQ(f[0].eta, 1.5f);
  EXPECT_EQ(f[1].organ, FibreOrgan::Fur);
  EXPECT_EQ(f[1].index, 7);
  ASSERT_TRUE(f[1].melanin.has_value());
  EXPECT_EQ(*f[1].melanin, glm::vec2(1.3f, 0.2f));
  EXPECT_EQ(f[2].organ, FibreOrgan::Feathers);
  EXPECT_EQ(*f[2].colour, glm::vec3(0.9f, 0.8f, 0.7f));
  // The later line for template 2 replaced the earlier.
  EXPECT_EQ(f[3].index, 2);
  EXPECT_EQ(f[3].model, FibreModel::Chiang);

  auto errorOf = [](const std::string& text) { return viewFileError(text, "fibre.v"); };
  EXPECT_NE(errorOf("fibre: hair chiang\n").find("fibre.v:1:8: error: expected 'hairs', 'fur' or"),
            std::string::npos)
      << errorOf("fibre: hair chiang\n");
  EXPECT_NE(errorOf("fibre: hairs 0 chiang\n").find("fibre.v:1:14: error:"), std::string::npos)
      << errorOf("fibre: hairs 0 chiang\n");
  EXPECT_NE(errorOf("fibre: fur marschner\n").find("expected the model 'chiang' or 'kajiya'"),
            std::string::npos);
  EXPECT_NE(errorOf("fibre: hairs chiang L: 2\n").find("fibre.v:1:24: error:"), std::string::npos)
      << errorOf("fibre: hairs chiang L: 2\n");
  EXPECT_NE(errorOf("fibre: hairs kajiya L: 0.2\n").find("from 'hair shading:'"),
            std::string::npos);
  EXPECT_NE(errorOf("fibre: hairs chiang C: 1,1,1 M: 1,0\n").find("not both"), std::string::npos);
}

}  // namespace
}  // namespace hirsute
