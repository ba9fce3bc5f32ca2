// A private folder for a fuzz target's files, under the build folder's `work/` (never in the
// repository, never in /tmp): made on first use with mkdtemp, removed with everything in it when
// the process ends. HIRSUTE_FUZZ_WORK_DIR is set by fuzz/CMakeLists.txt.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace hirsute::fuzz {

class FuzzFolder {
 public:
  explicit FuzzFolder(const std::string& target) {
    std::error_code ignored;
    std::filesystem::create_directories(HIRSUTE_FUZZ_WORK_DIR, ignored);
    std::string pattern =
        (std::filesystem::path(HIRSUTE_FUZZ_WORK_DIR) / (target + "-XXXXXX")).string();
    if (!mkdtemp(pattern.data())) std::abort();
    path_ = pattern;
  }
  ~FuzzFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  FuzzFolder(const FuzzFolder&) = delete;
  FuzzFolder& operator=(const FuzzFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A folder of the repository's models, read and never written: the files a fuzzed text names
// (afterfeathers, function sets, specification files) are found there.
inline std::filesystem::path modelFolder(const char* name) {
  return std::filesystem::path(HIRSUTE_SOURCE_DIR) / "models" / name;
}

}  // namespace hirsute::fuzz
