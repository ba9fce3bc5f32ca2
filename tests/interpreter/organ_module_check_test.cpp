// The check of organ modules before the derivation (checkConstantOrganModules): a parameter the
// .l file gives as a constant expression is judged by the organ's own table, at its place in the
// file; one the derivation computes is left to the turtle. Fixture models are in
// tests/fixtures/interpreter/organ_modules.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kFixtures =
    fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "interpreter" / "organ_modules";

TEST(OrganModuleCheck, ConstantsInRangeAndComputedValuesPass) {
  Diagnostics diagnostics;
  const Model model = loadModel(kFixtures / "fur_values_in_range.l", std::nullopt, diagnostics);
  EXPECT_NO_THROW(checkConstantOrganModules(model.program));
}

TEST(OrganModuleCheck, ConstantOutOfRangeIsAnErrorAtItsParameter) {
  Diagnostics diagnostics;
  const Model model =
      loadModel(kFixtures / "fur_mass_in_homomorphism.l", std::nullopt, diagnostics);
  try {
    checkConstantOrganModules(model.program);
    FAIL() << "a zero mass passed";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(e.diagnostic().where.line, 6);
    EXPECT_EQ(e.diagnostic().where.column, 15);  // `1 - 1`, the second parameter
    EXPECT_EQ(e.diagnostic().message, "@Us: m 0 must be at least 1e-06");
  }
}

TEST(OrganModuleCheck, ComputedValueOutOfRangeIsTheTurtlesWarning) {
  Diagnostics diagnostics;
  const Model model = loadModel(kFixtures / "fur_length_computed.l", std::nullopt, diagnostics);
  ASSERT_NO_THROW(checkConstantOrganModules(model.program));
  ModelResources resources = loadModelResources(std::nullopt, {}, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  Derivation derivation(model.program, evaluator, diagnostics);
  derivation.run();
  Scene scene;
  Turtle turtle(resources, &scene, diagnostics);
  turtle.setSourceString(&derivation.mutableString());
  derivation.emit(turtle, true);
  turtle.finish();
  bool warned = false;
  for (const Diagnostic& warning : diagnostics.warnings())
    warned |= warning.message.find("@Ul: length -1 must be at least 0; module ignored") !=
              std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace hirsute
