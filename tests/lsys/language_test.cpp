// The language, construct by construct: each fixture model in tests/fixtures/lsys has the
// string it must derive beside it (NAME.expected, and NAME.homo.expected after the
// homomorphism), written by hand from cpfg's semantics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// A private copy of tests/fixtures: some fixture models write files into their folder.
fs::path fixtures() {
  static const fs::path copy = [] {
    fs::path root = fs::temp_directory_path() / ("hirsute-fixtures-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::copy(fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures", root, fs::copy_options::recursive);
    return root / "lsys";
  }();
  return copy;
}

std::string readLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

struct Derived {
  std::string text;
  std::string printed;  // what printf wrote
  std::vector<Diagnostic> warnings;
};

// `streamed`: the last step's string goes to the writer as it is derived, as `hirsute derive -o`
// writes it (Derivation::runStreamingLastStep).
Derived derive(const fs::path& lfile, bool homomorphism, std::optional<int> steps = std::nullopt,
               bool streamed = false) {
  Diagnostics diagnostics;
  std::optional<fs::path> view;
  fs::path v = fs::path(lfile).replace_extension(".v");
  if (fs::exists(v)) view = v;
  Model model = loadModel(lfile, view, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = steps;
  Derivation derivation(model.program, evaluator, diagnostics, options);
  if (!streamed) derivation.run();
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, StringFormat::Compact);
    writer.setStrings(&model.program.strings);
    if (!streamed || !derivation.runStreamingLastStep(writer, homomorphism)) {
      derivation.emit(writer, homomorphism);
    }
    writer.finish();
  }
  std::fclose(memory);
  std::string text(buffer, size);
  std::free(buffer);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return {text, printed.str(), diagnostics.warnings()};
}

std::vector<std::string> fixtureNames() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fixtures())) {
    if (entry.path().extension() == ".l" && fs::exists(fs::path(entry.path()).replace_extension(".expected"))) {
      names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

class FixtureModel : public ::testing::TestWithParam<std::string> {};

TEST_P(FixtureModel, DerivesTheExpectedString) {
  fs::path l = fixtures() / (GetParam() + ".l");
  const std::string expected = readLine(fs::path(l).replace_extension(".expected"));
  EXPECT_EQ(derive(l, false).text, expected);
  EXPECT_EQ(derive(l, false, std::nullopt, true).text, expected) << "written while derived";
  fs::path homo = fixtures() / (GetParam() + ".homo.expected");
  if (fs::exists(homo)) {
    EXPECT_EQ(derive(l, true).text, readLine(homo));
    EXPECT_EQ(derive(l, true, std::nullopt, true).text, readLine(homo)) << "written while derived";
  }
}

INSTANTIATE_TEST_SUITE_P(Lsys, FixtureModel, ::testing::ValuesIn(fixtureNames()),
                         [](const auto& info) { return info.param; });

// A math built-in that a loop calls on a value the loop never changes is computed once before
// it (hoisted.l): P's cos(x) comes before its loop, its sin(i x) stays inside; Q, whose loop
// assigns x, computes nothing before its loop. Both give the same values (hoisted.expected).
TEST(Blocks, LoopInvariantCallsAreComputedBeforeTheLoop) {
  Diagnostics diagnostics;
  const Model model = loadModel(fixtures() / "hoisted.l", std::nullopt, diagnostics);
  const auto& productions = model.program.lsystems.front().productions.productions;
  ASSERT_EQ(productions.size(), 2u);
  // Calls before the loop's top (the LoopBack's target) and within it.
  auto calls = [](const Code& code) {
    int top = -1;
    for (const Instruction& in : code.instructions)
      if (in.op == Op::LoopBack) top = in.operand;
    std::pair<int, int> count{0, 0};
    for (std::size_t i = 0; i < code.instructions.size(); ++i) {
      const Op op = code.instructions[i].op;
      const bool call = op == Op::Call || op == Op::CallSin || op == Op::CallCos ||
                        op == Op::CallSqrt || op == Op::CallFabs || op == Op::CallExp ||
                        op == Op::CallLog;
      if (!call) continue;
      (static_cast<int>(i) < top ? count.first : count.second) += 1;
    }
    return count;
  };
  EXPECT_EQ(calls(productions[0].before), std::make_pair(1, 1));  // cos before, sin inside
  EXPECT_EQ(calls(productions[1].before), std::make_pair(0, 2));
  EXPECT_GT(productions[0].frameSize, productions[1].frameSize);  // the slot of cos(x)
}

// Conditions that compare a parameter of the strict predecessor with a constant are tested
// before the contexts and the binding (guards.l; guards.expected holds the strings the
// conditions give): those comparisons, either way round, and only where the whole condition is
// free of effects, errors and warnings.
TEST(Conditions, ParameterComparisonsAreTestedFirst) {
  Diagnostics diagnostics;
  const Model model = loadModel(fixtures() / "guards.l", std::nullopt, diagnostics);
  const auto& productions = model.program.lsystems.front().productions.productions;
  ASSERT_EQ(productions.size(), 8u);
  const auto tests = [&](std::size_t i) { return productions[i].guard; };
  ASSERT_EQ(tests(0).size(), 1u);  // x == 0
  EXPECT_EQ(tests(0)[0].parameter, 0);
  EXPECT_EQ(tests(0)[0].constant, 0.0);
  EXPECT_TRUE(tests(0)[0].holds(0.0));
  EXPECT_FALSE(tests(0)[0].holds(-1.0));
  EXPECT_FALSE(tests(0)[0].holds(std::nan("")));
  ASSERT_EQ(tests(1).size(), 2u);  // x != 0 && ONE < x
  EXPECT_TRUE(tests(1)[0].holds(std::nan("")));
  EXPECT_FALSE(tests(1)[0].holds(0.0));
  EXPECT_EQ(tests(1)[1].constant, 1.0);
  EXPECT_TRUE(tests(1)[1].holds(2.0));  // 1 < x read as x > 1
  EXPECT_FALSE(tests(1)[1].holds(1.0));
  EXPECT_FALSE(tests(1)[1].holds(std::nan("")));
  ASSERT_EQ(tests(2).size(), 1u);  // 0 >= x read as x <= 0
  EXPECT_TRUE(tests(2)[0].holds(0.0));
  EXPECT_TRUE(tests(2)[0].holds(-1.0));
  EXPECT_FALSE(tests(2)[0].holds(1.0));
  EXPECT_EQ(tests(3).size(), 1u);
  ASSERT_EQ(tests(4).size(), 1u);  // S(s) < L(y) : y == 0
  ASSERT_EQ(tests(5).size(), 1u);  // x > 0 compares the context's parameter: not tested first
  EXPECT_EQ(tests(5)[0].parameter, 0);
  EXPECT_TRUE(tests(6).empty());   // a division may fail
  EXPECT_TRUE(tests(7).empty());   // z is no parameter: it may be unassigned, which warns
  EXPECT_EQ(derive(fixtures() / "guards.l", false).warnings.size(), 1u);
}

TEST(Stochastic, WeightsAreNormalisedByTheirSum) {
  std::string text = derive(fixtures() / "stochastic.l", false).text;
  double b = static_cast<double>(std::count(text.begin(), text.end(), 'B'));
  double c = static_cast<double>(std::count(text.begin(), text.end(), 'C'));
  double n = b + c;
  ASSERT_GT(n, 1000);
  // Binomial with p = 1/4: four standard deviations either way.
  double sd = std::sqrt(n * 0.25 * 0.75);
  EXPECT_NEAR(b, n * 0.25, 4 * sd);
}

TEST(Stochastic, TheSeedMakesTheChoiceReproducible) {
  EXPECT_EQ(derive(fixtures() / "stochastic.l", false).text, derive(fixtures() / "stochastic.l", false).text);
}

TEST(Steps, StepsOverrideTheDerivationLength) {
  EXPECT_EQ(derive(fixtures() / "parametric.l", false, 0).text, "A(1)B");
  EXPECT_EQ(derive(fixtures() / "parametric.l", false, 1).text, "A(2)C(2,-2)B");
}

TEST(Printf, FormatsEachConversionWithTheNextValue) {
  fs::path l = fixtures() / "printf.l";
  EXPECT_EQ(derive(l, false).printed, "x=1.5 n=3 100%\nvalues 2 and 0.25\n");
}

TEST(Variables, ReadingAnUnassignedVariableWarnsAndReadsZero) {
  Derived d = derive(fixtures() / "undefined_variable.l", false);
  EXPECT_EQ(d.text, "R(0)");
  ASSERT_FALSE(d.warnings.empty());
  EXPECT_NE(d.warnings.front().message.find("'nothing'"), std::string::npos);
  EXPECT_EQ(d.warnings.front().where.line, 5);
}

TEST(Derivation, EachStepGivesTheStringOfThatStep) {
  Diagnostics diagnostics;
  Model model = loadModel(fixtures() / "parametric.l", std::nullopt, diagnostics);
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  Derivation derivation(model.program, evaluator, diagnostics);
  derivation.start();
  EXPECT_EQ(derivation.string().moduleCount(), 2u);
  ASSERT_TRUE(derivation.step());
  EXPECT_EQ(derivation.string().moduleCount(), 3u);
  ASSERT_TRUE(derivation.step());
  EXPECT_EQ(derivation.string().moduleCount(), 4u);
  EXPECT_FALSE(derivation.step());
  EXPECT_EQ(derivation.stepsDone(), 2);
}

}  // namespace
}  // namespace hirsute

namespace hirsute {
namespace {

// Every model shipped in models/ derives cleanly: no error and no warning.
TEST(ShippedModels, DeriveWithoutErrorsOrWarnings) {
  fs::path models = fs::path(HIRSUTE_SOURCE_DIR) / "models";
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    if (entry.path().extension() != ".l" || entry.path().string().find("/bench/") != std::string::npos) continue;
    SCOPED_TRACE(entry.path().string());
    Derived d;
    ASSERT_NO_THROW(d = derive(entry.path(), true));
    EXPECT_FALSE(d.text.empty());
    for (const Diagnostic& w : d.warnings) ADD_FAILURE() << w.text();
    ++count;
  }
  EXPECT_GT(count, 0);
}

}  // namespace
}  // namespace hirsute
