// libFuzzer target: arbitrary bytes as `.l` text, derived a few steps and then interpreted by the
// turtle into a Scene and covered with plant hairs: every turtle module, generalized cylinders
// (closed, and open through contour 1), the @H modules and hair placement.
//
// A DiagnosticError, or a geometry or hair limit error, is the expected answer to broken or
// excessive input; anything else (another exception, a crash, a sanitizer report, a hang,
// memory beyond libFuzzer's limit) is a bug. The view is fixed and written once at start: lines
// drawn as cylinders, an open contour, hair interpolation on.
#include <signal.h>
#include <sys/resource.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <system_error>

#include "hirsute/hairs/plant/hair_placement.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/parser.h"
#include "hirsute/lsys/program.h"

namespace {

// Limits the command line also has, only lower, so that every input takes milliseconds.
constexpr int kSteps = 4;
constexpr std::size_t kMaxModules = 20'000;
constexpr std::uint64_t kMaxLoopIterations = 100'000;
constexpr std::size_t kMaxVertices = 400'000;
constexpr std::size_t kMaxHairs = 200'000;

class Fixture {
 public:
  Fixture() {
    std::string pattern = (std::filesystem::temp_directory_path() / "hirsute-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    folder_ = pattern;
    std::ofstream(folder_ / "open.con")
        << "cver 1 3\nname: open\npoints: 4 8\ntype: or\nsamples: 6\n"
           "-1 0.2 0 3\n-0.3 0 0 1\n0.3 0 0 1\n1 0.2 0 3\n";
    std::ofstream(folder_ / "fuzz.v") << "line style: cylinder\ncontour: 1 open.con\n"
                                         "hair interpolation: on\nhair texture: 32 3\n";
    hirsute::Diagnostics diagnostics;
    resources_ = hirsute::loadModelResources(folder_ / "fuzz.v", {}, diagnostics);
    std::filesystem::create_directory(modelFolder());
  }
  // Where fopen/fprintf of an input write; emptied after each input.
  std::filesystem::path modelFolder() const { return folder_ / "model"; }
  void resetModelFolder() const {
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(modelFolder(), ignored)) {
      std::filesystem::remove_all(entry.path(), ignored);
    }
  }
  ~Fixture() {
    std::error_code ignored;
    std::filesystem::remove_all(folder_, ignored);
  }
  const hirsute::ModelResources& resources() const { return resources_; }
  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
  hirsute::ModelResources resources_;
};

Fixture& fixture() {
  static Fixture f;  // created on first use, removed at exit
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // A write past 4 MiB fails with EFBIG instead of killing the process.
  signal(SIGXFSZ, SIG_IGN);
  rlimit limit{4 << 20, 4 << 20};
  setrlimit(RLIMIT_FSIZE, &limit);
  fixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  std::ostream printed(nullptr);
  try {
    hirsute::ast::File file = hirsute::parseLsystemText(text, "fuzz.l");
    hirsute::Program program = hirsute::compileProgram(file, diagnostics);
    hirsute::EvaluationLimits limits;
    limits.maxLoopIterations = kMaxLoopIterations;
    hirsute::Evaluator evaluator(program, diagnostics, nullptr, fixture().modelFolder(), printed,
                                 limits);
    hirsute::DerivationOptions options;
    options.steps = kSteps;
    options.maxModules = kMaxModules;
    hirsute::Derivation derivation(program, evaluator, diagnostics, options);
    derivation.run();
    hirsute::Scene scene;
    hirsute::interpret(derivation, fixture().resources(), scene, diagnostics, kMaxVertices);
    hirsute::HairPlacementSettings settings;
    settings.texture.width = settings.texture.height = 32;
    settings.interpolation = true;
    settings.maxHairs = kMaxHairs;
    settings.function = [](int index, double x) {
      return index == 1 ? 2.0 * x - 1.0 : std::nan("");
    };
    hirsute::placeHairs(scene, settings);
  } catch (const hirsute::DiagnosticError&) {
  } catch (const hirsute::GeometryLimitError&) {
  } catch (const hirsute::HairLimitError&) {
  }
  fixture().resetModelFolder();
  return 0;
}
