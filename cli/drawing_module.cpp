// The drawing module's entry points (drawing_commands.h): the commands that draw, run inside
// libhirsute-drawing.so with every GL library it links. Nothing is thrown across the boundary.
#include <exception>
#include <iostream>
#include <new>

#include "command.h"
#include "drawing_commands.h"

namespace {

template <class Options, class Run>
int guarded(const Options* options, Run run) {
  try {
    return run(*options);
  } catch (const std::bad_alloc&) {
    std::cerr << hirsute::cli::outOfMemoryMessage() << '\n';
    return hirsute::cli::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "hirsute: error: " << e.what() << '\n';
    return hirsute::cli::kExitIoError;
  }
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int hirsuteRunRender(
    const hirsute::cli::RenderOptions* options) {
  return guarded(options, hirsute::cli::runRender);
}

extern "C" __attribute__((visibility("default"))) int hirsuteRunView(
    const hirsute::cli::ViewOptions* options) {
  return guarded(options, hirsute::cli::runView);
}
