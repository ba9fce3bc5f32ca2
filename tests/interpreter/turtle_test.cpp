// The turtle: cpfg's conventions for the frame and its rotations, what F, polygons, spheres,
// discs, surfaces and tropisms draw, the cut, sub-L-system scale, and the query pass
// (cpfg-features.md (d)). Fixture models are in tests/fixtures/interpreter/turtle.
#include "hirsute/interpreter/turtle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures =
    fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter" / "turtle";
constexpr double kTolerance = 1e-6;

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected,
                double tolerance = kTolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << "x";
  EXPECT_NEAR(actual.y, expected.y, tolerance) << "y";
  EXPECT_NEAR(actual.z, expected.z, tolerance) << "z";
}

void expectOrthonormal(const TurtleState& s, double tolerance = 1e-9) {
  EXPECT_NEAR(glm::length(s.heading), 1, tolerance);
  EXPECT_NEAR(glm::length(s.left), 1, tolerance);
  EXPECT_NEAR(glm::length(s.up), 1, tolerance);
  EXPECT_NEAR(glm::dot(s.heading, s.left), 0, tolerance);
  EXPECT_NEAR(glm::dot(s.heading, s.up), 0, tolerance);
  EXPECT_NEAR(glm::dot(s.left, s.up), 0, tolerance);
  // cpfg's handedness: U = L × H (the initial frame H = +y, L = -x, U = -z).
  expectNear(glm::cross(s.left, s.heading), s.up, tolerance);
}

// Feeds modules to a turtle by hand: "name" for a module, with its parameters.
struct Feeder {
  Turtle& turtle;
  void operator()(char symbol, std::vector<float> parameters = {}) {
    turtle.module(symbol, parameters.data(), parameters.size());
  }
};

// A fixture model derived and drawn as `hirsute render` would.
struct Drawn {
  Scene scene;
  Turtle::Counts counts;
  TurtleState state;
  std::string string;  // the derived string, compact
};

std::string compactString(Derivation& derivation) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, StringFormat::Compact);
    derivation.emit(writer, false);
    writer.finish();
  }
  std::fclose(memory);
  std::string text(buffer, size);
  std::free(buffer);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

Drawn draw(const std::string& lsystem, const std::string& view = "") {
  Diagnostics diagnostics;
  std::optional<fs::path> viewFile;
  if (!view.empty()) viewFile = kFixtures / view;
  Model model = loadModel(kFixtures / lsystem, viewFile, diagnostics);
  ModelResources resources = loadModelResources(viewFile, {}, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  Derivation derivation(model.program, evaluator, diagnostics);
  installQueryPass(derivation, resources, diagnostics);
  derivation.run();
  Drawn drawn;
  Turtle turtle(resources, &drawn.scene, diagnostics);
  turtle.setSourceString(&derivation.mutableString());
  turtle.setStrings(&model.program.strings);
  derivation.emit(turtle, true);
  turtle.finish();
  drawn.counts = turtle.counts();
  drawn.state = turtle.state();
  drawn.string = compactString(derivation);
  return drawn;
}

double triangleArea(const TriangleMesh& mesh, std::size_t t) {
  const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]),
      b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
  return glm::length(glm::cross(b - a, c - a)) / 2;
}

// ---- conventions --------------------------------------------------------------------------

TEST(TurtleConventions, InitialTurtleIsCpfgs) {
  ModelResources resources;
  resources.view.initialLineWidth = 3;
  resources.view.initialColor = 17;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  expectNear(turtle.state().position, {0, 0, 0});
  expectNear(turtle.state().heading, {0, 1, 0});
  expectNear(turtle.state().left, {-1, 0, 0});
  expectNear(turtle.state().up, {0, 0, -1});
  EXPECT_EQ(turtle.state().lineWidth, 3);
  EXPECT_EQ(turtle.state().color, 17);
  expectOrthonormal(turtle.state());
}

TEST(TurtleConventions, PlusTurnsLeftAboutUpTowardsLeft) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('+', {90});
  expectNear(turtle.state().heading, {-1, 0, 0});  // H ← H·cos + L·sin
  expectNear(turtle.state().left, {0, -1, 0});
  expectNear(turtle.state().up, {0, 0, -1});
  feed('-', {90});
  expectNear(turtle.state().heading, {0, 1, 0});
  feed('-');  // the view's angle increment, 45 by default
  expectNear(turtle.state().heading, {std::sqrt(0.5), std::sqrt(0.5), 0});
}

TEST(TurtleConventions, AmpersandPitchesDownAboutLeftTowardsUp) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('&', {90});
  expectNear(turtle.state().heading, {0, 0, -1});
  expectNear(turtle.state().up, {0, -1, 0});
  expectNear(turtle.state().left, {-1, 0, 0});
  feed('^', {90});
  expectNear(turtle.state().heading, {0, 1, 0});
  expectNear(turtle.state().up, {0, 0, -1});
}

TEST(TurtleConventions, SlashRollsRightAboutHeadingTowardsUp) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('/', {90});
  expectNear(turtle.state().left, {0, 0, -1});  // L ← L·cos + U·sin
  expectNear(turtle.state().up, {1, 0, 0});
  expectNear(turtle.state().heading, {0, 1, 0});
  feed('\\', {90});
  expectNear(turtle.state().left, {-1, 0, 0});
}

TEST(TurtleConventions, BarTurnsHalfwayAboutUp) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('/', {30});
  const TurtleState before = turtle.state();
  feed('|', {77});  // a parameter changes nothing
  expectNear(turtle.state().heading, -before.heading);
  expectNear(turtle.state().left, -before.left);
  expectNear(turtle.state().up, before.up);
}

TEST(TurtleConventions, RollToVerticalPutsUpInTheVerticalPlaneOfHeading) {
  for (const char* module : {"@v", "$"}) {
    ModelResources resources;
    Diagnostics diagnostics;
    Turtle turtle(resources, nullptr, diagnostics);
    Feeder feed{turtle};
    feed('&', {30});
    feed('/', {40});
    feed('+', {20});
    const glm::dvec3 heading = turtle.state().heading;
    if (module[0] == '@') {
      feed('@');
      feed('v');
    } else {
      feed('$');  // outside a sub-L-system: ABOP's $
    }
    SCOPED_TRACE(module);
    expectNear(turtle.state().heading, heading);
    EXPECT_NEAR(turtle.state().left.y, 0, 1e-12);  // L horizontal
    EXPECT_GT(turtle.state().up.y, 0);             // U on the side of +y
    expectOrthonormal(turtle.state());
  }
}

TEST(TurtleConventions, SetHeadingTurnsTheFrameLeastOrToTheGivenUp) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('@');
  feed('R', {2, 0, 0});
  expectNear(turtle.state().heading, {1, 0, 0});
  expectNear(turtle.state().up, {0, 0, -1});  // the turn about U leaves U
  expectNear(turtle.state().left, {0, 1, 0});
  feed('@');
  feed('R', {0, 0, 1, 0, 3, 0});
  expectNear(turtle.state().heading, {0, 0, 1});
  expectNear(turtle.state().up, {0, 1, 0});
  expectOrthonormal(turtle.state());
  feed('@');
  feed('M', {1, 2, 3});
  expectNear(turtle.state().position, {1, 2, 3});
}

TEST(TurtleConventions, FrameStaysOrthonormalOverAMillionRandomRotations) {
  ModelResources resources;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  std::mt19937 random(20261121);
  std::uniform_real_distribution<float> angle(-180, 180);
  const char symbols[] = "+-&^/\\|";
  for (int i = 0; i < 1'000'000; ++i) {
    const float a = angle(random);
    turtle.module(symbols[random() % 7], &a, 1);
  }
  expectOrthonormal(turtle.state(), 1e-12);
}

// ---- modules with several characters, turtle parameters ---------------------------------

TEST(TurtleModules, ParametersBelongToTheLastCharacter) {
  ModelResources resources;
  resources.view.tropisms.push_back(Tropism{});
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('@'), feed('T'), feed('s', {1, 0.25f});
  EXPECT_DOUBLE_EQ(turtle.state().elasticity[0], 0.25);
  feed('@'), feed('G'), feed('t', {2, 3});
  EXPECT_EQ(turtle.state().tangentParameter[0], 2);
  EXPECT_EQ(turtle.state().tangentParameter[1], 3);
  feed('@'), feed('!', {5});
  EXPECT_EQ(turtle.state().cylinderSides, 5);
  feed('@'), feed('!');
  EXPECT_EQ(turtle.state().cylinderSides, 8);
  feed('@'), feed('#', {2});
  EXPECT_EQ(turtle.state().contour, 2);
  feed('@'), feed('T'), feed('x', {3});
  EXPECT_EQ(turtle.state().texture, 3);
  feed('@'), feed('D', {0.5f});
  EXPECT_DOUBLE_EQ(turtle.state().scale, 0.5);
  feed('F', {4});
  expectNear(turtle.state().position, {0, 2, 0});
}

TEST(TurtleModules, ColorsStepWithinTheirBankOf256) {
  ModelResources resources;
  resources.view.colorIncrement = 1;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  EXPECT_EQ(turtle.state().color, 128);
  feed(';', {255});
  feed(';');
  EXPECT_EQ(turtle.state().color, 0);
  feed(',');
  EXPECT_EQ(turtle.state().color, 255);
  feed(';', {511});
  feed(';');
  EXPECT_EQ(turtle.state().color, 256);
  feed(';', {7.9f});  // truncated, as cpfg reads it
  EXPECT_EQ(turtle.state().color, 7);
}

TEST(TurtleModules, WidthsChangeByTheIncrementAndStayPositive) {
  ModelResources resources;
  resources.view.lineWidthIncrement = 0.5f;
  Diagnostics diagnostics;
  Turtle turtle(resources, nullptr, diagnostics);
  Feeder feed{turtle};
  feed('#');
  EXPECT_DOUBLE_EQ(turtle.state().lineWidth, 1.5);
  feed('!');
  feed('!');
  EXPECT_DOUBLE_EQ(turtle.state().lineWidth, 0.5);
  feed('#', {0});
  EXPECT_DOUBLE_EQ(turtle.state().lineWidth, 1e-7);  // cpfg's floor
}

TEST(TurtleModules, SubLsystemScalesItsModulesAndReturns) {
  ModelResources resources;
  Diagnostics diagnostics;
  Scene scene;
  Turtle turtle(resources, &scene, diagnostics);
  Feeder feed{turtle};
  feed('F');
  feed('?', {2, 0.5f});
  feed('F', {2});
  feed('#', {4});
  feed('$');
  feed('F');
  turtle.finish();
  ASSERT_EQ(scene.lines.size(), 3u);
  EXPECT_FLOAT_EQ(glm::length(scene.lines[1].to - scene.lines[1].from), 1.0f);
  EXPECT_FLOAT_EQ(scene.lines[1].widthTo, 2.0f);           // #(4) in the sub-L-system is scaled too
  expectNear(glm::dvec3(scene.lines[2].from), {0, 1, 0});  // `$` returns to the caller's state
  EXPECT_DOUBLE_EQ(turtle.state().scale, 1);
}

// ---- what F draws -------------------------------------------------------------------------

TEST(TurtleSegments, FDrawsWhenTheNextNodeClosesTheSegment) {
  const Drawn d = draw("segments.l", "pixels.v");
  EXPECT_EQ(d.scene.lineStyle, LineStyle::Pixel);
  ASSERT_EQ(d.scene.lines.size(), 3u);  // F(0) draws nothing
  EXPECT_EQ(d.counts.segments, 3u);
  const LineSegment& first = d.scene.lines[0];
  expectNear(glm::dvec3(first.from), {0, 0, 0});
  expectNear(glm::dvec3(first.to), {0, 3, 0});
  EXPECT_EQ(first.widthFrom, 2);
  EXPECT_EQ(first.widthTo, 4);   // #(4) came before `[`, which closed the segment
  EXPECT_EQ(first.material, 3);  // the colour the segment started with, not ;(5)
  // The branch, then the main axis again from where `[` saved it.
  expectNear(glm::dvec3(d.scene.lines[1].from), {0, 3, 0});
  expectNear(glm::dvec3(d.scene.lines[1].to), {-2, 3, 0});
  EXPECT_EQ(d.scene.lines[1].material, 5);
  expectNear(glm::dvec3(d.scene.lines[2].from), {0, 3, 0});
  expectNear(glm::dvec3(d.scene.lines[2].to), {0, 4, 0});
  expectNear(d.state.position, {0, 4, 0});
  expectNear(d.state.heading, {0, 1, 0});
}

TEST(TurtleSegments, UntaperedLinesKeepTheStartWidth) {
  const Drawn d = draw("segments.l", "untapered.v");
  ASSERT_FALSE(d.scene.lines.empty());
  EXPECT_EQ(d.scene.lines[0].widthFrom, 2);
  EXPECT_EQ(d.scene.lines[0].widthTo, 2);
}

TEST(TurtleSegments, CylinderStyleDrawsOpenConesOfContourSides) {
  const Drawn d = draw("segments.l", "cylinders.v");
  EXPECT_TRUE(d.scene.lines.empty());
  EXPECT_EQ(d.counts.segments, 3u);
  EXPECT_EQ(d.scene.triangleCount(), 3u * 2 * 6);
  // The first cone: radius 1 at y = 0, radius 2 at y = 3, every vertex on its circle.
  const TriangleMesh* mesh = nullptr;
  for (const TriangleMesh& m : d.scene.meshes) {
    if (m.material == 3) mesh = &m;
  }
  ASSERT_NE(mesh, nullptr);
  ASSERT_EQ(mesh->positions.size(), 2u * 7);
  for (const glm::vec3& p : mesh->positions) {
    const double radius = std::hypot(p.x, p.z);
    EXPECT_NEAR(radius, p.y < 1.5 ? 1.0 : 2.0, 1e-6);
  }
  // Faces look outwards: each triangle's normal agrees with its first vertex's normal.
  for (std::size_t t = 0; t < mesh->triangleCount(); ++t) {
    const glm::vec3 a = mesh->positions[mesh->indices[3 * t]],
                    b = mesh->positions[mesh->indices[3 * t + 1]],
                    c = mesh->positions[mesh->indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), mesh->normals[mesh->indices[3 * t]]), 0);
  }
}

// ---- polygons, spheres, discs, surfaces ------------------------------------------------------

TEST(TurtlePolygons, PolygonsFillTheirAreaConcaveToo) {
  const Drawn d = draw("polygons.l");
  EXPECT_EQ(d.counts.polygons, 2u);
  EXPECT_EQ(d.counts.polygonTriangles, 2u + 4u);  // n − 2 triangles each
  double square = 0, concave = 0;
  for (const TriangleMesh& mesh : d.scene.meshes) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const bool first = mesh.positions[mesh.indices[3 * t]].y < 5;
      (first ? square : concave) += triangleArea(mesh, t);
      const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]),
          b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
      // All triangles of a polygon face the side its winding gives (no fold-over): the square
      // turns left (+) about U = -z, the L-shape mostly right.
      expectNear(glm::normalize(glm::cross(b - a, c - a)),
                 first ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 0, -1));
    }
  }
  EXPECT_NEAR(square, 4, 1e-6);
  EXPECT_NEAR(concave, 3, 1e-6);  // the L-shape: ears clipped, nothing outside it
}

TEST(TurtlePolygons, SpheresAndDiscsTakeTheirDiameterOrTheWidth) {
  const Drawn d = draw("spheres.l");
  ASSERT_EQ(d.scene.spheres.size(), 2u);
  expectNear(glm::dvec3(d.scene.spheres[0].center), {0, 2, 0});
  EXPECT_FLOAT_EQ(d.scene.spheres[0].radius, 1);
  EXPECT_FLOAT_EQ(d.scene.spheres[1].radius, 1.5);  // @O: the line width, 3
  ASSERT_EQ(d.scene.discs.size(), 2u);
  expectNear(glm::dvec3(d.scene.discs[0].center), {0, 3, 0});
  expectNear(glm::dvec3(d.scene.discs[0].normal), {0, -1, 0});  // @c lies in the HL plane: normal U
  EXPECT_FLOAT_EQ(d.scene.discs[0].radius, 2);
  expectNear(glm::dvec3(d.scene.discs[1].normal), {0, 0, 0});  // @o faces the screen
  EXPECT_FLOAT_EQ(d.scene.discs[1].radius, 1.5);
}

TEST(TurtleSurfaces, SurfaceIsPlacedAtTheTurtleAndTheTurtleGoesOnFromItsEndPoint) {
  const Drawn d = draw("surface.l", "surface.v");
  EXPECT_EQ(d.counts.surfaces, 1u);
  EXPECT_EQ(d.counts.surfaceTriangles, 2u * 3 * 2);  // `surface: s flat.s 1 3 2`
  // The 3×3 square, contact point (1.5, 0) on the turtle at (0, 1, 0), y along H, x along L,
  // scaled by 2: x from −3 to 3, y from 1 to 7.
  Bounds bounds;
  double area = 0;
  for (const TriangleMesh& mesh : d.scene.meshes) {
    if (mesh.triangleCount() != 12) continue;
    for (const glm::vec3& p : mesh.positions) bounds.add(p);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) area += triangleArea(mesh, t);
  }
  expectNear(glm::dvec3(bounds.min), {-3, 1, 0});
  expectNear(glm::dvec3(bounds.max), {3, 7, 0});
  EXPECT_NEAR(area, 36, 1e-6);
  // F(1) after the surface starts at its end point (1.5, 3) → (0, 7, 0).
  expectNear(d.state.position, {0, 8, 0});
}

// ---- tropisms, cut, queries ----------------------------------------------------------------

TEST(TurtleTropisms, TropismBendsTowardsItsDirectionBeforeEachStep) {
  const Drawn d = draw("tropism.l", "tropism.v");
  ASSERT_EQ(d.scene.lines.size(), 10u);
  // The first step is already bent: sin α = e·|H × T| = 0.2.
  const glm::dvec3 first = glm::dvec3(d.scene.lines[0].to - d.scene.lines[0].from);
  EXPECT_NEAR(first.x, 0.2, 1e-6);
  double previous = 0;
  for (const LineSegment& l : d.scene.lines) {
    const glm::dvec3 step = glm::normalize(glm::dvec3(l.to - l.from));
    EXPECT_GT(step.x, previous);  // ever closer to T = +x
    EXPECT_LE(step.x, 1);
    previous = step.x;
  }
  expectOrthonormal(d.state);
}

TEST(TurtleTropisms, OldTropismBendsAfterEachStepTowardsTheUnitDirection) {
  const Drawn d = draw("tropism.l", "old_tropism.v");
  ASSERT_EQ(d.scene.lines.size(), 10u);
  const glm::dvec3 first = glm::dvec3(d.scene.lines[0].to - d.scene.lines[0].from);
  const glm::dvec3 second = glm::dvec3(d.scene.lines[1].to - d.scene.lines[1].from);
  EXPECT_NEAR(first.x, 0, 1e-9);  // bent after the move
  // `tropism direction: 2,0,0` acts as (1,0,0): sin α = 0.2·|H × T| = 0.2.
  EXPECT_NEAR(second.x, 0.2, 1e-6);
}

TEST(TurtleCut, PercentEndsTheBranchOnlyWhenInterpretationPastItIsOff) {
  EXPECT_EQ(draw("cut.l").counts.segments, 7u);
  // The string's % ends its branch; the % the homomorphism makes of C is ignored (cpfg).
  EXPECT_EQ(draw("cut.l", "cut_off.v").counts.segments, 5u);
}

TEST(TurtleQueries, QueryPassFillsPositionAndHeading) {
  const Drawn d = draw("query.l");
  // Before the step, ?P and ?H took the turtle's position and heading after F(2)+(90)F(3),
  // two components for ?H(hx,hy); the production read them. (cos 90° in double is 6.12323e-17,
  // as cpfg writes it too.)
  EXPECT_EQ(d.string, "F(2)+(90)F(3)B(-3,2,0,-1,6.12323e-17)?P(-3,2,0)?H(-1,6.12323e-17)");
}

// cpfg's own string for a model that steers its growth by ?H (../shared/conformance).
TEST(TurtleQueries, HorneophytonMatchesCpfg) {
  const fs::path folder =
      fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance" / "cpfg-Horneophyton";
  if (!fs::exists(folder / "expected.str")) GTEST_SKIP() << folder << " is absent";
  Diagnostics diagnostics;
  const fs::path view = folder / "plant.v";
  Model model = loadModel(folder / "plant.l", view, diagnostics);
  ASSERT_TRUE(model.program.usesQueries);
  ModelResources resources = loadModelResources(view, {}, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = 8;  // index.tsv
  Derivation derivation(model.program, evaluator, diagnostics, options);
  installQueryPass(derivation, resources, diagnostics);
  derivation.run();
  std::ifstream in(folder / "expected.str");
  std::string expected((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::erase(expected, '\n');
  EXPECT_EQ(compactString(derivation), expected);
}

// cpfg-manual.txt §6.10: @L prints its format with the values that follow, where the turtle is.
TEST(TurtleLabels, LabelTextIsTheFormatAppliedToTheValues) {
  Drawn drawn = draw("label.l");
  ASSERT_EQ(drawn.scene.labels.size(), 2u);
  EXPECT_EQ(drawn.scene.labels[0].text, "start");
  expectNear(glm::dvec3(drawn.scene.labels[0].position), glm::dvec3(0, 0, 0));
  EXPECT_EQ(drawn.scene.labels[1].text, "height 3, step 1 of 2");
  expectNear(glm::dvec3(drawn.scene.labels[1].position), glm::dvec3(0, 3, 0));
  EXPECT_EQ(drawn.scene.labels[1].material, 2);
  EXPECT_NE(drawn.scene.labels[0].material, drawn.scene.labels[1].material);
}

// Without the program's string table (a turtle fed by hand) a label shows its numbers.
TEST(TurtleLabels, LabelWithoutStringTableShowsItsParameters) {
  Diagnostics diagnostics;
  ModelResources resources = loadModelResources(std::nullopt, {}, diagnostics);
  Scene scene;
  Turtle turtle(resources, &scene, diagnostics);
  Feeder feed{turtle};
  feed('@');
  feed('L', {1.5f, 2});
  turtle.finish();
  ASSERT_EQ(scene.labels.size(), 1u);
  EXPECT_EQ(scene.labels[0].text, "1.5 2");
}

}  // namespace
}  // namespace hirsute
