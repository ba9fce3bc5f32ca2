// `hirsute render`: the model drawn headless (OSMesa) into a PNG, framed as cpfg frames it.
#include <iostream>
#include <memory>
#include <regex>
#include <string>

#include "command.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "hirsute/viewer/gl/png_image.h"
#include "model_pipeline.h"

namespace hirsute::cli {
namespace {

struct RenderOptions {
  ModelOptions model;
  std::string output;
  std::string size = "800x600";
  int samples = 4;
};

int runRender(const RenderOptions& o) {
  Diagnostics diagnostics(&std::cerr);
  BuiltScene built;
  try {
    built = buildScene(o.model, diagnostics);
  } catch (const DiagnosticError& e) {
    std::cerr << e.diagnostic().text() << '\n';
    return kExitBadInput;
  }
  OffscreenOptions options;
  std::size_t x = o.size.find('x');
  options.width = std::stoi(o.size.substr(0, x));
  options.height = std::stoi(o.size.substr(x + 1));
  options.samples = o.samples;
  RgbaImage image;
  try {
    image =
        renderOffscreen(built.scene, built.resources.view, built.resources.materialMode, options);
  } catch (const std::runtime_error& e) {
    std::cerr << "hirsute: error: cannot render: " << e.what() << '\n';
    return kExitIoError;
  }
  try {
    writePng(o.output, image);
  } catch (const std::runtime_error& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return kExitIoError;
  }
  return kExitOk;
}

}  // namespace

void registerRenderCommand(CLI::App& app, Action& action) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* render = app.add_subcommand(
      "render", "Render the model headless to a PNG image, with the view file's camera and lights");
  addModelOptions(*render, options->model);
  render->add_option("-o,--output", options->output, "The PNG file to write")->required();
  render
      ->add_option("--size", options->size, "Image size in pixels, WIDTHxHEIGHT (default 800x600)")
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
  render
      ->add_option("--samples", options->samples,
                   "Multisample antialiasing: samples a pixel (default 4; 1 turns it off)")
      ->check(CLI::Range(1, 64));
  render->callback([options, &action] { action = [options] { return runRender(*options); }; });
}

}  // namespace hirsute::cli
