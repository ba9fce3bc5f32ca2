// The organs' stages (organ_stage.h), registered (organ_list.h), in the order the pipeline runs
// them (the feathers' coats and the fur are placed after the hairs, as they always were), then
// the passes over what they placed: the coats laid shingled (coat_shingling.h).
#include "hirsute/hairs/dynamics/coat_shingling.h"
#include "hirsute/hairs/organ_stage.h"
#include "organ_list.h"

namespace hirsute {

#define HIRSUTE_DECLARE(folder, name) const OrganStage& name##Stage();
HIRSUTE_ORGANS(HIRSUTE_DECLARE)
#undef HIRSUTE_DECLARE

std::span<const OrganStage* const> organStages() {
#define HIRSUTE_STAGE(folder, name) &name##Stage(),
  static const OrganStage* const stages[] = {HIRSUTE_ORGANS(HIRSUTE_STAGE)
                                                 &dynamics::coatShinglingStage()};
#undef HIRSUTE_STAGE
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
