// libFuzzer target: arbitrary bytes as `.l` text through the parser, the compiler and a short
// derivation, with the homomorphism applied to the result.
//
// A DiagnosticError is the expected answer to broken input. Anything else is a bug: another
// exception (libFuzzer reports it as a crash), a crash, a sanitizer report, a leak, a hang or
// memory beyond libFuzzer's limits. A program whose steps may be rewritten in parts on several
// threads (parallel_rewriting.h) is derived again so, every step split in three, and a string,
// error or warning that differs is a bug too (an abort); so is one that differs when the
// program's machine code (native_code.h) is dropped and the evaluator runs all of it. The C
// preprocessor is skipped (it is an external program); the input may still carry cpp's
// `# line "file"` markers, which the lexer reads.
#include <signal.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <system_error>

#include "hirsute/lsys/derivation.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/module_sink.h"
#include "hirsute/lsys/native_code.h"
#include "hirsute/lsys/parallel_rewriting.h"
#include "hirsute/lsys/parser.h"
#include "hirsute/lsys/program.h"

namespace {

// Small limits, so that every input finishes in milliseconds; they are limits the command line
// also has (--max-modules, --max-loop-iterations, -n), only lower.
constexpr int kSteps = 4;
constexpr std::size_t kMaxModules = 100'000;
constexpr std::uint64_t kMaxLoopIterations = 100'000;
// Files a model writes with fopen/fprintf may not grow past this (writes beyond it fail).
constexpr rlim_t kMaxFileBytes = 4 << 20;

// Reads every module of the derived string as an interpreter would, keeping its bytes.
class ReadingSink : public hirsute::ModuleSink {
 public:
  void module(char symbol, const float* parameters, std::size_t count) override {
    text_ += symbol;
    text_.append(reinterpret_cast<const char*>(parameters), count * sizeof(float));
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

// The model's folder for fopen: private to this process, holding one data file for fscanf.
// Whatever an input writes there is removed after it, so the disk does not fill up.
class ModelFolder {
 public:
  ModelFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "hirsute-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    path_ = pattern;
    reset();
  }
  ~ModelFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }
  void reset() {
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(path_, ignored)) {
      std::filesystem::remove_all(entry.path(), ignored);
    }
    std::ofstream(path_ / "data.txt") << "1 2.5 -3\n4e2 x 7\n";
  }

 private:
  std::filesystem::path path_;
};

ModelFolder& modelFolder() {
  static ModelFolder folder;  // created on first use, removed at exit
  return folder;
}

// What a derivation gave: the string's bytes (after the homomorphism), the error, the warnings.
struct Outcome {
  std::string text, error, warnings;
  bool operator==(const Outcome&) const = default;
};

Outcome derive(const hirsute::Program& program, int threads) {
  Outcome outcome;
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  std::ostream printed(nullptr);     // printf output goes nowhere
  hirsute::EvaluationLimits limits;
  limits.maxLoopIterations = kMaxLoopIterations;
  hirsute::Evaluator evaluator(program, diagnostics, nullptr, modelFolder().path(), printed,
                               limits);
  hirsute::DerivationOptions options;
  options.steps = kSteps;
  options.maxModules = kMaxModules;
  options.threads = threads;
  options.parallelMinimumModules = 0;  // every step split when it may be
  options.parallelMinimumCost = 0;
  try {
    hirsute::Derivation derivation(program, evaluator, diagnostics, options);
    derivation.run();
    ReadingSink sink;
    derivation.emit(sink, true);
    outcome.text = sink.text();
  } catch (const hirsute::DiagnosticError& e) {
    outcome.error = e.diagnostic().text();  // the expected answer to broken input
  }
  for (const hirsute::Diagnostic& w : diagnostics.warnings()) outcome.warnings += w.text() + "\n";
  return outcome;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // A write past the size limit fails with EFBIG instead of killing the process.
  signal(SIGXFSZ, SIG_IGN);
  rlimit limit{kMaxFileBytes, kMaxFileBytes};
  setrlimit(RLIMIT_FSIZE, &limit);
  modelFolder();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  hirsute::Diagnostics diagnostics;
  hirsute::Program program;
  try {
    hirsute::ast::File file = hirsute::parseLsystemText(text, "fuzz.l");
    program = hirsute::compileProgram(file, diagnostics);
  } catch (const hirsute::DiagnosticError&) {
    return 0;  // the expected answer to broken input
  }
  const Outcome one = derive(program, 1);
  modelFolder().reset();
  if (hirsute::rewritesModulesIndependently(program) && !(derive(program, 3) == one)) {
    std::abort();  // the parts gave another string, error or warnings than one thread
  }
  modelFolder().reset();
  if (program.nativeCode) {
    hirsute::dropNativeCode(program);
    if (!(derive(program, 1) == one)) {
      std::abort();  // the machine code gave another string, error or warnings than the evaluator
    }
    modelFolder().reset();
  }
  return 0;
}
