// The @H modules of plant hairs (Fuhrer, Jensen & Prusinkiewicz 2004, Table 1; docs/design.md,
// "Plant hairs"): one row each, read by the turtle through organ_modules.h.
#include <algorithm>

#include "hirsute/hairs/plant/hair_part.h"
#include "hirsute/hairs/plant/hair_settings.h"
#include "hirsute/interpreter/organ_modules.h"

namespace hirsute {
namespace {

using HairRow = OrganModuleRow<HairAttributes>;

HairRow sideSwitch(char letter, HairSide side) {
  return switchRow<HairAttributes>(letter, static_cast<int>(side), &HairSideAttributes::enabled);
}

HairRow value(char letter, OrganValue HairSideAttributes::*attribute) {
  return valueRow<HairAttributes>(letter, attribute);
}

// @Hp(P1, …, Pn[, loc]): n is the number of templates the view file declares (one, the default
// straight hair, when it declares none).
HairRow templateProbabilities(char letter) {
  HairRow row;
  row.letter = letter;
  row.form = ParameterForm::Probabilities;
  row.setWeights = [](HairSideAttributes& side, std::span<const float> weights) {
    side.probability.fill(0.0f);
    std::copy(weights.begin(), weights.end(), side.probability.begin());
    side.probabilityCount = static_cast<int>(weights.size());
  };
  row.choices = [](const ModelResources& resources) {
    return std::max<std::size_t>(1, resources.view.organ<HairSettings>().templates.size());
  };
  row.capacity = kMaxHairTemplates;
  row.choiceNoun = "template hair(s)";
  return row;
}

}  // namespace

const OrganModuleTable& plantHairModuleTable() {
  static const AttributeModuleTable<HairAttributes> table(
      "hair",
      [](Scene& scene) -> std::vector<HairAttributes>& {
        return scene.organ<HairPart>().attributes;
      },
      {
          sideSwitch('f', HairSide::Front),
          sideSwitch('b', HairSide::Back),
          sideSwitch('e', HairSide::Edge),
          value('d', &HairSideAttributes::density),
          value('l', &HairSideAttributes::length),
          value('r', &HairSideAttributes::radius),
          value('i', &HairSideAttributes::incline),
          value('t', &HairSideAttributes::twist),
          value('w', &HairSideAttributes::wrap),
          templateProbabilities('p'),
      });
  return table;
}

}  // namespace hirsute
