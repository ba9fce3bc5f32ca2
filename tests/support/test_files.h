// What the tests that write and read files share: a fresh folder per test, and reading text
// back line by line.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hirsute::testing {

// A fresh, empty folder per test under the system's temporary folder, named after the test and
// the process, removed afterwards.
class TemporaryFolderTest : public ::testing::Test {
 protected:
  explicit TemporaryFolderTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = std::filesystem::temp_directory_path() /
              (prefix_ + info->name() + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::filesystem::path file(const std::string& name) const { return folder_ / name; }

  std::filesystem::path folder_;

 private:
  std::string prefix_;
};

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::size_t countLinesStarting(const std::string& text, const std::string& prefix) {
  std::size_t n = 0;
  for (const std::string& line : linesOf(text)) n += line.rfind(prefix, 0) == 0;
  return n;
}

// The polylines of an OBJ's `l` elements, each its vertex numbers: an element that starts where
// the one before it ended continues its polyline (the OBJ export writes one `l` a segment).
inline std::vector<std::vector<std::uint64_t>> objPolylines(const std::string& text) {
  std::vector<std::vector<std::uint64_t>> polylines;
  for (const std::string& line : linesOf(text)) {
    if (line.rfind("l ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    std::vector<std::uint64_t> element;
    for (std::uint64_t v; in >> v;) element.push_back(v);
    if (element.empty()) continue;
    if (!polylines.empty() && polylines.back().back() == element.front()) {
      polylines.back().insert(polylines.back().end(), element.begin() + 1, element.end());
    } else {
      polylines.push_back(element);
    }
  }
  return polylines;
}

inline std::size_t countOccurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace hirsute::testing
