// `hirsute render`, in the drawing module: the model drawn headless (OSMesa) into a PNG, framed
// as cpfg frames it.
#include <iostream>
#include <string>

#include "command.h"
#include "drawing_commands.h"
#include "hirsute/viewer/gl/offscreen.h"
#include "hirsute/viewer/view/png_image.h"

namespace hirsute::cli {

int runRender(const RenderOptions& o) {
  Progress progress = Progress::onTerminal(stderr);
  ModelOptions model = o.model;
  model.terminalProgress = &progress;
  Diagnostics diagnostics(&std::cerr);
  std::optional<BuiltScene> built = buildSceneOrSay(model, diagnostics, progress);
  if (!built) return kExitBadInput;
  OffscreenOptions options;
  const glm::ivec2 size = imageSize(o.size);
  options.width = size.x;
  options.height = size.y;
  options.samples = o.samples;
  RgbaImage image;
  progress.begin("rendering with OpenGL", Progress::Unit::None);
  progress.update(0);
  try {
    const ProgressHeartbeat heartbeat(progress);  // the render says nothing while it runs
    image =
        renderOffscreen(built->scene, built->resources.view, built->resources.materialMode, options);
  } catch (const GeometryLimitError& e) {
    // An organ's geometry, built at the picture's detail, passed --max-vertices.
    progress.clear();
    std::cerr << model.lsystemFile << ": error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    progress.clear();
    std::cerr << "hirsute: error: cannot render: " << e.what() << '\n';
    return kExitIoError;
  }
  progress.clear();
  try {
    writeImage(o.output, image, imageFormatOf(o.output).value_or(ImageFormat::Png));
  } catch (const std::runtime_error& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return kExitIoError;
  }
  return kExitOk;
}

}  // namespace hirsute::cli
