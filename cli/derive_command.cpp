// `hirsute derive`: the string cpfg derives from the same files, in cpfg's -str format.
#include <cerrno>
#include <cstring>
#include <iostream>
#include <optional>

#include "command.h"
#include "hirsute/environment/environment.h"
#include "model_pipeline.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/core/output_target.h"
#include "hirsute/core/progress.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute::cli {
namespace {

struct DeriveOptions {
  std::string lsystemFile;
  std::string viewFile;
  std::optional<int> steps;
  bool homomorphism = false;
  bool eachStep = false;
  std::string output;
  std::string format = "cpfg";
  std::string environmentFile;
  bool externalEnvironment = false;
  int environmentTimeout = 60;
  std::size_t maxModules = 100'000'000;
  std::uint64_t maxLoopIterations = 10'000'000;
  std::uint64_t maxFileBytes = EvaluationLimits{}.maxWrittenBytes;
  std::size_t maxSourceBytes = kDefaultMaxSourceBytes;
  int threads = 0;
  std::vector<std::string> warningFlags;
  bool werror = false;
};

int runDerive(const DeriveOptions& o) {
  Progress progress = Progress::onTerminal(stderr);
  Diagnostics diagnostics(&std::cerr);
  diagnostics.setProgress(&progress);
  try {
    std::optional<std::filesystem::path> view;
    if (!o.viewFile.empty()) view = o.viewFile;
    applyWarningOptions(o.warningFlags, o.werror, diagnostics);
    hirsute::ModelOptions loading;
    loading.maxSourceBytes = o.maxSourceBytes;
    const ModuleMeanings meanings = turtleModuleMeanings();
    loading.checks = &meanings;
    Model model = loadModel(o.lsystemFile, view, diagnostics, loading);
    stopOnWarnings(diagnostics, o.lsystemFile);
    EvaluationLimits limits;
    limits.maxLoopIterations = o.maxLoopIterations;
    limits.maxWrittenBytes = o.maxFileBytes;
    Evaluator evaluator(model.program, diagnostics, &model.functions, model.folder, std::cerr,
                        limits);
    DerivationOptions options;
    options.steps = o.steps;
    options.maxModules = o.maxModules;
    options.threads = o.threads;
    options.progress = &progress;
    // ?P ?H ?L ?U take the turtle's values before every step (cpfg manual §6.9), so a model
    // with queries needs its view file's turtle settings; colours play no part in them. The
    // resources outlive the derivation whose query pass reads them.
    ModelResources resources;
    Derivation derivation(model.program, evaluator, diagnostics, options);
    // cpfg -e: an environmental program answers the ?E modules in the same pass.
    std::unique_ptr<Environment> environment;
    if (!o.environmentFile.empty()) {
      EnvironmentOptions environmentOptions;
      environmentOptions.forceExternal = o.externalEnvironment;
      environmentOptions.timeoutSeconds = o.environmentTimeout;
      environment = openEnvironment(o.environmentFile, diagnostics, environmentOptions);
    }
    if (model.program.usesQueries || environment) {
      resources = loadModelResources(view, {}, diagnostics, kDefaultMaxMeshTriangles,
                                     o.maxSourceBytes);
      installQueryPass(derivation, resources, diagnostics, environment.get());
    }

    // No file, or "-": standard output. Otherwise the shared rule for output files.
    std::optional<OutputTarget> file;
    if (!o.output.empty() && o.output != "-") file.emplace(o.output);
    std::FILE* out = file ? file->stream() : stdout;
    StringWriter writer(out, o.format == "compact" ? StringFormat::Compact : StringFormat::Cpfg);
    writer.setStrings(&model.program.strings);  // @L("text") is written with its text
    // The string may go to the terminal the progress line is on: the line is cleared first.
    const auto emitString = [&] {
      progress.clear();
      derivation.emit(writer, o.homomorphism);
    };
    derivation.start();
    if (o.eachStep) {
      // Every string from the axiom on; in the cpfg format they are separated by an empty line.
      emitString();
      writer.finish();
      while (derivation.step()) {
        progress.clear();
        if (o.format != "compact") std::fputc('\n', out);
        emitString();
        writer.finish();
      }
    } else if (!o.output.empty() && o.output != "-") {
      // Into a file, the last step's string is written while it is derived and never held
      // whole; the file only appears once it is complete (OutputTarget::commit).
      if (!derivation.runStreamingLastStep(writer, o.homomorphism)) {
        emitString();
      }
    } else {
      // On standard output an error must leave nothing written, so the string is built first.
      derivation.run();
      emitString();
    }
    progress.clear();
    if (!writer.finish() || (!file && std::fflush(stdout) != 0)) {
      std::cerr << (file ? o.output : std::string("<stdout>"))
                << ": error: cannot write: " << std::strerror(errno) << '\n';
      return kExitIoError;
    }
    // A warning of the derivation's, with --Werror, leaves no file.
    stopOnWarnings(diagnostics, o.lsystemFile);
    if (file) {
      try {
        file->commit();
      } catch (const std::runtime_error& e) {
        std::cerr << "hirsute: error: " << e.what() << '\n';
        return kExitIoError;
      }
    }
    return kExitOk;
  } catch (const DiagnosticError& e) {
    progress.clear();
    std::cerr << diagnostics.report(e.diagnostic());
    return kExitBadInput;
  }
}

}  // namespace

void registerDeriveCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<DeriveOptions>();
  CLI::App* derive =
      app.add_subcommand("derive", "Derive the L-system and print the string as cpfg's -str does");
  derive->add_option("lsystem", options->lsystemFile, "The .l file")
      ->required()
      ->check(CLI::ExistingFile);
  derive
      ->add_option("view", options->viewFile,
                   "The .v file (its function: and function set: lines are used)")
      ->check(CLI::ExistingFile);
  derive
      ->add_option("-n,--steps", options->steps,
                   "Derivation steps (default: the file's derivation length)")
      ->check(CLI::Range(0, 1000000000));
  derive->add_flag("--homomorphism", options->homomorphism,
                   "Apply the homomorphism to the output (cpfg -homo)");
  derive->add_flag("--each-step", options->eachStep,
                   "Print the string after every step, starting with the axiom");
  derive->add_option("-o,--output", options->output, "Write to FILE instead of standard output");
  derive->add_option("--format", options->format, "cpfg (cpfg's -str text) or compact (one line)")
      ->check(CLI::IsMember({"cpfg", "compact"}));
  addEnvironmentOptions(*derive, options->environmentFile, options->externalEnvironment,
                        options->environmentTimeout);
  derive->add_option("--max-modules", options->maxModules,
                     "A longer string is an error (default 100000000)");
  derive->add_option("--max-loop-iterations", options->maxLoopIterations,
                     "Iterations of while/do loops per block run (default 10000000)");
  addMaxFileBytesOption(*derive, options->maxFileBytes);
  addMaxSourceBytesOption(*derive, options->maxSourceBytes);
  addThreadsOption(*derive, options->threads);
  addWarningOptions(*derive, options->warningFlags, options->werror);
  derive->callback([options, &action] { action = [options] { return runDerive(*options); }; });
}

}  // namespace hirsute::cli
