// The organs' stages, registered: one line an organ, in the order the pipeline runs them (the
// feathers' coats and the fur are placed after the hairs, as they always were).
#include "hirsute/hairs/feathers/feather_stage.h"
#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/hairs/plant/plant_hairs.h"

namespace hirsute {

std::span<const OrganStage* const> organStages() {
  static const OrganStage* const stages[] = {
      &plantHairStage(),
      &featherStage(),
      &furStage(),
  };
  return stages;
}

OrganSettingsSet::OrganSettingsSet() {
  for (const OrganStage* stage : organStages()) settings_.push_back(stage->defaultSettings());
}

OrganSettingsSet::OrganSettingsSet(const OrganSettingsSet& other) {
  for (const auto& settings : other.settings_) settings_.push_back(settings->clone());
}

OrganSettingsSet& OrganSettingsSet::operator=(const OrganSettingsSet& other) {
  if (this != &other) *this = OrganSettingsSet(other);
  return *this;
}

OrganSettingsSet::~OrganSettingsSet() = default;

}  // namespace hirsute
