// `hirsute view`: the interactive window (viewer_window.h). This file turns the command line
// into ViewerOptions and gives the window its builder: buildScene on the worker's thread, with the
// panel's `#define` values applied to a hidden copy of the `.l` beside it.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>
#include <string>

#include "command.h"
#include "hirsute/viewer/interaction/define_editor.h"
#include "hirsute/viewer/interaction/view_script.h"
#include "hirsute/viewer/window/viewer_window.h"
#include "model_pipeline.h"

namespace hirsute::cli {
namespace {

struct ViewOptions {
  ModelOptions model;
  std::string animation;
  std::string commands;
  std::string scriptFile;
  std::string size = "800x600";
  int samples = 4;
  bool save = false;
  bool noWatch = false;
  bool noPanel = false;
  std::size_t movingHairs = 20000;
};

std::string readFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
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
  // The panel's values go into a hidden copy beside the .l (includes and fopen stay relative to
  // its folder, and the file watcher skips hidden files); messages name the user's file.
  std::filesystem::path original = base.lsystemFile, temporary;
  if (!request.defines.empty()) {
    temporary = original.parent_path() / ("." + original.filename().string() + ".hirsute-view.l");
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << replaceDefineValues(readFile(original), request.defines);
    if (!out.flush()) throw std::runtime_error(temporary.string() + ": cannot write the file");
    options.lsystemFile = temporary.string();
  }
  struct RemoveTemporary {
    std::filesystem::path file;
    ~RemoveTemporary() {
      std::error_code ec;
      if (!file.empty()) std::filesystem::remove(file, ec);
    }
  } removeTemporary{temporary};
  auto ownNames = [&](std::string text) {
    if (!temporary.empty()) replaceAll(text, temporary.string(), original.string());
    return text;
  };

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
    build.model = std::move(model);
  } catch (const DiagnosticError& e) {
    build.error = ownNames(e.diagnostic().text());
  }
  std::cerr << ownNames(warnings.str());
  return build;
}

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
  std::size_t x = o.size.find('x');
  options.width = std::stoi(o.size.substr(0, x));
  options.height = std::stoi(o.size.substr(x + 1));
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

}  // namespace

void registerViewCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* view = app.add_subcommand(
      "view", "Open the model in a window: mouse and keys as in cpfg, live reloading on edits");
  addModelOptions(*view, options->model);
  view->add_option("animation", options->animation, "The .a animation file")
      ->check(CLI::ExistingFile);
  view->add_option("--commands", options->commands,
                   "Run these viewer commands (separated by ';') instead of waiting for a person, "
                   "then close; see docs/viewer.md");
  view->add_option("--script", options->scriptFile, "Run the viewer commands in FILE, then close")
      ->check(CLI::ExistingFile);
  view->add_option("--size", options->size, "Window size in pixels, WIDTHxHEIGHT (default 800x600)")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string {
            static const std::regex kSize("([1-9][0-9]{0,4})x([1-9][0-9]{0,4})");
            std::smatch m;
            if (!std::regex_match(value, m, kSize)) return "expected WIDTHxHEIGHT, as 1024x768";
            if (std::stoi(m[1]) > 16384 || std::stoi(m[2]) > 16384) {
              return "at most 16384 pixels a side";
            }
            return "";
          },
          "WIDTHxHEIGHT"));
  view->add_option("--samples", options->samples,
                   "Multisample antialiasing: samples a pixel (default 4; 1 turns it off)")
      ->check(CLI::Range(1, 64));
  view->add_flag("--save", options->save,
                 "Write constants changed in the panel back into the .l file at once");
  view->add_flag("--no-watch", options->noWatch, "Do not re-derive when the model's files change");
  view->add_flag("--no-panel", options->noPanel, "Start with the constants panel hidden");
  view->add_option("--moving-hairs", options->movingHairs,
                   "Hairs drawn at most while the camera moves (default 20000)");
  view->callback([options, &action] { action = [options] { return runView(*options); }; });
}

}  // namespace hirsute::cli
