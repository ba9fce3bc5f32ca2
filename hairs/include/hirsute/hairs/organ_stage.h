// An organ's stage of the pipeline (DESIGN.md, "Organs as plug-ins"): after interpretation, each
// organ in turn adds its own data to the Scene from the records the turtle left there. The
// pipeline runs organStages() in order and names no organ; an organ brings its command-line
// options (its settings), its limits, its warnings and its progress.
//
// Adding an organ's stage: a class derived from OrganStageOf in the organ's folder, and one line
// in organ_stages.cpp's list. The list's order is the order the stages run in.
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
#include "hirsute/lsys/function_curve.h"

namespace CLI {
class App;
}

namespace hirsute {

// An organ's own settings, from its command-line options. The model's options hold one of each
// stage's (OrganSettingsSet) and copy them with the rest.
class OrganSettings {
 public:
  virtual ~OrganSettings() = default;
  virtual std::unique_ptr<OrganSettings> clone() const = 0;

  bool enabled = true;  // the organ's --no-… option switches it off
};

// The clone every settings type writes the same way.
template <class Settings>
class OrganSettingsOf : public OrganSettings {
 public:
  std::unique_ptr<OrganSettings> clone() const override {
    return std::make_unique<Settings>(static_cast<const Settings&>(*this));
  }
};

// What a stage is given besides its settings.
struct OrganStageRun {
  Scene& scene;
  const ModelResources& resources;
  const ViewFunctions& functions;
  Diagnostics& diagnostics;
  std::string lsystemFile;       // where errors without a place of their own point
  std::uint64_t seed = 0;        // of placement (--hair-seed); 0: the view file's
  Progress* progress = nullptr;  // the terminal's progress line (null: nothing shown)
};

class OrganStage {
 public:
  virtual ~OrganStage() = default;

  // What the viewer shows while the stage runs ("placing hairs").
  virtual const char* activity() const = 0;
  // The organ's settings at their defaults, and its options on a command that builds models.
  virtual std::unique_ptr<OrganSettings> defaultSettings() const = 0;
  virtual void addOptions(CLI::App& command, OrganSettings& settings) const = 0;
  // Whether the interpreted scene (or the view file) gives the stage something to do.
  virtual bool wanted(const Scene& scene, const ModelResources& resources) const = 0;
  // Adds the organ's data to run.scene; returns what -v prints about it (without the time). Throws
  // DiagnosticError on bad input and past the organ's limits.
  virtual std::string grow(const OrganStageRun& run, const OrganSettings& settings) const = 0;
  // What a switched-off organ takes out of the scene the turtle made (its instances).
  virtual void leaveOut(Scene& /*scene*/) const {}
};

// A stage over its own settings type: the casts and the defaults written once.
template <class Settings>
class OrganStageOf : public OrganStage {
 public:
  std::unique_ptr<OrganSettings> defaultSettings() const final {
    return std::make_unique<Settings>();
  }
  void addOptions(CLI::App& command, OrganSettings& settings) const final {
    declareOptions(command, static_cast<Settings&>(settings));
  }
  std::string grow(const OrganStageRun& run, const OrganSettings& settings) const final {
    return growFrom(run, static_cast<const Settings&>(settings));
  }

 protected:
  virtual void declareOptions(CLI::App& command, Settings& settings) const = 0;
  virtual std::string growFrom(const OrganStageRun& run, const Settings& settings) const = 0;
};

// Every organ's stage, in the order they run (organ_stages.cpp).
std::span<const OrganStage* const> organStages();

// One settings object per stage of organStages(), copied deeply.
class OrganSettingsSet {
 public:
  OrganSettingsSet();
  OrganSettingsSet(const OrganSettingsSet& other);
  OrganSettingsSet& operator=(const OrganSettingsSet& other);
  OrganSettingsSet(OrganSettingsSet&&) noexcept = default;
  OrganSettingsSet& operator=(OrganSettingsSet&&) noexcept = default;
  ~OrganSettingsSet();

  // The settings of organStages()[stage].
  OrganSettings& operator[](std::size_t stage) { return *settings_[stage]; }
  const OrganSettings& operator[](std::size_t stage) const { return *settings_[stage]; }
  std::size_t size() const { return settings_.size(); }

 private:
  std::vector<std::unique_ptr<OrganSettings>> settings_;
};

}  // namespace hirsute
