// libFuzzer target: arbitrary bytes as the argument vector of `hirsute simulate` (the arguments
// after the command's name, separated by NUL bytes), parsed by CLI11 with simulate's own options
// (simulate_options.h) and, when they parse, checked as the run checks them before it derives:
// the .a taking the view file's place, --animate NAME=FROM:TO against the .l's #define
// constants, and the colour files of -m and -M with their banks.
//
// Every "@/" in an argument becomes the folder of models/coat-bending (read, never written), so
// that the vector can name real files (`@/bending.l @/bending.v @/bending.a`) wherever the
// fuzzer runs. A CLI11 parse error or a DiagnosticError is the expected answer to a bad vector;
// anything else (another exception, a crash, a sanitizer report, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_folder.h"
#include "hirsute/core/diagnostic.h"
#include "simulate_options.h"

namespace {

std::vector<std::string> arguments(const std::uint8_t* data, std::size_t size) {
  static const std::string kFolder = hirsute::fuzz::modelFolder("coat-bending").string() + "/";
  std::vector<std::string> out{"hirsute", "simulate"};
  std::string current;
  const auto finish = [&] {
    for (std::size_t at = 0; (at = current.find("@/", at)) != std::string::npos;
         at += kFolder.size()) {
      current.replace(at, 2, kFolder);
    }
    out.push_back(current);
    current.clear();
  };
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      finish();
    } else {
      current += static_cast<char>(data[i]);
    }
  }
  if (!current.empty()) finish();
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words = arguments(data, size);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  CLI::App app{"hirsute"};
  app.require_subcommand(1);
  hirsute::cli::SimulateOptions options;
  CLI::App* command = app.add_subcommand("simulate", "simulate");
  hirsute::cli::addSimulateOptions(*command, options);
  try {
    app.parse(static_cast<int>(argv.size() - 1), argv.data());
  } catch (const CLI::ParseError&) {
    return 0;  // the expected answer to a bad vector (CLI11 prints it, exit code 2)
  }
  // What runSimulate checks before it reads the model.
  hirsute::Diagnostics diagnostics;  // warnings are collected, not printed
  try {
    if (!options.animate.empty())
      hirsute::cli::animatedDefine(options.animate, options.model.lsystemFile);
    hirsute::cli::colorFilesFor(options.model, diagnostics);
  } catch (const hirsute::DiagnosticError&) {
  }
  return 0;
}
