// `hirsute check MODEL.l [VIEW.v]`: the model parsed, checked for likely mistakes
// (lsys/model_checks.h) and compiled, without deriving it.
#include <iostream>
#include <memory>

#include "command.h"
#include "hirsute/core/diagnostic.h"
#include "model_pipeline.h"

namespace hirsute::cli {
namespace {

int runCheck(const ModelOptions& o) {
  Diagnostics diagnostics(&std::cerr);
  try {
    loadLsystem(o, diagnostics);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace

void registerCheckCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<ModelOptions>();
  CLI::App* check = app.add_subcommand(
      "check", "Read and compile the model and warn of likely mistakes, without deriving it");
  check->add_option("lsystem", options->lsystemFile, "The .l file")
      ->required()
      ->check(CLI::ExistingFile);
  check
      ->add_option("view", options->viewFile,
                   "The .v file (its function: and function set: lines are used)")
      ->check(CLI::ExistingFile);
  addMaxSourceBytesOption(*check, options->maxSourceBytes);
  addWarningOptions(*check, options->warningFlags, options->werror);
  check->callback([options, &action] { action = [options] { return runCheck(*options); }; });
}

}  // namespace hirsute::cli
