// The trace module's entry point (drawing_commands.h): `render --trace`, run inside
// libhirsute-trace.so with Embree and OpenEXR. Nothing is thrown across the boundary.
#include "drawing_commands.h"
#include "module_guard.h"

extern "C" __attribute__((visibility("default"))) int hirsuteRunTrace(
    const hirsute::cli::RenderOptions* options) {
  return hirsute::cli::guarded(options, hirsute::cli::runTrace);
}
