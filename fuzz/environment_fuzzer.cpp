// libFuzzer target: the text of open L-systems (docs/environment.md). The first byte picks what
// the rest of the input is:
//   0  a `.e` communication file (parseCommunicationFile, the reader readCommunicationFile goes
//      through): its executable line taken apart, and when it names a built-in program, that
//      program started with the specification file it names and sent a batch of queries written
//      with the file's own turtle formats, its answers read back;
//   1  the answer text an environmental program sends back (parseAnswers);
//   2  query text as the programs' side reads it (QueryReader), every turtle line present;
//   3  the specification file of the built-in program the second byte picks (honda81,
//      ecosystem, clover, chiba, density), started from a `.e` and sent the same batch.
// The `.e` and specification files are read in a private folder under build/fuzz/work/ that
// holds copies of the models' specification files; no program is started as a process.
//
// A DiagnosticError is the expected answer to broken input; anything else (another exception,
// a crash, a sanitizer report, a hang, memory beyond libFuzzer's limit) is a bug.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_folder.h"
#include "hirsute/environment/communication_file.h"
#include "hirsute/environment/environment_program.h"
#include "hirsute/environment/exchange_text.h"
#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/core/diagnostic.h"

namespace {

namespace fs = std::filesystem;

// The folder: the models' specification files under their own names, for `.e` texts to name,
// and in `spec/` the one specification file that a mode-3 input writes (apart, so that no
// other input reads it: every input's outcome is its own).
const hirsute::fuzz::FuzzFolder& folder() {
  static const hirsute::fuzz::FuzzFolder made("environment_fuzzer");
  static const bool filled = [] {
    for (const char* model :
         {"competing-plants", "density-field", "shaded-balls", "shaded-ground", "tip-collision"}) {
      for (const auto& entry : fs::directory_iterator(hirsute::fuzz::modelFolder(model))) {
        if (entry.path().extension() == ".spec")
          fs::copy_file(entry.path(), made.path() / entry.path().filename());
      }
    }
    fs::create_directory(made.path() / "spec");
    return true;
  }();
  (void)filled;
  return made;
}

// A batch of queries as the query pass writes it: turtles on a small grid, E modules with
// zero to three parameters, some followed by a module.
std::string queryBatch(const hirsute::CommunicationFile& file) {
  std::string batch;
  const float parameters[3] = {1.5f, -2.0f, 0.25f};
  for (unsigned long id = 1; id <= 6; ++id) {
    hirsute::TurtleState turtle;
    turtle.position = {static_cast<double>(id % 3) - 1.0, 0.5 * static_cast<double>(id), 0.0};
    turtle.lineWidth = 0.1 * static_cast<double>(id);
    hirsute::EnvironmentQuery q;
    q.turtle = &turtle;
    q.parameters = parameters;
    q.count = id % 4;
    if (id % 2 == 0) {
      q.followingSymbols = id == 4 ? "@O" : "F";
      q.followingParameters = parameters;
      q.followingCount = 1;
    }
    hirsute::appendQueryRecord(batch, id, q, file);
  }
  return batch + hirsute::batchEndLine(1);
}

// The built-in program the file names, if any, sent the batch; its answers read back.
void exchange(const hirsute::CommunicationFile& file, hirsute::Diagnostics& diagnostics) {
  const std::unique_ptr<hirsute::EnvironmentProgram> program =
      hirsute::makeBuiltinProgram(file, diagnostics);
  if (!program) return;
  hirsute::parseAnswers(program->exchange(queryBatch(file)));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  folder();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    switch (data[0] % 4) {
      case 0: {
        const hirsute::CommunicationFile file =
            hirsute::parseCommunicationFile(text, folder().path() / "fuzz.e", diagnostics);
        hirsute::parseProgramCommand(file);
        exchange(file, diagnostics);
        break;
      }
      case 1: {
        std::vector<std::string> rejected;
        hirsute::parseAnswers(text, &rejected);
        break;
      }
      case 2: {
        const hirsute::CommunicationFile file = hirsute::parseCommunicationFile(
            "turtle position: %g %g %g\nturtle heading: %g %g %g\nturtle left: %g %g %g\n"
            "turtle up: %g %g %g\nturtle line width: %g\nturtle scale factor: %g\n",
            folder().path() / "fuzz.e", diagnostics);
        hirsute::QueryReader reader(file);
        std::vector<hirsute::EnvironmentQueryRecord> records;
        reader.read(text, records);
        break;
      }
      default: {
        if (text.empty()) return 0;
        static const char* const kPrograms[] = {"honda81", "ecosystem", "clover", "chiba",
                                                "density"};
        const std::string program = kPrograms[static_cast<unsigned char>(text[0]) % 5];
        const fs::path specFolder = folder().path() / "spec";
        std::ofstream(specFolder / "fuzz.spec", std::ios::binary | std::ios::trunc)
            << text.substr(1);
        const hirsute::CommunicationFile file = hirsute::parseCommunicationFile(
            "executable: " + program +
                " fuzz.spec\nturtle position: %g %g %g\n"
                "turtle heading: %g %g %g\nturtle up: %g %g %g\nturtle line width: %g\n",
            specFolder / "fuzz.e", diagnostics);
        exchange(file, diagnostics);
        break;
      }
    }
  } catch (const hirsute::DiagnosticError&) {
  }
  return 0;
}
