// The command line on broken input: every `.l` in tests/bad_input must end `hirsute derive` with
// exit code 2 and the `file:line:col: error: message` its first line announces, without a crash
// and without hanging.
//
// A corpus file states its expectation in its first line, as a C comment:
//   /* expect: LINE:COL: substring of the message */
//   /* expect: LINE: substring */                      (any column, or none)
//   /* expect: NAME:LINE:COL: substring */             (the error is in NAME beside it: an included
//                                                       file, the view file)
// Its second line may give more arguments:   /* args: --max-modules 100000 */
// and, when its first word is `render`, runs `hirsute render … -o PNG` instead (the errors that
// only geometry and hairs meet) and checks that no PNG is left behind.
// A `.v` of the same name is passed as the view file.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/run_hirsute.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

struct Expectation {
  std::string file;  // empty: the `.l` itself; else a file beside it
  int line = 0;
  std::optional<int> column;
  std::string message;  // a substring of the error's message
};

// The first line's `/* expect: … */`; nullopt when the file has none.
std::optional<Expectation> readExpectation(const std::string& firstLine) {
  static const std::regex kExpect(R"(^/\* expect: (?:([A-Za-z0-9_.\-]*[A-Za-z_.\-][A-Za-z0-9_.\-]*):)?(\d+):(?:(\d+):)?(?: (.*?))? ?\*/\s*$)");
  // An error about the whole model (a limit no single line sets) names only the file.
  static const std::regex kWholeFile(R"(^/\* expect: ([A-Za-z0-9_.\-]*[A-Za-z_.\-][A-Za-z0-9_.\-]*): (.*?) ?\*/\s*$)");
  std::smatch m;
  if (std::regex_match(firstLine, m, kWholeFile)) {
    Expectation e;
    e.file = m[1].str();
    e.line = 0;
    e.message = m[2].str();
    return e;
  }
  if (!std::regex_match(firstLine, m, kExpect)) return std::nullopt;
  Expectation e;
  e.file = m[1].str();
  e.line = std::stoi(m[2].str());
  if (m[3].matched) e.column = std::stoi(m[3].str());
  e.message = m[4].str();
  return e;
}

// The second line's `/* args: … */`, split at spaces.
std::vector<std::string> readArguments(const std::string& secondLine) {
  static const std::regex kArgs(R"(^/\* args: (.*?) \*/\s*$)");
  std::smatch m;
  std::vector<std::string> words;
  if (!std::regex_match(secondLine, m, kArgs)) return words;
  std::istringstream in(m[1].str());
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::vector<std::string> firstLines(const fs::path& file, std::size_t count) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string line; lines.size() < count && std::getline(in, line);) lines.push_back(line);
  lines.resize(count);
  return lines;
}

// The message of the error reported at `where` ("path:line:" plus, when given, "col:"), if any.
std::optional<std::string> errorAt(const std::string& stderrText, const std::string& path, int line,
                                   std::optional<int> column) {
  static const std::regex kRest(R"(^(?:(\d+):)? error: (.*)$)");
  if (line == 0) {  // the whole file: "path: error: message"
    const std::string whole = path + ": error: ";
    std::istringstream lines(stderrText);
    for (std::string text; std::getline(lines, text);) {
      if (text.compare(0, whole.size(), whole) == 0) return text.substr(whole.size());
    }
    return std::nullopt;
  }
  const std::string prefix = path + ":" + std::to_string(line) + ":";
  std::istringstream lines(stderrText);
  for (std::string text; std::getline(lines, text);) {
    if (text.compare(0, prefix.size(), prefix) != 0) continue;
    std::smatch m;
    const std::string rest = text.substr(prefix.size());
    if (!std::regex_match(rest, m, kRest)) continue;
    if (column && (!m[1].matched || std::stoi(m[1].str()) != *column)) continue;
    return m[2].str();
  }
  return std::nullopt;
}

fs::path corpusFolder() { return fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "bad_input"; }

std::vector<std::string> corpusCases() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(corpusFolder())) {
    if (entry.path().extension() == ".l") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The corpus runs on a private copy, so that no case can write into the source tree.
class BadInputTest : public testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    copy_ = new TemporaryFolder;
    fs::copy(corpusFolder(), copy_->path() / "bad_input", fs::copy_options::recursive);
  }
  static void TearDownTestSuite() {
    delete copy_;
    copy_ = nullptr;
  }
  static fs::path casePath(const std::string& name) { return copy_->path() / "bad_input" / (name + ".l"); }

  static TemporaryFolder* copy_;
};

TemporaryFolder* BadInputTest::copy_ = nullptr;

TEST_P(BadInputTest, EndsWithTheAnnouncedError) {
  const fs::path file = casePath(GetParam());
  const std::vector<std::string> head = firstLines(file, 2);
  const std::optional<Expectation> expected = readExpectation(head[0]);
  ASSERT_TRUE(expected) << file << ": the first line must be /* expect: LINE[:COL]: message */, found: "
                        << head[0];

  std::vector<std::string> more = readArguments(head[1]);
  const bool render = !more.empty() && more.front() == "render";
  if (render) more.erase(more.begin());
  std::vector<std::string> arguments = {render ? "render" : "derive", file.string()};
  fs::path view = fs::path(file).replace_extension(".v");
  if (fs::exists(view)) arguments.push_back(view.string());
  const fs::path image = fs::path(file).replace_extension(".png");
  if (render) arguments.insert(arguments.end(), {"-o", image.string()});
  for (const std::string& a : more) arguments.push_back(a);

  const RunResult run = runHirsute(arguments);
  ASSERT_FALSE(run.killed) << GetParam() << " still ran after " << kKillAfter.count() << " s; stderr:\n"
                           << run.err.substr(0, 2000);
  if (run.seconds > kSlowSeconds) {
    std::printf("[ WARNING  ] %s took %.2f s (more than %.0f s)\n", GetParam().c_str(), run.seconds, kSlowSeconds);
  }
  ASSERT_TRUE(run.exited) << GetParam() << " died of signal " << run.signal << " after " << run.seconds
                          << " s; stderr:\n" << run.err.substr(0, 4000);
  EXPECT_EQ(run.exitCode, 2) << "stderr:\n" << run.err.substr(0, 2000);
  EXPECT_EQ(run.err.find("Sanitizer"), std::string::npos) << run.err.substr(0, 4000);
  if (render) {
    EXPECT_FALSE(fs::exists(image)) << "a failed render left " << image;
  }

  const std::string path = expected->file.empty() ? file.string() : (file.parent_path() / expected->file).string();
  const std::optional<std::string> message = errorAt(run.err, path, expected->line, expected->column);
  std::string where = path + ":" + std::to_string(expected->line) +
                      (expected->column ? ":" + std::to_string(*expected->column) : std::string()) + ": error: ";
  ASSERT_TRUE(message) << "expected an error at " << where << "… (in " << run.seconds << " s); stderr:\n"
                       << run.err.substr(0, 2000);
  EXPECT_NE(message->find(expected->message), std::string::npos)
      << "the error at " << where << " says \"" << *message << "\", expected it to contain \""
      << expected->message << "\"";
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputTest, testing::ValuesIn(corpusCases()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(BadInputCorpus, HasACaseForEachKindOfMistake) {
  // The issue asks for at least 45 broken inputs; each must announce its error.
  const std::vector<std::string> names = corpusCases();
  EXPECT_GE(names.size(), 45u);
  for (const std::string& name : names) {
    EXPECT_TRUE(readExpectation(firstLines(corpusFolder() / (name + ".l"), 1)[0])) << name;
  }
}

TEST(BadInputCorpus, ExpectationLinesAreRead) {
  auto e = readExpectation("/* expect: 12:7: unknown function 'grow' */");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file, "");
  EXPECT_EQ(e->line, 12);
  EXPECT_EQ(e->column, 7);
  EXPECT_EQ(e->message, "unknown function 'grow'");
  e = readExpectation("/* expect: 3: the file contains NUL bytes */");
  ASSERT_TRUE(e);
  EXPECT_FALSE(e->column);
  EXPECT_EQ(e->message, "the file contains NUL bytes");
  e = readExpectation("/* expect: shared.inc:4:12: unknown function */");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->file, "shared.inc");
  EXPECT_EQ(e->line, 4);
  EXPECT_FALSE(readExpectation("/* a comment */"));
  EXPECT_EQ(readArguments("/* args: --max-modules 1000 --homomorphism */"),
            (std::vector<std::string>{"--max-modules", "1000", "--homomorphism"}));
}

TEST(BadInputCorpus, ErrorsAreFoundOnlyAtTheirPlace) {
  const std::string err = "warning: x\n/m.l:4:12: error: unknown function 'grow'\n";
  EXPECT_EQ(errorAt(err, "/m.l", 4, 12), "unknown function 'grow'");
  EXPECT_EQ(errorAt(err, "/m.l", 4, std::nullopt), "unknown function 'grow'");
  EXPECT_FALSE(errorAt(err, "/m.l", 4, 11));
  EXPECT_FALSE(errorAt(err, "/m.l", 5, std::nullopt));
  EXPECT_FALSE(errorAt(err, "/other.l", 4, 12));
  EXPECT_EQ(errorAt("/m.l:3: error: unterminated comment\n", "/m.l", 3, std::nullopt), "unterminated comment");
}

TEST(BadInputCorpus, AnEmptyFileHasNoLsystem) {
  // A file of zero bytes cannot announce its own error; it is made here.
  TemporaryFolder folder;
  const fs::path file = folder.path() / "empty.l";
  std::ofstream(file).close();
  const RunResult run = runHirsute({"derive", file.string()});
  ASSERT_FALSE(run.killed);
  EXPECT_EQ(run.exitCode, 2);
  const auto message = errorAt(run.err, file.string(), 1, 1);
  ASSERT_TRUE(message) << run.err;
  EXPECT_NE(message->find("no L-system in the file"), std::string::npos) << *message;
}

TEST(BadInputCorpus, RandomBytesEndInADiagnostic) {
  // Seeded garbage, with and without NUL bytes: every file gets exit code 2 and a message that
  // names it, never a crash.
  TemporaryFolder folder;
  std::uint32_t state = 2026;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<unsigned char>(state >> 24);
  };
  for (int i = 0; i < 12; ++i) {
    const fs::path file = folder.path() / ("garbage" + std::to_string(i) + ".l");
    std::string bytes;
    for (int k = 0; k < 1500; ++k) {
      unsigned char c = next();
      if (i % 2 == 0 && c == 0) c = '\n';  // even files have no NUL byte
      bytes += static_cast<char>(c);
    }
    std::ofstream(file, std::ios::binary) << bytes;
    const RunResult run = runHirsute({"derive", file.string()});
    ASSERT_FALSE(run.killed) << file;
    ASSERT_TRUE(run.exited) << file << " died of signal " << run.signal << ":\n" << run.err.substr(0, 2000);
    EXPECT_EQ(run.exitCode, 2) << file << ":\n" << run.err.substr(0, 2000);
    EXPECT_EQ(run.err.rfind(file.string() + ":", 0), 0u) << run.err.substr(0, 2000);
    EXPECT_NE(run.err.find(": error: "), std::string::npos) << run.err.substr(0, 2000);
  }
}

// ---- -o: an output file appears complete or not at all ----

// `derive CASE -o OUTPUT ARGUMENTS…` for a case of the corpus.
RunResult deriveInto(const std::string& caseName, const fs::path& output, std::vector<std::string> more = {}) {
  std::vector<std::string> arguments = {"derive", (corpusFolder() / (caseName + ".l")).string(), "-o", output.string()};
  arguments.insert(arguments.end(), more.begin(), more.end());
  return runHirsute(arguments);
}

// The homomorphism doubles every module 60 times: with this limit it fails after some 200 KB of
// the string have gone out through the writer's 64 KB buffer, into the temporary file.
const std::vector<std::string> kFailWhileWriting = {"--homomorphism", "--max-modules", "200000"};

TEST(OutputFile, BadInputLeavesNoFile) {
  struct Case {
    const char* name;
    std::vector<std::string> arguments;
  };
  // A parse error, an error in the first step, one in a later step, and one while writing.
  const Case cases[] = {{"missing_axiom", {}},
                        {"division_by_zero", {}},
                        {"exponential_growth", {"--max-modules", "100000"}},
                        {"homomorphism_explosion", kFailWhileWriting}};
  for (const Case& c : cases) {
    TemporaryFolder folder;
    const RunResult run = deriveInto(c.name, folder.path() / "out.str", c.arguments);
    ASSERT_FALSE(run.killed) << c.name;
    EXPECT_EQ(run.exitCode, 2) << c.name << ":\n" << run.err;
    EXPECT_EQ(folder.entries(), std::vector<std::string>{}) << c.name << " left files behind";
  }
}

TEST(OutputFile, BadInputKeepsThePreviousFile) {
  TemporaryFolder folder;
  const fs::path output = folder.path() / "out.str";
  std::ofstream(output) << "F(1)\n";
  const RunResult run = deriveInto("homomorphism_explosion", output, kFailWhileWriting);
  ASSERT_FALSE(run.killed);
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_EQ(readText(output), "F(1)\n");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"out.str"});
}

TEST(OutputFile, GoodModelWritesTheWholeString) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "branching.l";
  const std::string expected = "F(1)[+F(0.5)[+A(0.25)]A(1.5)]F(2)[+A(1)]A(3)\n";
  TemporaryFolder folder;
  const fs::path output = folder.path() / "out.str";
  std::ofstream(output) << "an older string\n";  // replaced in one piece

  const RunResult run = runHirsute({"derive", model.string(), "-o", output.string()});
  ASSERT_FALSE(run.killed);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out, "");
  EXPECT_EQ(readText(output), expected);
  // Nothing but the target: the temporary file it was written to has been renamed into place.
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"out.str"});

  const RunResult toStdout = runHirsute({"derive", model.string()});
  EXPECT_EQ(toStdout.exitCode, 0) << toStdout.err;
  EXPECT_EQ(toStdout.out, expected);
}

// Outputs that exist and are not regular files are written in place: renaming a finished file
// over /dev/null (as root) or over a FIFO would replace the device or the pipe with a file.
struct FileKind {
  mode_t type = 0;
  dev_t device = 0;
  ino_t inode = 0;
  bool operator==(const FileKind&) const = default;
};

FileKind kindOf(const fs::path& path) {
  struct stat info {};
  if (lstat(path.c_str(), &info) != 0) return {};
  return {static_cast<mode_t>(info.st_mode & S_IFMT), info.st_rdev, info.st_ino};
}

// Everything a reader gets from the FIFO while `run` writes into it.
std::string readFifoWhile(const fs::path& fifo, const std::function<void()>& run) {
  std::string text;
  std::thread reader([&] {
    int fd = open(fifo.c_str(), O_RDONLY);
    if (fd < 0) return;
    char buffer[65536];
    for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
    close(fd);
  });
  run();
  // A writer that was killed (or failed) before it opened the FIFO leaves the reader blocked in
  // open(): opening the write end without blocking lets it go on to the end of the (empty) pipe.
  // When the reader has already finished there is no reader and the open fails: nothing to do.
  if (int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) close(fd);
  reader.join();
  return text;
}

TEST(OutputFile, DevNullStaysADevice) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "branching.l";
  const FileKind before = kindOf("/dev/null");
  ASSERT_EQ(before.type, static_cast<mode_t>(S_IFCHR));
  const RunResult derive = runHirsute({"derive", model.string(), "-o", "/dev/null"});
  EXPECT_EQ(derive.exitCode, 0) << derive.err;
  EXPECT_EQ(kindOf("/dev/null"), before);
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  const RunResult exported = runHirsute({"export", (herb / "herb.l").string(), (herb / "herb.v").string(),
                                         "--pov", "/dev/null", "--obj", "/dev/null"});
  EXPECT_EQ(exported.exitCode, 0) << exported.err;
  EXPECT_EQ(kindOf("/dev/null"), before);
  const RunResult rendered = runHirsute({"render", (herb / "herb.l").string(), (herb / "herb.v").string(), "-o",
                                         "/dev/null", "--size", "32x32"});
  EXPECT_EQ(rendered.exitCode, 0) << rendered.err;
  EXPECT_EQ(kindOf("/dev/null"), before);
}

TEST(OutputFile, FifoGetsTheStringAndStaysAFifo) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "branching.l";
  TemporaryFolder folder;
  const fs::path fifo = folder.path() / "string.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const FileKind before = kindOf(fifo);
  RunResult run;
  const std::string text = readFifoWhile(fifo, [&] { run = runHirsute({"derive", model.string(), "-o", fifo.string()}); });
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(text, "F(1)[+F(0.5)[+A(0.25)]A(1.5)]F(2)[+A(1)]A(3)\n");
  EXPECT_EQ(kindOf(fifo), before);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"string.fifo"});  // no temporary left

  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  const std::string png = readFifoWhile(fifo, [&] {
    run = runHirsute({"render", (herb / "herb.l").string(), (herb / "herb.v").string(), "-o", fifo.string(),
                      "--size", "32x32"});
  });
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(png.substr(0, 4), "\x89PNG");
  EXPECT_EQ(kindOf(fifo), before);
}

// An OBJ written to a FIFO (or a device) has no folder of its own: no material library or
// image is written beside it, and it names none.
TEST(OutputFile, AnObjToAFifoWritesNothingBesideIt) {
  TemporaryFolder folder;
  const fs::path fifo = folder.path() / "scene.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  RunResult run;
  const std::string obj = readFifoWhile(fifo, [&] {
    run = runHirsute({"export", (herb / "herb.l").string(), (herb / "herb.v").string(), "--obj",
                      fifo.string()});
  });
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(obj.find("\nv "), std::string::npos);
  EXPECT_EQ(obj.find("mtllib"), std::string::npos);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"scene.fifo"});
}

// Several outputs are written, then renamed together: when one cannot be written, the others
// are left as they were.
TEST(OutputFile, AFailedExportLeavesEveryOutputAsItWas) {
  TemporaryFolder folder;
  const fs::path keep = folder.path() / "keep.pov";
  std::ofstream(keep) << "// the scene of an earlier run\n";
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  const RunResult run =
      runHirsute({"export", (herb / "herb.l").string(), (herb / "herb.v").string(), "--pov",
                  keep.string(), "--hairs", (folder.path() / "hairs.csv").string(), "--obj",
                  (folder.path() / "missing" / "x.obj").string()});
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("x.obj"), std::string::npos) << run.err;
  EXPECT_EQ(readText(keep), "// the scene of an earlier run\n");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"keep.pov"});  // no hairs.csv, no temporary
}

// The organs' tables are the export command's options, each named by its organ's writer
// (organ_writer.h); export without any output names them all.
TEST(OutputFile, ExportWithoutAnOutputNamesEachOrgansTable) {
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  const RunResult run =
      runHirsute({"export", (herb / "herb.l").string(), (herb / "herb.v").string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_EQ(run.err.rfind("hirsute: error: export needs an output: --pov FILE or --obj FILE or "
                          "--blender FILE or --gltf FILE or --hairs FILE or --feathers FILE (or "
                          "several)\n",
                          0),
            0u)
      << run.err;
}

TEST(OutputFile, DevStdoutWritesToTheProcessOutput) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "branching.l";
  const RunResult run = runHirsute({"derive", model.string(), "-o", "/dev/stdout"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out, "F(1)[+F(0.5)[+A(0.25)]A(1.5)]F(2)[+A(1)]A(3)\n");
}

// The program links no GL library: commands that draw nothing start without OSMesa, libGL, GLFW,
// X11 or LLVM, which only the drawing module (libhirsute-drawing.so) loads; nor Embree, TBB and
// OpenEXR (the trace module's) or Assimp (the mesh module's).
TEST(DrawingModule, ProgramLinksNoGlLibrary) {
  const RunResult run = [] {
    // ldd prints the libraries the dynamic loader would map.
    TemporaryFolder folder;
    const std::string listing = (folder.path() / "libraries").string();
    const std::string command = std::string("ldd '") + HIRSUTE_BINARY + "' > '" + listing + "'";
    RunResult result;
    result.exitCode = std::system(command.c_str());
    result.out = readText(listing);
    return result;
  }();
  ASSERT_EQ(run.exitCode, 0);
  ASSERT_NE(run.out.find("libc.so"), std::string::npos) << run.out;
  for (const char* library : {"libOSMesa", "libGL", "libglfw", "libX11", "libLLVM", "libembree",
                              "libtbb", "libOpenEXR", "libassimp"})
    EXPECT_EQ(run.out.find(library), std::string::npos) << library << " in\n" << run.out;
}

TEST(DrawingModule, MissingModuleIsAClearError) {
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  TemporaryFolder folder;
  setenv("HIRSUTE_DRAWING_MODULE", (folder.path() / "libnothing.so").c_str(), 1);
  const RunResult run = runHirsute({"render", (herb / "herb.l").string(), (herb / "herb.v").string(),
                                    "-o", (folder.path() / "herb.png").string()});
  unsetenv("HIRSUTE_DRAWING_MODULE");
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("cannot load " + (folder.path() / "libnothing.so").string()),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("need the drawing library"), std::string::npos) << run.err;
  EXPECT_EQ(folder.entries(), std::vector<std::string>{});
  // Commands that draw nothing do not need it.
  setenv("HIRSUTE_DRAWING_MODULE", (folder.path() / "libnothing.so").c_str(), 1);
  const RunResult derive = runHirsute({"derive", (herb / "herb.l").string()});
  unsetenv("HIRSUTE_DRAWING_MODULE");
  EXPECT_EQ(derive.exitCode, 0) << derive.err;
}

// The trace module and the mesh module likewise: a clear message and exit code 1 when missing,
// not needed by the commands that do not use them.
TEST(TraceModule, MissingModuleIsAClearError) {
  const fs::path herb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
  TemporaryFolder folder;
  setenv("HIRSUTE_TRACE_MODULE", (folder.path() / "libnothing.so").c_str(), 1);
  const RunResult run =
      runHirsute({"render", "--trace", (herb / "herb.l").string(), (herb / "herb.v").string(),
                  "--size", "8x6", "-o", (folder.path() / "herb.png").string()});
  const RunResult gl = runHirsute({"render", (herb / "herb.l").string(), (herb / "herb.v").string(),
                                   "--size", "8x6", "-o", (folder.path() / "gl.png").string()});
  unsetenv("HIRSUTE_TRACE_MODULE");
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("render --trace needs the trace library"), std::string::npos) << run.err;
  EXPECT_EQ(gl.exitCode, 0) << gl.err;
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"gl.png"});
}

TEST(MeshModule, MissingModuleIsAClearError) {
  const fs::path leaf = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "mesh-leaf";
  TemporaryFolder folder;
  setenv("HIRSUTE_MESHES_MODULE", (folder.path() / "libnothing.so").c_str(), 1);
  const RunResult run =
      runHirsute({"export", (leaf / "leaf.l").string(), (leaf / "leaf.v").string(), "--obj",
                  (folder.path() / "leaf.obj").string()});
  const RunResult derive = runHirsute({"derive", (leaf / "leaf.l").string()});
  unsetenv("HIRSUTE_MESHES_MODULE");
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("need the mesh library and Assimp"), std::string::npos) << run.err;
  EXPECT_EQ(folder.entries(), std::vector<std::string>{});
  EXPECT_EQ(derive.exitCode, 0) << derive.err;
}

}  // namespace

// ---- hirsute bench ccd: broken CCD query files ----

struct BrokenQueryFile {
  const char* folder;  // the folder names the query kind
  std::string text;
  int line;
  int column;  // 0: the error is about the whole file
  const char* message;
};

std::string repeatRows(const std::string& row, int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += row;
  return text;
}

TEST(BenchCcdBadInput, EachMistakeIsReportedAtItsPlace) {
  const std::string row = "0,1,0,1,0,1,0\n";
  const BrokenQueryFile cases[] = {
      {"edge-edge", "0,1,0,1,0,1\n", 1, 12, "7 comma-separated integers, this one has 6"},
      {"edge-edge", row + "0,1,0,1,0,1,0,5\n", 2, 15, "this one has more"},
      {"vertex-face", repeatRows(row, 3) + "0,1,0.5,1,0,1,0\n", 4, 6, "expected an integer"},
      {"vertex-face", "0,1,,1,0,1,0\n", 1, 5, "expected an integer"},
      {"edge-edge", "1,0,0,1,0,1,0\n", 1, 3, "a zero denominator"},
      {"edge-edge", row + "0,1,0,1,0,1,2\n", 2, 13, "the ground truth is 0 or 1"},
      {"edge-edge", repeatRows(row, 5) + "0,1,0,1,0,1,1\n", 6, 13, "differs from the query's first row"},
      {"vertex-face", repeatRows(row, 9), 9, 1, "ends inside the query that starts here"},
      {"edge-edge", "1" + std::string(500, '0') + ",1,0,1,0,1,0\n", 1, 1, "more than 400 digits"},
      {"edge-edge", "1" + std::string(350, '0') + ",1,0,1,0,1,0\n", 1, 1, "beyond the range"},
      {"queries", repeatRows(row, 8), 0, 0, "cannot tell the query kind"},
  };
  for (const BrokenQueryFile& c : cases) {
    TemporaryFolder folder;
    fs::create_directories(folder.path() / c.folder);
    const fs::path file = folder.path() / c.folder / "broken.csv";
    std::ofstream(file, std::ios::binary) << c.text;
    // A good file before it: bad input prints no figures at all.
    fs::create_directories(folder.path() / "edge-edge");
    const fs::path good = folder.path() / "edge-edge" / "good.csv";
    std::ofstream(good, std::ios::binary) << repeatRows(row, 8);
    const RunResult run = runHirsute({"bench", "ccd", good.string(), file.string()});
    ASSERT_FALSE(run.killed) << c.message;
    ASSERT_TRUE(run.exited) << c.message << ": signal " << run.signal;
    EXPECT_EQ(run.exitCode, 2) << c.message << ":\n" << run.err;
    EXPECT_EQ(run.out, "") << c.message;
    const std::optional<std::string> message =
        errorAt(run.err, file.string(), c.line, c.column ? std::optional<int>(c.column) : std::nullopt);
    ASSERT_TRUE(message) << "expected " << file.string() << ":" << c.line << ":" << c.column
                         << ": error: " << c.message << "; stderr:\n" << run.err;
    EXPECT_NE(message->find(c.message), std::string::npos) << *message;
  }
}

TEST(BenchCcdBadInput, AMissingFileOrAFolderCannotBeRead) {
  TemporaryFolder folder;
  fs::create_directories(folder.path() / "edge-edge" / "sub.csv");
  for (const fs::path& path : {folder.path() / "edge-edge" / "absent.csv", folder.path() / "edge-edge" / "sub.csv"}) {
    const RunResult run = runHirsute({"bench", "ccd", path.string()});
    ASSERT_FALSE(run.killed);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    const std::optional<std::string> message = errorAt(run.err, path.string(), 0, std::nullopt);
    ASSERT_TRUE(message) << run.err;
    EXPECT_NE(message->find("cannot read"), std::string::npos) << *message;
  }
}

namespace hirsute {
namespace {

fs::path excerptFixture(const std::string& name) {
  return fs::path(HIRSUTE_SOURCE_DIR) / "tests" / "fixtures" / "cli" / "excerpts" / name;
}

// A message shows the line it points at and a caret under its column, as compilers do; a tab
// before the column stays a tab, so that the caret lines up in a terminal.
TEST(SourceExcerpt, AnErrorShowsItsLineAndACaretUnderTheColumn) {
  const fs::path model = excerptFixture("arrow.l");
  const RunResult run = runHirsute({"derive", model.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  const std::string expected = model.string() +
                               ":5:6: error: expected '-->' (two dashes and '>'), found '->': a "
                               "production is 'predecessor --> successor'\n"
                               " 5 | A(n)\t-> I(LEN*0.6) A(n+1)\n"
                               "   |     \t^\n";
  EXPECT_EQ(run.err, expected);
}

// A mistake that comes from a macro's text shows where the macro is defined, as compilers note
// an expansion; a mistake in the line as written (the '->' above) has no such note.
TEST(SourceExcerpt, AMistakeInAMacrosTextShowsTheMacrosDefinition) {
  const fs::path model = excerptFixture("macro.l");
  const RunResult run = runHirsute({"derive", model.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  const std::string expected = model.string() +
                               ":7:11: error: the '(' of module 'F' is not closed with ')' before "
                               "'endlsystem'\n"
                               " 7 | I(x) --> F(SHORT)\n"
                               "   |           ^\n" +
                               model.string() +
                               ":2:9: note: 'SHORT' is a macro, defined here\n"
                               " 2 | #define SHORT (LEN * 0.6\n"
                               "   |         ^\n";
  EXPECT_EQ(run.err, expected);
}

// A name no #define gives a value, a slip of the hand away from one that is, is named with it.
TEST(SourceExcerpt, AnUndefinedNameIsShownTheDefineItMostLikelyMeant) {
  const fs::path model = excerptFixture("misspelt_define.l");
  const RunResult run = runHirsute({"derive", model.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  const std::string expected = model.string() +
                               ":3:20: error: 'STEPZ' is no constant (a name here must be one the "
                               "file #defines): the derivation length must be a constant "
                               "expression (numbers, operators and math functions)\n"
                               " 3 | derivation length: STEPZ\n"
                               "   |                    ^\n" +
                               model.string() +
                               ":1:9: note: did you mean 'STEPS'? It is defined here\n"
                               " 1 | #define STEPS 4\n"
                               "   |         ^\n";
  EXPECT_EQ(run.err, expected);
}

// A `#line` directive may make a location name any file: only files beneath the model's folder
// are quoted, so no line of /etc/passwd reaches the terminal.
TEST(SourceExcerpt, NoLineOfAFileOutsideTheModelsFolderIsShown) {
  const fs::path model = excerptFixture("line_elsewhere.l");
  const RunResult run = runHirsute({"derive", model.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_EQ(run.err.rfind("/etc/passwd:", 0), 0u) << run.err;
  EXPECT_EQ(run.err.find(" | "), std::string::npos) << run.err;
}

}  // namespace
}  // namespace hirsute

namespace hirsute {
namespace {

TEST(CommandLine, AnUnknownCommandIsNamedWithTheOneMostLikelyMeant) {
  RunResult run = runHirsute({"rendr", "tree.l"});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(run.err,
            "hirsute: error: unknown command 'rendr'; did you mean 'render'? (hirsute --help "
            "lists the commands)\n");
  run = runHirsute({"frobnicate"});
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(run.err, "hirsute: error: unknown command 'frobnicate' (hirsute --help lists the commands)\n");
}

// The help reads as a person expects: the program's name (not the path it was started by), a
// flag by its name, and what an option needs in its description.
TEST(CommandLine, HelpShowsNoBuildPathNoFlagValueAndNoNeedsColumn) {
  for (const std::string command : {"render", "export", "simulate", "render-frames", "derive"}) {
    const RunResult run = runHirsute({command, "--help"});
    EXPECT_EQ(run.exitCode, 0) << command;
    EXPECT_NE(run.out.find("Usage: hirsute " + command + " "), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("{false}"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("Needs:"), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("TEXT:FILE"), std::string::npos) << run.out;
  }
  const RunResult exportHelp = runHirsute({"export", "--help"});
  EXPECT_NE(exportHelp.out.find("(with --pov)"), std::string::npos) << exportHelp.out;
}

}  // namespace
}  // namespace hirsute
// ---- hirsute simulate: option values ----

// A value of tens of thousands of characters once overflowed the stack of the pattern that read
// it.
TEST(SimulateBadInput, AVeryLongAnimateValueIsAnErrorNotACrash) {
  const fs::path coat = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "coat-bending";
  TemporaryFolder folder;
  for (const std::string& value :
       {"BEND=" + std::string(40000, '9') + ":9", "BEND=0:" + std::string(40000, '1'),
        std::string(40000, 'B') + "=0:9"}) {
    const RunResult run = runHirsute(
        {"simulate", (coat / "bending.l").string(), (coat / "bending.v").string(), "-o",
         (folder.path() / "frames").string(), "--animate", value, "--frames", "1", "--no-frames"});
    ASSERT_FALSE(run.killed);
    ASSERT_TRUE(run.exited) << "signal " << run.signal;
    EXPECT_EQ(run.exitCode, 2) << run.err.substr(0, 200);
    EXPECT_EQ(run.err.rfind("hirsute: error: --animate takes NAME=FROM:TO", 0), 0u)
        << run.err.substr(0, 200);
  }
}
