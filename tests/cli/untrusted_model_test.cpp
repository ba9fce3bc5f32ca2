// A downloaded model is untrusted code: what it makes `hirsute` write stays beneath its folder.
// Each case is a reproduction of a write that once left the folder (tar keeps symbolic links, so
// a model may carry one), run end to end through the program.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kModels = fs::path(HIRSUTE_SOURCE_DIR) / "models";

class UntrustedModel : public ::testing::Test {
 protected:
  void SetUp() override {
    model_ = root_.path() / "model";
    outside_ = root_.path() / "outside";
    fs::create_directories(model_);
    fs::create_directories(outside_);
    std::ofstream(outside_ / "profile", std::ios::binary) << "# the user's own file\n";
  }
  // A model whose Start block runs `statement`.
  fs::path modelRunning(const std::string& statement) const {
    const fs::path file = model_ / "model.l";
    std::ofstream(file, std::ios::binary) << "Lsystem: 1\nderivation length: 1\nStart: { "
                                          << statement << " }\nAxiom: A\nendlsystem\n";
    return file;
  }
  std::string profile() const { return readText(outside_ / "profile"); }

  TemporaryFolder root_;
  fs::path model_, outside_;
};

TEST_F(UntrustedModel, FopenDoesNotWriteThroughALinkToAFileOutside) {
  fs::create_symlink(outside_ / "profile", model_ / "link.txt");
  for (const char* mode : {"w", "a", "r+", "a+"}) {
    const fs::path file = modelRunning(std::string("f = fopen(\"link.txt\", \"") + mode +
                                       "\"); fprintf(f, \"echo pwned\\n\");");
    const RunResult run = runHirsute({"derive", file.string()});
    EXPECT_EQ(run.exitCode, 2) << mode << ": " << run.err;
    EXPECT_NE(run.err.find("model.l:3:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("error: fopen: cannot open 'link.txt': a symbolic link leads out of "
                           "the model's folder"),
              std::string::npos)
        << run.err;
  }
  EXPECT_EQ(profile(), "# the user's own file\n");
}

// A hard link is the outside file under a name in the folder: no link to follow, the same file.
TEST_F(UntrustedModel, FopenDoesNotWriteThroughAHardLinkToAFileOutside) {
  ASSERT_EQ(link((outside_ / "profile").c_str(), (model_ / "link.txt").c_str()), 0);
  for (const char* mode : {"w", "a", "r+", "w+", "a+"}) {
    const fs::path file = modelRunning(std::string("f = fopen(\"link.txt\", \"") + mode +
                                       "\"); fprintf(f, \"echo pwned\\n\");");
    const RunResult run = runHirsute({"derive", file.string()});
    EXPECT_EQ(run.exitCode, 2) << mode << ": " << run.err;
    EXPECT_NE(run.err.find("model.l:3:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("error: fopen: cannot open 'link.txt': it has 2 names (hard links)"),
              std::string::npos)
        << run.err;
  }
  EXPECT_EQ(profile(), "# the user's own file\n");
  // Reading it is no harm.
  const fs::path file = modelRunning("f = fopen(\"link.txt\", \"r\"); fclose(f);");
  const RunResult run = runHirsute({"derive", file.string()});
  EXPECT_EQ(run.exitCode, 0) << run.err;
}

TEST_F(UntrustedModel, FopenDoesNotEnterALinkedFolderOutside) {
  fs::create_directory_symlink(outside_, model_ / "home");
  const fs::path file = modelRunning("f = fopen(\"home/x\", \"a\"); fprintf(f, \"x\");");
  const RunResult run = runHirsute({"derive", file.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("cannot open 'home/x'"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(outside_ / "x"));
}

TEST_F(UntrustedModel, FopenStillWritesPlainFilesOfTheFolder) {
  const fs::path file =
      modelRunning("f = fopen(\"out.txt\", \"w\"); fprintf(f, \"%d\\n\", 42); fclose(f);");
  const RunResult run = runHirsute({"derive", file.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(readText(model_ / "out.txt"), "42\n");
}

TEST_F(UntrustedModel, FopenOfAFifoIsRefusedAtOnce) {
  ASSERT_EQ(mkfifo((model_ / "pipe").c_str(), 0600), 0);
  for (const char* mode : {"r", "w"}) {
    const fs::path file = modelRunning(std::string("f = fopen(\"pipe\", \"") + mode + "\");");
    const RunResult run = runHirsute({"derive", file.string()});
    EXPECT_FALSE(run.killed) << "fopen of a FIFO hung";
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find("cannot open 'pipe': it is a FIFO"), std::string::npos) << run.err;
  }
}

TEST_F(UntrustedModel, WhatBlocksWriteHasAByteLimit) {
  const fs::path file = modelRunning(
      "f = fopen(\"big.txt\", \"w\"); i = 0; while (i < 100000) { fprintf(f, \"0123456789\"); "
      "i = i + 1; }");
  const RunResult run = runHirsute({"derive", file.string(), "--max-file-bytes", "50000"});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("model.l:3:"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("would write more than 50000 bytes to files (--max-file-bytes)"),
            std::string::npos)
      << run.err;
  EXPECT_LE(fs::file_size(model_ / "big.txt"), 50000u);
  // The default lets the same model write its megabyte.
  const RunResult fine = runHirsute({"derive", file.string()});
  EXPECT_EQ(fine.exitCode, 0) << fine.err;
  EXPECT_EQ(fs::file_size(model_ / "big.txt"), 1000000u);
}

// The preprocessor opens the .l's includes itself; it reads only beneath the model's folder.
TEST_F(UntrustedModel, AnIncludeDoesNotReadThroughALinkOut) {
  std::ofstream(outside_ / "secret.h", std::ios::binary) << "#define SECRET 12345\n";
  fs::create_symlink(outside_ / "secret.h", model_ / "link.h");
  for (const std::string& name : {std::string("link.h"), (outside_ / "secret.h").string()}) {
    const fs::path file = model_ / "model.l";
    std::ofstream(file, std::ios::binary)
        << "#include \"" << name << "\"\nLsystem: 1\nderivation length: 1\nAxiom: A(SECRET)\n"
        << "endlsystem\n";
    const RunResult run = runHirsute({"derive", file.string()});
    EXPECT_EQ(run.exitCode, 2) << name << ": " << run.err;
    EXPECT_NE(run.err.find("model.l:1:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("an #include reads only files beneath the model's folder"),
              std::string::npos)
        << run.err;
    EXPECT_EQ(run.out.find("12345"), std::string::npos) << run.out;
  }
}

TEST_F(UntrustedModel, AnIncludeBeneathTheFolderIsRead) {
  fs::create_directories(model_ / "parts");
  std::ofstream(model_ / "parts" / "sizes.h", std::ios::binary) << "#define SIZE 7\n";
  fs::create_symlink("parts/sizes.h", model_ / "alias.h");  // a link that stays inside
  const fs::path file = model_ / "model.l";
  std::ofstream(file, std::ios::binary) << "#include \"parts/sizes.h\"\n#include \"alias.h\"\n"
                                        << "Lsystem: 1\nderivation length: 1\nAxiom: A(SIZE)\n"
                                        << "endlsystem\n";
  const RunResult run = runHirsute({"derive", file.string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("A(7)"), std::string::npos) << run.out;
}

// Every file a view file names must stay beneath its folder: a link out of it, an absolute name
// or `..` is an error at the line, for each kind of reference.
TEST_F(UntrustedModel, AViewFileNamesNoFileOutsideItsFolder) {
  fs::create_symlink(outside_ / "profile", model_ / "link");
  const fs::path lsystem = modelRunning("");
  for (const std::string& line :
       {std::string("contour: 1 link"), std::string("surface: X link 1"),
        std::string("texture: F: link"), std::string("background scene: link"),
        std::string("hair: link"), std::string("feather: link"), std::string("function: link"),
        std::string("contour: 1 ") + (outside_ / "profile").string(),
        std::string("surface: X ../outside/profile 1")}) {
    const fs::path view = model_ / "model.v";
    std::ofstream(view, std::ios::binary) << "\n" << line << "\n";
    const RunResult run = runHirsute({"render", lsystem.string(), view.string(), "-o",
                                      (root_.path() / "out.png").string(), "--size", "16x16"});
    EXPECT_EQ(run.exitCode, 2) << line << ": " << run.err;
    EXPECT_NE(run.err.find("model.v:2:"), std::string::npos) << line << ": " << run.err;
    EXPECT_NE(run.err.find("the model's folder"), std::string::npos) << line << ": " << run.err;
    EXPECT_FALSE(fs::exists(root_.path() / "out.png")) << line;
  }
}

TEST_F(UntrustedModel, AFeatherFileNamesNoFileOutsideItsFolder) {
  fs::copy(kModels / "feather-types" / "contour.fea", model_ / "contour.fea");
  fs::create_symlink(outside_ / "profile", model_ / "after.fea");
  std::ofstream(model_ / "contour.fea", std::ios::app) << "afterfeather: after.fea\n";
  const fs::path lsystem = model_ / "model.l";
  std::ofstream(lsystem, std::ios::binary) << "Lsystem: 1\nderivation length: 1\nAxiom: @Fe(1)\n"
                                           << "endlsystem\n";
  std::ofstream(model_ / "model.v", std::ios::binary) << "feather: contour.fea\n";
  const RunResult run =
      runHirsute({"render", lsystem.string(), (model_ / "model.v").string(), "-o",
                  (root_.path() / "out.png").string(), "--size", "16x16"});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("contour.fea:"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("cannot open 'after.fea': a symbolic link leads out of the model's folder"),
            std::string::npos)
      << run.err;
}

// A view file's line with a terminal escape (an OSC that sets the window title, a clear-screen)
// is quoted in the warning with the bytes shown, not sent to the terminal.
TEST_F(UntrustedModel, ControlSequencesOfAViewFileAreNotEchoed) {
  const fs::path lsystem = modelRunning("");
  const fs::path view = model_ / "model.v";
  std::ofstream(view, std::ios::binary) << "\x1b]0;owned\x07\x1b[2J: 1\n";
  const RunResult run = runHirsute({"render", lsystem.string(), view.string(), "-o",
                                    (root_.path() / "out.png").string(), "--size", "16x16"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("\\x1b]0;owned\\x07\\x1b[2J"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\x1b'), std::string::npos);
  EXPECT_EQ(run.err.find('\x07'), std::string::npos);
}

// simulate --animate once wrote the frame's .l into a hidden file beside the model, through any
// link of that name, and deleted a file of that name afterwards.
TEST_F(UntrustedModel, SimulateAnimateWritesNothingIntoTheModelFolder) {
  for (const auto& entry : fs::directory_iterator(kModels / "coat-bending"))
    fs::copy(entry.path(), model_ / entry.path().filename());
  fs::create_symlink(outside_ / "profile", model_ / ".bending.l.hirsute-simulate.l");
  std::ofstream(model_ / ".bending.l.hirsute-view.l", std::ios::binary) << "mine\n";
  const RunResult run =
      runHirsute({"simulate", (model_ / "bending.l").string(), (model_ / "bending.v").string(),
                  "-o", (root_.path() / "frames").string(), "--animate", "BEND=0:9", "--frames",
                  "2", "--no-frames"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(profile(), "# the user's own file\n");
  EXPECT_TRUE(fs::is_symlink(model_ / ".bending.l.hirsute-simulate.l"));
  EXPECT_EQ(readText(model_ / ".bending.l.hirsute-view.l"), "mine\n");
  // A mistake in the frame's text names the user's file, not a copy.
  std::string text = readText(model_ / "bending.l");
  const std::string production = "Body(t) --> Body(t + 1)";
  ASSERT_NE(text.find(production), std::string::npos);
  text.replace(text.find(production), production.size(), "Body(t) --> Body(t + )");
  std::ofstream(model_ / "bending.l", std::ios::binary) << text;
  const RunResult broken =
      runHirsute({"simulate", (model_ / "bending.l").string(), (model_ / "bending.v").string(),
                  "-o", (root_.path() / "frames2").string(), "--animate", "BEND=0:9", "--frames",
                  "2", "--no-frames"});
  EXPECT_EQ(broken.exitCode, 2) << broken.err;
  EXPECT_NE(broken.err.find((model_ / "bending.l").string() + ":"), std::string::npos)
      << broken.err;
  EXPECT_EQ(broken.err.find("hirsute-simulate"), std::string::npos) << broken.err;
}

}  // namespace
