// The drawing module's entry points (drawing_commands.h): the commands that draw, run inside
// libhirsute-drawing.so with every GL library it links. Nothing is thrown across the boundary.
#include "drawing_commands.h"
#include "module_guard.h"

extern "C" __attribute__((visibility("default"))) int hirsuteRunRender(
    const hirsute::cli::RenderOptions* options) {
  return hirsute::cli::guarded(options, hirsute::cli::runRender);
}

extern "C" __attribute__((visibility("default"))) int hirsuteRunView(
    const hirsute::cli::ViewOptions* options) {
  return hirsute::cli::guarded(options, hirsute::cli::runView);
}
