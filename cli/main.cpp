// hirsute: the command-line entry point.
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "command.h"
#include "help_formatter.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/core/nearest_name.h"

int main(int argc, char** argv) {
  // Named, so that usage lines say `hirsute` and not the path it was started by.
  CLI::App app{"Hirsute: an L-system plant modelling environment that reads cpfg models", "hirsute"};
  // Before the commands are added: each takes the formatter of the program when it is made.
  app.formatter(std::make_shared<hirsute::cli::HelpFormatter>());
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
  // A first word that names no command is named back, with the command it most likely meant.
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> commands;
    for (const CLI::App* command : app.get_subcommands({})) commands.push_back(command->get_name());
    const std::string word = argv[1];
    if (std::find(commands.begin(), commands.end(), word) == commands.end()) {
      const std::string meant = hirsute::nearestName(word, commands, 2);
      std::cerr << "hirsute: error: unknown command '" << hirsute::printableText(word) << "'"
                << (meant.empty() ? "" : "; did you mean '" + meant + "'?")
                << " (hirsute --help lists the commands)\n";
      return hirsute::cli::kExitBadInput;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's messages quote the arguments (`File does not exist: NAME`): their control bytes
    // are shown escaped, as in every other message, never passed to the terminal.
    std::ostringstream message;
    const int code = app.exit(e, std::cout, message);
    if (!message.str().empty()) {
      std::cerr << "hirsute: error: " << hirsute::printableText(message.str()) << std::flush;
    }
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
