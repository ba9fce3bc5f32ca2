#include "hirsute/core/loadable_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace hirsute {
namespace {

namespace fs = std::filesystem;

// The folder of the running program.
fs::path programFolder() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path(".") : self.parent_path();
}

}  // namespace

void* moduleEntry(const char* fileName, const char* environmentVariable, const char* entry,
                  std::string& error) {
  fs::path path;
  if (const char* given = std::getenv(environmentVariable); given != nullptr && *given) {
    path = given;
  } else {
    // Beside the program (the build's cli/ folder), else where `cmake --install` puts the
    // modules relative to the program (PREFIX/bin and PREFIX/lib/hirsute), else this build's.
    const fs::path folder = programFolder();
    std::vector<fs::path> candidates = {folder / fileName};
#ifdef HIRSUTE_MODULE_INSTALL_DIR
    candidates.push_back((folder / HIRSUTE_MODULE_INSTALL_DIR / fileName).lexically_normal());
#endif
#ifdef HIRSUTE_MODULE_BUILD_DIR
    candidates.push_back(fs::path(HIRSUTE_MODULE_BUILD_DIR) / fileName);
#endif
    path = candidates.front();
    for (const fs::path& candidate : candidates) {
      std::error_code ignored;
      if (fs::exists(candidate, ignored)) {
        path = candidate;
        break;
      }
    }
  }
  // dlopen keeps one handle a file: a second call returns the loaded module.
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (module == nullptr) {
    const char* why = dlerror();
    error = "cannot load " + path.string() + ": " + (why ? why : "unknown error");
    return nullptr;
  }
  void* symbol = dlsym(module, entry);
  if (symbol == nullptr) {
    error = path.string() + " has no " + entry + " (it is not this program's)";
    return nullptr;
  }
  return symbol;
}

}  // namespace hirsute
