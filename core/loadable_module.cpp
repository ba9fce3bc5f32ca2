#include "hirsute/core/loadable_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace hirsute {
namespace {

namespace fs = std::filesystem;

fs::path besideProgram(const char* fileName) {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return (error ? fs::path(".") : self.parent_path()) / fileName;
}

}  // namespace

void* moduleEntry(const char* fileName, const char* environmentVariable, const char* entry,
                  std::string& error) {
  fs::path path;
  if (const char* given = std::getenv(environmentVariable); given != nullptr && *given) {
    path = given;
  } else {
    path = besideProgram(fileName);
#ifdef HIRSUTE_MODULE_BUILD_DIR
    std::error_code ignored;
    if (!fs::exists(path, ignored)) path = fs::path(HIRSUTE_MODULE_BUILD_DIR) / fileName;
#endif
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
