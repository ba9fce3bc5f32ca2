// The warnings of likely mistakes in a model (lsys/model_checks.h): each fixture in
// tests/fixtures/warnings gives the one its first comment names, at its place, once; `-W no-NAME`
// silences it and `--Werror` ends the run with exit code 2. The shipped models and cpfg's
// conformance models (../shared/conformance, when present) give none.
//
// A fixture's comment holds `warning: LINE:COL: NAME`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kFixtures = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "warnings";

struct Expected {
  std::string where;  // "LINE:COL"
  std::string name;
};

Expected expectedOf(const fs::path& model) {
  std::ifstream in(model);
  std::stringstream text;
  text << in.rdbuf();
  static const std::regex kWarning(R"(warning: (\d+:\d+): ([a-z-]+))");
  std::smatch m;
  const std::string s = text.str();
  if (!std::regex_search(s, m, kWarning)) return {};
  return {m[1], m[2]};
}

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

std::vector<fs::path> fixtures() {
  std::vector<fs::path> models;
  for (const auto& entry : fs::directory_iterator(kFixtures))
    if (entry.path().extension() == ".l") models.push_back(entry.path());
  std::sort(models.begin(), models.end());
  return models;
}

TEST(ModelWarnings, EachMistakeIsNamedOnceAtItsPlace) {
  const std::vector<fs::path> models = fixtures();
  ASSERT_EQ(models.size(), 5u);
  for (const fs::path& model : models) {
    SCOPED_TRACE(model.filename().string());
    const Expected expected = expectedOf(model);
    ASSERT_FALSE(expected.name.empty());
    const std::string line = model.string() + ":" + expected.where + ": warning: ";
    // `check` reads the model without deriving it: exit 0, the warning printed.
    const RunResult check = runHirsute({"check", model.string()});
    EXPECT_EQ(check.exitCode, 0) << check.err;
    EXPECT_EQ(occurrences(check.err, line), 1u) << check.err;
    EXPECT_EQ(occurrences(check.err, "[-W" + expected.name + "]"), 1u) << check.err;
    // Deriving, every module of every step: still once.
    const RunResult derive = runHirsute({"derive", model.string()});
    EXPECT_EQ(derive.exitCode, 0) << derive.err;
    EXPECT_EQ(occurrences(derive.err, "[-W" + expected.name + "]"), 1u) << derive.err;
  }
}

TEST(ModelWarnings, NoNameSilencesTheWarning) {
  for (const fs::path& model : fixtures()) {
    SCOPED_TRACE(model.filename().string());
    const Expected expected = expectedOf(model);
    const RunResult check = runHirsute({"check", "-W", "no-" + expected.name, model.string()});
    EXPECT_EQ(check.exitCode, 0) << check.err;
    EXPECT_EQ(check.err, "");
    const RunResult derive = runHirsute({"derive", "-Wno-" + expected.name, model.string()});
    EXPECT_EQ(derive.exitCode, 0) << derive.err;
    EXPECT_EQ(derive.err, "");
  }
}

TEST(ModelWarnings, WerrorEndsTheRunWithExitCode2) {
  TemporaryFolder folder;
  for (const fs::path& model : fixtures()) {
    SCOPED_TRACE(model.filename().string());
    const Expected expected = expectedOf(model);
    const RunResult check = runHirsute({"check", "--Werror", model.string()});
    EXPECT_EQ(check.exitCode, 2) << check.err;
    EXPECT_NE(check.err.find(": error: "), std::string::npos) << check.err;
    EXPECT_NE(check.err.find("[-Werror,-W" + expected.name + "]"), std::string::npos) << check.err;
    const fs::path out = folder.path() / "string.txt";
    const RunResult derive = runHirsute({"derive", "--Werror", model.string(), "-o", out.string()});
    EXPECT_EQ(derive.exitCode, 2) << derive.err;
    EXPECT_FALSE(fs::exists(out));
    // Silenced, it no longer counts.
    EXPECT_EQ(
        runHirsute({"check", "--Werror", "-W", "no-" + expected.name, model.string()}).exitCode, 0);
  }
}

// The commands that draw take the same options: once each, silenced, or fatal with no file.
TEST(ModelWarnings, ExportTakesTheSameOptions) {
  TemporaryFolder folder;
  const std::string model = (kFixtures / "unbalanced_brackets.l").string();
  const fs::path pov = folder.path() / "plant.pov";
  RunResult run = runHirsute({"export", model, "--pov", pov.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(occurrences(run.err, "[-Wunbalanced-brackets]"), 1u) << run.err;
  run = runHirsute({"export", "-W", "no-unbalanced-brackets", model, "--pov", pov.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  fs::remove(pov);
  run = runHirsute({"export", "--Werror", model, "--pov", pov.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_FALSE(fs::exists(pov));
}

TEST(ModelWarnings, UnknownWarningNameIsRefused) {
  const RunResult run =
      runHirsute({"check", "-W", "no-such-thing", (kFixtures / "parameter_count.l").string()});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_NE(run.err.find("no-such-thing"), std::string::npos) << run.err;
}

// `hirsute check MODEL.l [VIEW.v]` gives no warning for `model`, beside `view` when given, but
// the one named `real` (empty: none), which must be there.
void expectNoWarning(const fs::path& model, const fs::path& view, const std::string& real = {}) {
  SCOPED_TRACE(model.string());
  std::vector<std::string> arguments = {"check", "--Werror", model.string()};
  if (!view.empty()) arguments.push_back(view.string());
  if (!real.empty()) {
    const RunResult run = runHirsute(arguments);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find("[-Werror,-W" + real + "]"), std::string::npos) << run.err;
    arguments.insert(arguments.begin() + 1, {"-W", "no-" + real});
  }
  const RunResult run = runHirsute(arguments);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
}

// The view file of a shipped model: the one of the same name, or else the folder's only one.
fs::path viewOf(const fs::path& model) {
  fs::path same = model;
  same.replace_extension(".v");
  if (fs::exists(same)) return same;
  std::vector<fs::path> views;
  for (const auto& entry : fs::directory_iterator(model.parent_path()))
    if (entry.path().extension() == ".v") views.push_back(entry.path());
  return views.size() == 1 ? views.front() : fs::path();
}

TEST(ModelWarnings, ShippedModelsGiveNone) {
  std::size_t checked = 0;
  for (const auto& entry :
       fs::recursive_directory_iterator(fs::path(HIRSUTE_SOURCE_DIR) / "models")) {
    if (entry.path().extension() != ".l") continue;
    expectNoWarning(entry.path(), viewOf(entry.path()));
    ++checked;
  }
  EXPECT_GT(checked, 30u);
}

TEST(ModelWarnings, ConformanceModelsGiveNone) {
  const char* given = std::getenv("HIRSUTE_CONFORMANCE_DIR");
  const fs::path folder =
      given ? fs::path(given) : fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "conformance";
  std::ifstream index(folder / "index.tsv");
  if (!index) GTEST_SKIP() << "no conformance models at " << folder;
  std::string line;
  std::getline(index, line);  // header: id lfile vfile …
  std::size_t checked = 0;
  while (std::getline(index, line)) {
    std::stringstream cells(line);
    std::string id, lfile, vfile;
    std::getline(cells, id, '\t');
    std::getline(cells, lfile, '\t');
    std::getline(cells, vfile, '\t');
    // Two of cpfg's own models hold a production that can never apply: Sedge's male spike
    // `spikem --> A(0)` (six modules, s p i k e m, none of which the string holds) and the
    // snowflake's `XF(x) --> …` (no X anywhere: the production switched off by a letter).
    std::string real;
    if (id == "cpfg-Sedge-male" || id == "cpfg-Snowflake") real = "unused-production";
    expectNoWarning(folder / id / lfile, vfile == "-" ? fs::path() : folder / id / vfile, real);
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

}  // namespace
