#include "drawing_loader.h"

#include <iostream>
#include <string>

#include "command.h"
#include "hirsute/core/loadable_module.h"

namespace hirsute::cli {
namespace {

int runInModule(const char* fileName, const char* environmentVariable, const char* needs,
                const char* entry, const void* options) {
  std::string error;
  void* symbol = moduleEntry(fileName, environmentVariable, entry, error);
  if (symbol == nullptr) {
    std::cerr << "hirsute: error: " << error << " (" << needs << ")\n";
    return kExitIoError;
  }
  using Entry = int (*)(const void*);
  return reinterpret_cast<Entry>(symbol)(options);
}

}  // namespace

int runInDrawingModule(const char* entry, const void* options) {
  return runInModule("libhirsute-drawing.so", "HIRSUTE_DRAWING_MODULE",
                     "render and view need the drawing library and the GL libraries it links: "
                     "Mesa's OSMesa, libGL, GLFW; scripts/install-deps.sh installs them",
                     entry, options);
}

int runInTraceModule(const char* entry, const void* options) {
  return runInModule("libhirsute-trace.so", "HIRSUTE_TRACE_MODULE",
                     "render --trace needs the trace library and the libraries it links: "
                     "Intel Embree 3 and OpenEXR; scripts/install-deps.sh installs them",
                     entry, options);
}

}  // namespace hirsute::cli
