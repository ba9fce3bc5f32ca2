// What the tests that derive every model share: the models (the lsys fixtures, models/, some
// benchmark kinds cut short, and cpfg's conformance set when it is there), the view file each is
// derived with, and a derivation's string in the compact format.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/lsys/derivation.h"
#include "hirsute/lsys/program.h"
#include "hirsute/lsys/string_writer.h"

namespace hirsute::testing {

// The view file a model is derived with: its own name's, else the folder's first (func() and
// the function set come from it).
inline std::optional<std::filesystem::path> viewFor(const std::filesystem::path& lfile) {
  std::filesystem::path same = std::filesystem::path(lfile).replace_extension(".v");
  if (std::filesystem::exists(same)) return same;
  std::optional<std::filesystem::path> first;
  for (const auto& entry : std::filesystem::directory_iterator(lfile.parent_path())) {
    if (entry.path().extension() == ".v" && (!first || entry.path() < *first)) first = entry.path();
  }
  return first;
}

struct CorpusModel {
  std::filesystem::path lfile;
  std::optional<int> steps;  // the benchmark kinds' steps, cut short
};

// Every model of the repository and of the conformance set. The fixtures are read from a private
// copy, removed with the object: some write files into their folder.
class ModelCorpus {
 public:
  // `source`: the repository; `benchmarks`: the models/bench kinds to add, with their steps.
  ModelCorpus(const std::filesystem::path& source, const std::string& name,
              const std::vector<std::pair<std::string, int>>& benchmarks)
      : copy_(std::filesystem::temp_directory_path() /
              ("hirsute-" + name + "-" + std::to_string(getpid()))) {
    std::filesystem::remove_all(copy_);
    std::filesystem::copy(source / "tests/fixtures/lsys", copy_,
                          std::filesystem::copy_options::recursive);
    for (const std::filesystem::path& root :
         {copy_, source / "models", source / "../shared/conformance"}) {
      if (!std::filesystem::exists(root)) continue;
      for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        const std::filesystem::path& p = entry.path();
        if (p.extension() != ".l" || p.string().find("/bench/") != std::string::npos) continue;
        models_.push_back({p, std::nullopt});
      }
    }
    for (const auto& [kind, steps] : benchmarks) {
      models_.push_back({source / "models/bench" / (kind + ".l"), steps});
    }
  }
  ~ModelCorpus() { std::filesystem::remove_all(copy_); }
  ModelCorpus(const ModelCorpus&) = delete;
  ModelCorpus& operator=(const ModelCorpus&) = delete;

  const std::vector<CorpusModel>& models() const { return models_; }

 private:
  std::filesystem::path copy_;
  std::vector<CorpusModel> models_;
};

// The derivation's string as `derive --format compact` writes it.
inline std::string compactString(Derivation& derivation, const Program& program) {
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* memory = open_memstream(&buffer, &size);
  {
    StringWriter writer(memory, StringFormat::Compact);
    writer.setStrings(&program.strings);
    derivation.emit(writer, false);
    writer.finish();
  }
  std::fclose(memory);
  std::string text(buffer, size);
  std::free(buffer);
  return text;
}

}  // namespace hirsute::testing
