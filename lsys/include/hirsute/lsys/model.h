// Loading a model as cpfg does: the view file first (its `function:`, `function set:` and
// `curve:` lines), then the `.l` through the preprocessor with the function-set names defined,
// then parsing and compiling.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/lsys/function_curve.h"
#include "hirsute/lsys/model_checks.h"
#include "hirsute/lsys/preprocessor.h"
#include "hirsute/lsys/program.h"

namespace hirsute {

struct Model {
  std::filesystem::path lsystemFile;
  std::optional<std::filesystem::path> viewFile;
  std::filesystem::path folder;  // the `.l` file's folder: includes and fopen are relative to it
  ViewFunctions functions;
  Program program;
};

struct ModelOptions {
  // cpfg defines the view file's function-set names for the preprocessor; its batch mode (-g)
  // reads the `.l` first and does not. Off reproduces that mode.
  bool defineFunctionSetNames = true;
  // The `.l` text to use instead of the file's (a constant changed by the viewer's panel or by
  // `simulate --animate`); messages still name the file, and includes and fopen its folder.
  std::optional<std::string> lsystemText;
  // The preprocessed text of the view file and of the `.l` each (--max-source-bytes).
  std::size_t maxSourceBytes = kDefaultMaxSourceBytes;
  // The view file already through the preprocessor (preprocessViewFile), which a caller that
  // also reads the view's settings (loadModelResources) hands to both: it is not run again.
  const std::string* viewText = nullptr;
  // When given, the parsed file is checked for likely mistakes (model_checks.h) with what the
  // interpreter makes of modules.
  const ModuleMeanings* checks = nullptr;
};

// The view file through the C preprocessor, as cpfg reads it (#define, comments), at most
// `maxSourceBytes` long after it; messages about it quote its lines. Run once per load: its text
// serves the function set (loadModel) and the settings (loadModelResources).
std::string preprocessViewFile(const std::filesystem::path& viewFile, std::size_t maxSourceBytes,
                               Diagnostics& diagnostics);

Model loadModel(const std::filesystem::path& lsystemFile,
                const std::optional<std::filesystem::path>& viewFile, Diagnostics& diagnostics,
                const ModelOptions& modelOptions = {});

}  // namespace hirsute
