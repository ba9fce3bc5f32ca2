// The C preprocessor's run: its limits (the size of the text it writes, its time) and its
// confinement to the model's folder.
#include "hirsute/lsys/preprocessor.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_files.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;

class PreprocessorRun : public testing::TemporaryFolderTest {
 protected:
  PreprocessorRun() : TemporaryFolderTest("preprocessor_") {}
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
  }
  // The message of the error preprocessing `name` ends in; empty when it ends in none.
  std::string errorOf(const std::string& name, const PreprocessorOptions& options) const {
    std::ostringstream warnings;
    Diagnostics diagnostics(&warnings);
    try {
      preprocessFile(file(name), options, diagnostics);
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return "";
  }
};

TEST_F(PreprocessorRun, IncludesThatDoubleAtEveryLevelStopAtTheSizeLimit) {
  // 40 levels, each file included twice by the one above: 2^40 copies of the bottom.
  for (int level = 1; level < 40; ++level) {
    const std::string next = "level" + std::to_string(level + 1) + ".h";
    write("level" + std::to_string(level) + ".h",
          "#include \"" + next + "\"\n#include \"" + next + "\"\n");
  }
  write("level40.h", "#define BOTTOM 1\n");
  write("model.l", "#include \"level1.h\"\nLsystem: 1\nAxiom: A\nendlsystem\n");
  PreprocessorOptions options;
  options.maxOutputBytes = 1 << 20;
  const auto started = std::chrono::steady_clock::now();
  const std::string error = errorOf("model.l", options);
  EXPECT_NE(error.find("the preprocessed text is larger than 1048576 bytes"), std::string::npos)
      << error;
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(30));
}

TEST_F(PreprocessorRun, AnIncludedFifoEndsAtTheTimeLimit) {
  ASSERT_EQ(mkfifo(file("pipe.h").c_str(), 0600), 0);
  write("model.l", "#include \"pipe.h\"\nLsystem: 1\nAxiom: A\nendlsystem\n");
  PreprocessorOptions options;
  options.timeoutSeconds = 1;
  const std::string error = errorOf("model.l", options);
  EXPECT_NE(error.find("the C preprocessor ran for more than 1 s"), std::string::npos) << error;
}

TEST_F(PreprocessorRun, AnOrdinaryModelIsWithinTheLimits) {
  write("sizes.h", "#define SIZE 7\n");
  write("model.l", "#include \"sizes.h\"\nLsystem: 1\nAxiom: A(SIZE)\nendlsystem\n");
  std::ostringstream warnings;
  Diagnostics diagnostics(&warnings);
  const std::string text = preprocessFile(file("model.l"), PreprocessorOptions{}, diagnostics);
  EXPECT_NE(text.find("A(7)"), std::string::npos) << text;
}

}  // namespace
}  // namespace hirsute
