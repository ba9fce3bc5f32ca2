// The C preprocessor's run: its limits (the size of the text it writes, its memory, its time),
// the include files it may open, the processes it leaves (none), and its messages read back.
#include "hirsute/lsys/preprocessor.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hirsute/lsys/preprocessor_messages.h"
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
    return errorAt(file(name), options);
  }
  static std::string errorAt(const fs::path& path, const PreprocessorOptions& options) {
    std::ostringstream warnings;
    Diagnostics diagnostics(&warnings);
    try {
      preprocessFile(path, options, diagnostics);
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return "";
  }
  // The processor time of the children this process has reaped, user and system.
  static double childrenSeconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  }
  // The processes whose command line names this test's folder (cpp's and cc1's -I), waiting up
  // to a second for killed ones to go; zombies have no command line and do not count.
  std::vector<std::string> processesInFolder() const {
    std::vector<std::string> found;
    for (int tries = 0; tries < 20; ++tries) {
      found.clear();
      for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string pid = entry.path().filename().string();
        if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream in(entry.path() / "cmdline", std::ios::binary);
        std::string command((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (command.find(folder_.string()) == std::string::npos) continue;
        for (char& c : command) c = c == '\0' ? ' ' : c;
        found.push_back(pid + ": " + command);
      }
      if (found.empty()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return found;
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

TEST_F(PreprocessorRun, AnIncludedFifoIsRefusedAtOnceAtItsDirective) {
  ASSERT_EQ(mkfifo(file("pipe.h").c_str(), 0600), 0);
  write("model.l", "Lsystem: 1\n  #  include \"pipe.h\"\nAxiom: A\nendlsystem\n");
  const auto started = std::chrono::steady_clock::now();
  const std::string error = errorOf("model.l", PreprocessorOptions{});
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(1));
  EXPECT_EQ(error, file("model.l").string() +
                       ":2:14: error: cannot include 'pipe.h': it is a FIFO, not a regular file");
  EXPECT_EQ(processesInFolder(), std::vector<std::string>{});
}

TEST_F(PreprocessorRun, AFifoThatAnIncludedFileIncludesIsRefusedThere) {
  fs::create_directories(file("parts"));
  ASSERT_EQ(mkfifo(file("parts/pipe.h").c_str(), 0600), 0);
  write("parts/outer.h", "#define OUTER 1\n#include <parts/inner.h>\n");
  write("parts/inner.h", "\n\n#include \"pipe.h\"\n");  // beside inner.h
  write("model.l", "#include \"parts/outer.h\"\nLsystem: 1\nAxiom: A\nendlsystem\n");
  const auto started = std::chrono::steady_clock::now();
  const std::string error = errorOf("model.l", PreprocessorOptions{});
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(1));
  EXPECT_EQ(error, file("parts/inner.h").string() +
                       ":3:10: error: cannot include 'pipe.h': it is a FIFO, not a regular file");
}

TEST_F(PreprocessorRun, AFifoNamedByAMacroEndsWithCppsWholeProcessGroup) {
  // The name is made by a macro, which the check before the run does not expand: cpp's cc1
  // waits for a writer until the time limit, and then it is ended with the driver.
  ASSERT_EQ(mkfifo(file("pipe.h").c_str(), 0600), 0);
  write("model.l", "#define PIPE \"pipe.h\"\n#include PIPE\nLsystem: 1\nAxiom: A\nendlsystem\n");
  PreprocessorOptions options;
  options.timeoutSeconds = 1;
  const std::string error = errorOf("model.l", options);
  EXPECT_NE(error.find("the C preprocessor ran for more than its time limit of 1 s"),
            std::string::npos)
      << error;
  EXPECT_EQ(processesInFolder(), std::vector<std::string>{}) << "cpp or cc1 outlived the run";
}

TEST_F(PreprocessorRun, DoublingMacrosStopAtTheMemoryLimit) {
  // 40 macros, each twice the one before: cpp builds 2^40 copies in memory before writing.
  const fs::path model =
      fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "bad_input" / "preprocessor_doubling_macros.l";
  PreprocessorOptions options;
  options.maxOutputBytes = 1 << 20;
  EXPECT_EQ(preprocessorMemoryLimit(options.maxOutputBytes), std::size_t{128} << 20);
  EXPECT_EQ(preprocessorMemoryLimit(kDefaultMaxSourceBytes), std::size_t{1} << 30);
  // The processor time cpp spent (its children's, reaped), which a busy machine does not
  // stretch as it does the wall-clock time: about 1.5 s; without the limit it runs until the
  // 60 s time limit, having taken several GB.
  const double before = childrenSeconds();
  const std::string error = errorAt(model, options);
  EXPECT_EQ(error, model.string() +
                       ": error: the C preprocessor ran out of memory (its limit is 128 MiB, 64 "
                       "times --max-source-bytes; does a macro expand to ever longer text?)");
  EXPECT_LT(childrenSeconds() - before, 5.0);
}

TEST_F(PreprocessorRun, LongMessagesAreReadWholeAndPrintedShortened) {
  const std::string letters(30000, 'A');
  write("error.l", "\n#error " + letters + "\n");
  const std::string error = errorOf("error.l", PreprocessorOptions{});
  EXPECT_EQ(error.rfind(file("error.l").string() + ":2:2: error: #error AAAA", 0), 0u) << error;
  EXPECT_NE(error.find("AAAA … (29607 bytes left out) … AAAA"), std::string::npos) << error;
  EXPECT_LT(error.size(), 600u);

  write("warning.l", "#warning " + letters + "\n");
  std::ostringstream printed;
  Diagnostics diagnostics(&printed);
  preprocessFile(file("warning.l"), PreprocessorOptions{}, diagnostics);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0].where.line, 1);
  EXPECT_EQ(diagnostics.warnings()[0].message.rfind("#warning AAAA", 0), 0u);
  EXPECT_LT(printed.str().size(), 600u);

  write("include.l", "#include \"" + letters + ".h\"\n");
  const std::string include = errorOf("include.l", PreprocessorOptions{});
  EXPECT_EQ(include.rfind(file("include.l").string() + ":1:10: error: AAAA", 0), 0u) << include;
  EXPECT_NE(include.find(".h: File name too long"), std::string::npos) << include;
}

TEST_F(PreprocessorRun, AnOrdinaryModelIsWithinTheLimits) {
  write("sizes.h", "#define SIZE 7\n");
  write("model.l", "#include \"sizes.h\"\nLsystem: 1\nAxiom: A(SIZE)\nendlsystem\n");
  std::ostringstream warnings;
  Diagnostics diagnostics(&warnings);
  const std::string text = preprocessFile(file("model.l"), PreprocessorOptions{}, diagnostics);
  EXPECT_NE(text.find("A(7)"), std::string::npos) << text;
}

TEST(PreprocessorMessages, LinesAreReadAsCppWritesThem) {
  PreprocessorMessage m;
  ASSERT_TRUE(parsePreprocessorMessage("dir/model.l:12:7: error: #error stop here", m));
  EXPECT_EQ(m.file, "dir/model.l");
  EXPECT_EQ(m.line, 12);
  EXPECT_EQ(m.column, 7);
  EXPECT_FALSE(m.warning);
  EXPECT_EQ(m.text, "#error stop here");

  ASSERT_TRUE(parsePreprocessorMessage("model.l:3: warning: #warning soft: 1:2: error: x", m));
  EXPECT_EQ(m.file, "model.l");
  EXPECT_EQ(m.line, 3);
  EXPECT_EQ(m.column, 0);
  EXPECT_TRUE(m.warning);
  EXPECT_EQ(m.text, "#warning soft: 1:2: error: x");

  // A file name with colons: the shortest prefix that is followed by a message.
  ASSERT_TRUE(parsePreprocessorMessage("a:b:9:x.l:4:1:   fatal error: gone.h: No such file", m));
  EXPECT_EQ(m.file, "a:b:9:x.l");
  EXPECT_EQ(m.line, 4);
  EXPECT_EQ(m.column, 1);
  EXPECT_EQ(m.text, "gone.h: No such file");

  ASSERT_TRUE(parsePreprocessorMessage("m.l:99999999999:5: error: far", m));
  EXPECT_EQ(m.line, 0);
  EXPECT_EQ(m.column, 5);

  EXPECT_FALSE(parsePreprocessorMessage("In file included from model.l:2:", m));
  EXPECT_FALSE(parsePreprocessorMessage("compilation terminated.", m));
  EXPECT_FALSE(parsePreprocessorMessage("cc1: out of memory allocating 8 bytes", m));
  ASSERT_TRUE(parsePreprocessorMessage("m.l:1:2:error: no space before the kind", m));
  EXPECT_EQ(m.column, 2);
  EXPECT_FALSE(parsePreprocessorMessage("m.l:1:2: failure: not a kind", m));
  EXPECT_FALSE(parsePreprocessorMessage("", m));
}

TEST(PreprocessorMessages, AMillionCharactersAreReadInAMoment) {
  const std::string colons(1'000'000, ':');
  PreprocessorMessage m;
  const auto started = std::chrono::steady_clock::now();
  EXPECT_FALSE(parsePreprocessorMessage(colons, m));
  EXPECT_FALSE(parsePreprocessorMessage(std::string(1'000'000, '1'), m));
  ASSERT_TRUE(parsePreprocessorMessage(std::string(500'000, ':') + "m.l:1:2: error: " + colons, m));
  EXPECT_EQ(m.text.size(), colons.size());
  EXPECT_EQ(m.file.size(), 500'003u);
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(1));
}

TEST(PreprocessorMessages, ShortenedTextKeepsItsEndsAndWholeCharacters) {
  EXPECT_EQ(shortenedMessage("short", 10), "short");
  EXPECT_EQ(shortenedMessage("abcdefghijklmnopqrstuvwxyz", 9),
            "abcdef … (17 bytes left out) … xyz");
  // "é" is two bytes: a cut never falls between them.
  std::string accents;
  for (int i = 0; i < 20; ++i) accents += "\xc3\xa9";
  const std::string shortened = shortenedMessage(accents, 9);
  EXPECT_EQ(shortened, "\xc3\xa9\xc3\xa9\xc3\xa9 … (32 bytes left out) … \xc3\xa9");
}

TEST(PreprocessorMessages, TheFirstErrorIsThrownAndWarningsPassOn) {
  std::ostringstream printed;
  Diagnostics diagnostics(&printed);
  try {
    reportPreprocessorMessages(
        "In file included from m.l:1:\nm.h:2:3: warning: soft\n"
        "m.h:5:2: error: hard\nm.l:9:1: error: later\n",
        "exit status 1", "m.l", ".", diagnostics);
    FAIL() << "no error thrown";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(e.diagnostic().text(), "m.h:5:2: error: hard");
  }
  EXPECT_EQ(printed.str(), "m.h:2:3: warning: soft\n");
  try {
    reportPreprocessorMessages("", "killed by signal 9, Killed", "m.l", ".", diagnostics);
    FAIL() << "no error thrown";
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(
        e.diagnostic().text(),
        "m.l: error: the C preprocessor failed (killed by signal 9, Killed) without a message");
  }
  EXPECT_NO_THROW(reportPreprocessorMessages("m.l:1:1: warning: w\n", "", "m.l", ".", diagnostics));
}

}  // namespace
}  // namespace hirsute
