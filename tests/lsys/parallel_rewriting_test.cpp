// Steps rewritten in parts on several threads (parallel_rewriting.h): which programs may be, and
// that every model gives the same strings, warnings and errors rewritten so as on one thread.
#include "hirsute/lsys/parallel_rewriting.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/lsys/string_writer.h"
#include "support/model_corpus.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = HIRSUTE_SOURCE_DIR;

fs::path fixture(const std::string& name) {
  return kSource / "tests/fixtures/lsys/parallel" / (name + ".l");
}

struct Outcome {
  std::string text;
  std::string warnings;
  std::string error;
  int stepsInParts = 0;
  bool operator==(const Outcome& o) const {
    return text == o.text && warnings == o.warnings && error == o.error;
  }
};

// Derives `model` with `threads` threads, every step split when it may be (`threads` > 1).
Outcome derive(const Model& model, int threads, std::optional<int> steps = std::nullopt) {
  Outcome outcome;
  Diagnostics diagnostics;
  std::ostringstream printed;
  Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, printed);
  DerivationOptions options;
  options.steps = steps;
  options.threads = threads;
  options.parallelMinimumModules = 0;
  options.parallelMinimumCost = 0;
  Derivation derivation(model.program, evaluator, diagnostics, options);
  try {
    derivation.run();
  } catch (const DiagnosticError& e) {
    outcome.error = e.diagnostic().text();
  }
  outcome.stepsInParts = derivation.stepsRewrittenInParts();
  outcome.text = testing::compactString(derivation, model.program);
  for (const Diagnostic& w : diagnostics.warnings()) outcome.warnings += w.text() + "\n";
  return outcome;
}

Model load(const fs::path& lfile) {
  Diagnostics diagnostics;
  return loadModel(lfile, testing::viewFor(lfile), diagnostics);
}

Program compiled(const fs::path& lfile) {
  return load(lfile).program;
}

TEST(ParallelRewriting, ProductionsOfModulesAloneAreIndependent) {
  std::string why;
  EXPECT_TRUE(rewritesModulesIndependently(compiled(fixture("independent")), &why)) << why;
}

TEST(ParallelRewriting, WhatOneModuleLeavesForTheNextKeepsTheOrder) {
  const std::pair<const char*, const char*> cases[] = {
      {"reads_before_writing", "has not set"},
      {"writes_in_one_branch", "has not set"},
      {"writes_a_global", "global variable count"},
      {"draws_random_numbers", "random numbers"},
  };
  for (const auto& [name, reason] : cases) {
    SCOPED_TRACE(name);
    std::string why;
    EXPECT_FALSE(rewritesModulesIndependently(compiled(fixture(name)), &why));
    EXPECT_NE(why.find(reason), std::string::npos) << why;
  }
}

TEST(ParallelRewriting, LoopsAndBranchesWriteTheirSlotsOnEveryPath) {
  // x = 1; while (x < 3) { y = x; x = x + 1; } -- y is not written when the loop never runs.
  Code code;
  code.instructions = {
      {Op::Constant, 0, 0},     {Op::StoreLocal, 0, 0},  {Op::LoadLocal, 0, 0},
      {Op::LessConstant, 0, 1}, {Op::JumpIfFalse, 0, 9}, {Op::LoadLocal, 0, 0},
      {Op::StoreLocal, 0, 1},   {Op::LoadLocal, 0, 0},   {Op::LoopBack, 0, 2},
  };
  std::vector<char> written(3, 0);
  ASSERT_TRUE(readsOnlyWrittenSlots(code, written));
  EXPECT_EQ(written, (std::vector<char>{1, 0, 0}));
  // The same with y read after the loop.
  code.instructions.push_back({Op::LoadLocal, 0, 1});
  written.assign(3, 0);
  EXPECT_FALSE(readsOnlyWrittenSlots(code, written));
  // A slot bound before the code (a formal parameter) may be read at once.
  Code read;
  read.instructions = {{Op::LoadLocal, 0, 2}, {Op::AddLocal, 0, 2}};
  written.assign(3, 0);
  EXPECT_FALSE(readsOnlyWrittenSlots(read, written));
  written = {0, 0, 1};
  EXPECT_TRUE(readsOnlyWrittenSlots(read, written));
}

TEST(ParallelRewriting, PartsGiveTheStringOfOneThread) {
  const Model model = load(fixture("independent"));
  const Outcome one = derive(model, 1);
  ASSERT_TRUE(one.error.empty()) << one.error;
  ASSERT_GT(one.text.size(), 10000u);
  for (int threads : {2, 3, 7}) {
    SCOPED_TRACE(threads);
    const Outcome parts = derive(model, threads);
    EXPECT_EQ(parts.stepsInParts, 11);
    EXPECT_EQ(parts.text, one.text);
    EXPECT_EQ(parts.warnings, one.warnings);
  }
}

TEST(ParallelRewriting, DependentProgramsStayOnOneThread) {
  for (const char* name : {"reads_before_writing", "writes_in_one_branch", "writes_a_global"}) {
    SCOPED_TRACE(name);
    const Model model = load(fixture(name));
    const Outcome parts = derive(model, 4);
    EXPECT_EQ(parts.stepsInParts, 0);
    EXPECT_EQ(parts, derive(model, 1));
  }
}

// Every model of the repository (the fixtures, models/, the benchmark kinds cut short) and, when
// present, of cpfg's conformance set: the same string, warnings and error with every step that
// may be split rewritten in three parts.
// The cost rule, fed with made-up step times: a step of a new kind (a growth step, or the first
// of other productions) is not held against splitting, and steps in parts that do not pay send
// the next 1, 2, 4, ... steps to one thread without ending splitting for good.
TEST(ParallelRewriting, TheCostRuleBacksOffAndTriesAgain) {
  const Program program = compiled(fixture("independent"));
  ParallelSteps steps(program, {2, 1000, 60, 1'000'000}, [] { return nullptr; });
  const std::size_t n = 4000;
  const auto seconds = [](double perModule, std::size_t modules) {
    return perModule * static_cast<double>(modules);
  };
  EXPECT_FALSE(steps.splitsNextStep(n)) << "nothing measured yet";
  steps.measured(n / 2, n, 0, seconds(70, n / 2));  // a growth step, cheap enough to split after
  ASSERT_TRUE(steps.splitsNextStep(n));
  // The first step of the costlier productions, in parts, took longer a module than the growth
  // step alone: not comparable, so the next step measures one thread again.
  steps.measured(n, n, 2, seconds(160, n));
  EXPECT_FALSE(steps.splitsNextStep(n));
  steps.measured(n, n, 0, seconds(140, n));
  ASSERT_TRUE(steps.splitsNextStep(n));
  steps.measured(n, n, 2, seconds(75, n));  // pays
  EXPECT_TRUE(steps.splitsNextStep(n));
  // Steps in parts that do not pay: 1, then 2, then 4 steps alone after them.
  for (int alone : {1, 2, 4}) {
    steps.measured(n, n, 2, seconds(150, n));
    for (int k = 0; k < alone; ++k) {
      EXPECT_FALSE(steps.splitsNextStep(n)) << alone;
      steps.measured(n, n, 0, seconds(140, n));
    }
    EXPECT_TRUE(steps.splitsNextStep(n)) << alone;
  }
  // One that pays ends the backing off.
  steps.measured(n, n, 2, seconds(75, n));
  steps.measured(n, n, 2, seconds(150, n));
  EXPECT_FALSE(steps.splitsNextStep(n));
  steps.measured(n, n, 0, seconds(140, n));
  EXPECT_TRUE(steps.splitsNextStep(n));
  // Cheap steps are not split, and neither are short strings.
  steps.measured(n, n, 0, seconds(20, n));
  EXPECT_FALSE(steps.splitsNextStep(n));
  steps.measured(n, n, 0, seconds(140, n));
  EXPECT_FALSE(steps.splitsNextStep(999));
}

TEST(ParallelRewriting, EveryModelDerivesAsOnOneThread) {
  const testing::ModelCorpus corpus(kSource, "parallel",
                                    {{"loops", 19}, {"signal", 24}, {"branching", 10}});
  int split = 0;
  for (const auto& [lfile, steps] : corpus.models()) {
    SCOPED_TRACE(lfile.string());
    // A file that does not load (a broken fixture) has no derivation to compare.
    std::optional<Model> model;
    try {
      model = load(lfile);
    } catch (const DiagnosticError&) {
      continue;
    }
    const Outcome one = derive(*model, 1, steps);
    const Outcome parts = derive(*model, 3, steps);
    EXPECT_EQ(parts.text, one.text);
    EXPECT_EQ(parts.warnings, one.warnings);
    EXPECT_EQ(parts.error, one.error);
    split += parts.stepsInParts > 0;
  }
  std::printf("%zu models, %d of them with steps rewritten in parts\n", corpus.models().size(),
              split);
  EXPECT_GT(split, 10);
}

}  // namespace
}  // namespace hirsute
