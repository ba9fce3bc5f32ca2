#include "support/build_paths.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace hirsute::build_paths {
namespace {

namespace fs = std::filesystem;

// The build folder: the test programs lie in its folder tests/.
const fs::path& buildFolder() {
  static const fs::path folder = [] {
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    if (error) {
      std::fprintf(stderr, "tests: cannot find the test program itself (/proc/self/exe): %s\n",
                   error.message().c_str());
      std::abort();
    }
    return self.parent_path().parent_path();
  }();
  return folder;
}

}  // namespace

const char* sourceDir() {
  // HIRSUTE_SOURCE_FROM_BUILD: the source tree relative to the build folder ("../.." for the
  // presets' build/NAME), the same in every clone.
  static const std::string source = [] {
    fs::path path = (buildFolder() / HIRSUTE_SOURCE_FROM_BUILD).lexically_normal();
    if (path.filename().empty() && path.has_relative_path()) path = path.parent_path();
    return path.string();
  }();
  return source.c_str();
}

const char* buildFile(const char* relative) {
  static std::mutex mutex;
  static std::map<std::string, std::string> paths;  // node-based: the strings never move
  const std::lock_guard<std::mutex> lock(mutex);
  auto [at, added] = paths.try_emplace(relative);
  if (added) at->second = (buildFolder() / relative).string();
  return at->second.c_str();
}

}  // namespace hirsute::build_paths
