#include "model_pipeline.h"

#include <iostream>
#include <sstream>

#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"

namespace hirsute::cli {
namespace {

// "FILE" is bank 1; "N:FILE" is bank N (cpfg's -mN).
std::pair<int, std::filesystem::path> bankAndFile(const std::string& text) {
  std::size_t colon = text.find(':');
  if (colon != std::string::npos && colon > 0 && text.find_first_not_of("0123456789") == colon) {
    return {std::stoi(text.substr(0, colon)), text.substr(colon + 1)};
  }
  return {1, text};
}

}  // namespace

void addModelOptions(CLI::App& command, ModelOptions& o) {
  command.add_option("lsystem", o.lsystemFile, "The .l file")->required()->check(CLI::ExistingFile);
  command.add_option("view", o.viewFile, "The .v file")->check(CLI::ExistingFile);
  command.add_option("-n,--steps", o.steps, "Derivation steps (default: the file's derivation length)")
      ->check(CLI::Range(0, 1000000000));
  command.add_option("-m,--colormap", o.colormaps, "Colour map (.map); N:FILE for bank N (cpfg -mN)");
  command.add_option("-M,--materials", o.materials, "Materials (.mat); N:FILE for bank N (cpfg -MN)");
  command.add_option("--max-modules", o.maxModules, "A longer string is an error (default 100000000)");
  command.add_option("--max-loop-iterations", o.maxLoopIterations,
                     "Iterations of while/do loops per block run (default 10000000)");
}

ColorFiles colorFilesFor(const ModelOptions& o, Diagnostics& diagnostics) {
  ColorFiles files;
  for (const std::string& m : o.colormaps) files.colormaps.push_back(bankAndFile(m));
  for (const std::string& m : o.materials) files.materials.push_back(bankAndFile(m));
  if (!files.colormaps.empty() || !files.materials.empty()) return files;
  // cpfg needs -m or -M; as a convenience, a folder with exactly one colour file uses it.
  std::filesystem::path folder = std::filesystem::path(o.lsystemFile).parent_path();
  if (folder.empty()) folder = ".";
  std::vector<std::filesystem::path> maps, mats;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.path().extension() == ".map") maps.push_back(entry.path());
    if (entry.path().extension() == ".mat") mats.push_back(entry.path());
  }
  if (maps.size() + mats.size() == 1) {
    if (maps.size() == 1) files.colormaps.push_back({1, maps.front()});
    if (mats.size() == 1) files.materials.push_back({1, mats.front()});
  } else if (maps.size() + mats.size() > 1) {
    diagnostics.warn(SourceLocation{std::make_shared<const std::string>(o.lsystemFile), 0, 0},
                     "several colour files in the model's folder; name one with -m or -M (using the default palette)");
  }
  return files;
}

BuiltScene buildScene(const ModelOptions& o, Diagnostics& diagnostics) {
  BuiltScene built;
  std::optional<std::filesystem::path> view;
  if (!o.viewFile.empty()) view = o.viewFile;
  built.resources = loadModelResources(view, colorFilesFor(o, diagnostics), diagnostics);
  built.model = loadModel(o.lsystemFile, view, diagnostics);
  EvaluationLimits limits;
  limits.maxLoopIterations = o.maxLoopIterations;
  Evaluator evaluator(built.model.program, diagnostics, &built.model.functions, built.model.folder, std::cerr,
                      limits);
  DerivationOptions options;
  options.steps = o.steps;
  options.maxModules = o.maxModules;
  Derivation derivation(built.model.program, evaluator, diagnostics, options);
  installQueryPass(derivation, built.resources, diagnostics);
  derivation.run();
  interpret(derivation, built.resources, built.scene, diagnostics);
  return built;
}

}  // namespace hirsute::cli
