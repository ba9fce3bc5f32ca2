#include "model_pipeline.h"

#include "command.h"
#include "hirsute/core/model_folder.h"

#include <charconv>
#include <chrono>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "hirsute/environment/environment.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/interpreter/organ_modules.h"
#include "hirsute/interpreter/turtle.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"

namespace hirsute::cli {
namespace {

// "FILE" is bank 1; "N:FILE" is bank N (cpfg's -mN).
std::pair<int, std::filesystem::path> bankAndFile(const std::string& text) {
  std::size_t colon = text.find(':');
  if (colon != std::string::npos && colon > 0 && text.find_first_not_of("0123456789") == colon) {
    const std::string file = text.substr(colon + 1);
    int bank = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + colon, bank);
    // A bank past int's range (std::stoi threw out_of_range here) is outside 1 to 12 too.
    if (error != std::errc() || bank < 1 || bank > kMaxColorBanks) {
      throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file), 0, 0},
                            "colour bank " + text.substr(0, colon) + " is outside 1 to " +
                                std::to_string(kMaxColorBanks));
    }
    return {bank, file};
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
  addEnvironmentOptions(command, o.environmentFile, o.externalEnvironment, o.environmentTimeout);
  command.add_option("--max-modules", o.maxModules, "A longer string is an error (default 100000000)");
  command.add_option("--max-loop-iterations", o.maxLoopIterations,
                     "Iterations of while/do loops per block run (default 10000000)");
  addMaxFileBytesOption(command, o.maxFileBytes);
  addMaxSourceBytesOption(command, o.maxSourceBytes);
  addThreadsOption(command, o.threads);
  command.add_option("--max-vertices", o.maxVertices,
                     "More vertices in the geometry are an error (default 100000000)");
  command.add_option("--max-mesh-triangles", o.maxMeshTriangles,
                     "A mesh surface of more triangles is an error (default 2000000)");
  command.add_option("--placement-seed", o.placementSeed,
                     "Seed of every organ's placement: hairs and feather follicles (default: the "
                     "view file's `hair texture:` seed)");
  // Its name before it placed more than hairs, kept for the scripts that use it.
  command.add_option("--hair-seed", o.placementSeed)->group("");
  const std::span<const OrganStage* const> stages = organStages();
  for (std::size_t k = 0; k < stages.size(); ++k) stages[k]->addOptions(command, o.organs[k]);
  command.add_flag("-v,--verbose", o.verbose, "Print counts and times of each stage on stderr");
  addWarningOptions(command, o.warningFlags, o.werror);
}

void leaveStageOut(ModelOptions& options, const OrganStage& stage) {
  const std::span<const OrganStage* const> stages = organStages();
  for (std::size_t k = 0; k < stages.size(); ++k)
    if (stages[k] == &stage) options.organs[k].enabled = false;
}

void addWarningOptions(CLI::App& command, std::vector<std::string>& flags, bool& werror) {
  std::vector<std::string> silenced;
  std::string names;
  for (std::string_view name : kModelWarnings) {
    silenced.push_back("no-" + std::string(name));
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  command.add_option("-W", flags, "-W no-NAME silences the warning NAME (" + names + ")")
      ->check(CLI::IsMember(silenced))
      ->allow_extra_args(false)  // one name each: `-W no-NAME model.l`
      ->type_name("no-NAME");
  command.add_flag("--Werror", werror, "Make warnings errors: the run ends with exit code 2");
}

void applyWarningOptions(const std::vector<std::string>& flags, bool werror,
                         Diagnostics& diagnostics) {
  for (const std::string& flag : flags) diagnostics.silence(flag.substr(3));  // "no-NAME"
  diagnostics.setWerror(werror);
}

void stopOnWarnings(const Diagnostics& diagnostics, const std::string& file) {
  if (!diagnostics.failed()) return;
  throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(file), 0, 0},
                        "warnings are errors (--Werror)");
}

void addEnvironmentOptions(CLI::App& command, std::string& file, bool& external, int& timeout) {
  command.add_option("-e,--environment", file, "The .e file of an open L-system's environment (cpfg -e)")
      ->check(CLI::ExistingFile);
  command.add_flag("--external-environment", external,
                   "Run the .e file's executable as a process even when Hirsute has it built in");
  command.add_option("--environment-timeout", timeout,
                     "Seconds an external environmental program may take to answer (default 60)")
      ->check(CLI::Range(1, 86400));
}

void addMaxSourceBytesOption(CLI::App& command, std::size_t& bytes) {
  command.add_option("--max-source-bytes", bytes,
                     "Bytes of the .l and .v files after the C preprocessor, each (default "
                     "16777216: 16 MiB)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 40));
}

void addMaxFileBytesOption(CLI::App& command, std::uint64_t& bytes) {
  command.add_option("--max-file-bytes", bytes,
                     "Bytes the blocks may write to files through fprintf, all files together "
                     "(default 268435456: 256 MiB)");
}

void addThreadsOption(CLI::App& command, int& threads) {
  command
      .add_option("--threads", threads,
                  "Threads that rewrite the parts of a long derivation step when its productions "
                  "allow it (default 0: one a processor core; 1: one thread)")
      ->check(CLI::Range(0, 64));
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
  const ModelFolder model(folder);
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::filesystem::path extension = entry.path().extension();
    if (extension != ".map" && extension != ".mat") continue;
    // Only a regular file beneath the folder is taken (model_folder.h), not a link out of it.
    const std::string refused = model.refusal(entry.path().filename().string());
    if (!refused.empty()) {
      diagnostics.warn(SourceLocation{std::make_shared<const std::string>(entry.path().string()), 0, 0},
                       "not used as the colour file: " + refused);
      continue;
    }
    (extension == ".map" ? maps : mats).push_back(entry.path());
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

ModelResources loadResources(const ModelOptions& o, Diagnostics& diagnostics,
                             const std::string* viewText) {
  applyWarningOptions(o.warningFlags, o.werror, diagnostics);
  std::optional<std::filesystem::path> view;
  if (!o.viewFile.empty()) view = o.viewFile;
  return loadModelResources(view, colorFilesFor(o, diagnostics), diagnostics,
                            o.maxMeshTriangles, o.maxSourceBytes, viewText);
}

Model loadLsystem(const ModelOptions& o, Diagnostics& diagnostics, const std::string* viewText) {
  std::optional<std::filesystem::path> view;
  if (!o.viewFile.empty()) view = o.viewFile;
  applyWarningOptions(o.warningFlags, o.werror, diagnostics);
  hirsute::ModelOptions loading;
  loading.lsystemText = o.lsystemText;
  loading.maxSourceBytes = o.maxSourceBytes;
  loading.viewText = viewText;
  const ModuleMeanings meanings = turtleModuleMeanings();
  loading.checks = &meanings;
  Model model = loadModel(o.lsystemFile, view, diagnostics, loading);
  // `@Ul(-1)` is an error at its place in the file, not a warning after the derivation.
  checkConstantOrganModules(model.program);
  stopOnWarnings(diagnostics, o.lsystemFile);
  return model;
}

BuiltScene buildScene(const ModelOptions& o, Diagnostics& diagnostics) {
  BuiltScene built;
  // The view file serves the settings and the function set: through the preprocessor once.
  std::optional<std::string> viewText;
  if (!o.viewFile.empty()) {
    applyWarningOptions(o.warningFlags, o.werror, diagnostics);
    viewText = preprocessViewFile(o.viewFile, o.maxSourceBytes, diagnostics);
  }
  const std::string* view = viewText ? &*viewText : nullptr;
  built.resources = loadResources(o, diagnostics, view);
  built.model = loadLsystem(o, diagnostics, view);
  built.scene = growScene(o, built.model, built.resources, diagnostics);
  stopOnWarnings(diagnostics, o.lsystemFile);
  return built;
}

ModelDerivation::ModelDerivation(const ModelOptions& o, const Model& model,
                                 Diagnostics& diagnostics, Progress* progress)
    : diagnostics_(diagnostics),
      evaluator_(model.program, diagnostics, &model.functions, model.folder, std::cerr,
                 EvaluationLimits{.maxLoopIterations = o.maxLoopIterations,
                                  .maxWrittenBytes = o.maxFileBytes}),
      derivation_(model.program, evaluator_, diagnostics,
                  DerivationOptions{.steps = o.steps,
                                    .maxModules = o.maxModules,
                                    .progress = progress,
                                    .threads = o.threads}) {
  // cpfg -e: the environment answers the ?E modules in the query pass before every step.
  if (!o.environmentFile.empty()) {
    EnvironmentOptions environmentOptions;
    environmentOptions.forceExternal = o.externalEnvironment;
    environmentOptions.timeoutSeconds = o.environmentTimeout;
    if (o.verbose) {
      if (progress) progress->clear();
      environmentOptions.log = &std::cerr;
    }
    environment_ = openEnvironment(o.environmentFile, diagnostics, environmentOptions);
  }
}

void ModelDerivation::installQueries(const ModelResources& resources) {
  installQueryPass(derivation_, resources, diagnostics_, environment_.get());
}

Scene growScene(const ModelOptions& o, const Model& model, const ModelResources& resources,
                Diagnostics& diagnostics) {
  Scene scene;
  diagnostics.setProgress(o.terminalProgress);
  ModelDerivation run(o, model, diagnostics, o.terminalProgress);
  Derivation& derivation = run.derivation();
  // -v's lines go to the terminal the progress line is on: it is cleared first.
  const auto say = [&o](const std::string& text) {
    if (o.terminalProgress) o.terminalProgress->clear();
    std::cerr << text;
  };
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point since) {
    return std::chrono::duration<double>(Clock::now() - since).count();
  };
  auto started = Clock::now();
  run.installQueries(resources);
  derivation.start();
  if (o.progress) o.progress(1, 0, derivation.totalSteps());
  while ((!o.stopAfter || derivation.stepsDone() < *o.stopAfter) && derivation.step()) {
    if (o.progress) o.progress(1, derivation.stepsDone(), derivation.totalSteps());
  }
  if (o.progress) o.progress(2, 0, 0);
  if (o.verbose) {
    say(fmt::format("derived {} modules in {:.3f} s\n", derivation.string().moduleCount(), seconds(started)));
  }
  started = Clock::now();
  try {
    interpret(derivation, resources, scene, diagnostics, o.maxVertices, o.terminalProgress);
  } catch (const GeometryLimitError& e) {
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(o.lsystemFile), 0, 0}, e.what());
  }
  if (o.verbose) {
    say(fmt::format("interpreted: {} triangles, {} lines, {} cylinder segments in {:.3f} s\n",
                    scene.triangleCount(), scene.lines.size(), scene.cylinderSegments.size(),
                    seconds(started)));
  }
  const std::span<const OrganStage* const> stages = organStages();
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const OrganStage& stage = *stages[k];
    if (!o.organs[k].enabled || !stage.wanted(scene, resources)) {
      stage.leaveOut(scene);
      continue;
    }
    started = Clock::now();
    if (o.progress) o.progress(3 + static_cast<int>(k), 0, 0);
    const OrganStageRun run{.scene = scene,
                            .resources = resources,
                            .functions = model.functions,
                            .diagnostics = diagnostics,
                            .lsystemFile = o.lsystemFile,
                            .seed = o.placementSeed,
                            .progress = o.terminalProgress,
                            .maxVertices = o.maxVertices,
                            .threads = o.threads};
    const std::string report = stage.grow(run, o.organs[k]);
    if (o.verbose) say(fmt::format("{} in {:.3f} s\n", report, seconds(started)));
  }
  return scene;
}

std::optional<BuiltScene> buildSceneOrSay(const ModelOptions& o, Diagnostics& diagnostics,
                                          Progress& progress) {
  try {
    return buildScene(o, diagnostics);
  } catch (const DiagnosticError& e) {
    progress.clear();
    std::cerr << diagnostics.report(e.diagnostic());
    return std::nullopt;
  }
}

}  // namespace hirsute::cli
