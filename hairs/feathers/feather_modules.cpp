// The @F modules of feathers (Streit & Heidrich 2002; docs/design.md, "Feathers"): one feather at
// the turtle (@Fe, @Fi) and the coat attributes of the following generalized-cylinder segments
// (@Ff @Fb @Fd @Fk @Fa @Fs @Fl @Ft), one row each, read by the turtle through organ_modules.h.
#include <algorithm>
#include <cmath>

#include "hirsute/hairs/feathers/feather_part.h"
#include "hirsute/hairs/feathers/feather_settings.h"
#include "hirsute/interpreter/cpfg_numbers.h"
#include "hirsute/interpreter/organ_modules.h"

namespace hirsute {
namespace {

using FeatherRow = OrganModuleRow<FeatherAttributes>;

FeatherRow sideSwitch(char letter, FeatherSide side) {
  return switchRow<FeatherAttributes>(letter, static_cast<int>(side),
                                      &FeatherSideAttributes::enabled);
}

FeatherRow value(char letter, OrganValue FeatherSideAttributes::*attribute) {
  return valueRow<FeatherAttributes>(letter, attribute);
}

// A feather type number of a module, 1 to the number of `feather:` lines; 0 after a warning.
int featherType(const OrganModuleCall& call, const std::string& name, float parameter) {
  const int type = truncated(parameter);
  const std::size_t declared = call.resources.view.organ<FeatherSettings>().types.size();
  if (type < 1 || static_cast<std::size_t>(type) > declared) {
    call.warnOnce(name + " type " + std::to_string(type),
                  name + ": no feather type " + std::to_string(type) + " (the view file declares " +
                      std::to_string(declared) + " with `feather:` lines); nothing is drawn");
    return 0;
  }
  return type;
}

// @Fe(k[,age[,size]]) and @Fi(k1,k2,t[,age[,size]]): one feather at the turtle, its calamus base
// at the turtle's position, the rachis along H, the front towards U (feather_geometry.h).
void emitFeather(const OrganModuleCall& call, const std::string& name, bool blended) {
  const std::size_t needed = blended ? 3 : 1;
  if (call.count < needed) {
    call.warnOnce(name + " empty", name + (blended ? " needs (k1, k2, t[, age[, size]])"
                                                   : " needs (k[, age[, size]])"));
    return;
  }
  const float* p = call.parameters;
  const int first = featherType(call, name, p[0]);
  const int second = blended ? featherType(call, name, p[1]) : first;
  if (first == 0 || second == 0) return;
  const std::size_t rest = needed;
  Feather feather;
  feather.position = glm::vec3(call.state.position);
  feather.heading = glm::vec3(call.state.heading);
  feather.up = glm::vec3(call.state.up);
  const auto a = static_cast<std::uint16_t>(first), b = static_cast<std::uint16_t>(second);
  feather.types = {a, b, a, b};
  const float t = blended ? std::clamp(p[2], 0.0f, 1.0f) : 0.0f;
  feather.across = {t, t};
  feather.age = call.count > rest ? std::clamp(p[rest], 0.0f, 1.0f) : 1.0f;
  feather.size = call.count > rest + 1 ? std::max(0.0f, p[rest + 1]) : 1.0f;
  if (!std::isfinite(feather.size)) feather.size = 0;
  if (feather.size <= 0) return;
  call.scene->organ<FeatherPart>().feathers.push_back(feather);
}

FeatherRow action(char letter, bool blended) {
  FeatherRow row;
  row.letter = letter;
  row.form = ParameterForm::Action;
  row.action = blended ? [](const OrganModuleCall& call,
                            const std::string& name) { emitFeather(call, name, true); }
                       : [](const OrganModuleCall& call, const std::string& name) {
                           emitFeather(call, name, false);
                         };
  return row;
}

// @Fk(k1[,k2[,fun]]): the key feather at the next control point.
FeatherRow keyFeather(char letter) {
  FeatherRow row;
  row.letter = letter;
  row.form = ParameterForm::Custom;
  row.custom = [](FeatherAttributes& record, const OrganModuleCall& call, const std::string& name) {
    if (call.count == 0) {
      call.warnOnce(name + " empty", name + " needs (k1[, k2[, fun]])");
      return false;
    }
    const int first = featherType(call, name, call.parameters[0]);
    const int second = call.count >= 2 ? featherType(call, name, call.parameters[1]) : first;
    if (first == 0 || second == 0) return false;
    record.key = KeyFeather{first, second, call.count >= 3 ? truncated(call.parameters[2]) : 0};
    return true;
  };
  return row;
}

}  // namespace

const OrganModuleTable& featherModuleTable() {
  static const AttributeModuleTable<FeatherAttributes> table(
      "feather",
      [](Scene& scene) -> std::vector<FeatherAttributes>& {
        return scene.organ<FeatherPart>().attributes;
      },
      {
          action('e', false),
          action('i', true),
          sideSwitch('f', FeatherSide::Front),
          sideSwitch('b', FeatherSide::Back),
          value('d', &FeatherSideAttributes::density),
          keyFeather('k'),
          value('a', &FeatherSideAttributes::age),
          value('s', &FeatherSideAttributes::size),
          value('l', &FeatherSideAttributes::lie),
          value('t', &FeatherSideAttributes::twist),
      });
  return table;
}

}  // namespace hirsute
