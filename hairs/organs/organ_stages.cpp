// The organs' stages, registered: one line an organ, in the order the pipeline runs them (the
// feathers' coats and the fur are placed after the hairs, as they always were).
#include "hirsute/hairs/dynamics/coat_shingling.h"
#include "hirsute/hairs/feathers/feather_stage.h"
#include "hirsute/hairs/fur/fur_stage.h"
#include "hirsute/hairs/organ_stage.h"
#include "hirsute/hairs/plant/plant_hairs.h"

namespace hirsute {

std::span<const OrganStage* const> organStages() {
  static const OrganStage* const stages[] = {
      &plantHairStage(),
      &featherStage(),
      &dynamics::coatShinglingStage(),
      &furStage(),
  };
  return stages;
}

OrganOptionsSet::OrganOptionsSet() {
  for (const OrganStage* stage : organStages()) options_.push_back(stage->defaultOptions());
}

OrganOptionsSet::OrganOptionsSet(const OrganOptionsSet& other) {
  for (const auto& options : other.options_) options_.push_back(options->clone());
}

OrganOptionsSet& OrganOptionsSet::operator=(const OrganOptionsSet& other) {
  if (this != &other) *this = OrganOptionsSet(other);
  return *this;
}

OrganOptionsSet::~OrganOptionsSet() = default;

}  // namespace hirsute
