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

TEST(BenchCcdCommand, PrintsEveryFileAndTheTotalWithoutFalseNegatives) {
  const fs::path root = fs::path(HIRSUTE_SOURCE_DIR) / ".." / "shared" / "ccd-queries";
  if (!fs::exists(root)) GTEST_SKIP() << "no public CCD queries at " << root;
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string folder = entry.path().parent_path().filename().string();
    if (entry.path().extension() == ".csv" && (folder == "edge-edge" || folder == "vertex-face")) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  std::string command = quoted(HIRSUTE_BINARY);
  command += " bench ccd";
  for (const std::string& f : files) {
    command += ' ';
    command += quoted(f);
  }
  const Output out = run(command);
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

}  // namespace
