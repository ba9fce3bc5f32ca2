// `hirsute view`, in the drawing module: the interactive window (viewer_window.h) with its
// builder, buildScene on the worker's thread, the panel's `#define` values applied to the `.l`'s
// text in memory.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "command.h"
#include "drawing_commands.h"
#include "hirsute/environment/environment_program.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/view_script.h"
#include "hirsute/viewer/window/viewer_window.h"

namespace hirsute::cli {
namespace {

std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One build for the window, on the worker's thread.
ModelBuild buildForViewer(const ModelOptions& base, const ModelRequest& request,
                          BuildProgress& progress) {
  ModelOptions options = base;
  // cpfg's frames: the string after that many steps of the whole derivation.
  options.stopAfter = request.steps;
  options.progress = [&progress](int stage, int done, int total) {
    progress.phase = stage;
    progress.stepsDone = done;
    progress.totalSteps = total;
  };
  // The panel's values go into the .l's text in memory: nothing is written beside the model,
  // includes and fopen stay relative to its folder, and messages name the user's file.
  if (!request.defines.empty())
    options.lsystemText = replaceDefineValues(readFile(base.lsystemFile), request.defines);

  std::ostringstream warnings;
  Diagnostics diagnostics(&warnings);
  ModelBuild build;
  try {
    BuiltScene built = buildScene(options, diagnostics);
    auto model = std::make_shared<ViewerModel>();
    const Lsystem& main = built.model.program.lsystems.front();
    model->derivationLength = options.steps.value_or(main.derivationLength);
    model->steps = request.steps ? std::clamp(*request.steps, 0, model->derivationLength)
                                 : model->derivationLength;
    model->scene = std::move(built.scene);
    model->bounds = model->scene.bounds();
    model->view = built.resources.view;
    model->materialMode = built.resources.materialMode;
    model->functionFiles = built.model.functions.functionFiles;
    model->curveFiles = built.model.functions.curveFiles;
    model->functionSamples = built.model.functions.functionSamples;
    build.model = std::move(model);
  } catch (const DiagnosticError& e) {
    build.error = e.diagnostic().text();
  }
  std::cerr << warnings.str();
  return build;
}

}  // namespace

int runView(const ViewOptions& o) {
  ViewerOptions options;
  options.lsystemFile = o.model.lsystemFile;
  options.viewFile = o.model.viewFile;
  options.animationFile = o.animation;
  // cpfg's order is .l .v .a; a lone .a after the .l is the animation file.
  if (options.animationFile.empty() && options.viewFile.extension() == ".a") {
    std::swap(options.animationFile, options.viewFile);
  }
  ModelOptions model = o.model;
  model.viewFile = options.viewFile.string();
  for (const auto& list : {o.model.colormaps, o.model.materials}) {
    for (const std::string& entry : list) {
      std::size_t colon = entry.find(':');
      options.extraFiles.push_back(colon != std::string::npos &&
                                           entry.find_first_not_of("0123456789") == colon
                                       ? entry.substr(colon + 1)
                                       : entry);
    }
  }
  // cpfg -e: the .e file and the program's specification file are watched too; every rebuild
  // starts the environment afresh, as cpfg restarts it when it regenerates from the axiom.
  if (!o.model.environmentFile.empty()) {
    options.extraFiles.push_back(o.model.environmentFile);
    try {
      Diagnostics quiet;
      const ProgramCommand command =
          parseProgramCommand(readCommunicationFile(o.model.environmentFile, quiet));
      if (command.specification) options.extraFiles.push_back(*command.specification);
    } catch (const DiagnosticError&) {
      // The build reports what is wrong with the .e file.
    }
  }
  // The colour files the builder will read (-m, -M, or the folder's one), for the editors.
  {
    Diagnostics quiet;
    options.colorFiles = colorFilesFor(model, quiet);
  }
  const glm::ivec2 size = imageSize(o.size);
  options.width = size.x;
  options.height = size.y;
  options.samples = o.samples;
  options.steps = o.model.steps;
  options.saveDefines = o.save;
  options.watch = !o.noWatch;
  options.showPanel = !o.noPanel;
  options.movingHairBudget = o.movingHairs;
  try {
    if (!o.scriptFile.empty() || !o.commands.empty()) {
      std::vector<ViewCommand> script;
      if (!o.scriptFile.empty()) script = parseViewScript(readFile(o.scriptFile), o.scriptFile);
      std::vector<ViewCommand> more = parseViewScript(o.commands, "--commands");
      script.insert(script.end(), more.begin(), more.end());
      options.script = std::move(script);
    }
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  return runViewer(options, [model](const ModelRequest& request, BuildProgress& progress) {
    return buildForViewer(model, request, progress);
  });
}

}  // namespace hirsute::cli
