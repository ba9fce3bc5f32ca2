// `hirsute view`: the interactive window (viewer_window.h). This file reads the command line; the
// drawing module runs the window (view_run.cpp).
#include <memory>
#include <string>

#include "command.h"
#include "drawing_commands.h"
#include "drawing_loader.h"

namespace hirsute::cli {

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
      ->check(imageSizeCheck());
  view->add_option("--samples", options->samples,
                   "Multisample antialiasing: samples a pixel (default 4; 1 turns it off)")
      ->check(CLI::Range(1, 64));
  view->add_flag("--save", options->save,
                 "Write constants changed in the panel back into the .l file at once");
  view->add_flag("--no-watch", options->noWatch, "Do not re-derive when the model's files change");
  view->add_flag("--no-panel", options->noPanel, "Start with the constants panel hidden");
  view->add_option("--moving-hairs", options->movingHairs,
                   "Hairs drawn at most while the camera moves (default 20000)");
  view->callback([options, &action] {
    action = [options] { return runInDrawingModule("hirsuteRunView", options.get()); };
  });
}

}  // namespace hirsute::cli
