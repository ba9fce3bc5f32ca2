// The steps every geometry command shares: load the model and its files, derive (with the
// turtle's query pass when the model has query modules), interpret into a Scene.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "hirsute/hairs/organ_stage.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/core/diagnostic.h"
#include "hirsute/environment/environment.h"
#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/evaluator.h"
#include "hirsute/lsys/model.h"
#include "hirsute/core/progress.h"

namespace hirsute::cli {

struct ModelOptions {
  std::string lsystemFile;
  // The .l's text when it differs from the file (the viewer's #define panel, simulate
  // --animate): nothing is written beside the model, and messages name lsystemFile.
  std::optional<std::string> lsystemText;
  std::string viewFile;
  std::optional<int> steps;
  std::vector<std::string> colormaps;  // -m FILE or -m N:FILE (bank N)
  std::vector<std::string> materials;  // -M FILE or -M N:FILE
  std::string environmentFile;           // -e FILE.e: an open L-system's environment
  bool externalEnvironment = false;      // run the .e's executable even when it is built in
  int environmentTimeout = 60;           // seconds an external program may take per batch
  std::size_t maxModules = 100'000'000;
  std::uint64_t maxLoopIterations = 10'000'000;
  std::uint64_t maxFileBytes = EvaluationLimits{}.maxWrittenBytes;  // --max-file-bytes
  std::size_t maxSourceBytes = kDefaultMaxSourceBytes;               // --max-source-bytes
  int threads = 0;  // --threads: of the derivation (0: one a core)
  std::size_t maxVertices = kDefaultMaxVertices;
  std::size_t maxMeshTriangles = kDefaultMaxMeshTriangles;  // --max-mesh-triangles
  std::uint64_t placementSeed = 0;       // --placement-seed; 0: the view file's `hair texture:` seed
  OrganOptionsSet organs;                // each organ's own options (organ_stage.h)
  bool verbose = false;                  // -v: counts and times on stderr
  std::vector<std::string> warningFlags;  // -W no-NAME: the named warnings silenced
  bool werror = false;                    // --Werror: warnings end the run with exit code 2
  // Called as the build goes on (`hirsute view` shows it while building off its render thread):
  // the stage (1 deriving, 2 interpreting, 3 + k the stage of organStages()[k]) and, while
  // deriving, the steps done of the steps to do.
  std::function<void(int stage, int done, int total)> progress;
  // Stop after this many steps of the derivation, whose length stays the file's (the derivation
  // length the model sees, and End, are as in the whole run): cpfg's animation frames.
  std::optional<int> stopAfter;
  // The terminal's progress line (stderr when it is a terminal, Progress::onTerminal): each stage
  // shows how far it has got. Null: nothing is shown.
  Progress* terminalProgress = nullptr;
};

// Adds the model arguments and options shared by render and export to `command`.
void addModelOptions(CLI::App& command, ModelOptions& options);
// Adds -e, --external-environment and --environment-timeout (derive has them too).
void addEnvironmentOptions(CLI::App& command, std::string& file, bool& external, int& timeout);
// Adds -W no-NAME (silences the named warning; NAME one of kModelWarnings) and --Werror.
void addWarningOptions(CLI::App& command, std::vector<std::string>& flags, bool& werror);
// Gives `diagnostics` the warnings silenced and --Werror.
void applyWarningOptions(const std::vector<std::string>& flags, bool werror,
                         Diagnostics& diagnostics);
// With --Werror, throws DiagnosticError (at `file`) once `diagnostics` has had a warning.
void stopOnWarnings(const Diagnostics& diagnostics, const std::string& file);
// Switches the organ's stage off for the run, whatever the command line said (a command whose
// own work replaces what the stage would do).
void leaveStageOut(ModelOptions& options, const OrganStage& stage);

// Adds --threads, the derivation's threads (derive has it too).
void addThreadsOption(CLI::App& command, int& threads);
// Adds --max-file-bytes, what the blocks may write through fprintf (derive has it too).
void addMaxFileBytesOption(CLI::App& command, std::uint64_t& bytes);
// Adds --max-source-bytes, the preprocessed text's limit (derive has it too).
void addMaxSourceBytesOption(CLI::App& command, std::size_t& bytes);

// A loaded model's derivation as every command that derives sets it up: the evaluator with the
// command's limits on loops and written bytes, the derivation with its steps, string limit,
// threads and progress line, and the environmental program of -e when one is named.
class ModelDerivation {
 public:
  ModelDerivation(const ModelOptions& options, const Model& model, Diagnostics& diagnostics,
                  Progress* progress);
  Derivation& derivation() { return derivation_; }
  Environment* environment() { return environment_.get(); }
  // Before every step, the turtle's query modules (?P ?H ?L ?U) take their values from an
  // interpretation with `resources`, and the environment answers the ?E modules; `resources`
  // must outlive the derivation.
  void installQueries(const ModelResources& resources);

 private:
  Diagnostics& diagnostics_;
  Evaluator evaluator_;
  Derivation derivation_;
  std::unique_ptr<Environment> environment_;
};

struct BuiltScene {
  Model model;
  ModelResources resources;
  Scene scene;
};

// Loads the model (loadResources, loadLsystem: the view file through the preprocessor once, for
// both) and grows its Scene (growScene). Throws
// DiagnosticError on bad input (including an organ's, and past an organ's limits).
BuiltScene buildScene(const ModelOptions& options, Diagnostics& diagnostics);
// buildScene for a command: a DiagnosticError is printed on standard error (after `progress`
// is cleared) and gives nothing, for the command to end with exit code 2.
std::optional<BuiltScene> buildSceneOrSay(const ModelOptions& options, Diagnostics& diagnostics,
                                          Progress& progress);
// The view file's resources (colours, contours, surfaces, functions, the organs' files, …).
// `viewText`: the view file already through the preprocessor (preprocessViewFile), if at hand.
ModelResources loadResources(const ModelOptions& options, Diagnostics& diagnostics,
                             const std::string* viewText = nullptr);
// The .l through the preprocessor, parsed and checked for likely mistakes (model_checks.h),
// compiled; constant organ parameters checked. `viewText` as for loadResources.
Model loadLsystem(const ModelOptions& options, Diagnostics& diagnostics,
                  const std::string* viewText = nullptr);
// Derives `model` (to options.stopAfter steps when set), interprets it and runs the organs'
// stages (organ_stage.h) that are switched on and have something to do: a model loaded once grows the Scene of each of its animation's frames.
Scene growScene(const ModelOptions& options, const Model& model, const ModelResources& resources,
                Diagnostics& diagnostics);

// The colour files: those given, or else the single .map or .mat in the model's folder.
ColorFiles colorFilesFor(const ModelOptions& options, Diagnostics& diagnostics);

}  // namespace hirsute::cli
