// Environmental programs of a model's own, built against Hirsute's libcomm.a (programs/), run
// over each transport cpfg offers; and the programs that die, hang or answer garbage end the
// run with an error that names them instead of hanging it.
#include "hirsute/environment/external_program.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "hirsute/environment/environment.h"
#include "support/test_files.h"

namespace hirsute {
namespace {

class ExternalProgramTest : public testing::TemporaryFolderTest {
 protected:
  ExternalProgramTest() : TemporaryFolderTest("hirsute_external_") {}

  std::unique_ptr<Environment> open(const std::string& program, const std::string& argument,
                                    const std::string& transport, int timeout = 20,
                                    std::ostream* log = nullptr) {
    std::ofstream(file("data.txt")) << "obstacles\n";
    std::ofstream(file("model.e")) << "executable: " << program << " " << argument << "\n"
                                   << "communication type: " << transport << "\n"
                                   << "turtle position:P:%.4f %.4f %.4f\n";
    EnvironmentOptions options;
    options.timeoutSeconds = timeout;
    options.log = log;
    return openEnvironment(file("model.e"), diagnostics_, options);
  }

  // One pass with the query ?E(x, 0) at a turtle standing at (2.5, 0, 0), twice; the values
  // of the E module after each.
  std::vector<std::pair<float, float>> twoPasses(Environment& environment, float x) {
    ModuleString s;
    s.append('F');
    s.append('?');
    const std::size_t at = s.end();
    const float values[] = {x, 0};
    s.append('E', std::span<const float>(values, 2));
    TurtleState turtle;
    turtle.position = {2.5, 0, 0};
    std::vector<std::pair<float, float>> out;
    for (int step = 0; step < 2; ++step) {
      environment.beginPass(s, step);
      EnvironmentQuery q;
      q.turtle = &turtle;
      const float current[] = {s.at(at).parameter(0), s.at(at).parameter(1)};
      q.parameters = current;
      q.count = 2;
      q.position = at;
      environment.query(q);
      environment.endPass();
      out.emplace_back(s.at(at).parameter(0), s.at(at).parameter(1));
    }
    return out;
  }

  std::string errorOf(const std::function<void()>& run) {
    try {
      run();
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return "no error";
  }

  Diagnostics diagnostics_;
};

const std::vector<std::pair<float, float>> kTwoAnswers = {{2, 2.5f}, {3, 2.5f}};

TEST_F(ExternalProgramTest, AnswersOverPipes) {
  auto environment = open(HIRSUTE_PLUS_ONE, "data.txt", "pipes");
  EXPECT_EQ(twoPasses(*environment, 1), kTwoAnswers);
}

TEST_F(ExternalProgramTest, AnswersOverFiles) {
  auto environment = open(HIRSUTE_PLUS_ONE, "data.txt", "files");
  EXPECT_EQ(twoPasses(*environment, 1), kTwoAnswers);
  // The exchange files lie beside the .e while the program runs, and go with it.
  environment.reset();
  for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
    EXPECT_EQ(entry.path().filename().string().find(".to_field"), std::string::npos);
  }
}

TEST_F(ExternalProgramTest, AnswersOverSharedMemory) {
  auto environment = open(HIRSUTE_PLUS_ONE, "data.txt", "memory");
  EXPECT_EQ(twoPasses(*environment, 1), kTwoAnswers);
}

TEST_F(ExternalProgramTest, AProgramThatCannotStartIsAnError) {
  const std::string message =
      errorOf([&] { open(file("no-such-program").string(), "data.txt", "pipes"); });
  EXPECT_NE(message.find("model.e:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("did not start"), std::string::npos) << message;
  // plus_one connects, then exits without its argument file: the first batch finds it gone.
  auto environment = open(HIRSUTE_PLUS_ONE, "missing.txt", "files");
  EXPECT_NE(errorOf([&] { twoPasses(*environment, 1); }).find("exited with status 1"),
            std::string::npos);
}

TEST_F(ExternalProgramTest, AProgramThatDiesIsAnErrorNamingIt) {
  for (const char* transport : {"pipes", "files", "memory"}) {
    auto environment = open(HIRSUTE_MISBEHAVING, "die", transport);
    const std::string message = errorOf([&] { twoPasses(*environment, 1); });
    EXPECT_NE(message.find(HIRSUTE_MISBEHAVING), std::string::npos) << message;
    EXPECT_NE(message.find("exited with status 3"), std::string::npos)
        << transport << ": " << message;
  }
}

TEST_F(ExternalProgramTest, AProgramThatHangsRunsIntoTheTimeout) {
  for (const char* transport : {"pipes", "files"}) {
    auto environment = open(HIRSUTE_MISBEHAVING, "hang", transport, 1);
    const auto started = std::chrono::steady_clock::now();
    const std::string message = errorOf([&] { twoPasses(*environment, 1); });
    EXPECT_NE(message.find("did not answer within the time limit"), std::string::npos) << message;
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
  }
}

// Whether process `pid` has ended (gone, or a zombie no one has reaped yet).
bool ended(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

// A .e file runs the program it names: -v shows its command line first, and what it starts
// ends with it.
TEST_F(ExternalProgramTest, WhatTheProgramStartsEndsWithIt) {
  std::ostringstream log;
  int child = 0;
  {
    auto environment = open(HIRSUTE_MISBEHAVING, "spawn", "pipes", 20, &log);
    for (int i = 0; i < 200 && !(std::ifstream(file("child.pid")) >> child); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_GT(child, 0);
    EXPECT_FALSE(ended(child));
  }
  for (int i = 0; i < 200 && !ended(child); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(ended(child)) << "process " << child << " outlived its environment";
  EXPECT_NE(log.str().find("environment: running " + std::string(HIRSUTE_MISBEHAVING) +
                           " -e model.e spawn in "),
            std::string::npos)
      << log.str();
}

TEST_F(ExternalProgramTest, GarbageAnswersAreAnErrorNamingTheProgram) {
  const std::pair<const char*, const char*> answers[] = {
      {"garbage", "the answer is blowing in the wind"}, {"open", "zz E(1,2"}, {"unclosed", "1 E(((("}};
  for (const auto& [mode, line] : answers) {
    auto environment = open(HIRSUTE_MISBEHAVING, mode, "pipes");
    const std::string message = errorOf([&] { twoPasses(*environment, 1); });
    EXPECT_NE(message.find("model.e:1:12: error: environmental program " +
                           std::string(HIRSUTE_MISBEHAVING) +
                           " answered a line that is not an answer record: '" + line + "'"),
              std::string::npos)
        << message;
  }
}

TEST_F(ExternalProgramTest, LibcommAnswersEachPartOfASplitBatch) {
  for (const char* transport : {"pipes 1", "files 1", "memory"}) {
    open(HIRSUTE_PLUS_ONE, "data.txt", transport);  // writes data.txt and model.e
    CommunicationFile e = readCommunicationFile(file("model.e"), diagnostics_);
    std::unique_ptr<EnvironmentProgram> program = startExternalProgram(e, 20, diagnostics_);
    EXPECT_EQ(program->exchange("0 E(1)\nP:1 2 3\nControl: 1 0\n"), "0 E(2)\nControl: 5\n")
        << transport;
    EXPECT_EQ(program->exchange("8 E(5,0)\nP:1 2 3\nControl: 4 0\n"), "8 E(6,1)\nControl: 5\n")
        << transport;
  }
}

TEST_F(ExternalProgramTest, TheBuiltinProgramsRunAsAProcessOfTheirOwn) {
  // hirsute-environment under the name honda81 answers as the built-in does: the tip of vigor
  // 1 lies within the radius of the tip of vigor 2 and stops.
  std::filesystem::create_symlink(HIRSUTE_ENVIRONMENT_SERVER, file("honda81"));
  std::ofstream(file("density.spec")) << "radius: 1\n3d case: on\n";
  const std::string batch = "0 E(1)\nP:0 0 0\n8 E(2)\nP:0.5 0 0\nControl: 5 0\n";
  for (const char* transport : {"pipes", "files", "memory"}) {
    std::ofstream(file("model.e"))
        << "executable: ./honda81 density.spec\ncommunication type: " << transport
        << "\nturtle position:P:%.4f %.4f %.4f\n";
    CommunicationFile e = readCommunicationFile(file("model.e"), diagnostics_);
    std::unique_ptr<EnvironmentProgram> program = startExternalProgram(e, 20, diagnostics_);
    EXPECT_EQ(program->exchange(batch), "0 E(0)\n8 E(1)\nControl: 5\n") << transport;
    EXPECT_EQ(makeBuiltinProgram(e, diagnostics_)->exchange(batch), "0 E(0)\n8 E(1)\nControl: 5\n");
  }
}

TEST_F(ExternalProgramTest, AnswersLargerThanTheSharedMemoryBlockComeInParts) {
  // 2 000 tips in a row, each within the radius of the next: the answers (about 19 000 bytes)
  // do not fit the 10 000-byte block back, so libcomm hands them over in parts and the whole
  // answer arrives joined under one control line, the built-in's to the byte.
  std::filesystem::create_symlink(HIRSUTE_ENVIRONMENT_SERVER, file("honda81"));
  std::ofstream(file("density.spec")) << "radius: 1\n3d case: on\n";
  std::ofstream(file("model.e")) << "executable: ./honda81 density.spec\ncommunication type: memory"
                                 << "\nturtle position:P:%.4f %.4f %.4f\n";
  std::string batch;
  for (int i = 0; i < 2000; ++i) {
    batch +=
        std::to_string(i * 7) + " E(" + std::to_string(i) + ")\nP:" + std::to_string(i) + " 0 0\n";
  }
  batch += "Control: 5 0\n";
  ASSERT_LT(batch.size(), 50000u);
  CommunicationFile e = readCommunicationFile(file("model.e"), diagnostics_);
  std::unique_ptr<EnvironmentProgram> program = startExternalProgram(e, 20, diagnostics_);
  const std::string expected = makeBuiltinProgram(e, diagnostics_)->exchange(batch);
  ASSERT_GT(expected.size(), 10000u);
  EXPECT_EQ(program->exchange(batch), expected);
  // The next batch starts afresh after the parts.
  EXPECT_EQ(program->exchange("0 E(1)\nP:0 0 0\n8 E(2)\nP:0.5 0 0\nControl: 5 1\n"),
            "0 E(0)\n8 E(1)\nControl: 5\n");
}

}  // namespace
}  // namespace hirsute
