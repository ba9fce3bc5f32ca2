#include "drawing_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "command.h"

namespace hirsute::cli {
namespace {

constexpr const char* kModuleName = "libhirsute-drawing.so";

std::filesystem::path modulePath() {
  if (const char* given = std::getenv("HIRSUTE_DRAWING_MODULE"); given != nullptr && *given)
    return given;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return (error ? std::filesystem::path(".") : self.parent_path()) / kModuleName;
}

}  // namespace

int runInDrawingModule(const char* entry, const void* options) {
  const std::filesystem::path path = modulePath();
  // Loaded once and kept for the process's life: the window's threads and GL stay in it.
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (module == nullptr) {
    std::cerr << "hirsute: error: cannot load the drawing library " << path.string() << ": "
              << dlerror()
              << " (render and view need it and the GL libraries it links: Mesa's OSMesa, "
                 "libGL, GLFW; scripts/install-deps.sh installs them)\n";
    return kExitIoError;
  }
  using Entry = int (*)(const void*);
  auto run = reinterpret_cast<Entry>(dlsym(module, entry));
  if (run == nullptr) {
    std::cerr << "hirsute: error: the drawing library " << path.string() << " has no " << entry
              << " (it is not this program's)\n";
    return kExitIoError;
  }
  return run(options);
}

}  // namespace hirsute::cli
