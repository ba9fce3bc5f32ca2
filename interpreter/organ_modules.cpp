// The look-up of organ tables by letter and the readers of the parameter forms they share
// (docs/design.md, "Organs"; the value form is Fuhrer et al. 2004, Table 1). The tables
// themselves are registered in hairs/organs/organ_list.h, which defines organModuleTables().
#include "hirsute/interpreter/organ_modules.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hirsute/interpreter/cpfg_numbers.h"

namespace hirsute {

int organModuleTableIndex(char organ) {
  const auto tables = organModuleTables();
  for (std::size_t i = 0; i < tables.size(); ++i) {
    if (tables[i]->organ() == organ) return static_cast<int>(i);
  }
  return -1;
}

std::size_t organSlot(char letter) {
  const int index = organModuleTableIndex(letter);
  if (index < 0) {
    throw std::logic_error(std::string("no organ table has the letter ") + letter);
  }
  return static_cast<std::size_t>(index);
}

namespace {

// The organ modules of one axiom or successor: `@`, the organ's letter (both without
// parameters) and the module's letter with its parameters, as the turtle reads them
// (turtle.cpp: `@Ul(1)` is `@`, `U`, `l(1)` in the string).
void checkModules(std::span<const SuccessorModule> modules,
                  std::span<const ModuleArgument> arguments) {
  std::vector<std::size_t> firstArgument(modules.size() + 1, 0);
  for (std::size_t i = 0; i < modules.size(); ++i)
    firstArgument[i + 1] = firstArgument[i] + modules[i].parameterCount;
  if (firstArgument.back() != arguments.size()) return;  // not from the compiler: nothing known
  for (std::size_t i = 0; i + 2 < modules.size(); ++i) {
    if (modules[i].symbol != '@' || modules[i].parameterCount != 0) continue;
    const int organ = organModuleTableIndex(modules[i + 1].symbol);
    if (organ < 0 || modules[i + 1].parameterCount != 0) continue;
    const SuccessorModule& module = modules[i + 2];
    const std::span<const ModuleArgument> given =
        arguments.subspan(firstArgument[i + 2], module.parameterCount);
    std::vector<std::optional<float>> values;
    for (const ModuleArgument& argument : given) {
      // cpfg: parameters are stored as float32, as the module string will hold them.
      values.push_back(argument.constant
                           ? std::optional<float>(static_cast<float>(*argument.constant))
                           : std::nullopt);
    }
    const auto problem =
        organModuleTables()[static_cast<std::size_t>(organ)]->checkConstants(module.symbol, values);
    if (problem) throw DiagnosticError(given[problem->index].where, problem->message);
    i += 2;
  }
}

}  // namespace

void checkConstantOrganModules(const Program& program) {
  for (const Lsystem& lsystem : program.lsystems) {
    checkModules(lsystem.axiom, lsystem.axiomArguments);
    for (const RuleSet* rules :
         {&lsystem.productions, &lsystem.decomposition, &lsystem.homomorphism}) {
      for (const Production& production : rules->productions)
        checkModules(production.successor, production.successorArguments);
    }
  }
}

namespace organ_parameters {

bool location(const OrganModuleCall& call, const std::string& name, float parameter,
              std::span<const std::string_view> sideNames, int& loc) {
  loc = truncated(parameter);
  if (loc < 0 || loc > static_cast<int>(sideNames.size())) {
    // "0 (all), 1 (front), 2 (back) or 3 (edge)"
    std::string choices = "0 (all)";
    for (std::size_t i = 0; i < sideNames.size(); ++i) {
      choices += (i + 1 == sideNames.size() ? " or " : ", ") + std::to_string(i + 1) + " (" +
                 std::string(sideNames[i]) + ")";
    }
    call.warnOnce(name + " loc", name + ": loc " + std::to_string(loc) + " is not " + choices +
                                     "; module ignored");
    return false;
  }
  return true;
}

bool value(const OrganModuleCall& call, const std::string& name,
           std::span<const std::string_view> sideNames, OrganValue& value, int& loc) {
  const float* p = call.parameters;
  const std::size_t count = call.count;
  if (count == 0) {
    call.warnOnce(name + " empty", name + " needs a value: " + name + "(value[,rng[,fun[,loc]]])");
    return false;
  }
  if (count > 4)
    call.warnOnce(name + " many", name + " takes at most 4 parameters; the rest are ignored");
  loc = 0;
  if (count >= 4 && !location(call, name, p[3], sideNames, loc)) return false;
  value = OrganValue{p[0], count >= 2 ? std::abs(p[1]) : 0.0f, count >= 3 ? truncated(p[2]) : 0};
  if (value.function < 0) value.function = 0;
  return true;
}

bool probabilities(const OrganModuleCall& call, const std::string& name, std::size_t choices,
                   std::size_t capacity, std::string_view noun,
                   std::span<const std::string_view> sideNames, std::vector<float>& weights,
                   int& loc) {
  const float* p = call.parameters;
  const std::size_t count = call.count;
  // n is the number of choices the view file declares; a parameter past them is loc.
  std::size_t n = std::min(count, choices);
  loc = 0;
  if (count == choices + 1) {
    if (!location(call, name, p[choices], sideNames, loc)) return false;
  } else if (count > choices + 1) {
    call.warnOnce(name + " many", name + ": " + std::to_string(count) + " parameters for " +
                                      std::to_string(choices) + " " + std::string(noun) +
                                      "; the extra ones are ignored");
  }
  n = std::min(n, capacity);
  weights.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] < 0.0f)
      call.warnOnce(name + " negative", name + ": a negative probability counts as 0");
    weights[i] = std::max(0.0f, p[i]);
  }
  return true;
}

}  // namespace organ_parameters
}  // namespace hirsute
