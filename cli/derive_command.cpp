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
  // The model and what its derivation takes, as every command that derives has them (the
  // geometry's options are not offered).
  ModelOptions model;
  bool homomorphism = false;
  bool eachStep = false;
  std::string output;
  std::string format = "cpfg";
};

int runDerive(const DeriveOptions& d) {
  const ModelOptions& o = d.model;
  Progress progress = Progress::onTerminal(stderr);
  Diagnostics diagnostics(&std::cerr);
  diagnostics.setProgress(&progress);
  try {
    std::optional<std::filesystem::path> view;
    if (!o.viewFile.empty()) view = o.viewFile;
    applyWarningOptions(o.warningFlags, o.werror, diagnostics);
    // The view file serves the function set and, for queries, the turtle's settings: through
    // the preprocessor once.
    std::optional<std::string> viewText;
    if (view) viewText = preprocessViewFile(*view, o.maxSourceBytes, diagnostics);
    hirsute::ModelOptions loading;
    loading.maxSourceBytes = o.maxSourceBytes;
    loading.viewText = viewText ? &*viewText : nullptr;
    const ModuleMeanings meanings = turtleModuleMeanings();
    loading.checks = &meanings;
    Model model = loadModel(o.lsystemFile, view, diagnostics, loading);
    stopOnWarnings(diagnostics, o.lsystemFile);
    // ?P ?H ?L ?U take the turtle's values before every step (cpfg manual §6.9), so a model
    // with queries needs its view file's turtle settings; colours play no part in them. So does
    // an environmental program (cpfg -e), which answers the ?E modules in the same pass. The
    // resources outlive the derivation whose query pass reads them.
    ModelResources resources;
    ModelDerivation run(o, model, diagnostics, &progress);
    Derivation& derivation = run.derivation();
    if (model.program.usesQueries || run.environment()) {
      resources = loadModelResources(view, {}, diagnostics, kDefaultMaxMeshTriangles,
                                     o.maxSourceBytes, loading.viewText);
      run.installQueries(resources);
    }

    // No file, or "-": standard output. Otherwise the shared rule for output files.
    std::optional<OutputTarget> file;
    if (!d.output.empty() && d.output != "-") file.emplace(d.output);
    std::FILE* out = file ? file->stream() : stdout;
    StringWriter writer(out, d.format == "compact" ? StringFormat::Compact : StringFormat::Cpfg);
    writer.setStrings(&model.program.strings);  // @L("text") is written with its text
    // The string may go to the terminal the progress line is on: the line is cleared first.
    const auto emitString = [&] {
      progress.clear();
      derivation.emit(writer, d.homomorphism);
    };
    derivation.start();
    if (d.eachStep) {
      // Every string from the axiom on; in the cpfg format they are separated by an empty line.
      emitString();
      writer.finish();
      while (derivation.step()) {
        progress.clear();
        if (d.format != "compact") std::fputc('\n', out);
        emitString();
        writer.finish();
      }
    } else if (!d.output.empty() && d.output != "-") {
      // Into a file, the last step's string is written while it is derived and never held
      // whole; the file only appears once it is complete (OutputTarget::commit).
      if (!derivation.runStreamingLastStep(writer, d.homomorphism)) {
        emitString();
      }
    } else {
      // On standard output an error must leave nothing written, so the string is built first.
      derivation.run();
      emitString();
    }
    progress.clear();
    if (!writer.finish() || (!file && std::fflush(stdout) != 0)) {
      std::cerr << (file ? d.output : std::string("<stdout>"))
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
  derive->add_option("lsystem", options->model.lsystemFile, "The .l file")
      ->required()
      ->check(CLI::ExistingFile);
  derive
      ->add_option("view", options->model.viewFile,
                   "The .v file (its function: and function set: lines are used)")
      ->check(CLI::ExistingFile);
  derive
      ->add_option("-n,--steps", options->model.steps,
                   "Derivation steps (default: the file's derivation length)")
      ->check(CLI::Range(0, 1000000000));
  derive->add_flag("--homomorphism", options->homomorphism,
                   "Apply the homomorphism to the output (cpfg -homo)");
  derive->add_flag("--each-step", options->eachStep,
                   "Print the string after every step, starting with the axiom");
  derive->add_option("-o,--output", options->output, "Write to FILE instead of standard output");
  derive->add_option("--format", options->format, "cpfg (cpfg's -str text) or compact (one line)")
      ->check(CLI::IsMember({"cpfg", "compact"}));
  addEnvironmentOptions(*derive, options->model.environmentFile, options->model.externalEnvironment,
                        options->model.environmentTimeout);
  derive->add_option("--max-modules", options->model.maxModules,
                     "A longer string is an error (default 100000000)");
  derive->add_option("--max-loop-iterations", options->model.maxLoopIterations,
                     "Iterations of while/do loops per block run (default 10000000)");
  addMaxFileBytesOption(*derive, options->model.maxFileBytes);
  addMaxSourceBytesOption(*derive, options->model.maxSourceBytes);
  addThreadsOption(*derive, options->model.threads);
  addWarningOptions(*derive, options->model.warningFlags, options->model.werror);
  derive->callback([options, &action] { action = [options] { return runDerive(*options); }; });
}

}  // namespace hirsute::cli
