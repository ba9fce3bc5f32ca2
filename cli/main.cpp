// hirsute: the command-line entry point.
#include <iostream>

#include "command.h"

int main(int argc, char** argv) {
  CLI::App app{"Hirsute: an L-system plant modelling environment that reads cpfg models"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hirsute 0.1.0");
  hirsute::cli::Action action;
  hirsute::cli::registerCheckCommand(app, action);
  hirsute::cli::registerDeriveCommand(app, action);
  hirsute::cli::registerRenderCommand(app, action);
  hirsute::cli::registerExportCommand(app, action);
  hirsute::cli::registerViewCommand(app, action);
  hirsute::cli::registerSimulateCommand(app, action);
  hirsute::cli::registerRenderFramesCommand(app, action);
  hirsute::cli::registerFeatherScanCommand(app, action);
  hirsute::cli::registerBenchCommand(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : hirsute::cli::kExitBadInput;
  }
  try {
    return action ? action() : 0;
  } catch (const std::bad_alloc&) {
    std::cerr << hirsute::cli::outOfMemoryMessage() << '\n';
    return hirsute::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return hirsute::cli::kExitIoError;
  }
}
