#include "hirsute/lsys/model.h"

#include "hirsute/lsys/parser.h"
#include "hirsute/lsys/preprocessor.h"

namespace hirsute {

std::string preprocessViewFile(const std::filesystem::path& viewFile, std::size_t maxSourceBytes,
                               Diagnostics& diagnostics) {
  diagnostics.addSourceFolder(ModelFolder(viewFile.parent_path()));
  PreprocessorOptions options;
  options.maxOutputBytes = maxSourceBytes;
  return preprocessFile(viewFile, options, diagnostics);
}

Model loadModel(const std::filesystem::path& lsystemFile,
                const std::optional<std::filesystem::path>& viewFile, Diagnostics& diagnostics,
                const ModelOptions& modelOptions) {
  Model model;
  model.lsystemFile = lsystemFile;
  model.viewFile = viewFile;
  model.folder = lsystemFile.parent_path().empty() ? std::filesystem::path(".") : lsystemFile.parent_path();
  // Messages about the model's files quote the line they point at.
  diagnostics.addSourceFolder(ModelFolder(model.folder));
  if (viewFile) diagnostics.addSourceFolder(ModelFolder(viewFile->parent_path()));
  PreprocessorOptions options;
  options.maxOutputBytes = modelOptions.maxSourceBytes;
  if (viewFile) {
    const std::string viewText =
        modelOptions.viewText != nullptr
            ? *modelOptions.viewText
            : preprocessViewFile(*viewFile, modelOptions.maxSourceBytes, diagnostics);
    model.functions = readViewFunctions(viewText, *viewFile);
    // cpfg defines every function-set name for the preprocessor before reading the `.l`.
    if (modelOptions.defineFunctionSetNames) options.defines = model.functions.macroDefinitions;
  }
  std::string text = modelOptions.lsystemText
                         ? preprocessText(*modelOptions.lsystemText, lsystemFile, options, diagnostics)
                         : preprocessFile(lsystemFile, options, diagnostics);
  ast::File file = parseLsystemText(text, lsystemFile.string());
  if (modelOptions.checks) checkModel(file, *modelOptions.checks, diagnostics);
  model.program = compileProgram(file, diagnostics);
  return model;
}

}  // namespace hirsute
