// `hirsute bench ccd` over the public CCD queries in ../shared/ccd-queries (skipped when absent):
// one line per file in the documented format, the total last, and no collision missed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Output {
  std::string text;
  int status = -1;
};

// The program's standard output (standard error goes to the test's own).
Output run(const std::string& command) {
  Output out;
  std::FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    out.text.append(buffer, n);
  out.status = pclose(pipe);
  return out;
}

// Between single quotes for the shell (the paths hold none).
std::string quoted(const std::string& text) {
  std::string out = "'";
  out += text;
  out += '\'';
  return out;
}

const fs::path kPublicQueries = fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "ccd-queries";

// The query files of the public set, in order.
std::vector<std::string> publicFiles() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(kPublicQueries)) {
    const std::string folder = entry.path().parent_path().filename().string();
    if (entry.path().extension() == ".csv" && (folder == "edge-edge" || folder == "vertex-face")) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// `hirsute bench ccd OPTIONS FILES…`
Output benchCcd(const std::string& options, const std::vector<std::string>& files) {
  std::string command = quoted(HIRSUTE_BINARY);
  command += " bench ccd ";
  command += options;
  for (const std::string& f : files) {
    command += ' ';
    command += quoted(f);
  }
  return run(command);
}

TEST(BenchCcdCommand, PrintsEveryFileAndTheTotalWithoutFalseNegatives) {
  if (!fs::exists(kPublicQueries)) GTEST_SKIP() << "no public CCD queries at " << kPublicQueries;
  const std::vector<std::string> files = publicFiles();
  ASSERT_FALSE(files.empty());
  const Output out = benchCcd("", files);
  ASSERT_EQ(out.status, 0) << out.text;

  static const std::regex kLine(
      R"(^(.+): (\d+) queries, (\d+) false negatives, (\d+) false positives, (\d+\.\d+) us/query$)");
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < out.text.size();) {
    const std::size_t end = out.text.find('\n', at);
    lines.push_back(out.text.substr(at, end - at));
    at = end == std::string::npos ? out.text.size() : end + 1;
  }
  ASSERT_EQ(lines.size(), files.size() + 1) << out.text;
  long queries = 0, falsePositives = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(lines[i], m, kLine)) << lines[i];
    EXPECT_EQ(m[1].str(), i < files.size() ? files[i] : "total");
    EXPECT_EQ(m[3].str(), "0") << lines[i];  // no collision missed
    EXPECT_GT(std::stod(m[5].str()), 0.0) << lines[i];
    if (i < files.size()) {
      EXPECT_GT(std::stol(m[2].str()), 0) << lines[i];
      queries += std::stol(m[2].str());
      falsePositives += std::stol(m[4].str());
    } else {
      EXPECT_EQ(std::stol(m[2].str()), queries);
      EXPECT_EQ(std::stol(m[4].str()), falsePositives);
    }
  }
  std::printf("[   INFO   ] %s\n", lines.back().c_str());
}

TEST(BenchCcdCommand, AMinimumSeparationTurnsNearMissesIntoContacts) {
  if (!fs::exists(kPublicQueries)) GTEST_SKIP() << "no public CCD queries at " << kPublicQueries;
  // Half a unit of separation: the queries' near misses, a fraction of a unit apart, collide.
  const Output out = benchCcd("--eta 0.5", publicFiles());
  ASSERT_EQ(out.status, 0) << out.text;
  static const std::regex kTotal(
      R"((?:^|\n)total: (\d+) queries, 0 false negatives, (\d+) false positives, )");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out.text, m, kTotal)) << out.text;
  EXPECT_GT(std::stol(m[2].str()), 0) << out.text;
  EXPECT_NE(benchCcd("--eta -1 2>/dev/null", publicFiles()).status, 0);
}

}  // namespace
