// An organ's stage of the pipeline (docs/design.md, "Organs"): after interpretation, each
// organ in turn adds its own data to the Scene from the records the turtle left there. The
// pipeline runs organStages() in order and names no organ; an organ brings its command-line
// options (its settings), its limits, its warnings and its progress.
//
// Adding an organ's stage: a class derived from OrganStageOf in the organ's folder, returned by its
// nameStage() (hairs/organs/organ_list.h). The list's order is the order the stages run in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/progress.h"
#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/lsys/function_curve.h"

namespace CLI {
class App;
}

namespace hirsute {

// An organ's command-line options (its view-file settings are organ_settings.h's). The model's
// options hold one of each stage's (OrganOptionsSet) and copy them with the rest.
class OrganOptions {
 public:
  virtual ~OrganOptions() = default;
  virtual std::unique_ptr<OrganOptions> clone() const = 0;

  bool enabled = true;  // the organ's --no-… option switches it off
};

// The clone every options type writes the same way.
template <class Options>
class OrganOptionsOf : public OrganOptions {
 public:
  std::unique_ptr<OrganOptions> clone() const override {
    return std::make_unique<Options>(static_cast<const Options&>(*this));
  }
};

// What a stage is given besides its options.
struct OrganStageRun {
  Scene& scene;
  const ModelResources& resources;
  const ViewFunctions& functions;
  Diagnostics& diagnostics;
  std::string lsystemFile;       // where errors without a place of their own point
  std::uint64_t seed = 0;        // of placement (--hair-seed); 0: the view file's
  Progress* progress = nullptr;  // the terminal's progress line (null: nothing shown)
  std::size_t maxVertices = kDefaultMaxVertices;  // --max-vertices, for what outputs build
  int threads = 0;  // --threads (0: one per core); a stage's result may not depend on it
};

class OrganStage {
 public:
  virtual ~OrganStage() = default;

  // What the viewer shows while the stage runs ("placing hairs").
  virtual const char* activity() const = 0;
  // The organ's options at their defaults, and their flags on a command that builds models.
  virtual std::unique_ptr<OrganOptions> defaultOptions() const = 0;
  virtual void addOptions(CLI::App& command, OrganOptions& options) const = 0;
  // Whether the interpreted scene (or the view file) gives the stage something to do.
  virtual bool wanted(const Scene& scene, const ModelResources& resources) const = 0;
  // Adds the organ's data to run.scene; returns what -v prints about it (without the time). Throws
  // DiagnosticError on bad input and past the organ's limits.
  virtual std::string grow(const OrganStageRun& run, const OrganOptions& options) const = 0;
  // What a switched-off organ takes out of the scene the turtle made (its instances).
  virtual void leaveOut(Scene& /*scene*/) const {}
};

// A stage over its own options type: the casts and the defaults written once.
template <class Options>
class OrganStageOf : public OrganStage {
 public:
  std::unique_ptr<OrganOptions> defaultOptions() const final { return std::make_unique<Options>(); }
  void addOptions(CLI::App& command, OrganOptions& options) const final {
    declareOptions(command, static_cast<Options&>(options));
  }
  std::string grow(const OrganStageRun& run, const OrganOptions& options) const final {
    return growFrom(run, static_cast<const Options&>(options));
  }

 protected:
  virtual void declareOptions(CLI::App& command, Options& options) const = 0;
  virtual std::string growFrom(const OrganStageRun& run, const Options& options) const = 0;
};

// Every organ's stage, in the order they run (hairs/organs/organ_list.h).
std::span<const OrganStage* const> organStages();

// One options object per stage of organStages(), copied deeply.
class OrganOptionsSet {
 public:
  OrganOptionsSet();
  OrganOptionsSet(const OrganOptionsSet& other);
  OrganOptionsSet& operator=(const OrganOptionsSet& other);
  OrganOptionsSet(OrganOptionsSet&&) noexcept = default;
  OrganOptionsSet& operator=(OrganOptionsSet&&) noexcept = default;
  ~OrganOptionsSet();

  // The options of organStages()[stage].
  OrganOptions& operator[](std::size_t stage) { return *options_[stage]; }
  const OrganOptions& operator[](std::size_t stage) const { return *options_[stage]; }
  std::size_t size() const { return options_.size(); }

 private:
  std::vector<std::unique_ptr<OrganOptions>> options_;
};

}  // namespace hirsute
