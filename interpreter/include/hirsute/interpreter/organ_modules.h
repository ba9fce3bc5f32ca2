// Organ modules declared in tables (docs/design.md, "Organs": a registry, not a growing switch).
// Every organ (plant hairs `@H…`, feathers `@F…`, …) is one table: the letter after
// `@`, its attribute record kept in its part of the Scene, and one row per module naming its
// parameter form and what it sets. The turtle looks `@XY` up by X and hands the module to the
// table; it knows no organ's modules itself.
//
// Adding a module to an organ adds a row to its table; an organ's record (with its letter,
// kOrgan), its part of the Scene and its table live in its folder, hairs/NAME/, and its one line
// in hairs/organs/organ_list.h registers the table.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/interpreter/organ_attributes.h"
#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/turtle_state.h"
#include "hirsute/lsys/program.h"

namespace hirsute {

// The parameter forms of organ modules (docs/design.md, "Organs").
enum class ParameterForm {
  Switch,         // (b): the row's side on (no parameter, or non-zero) or off (0)
  Value,          // (v[,rng[,fun[,loc]]]): an OrganValue on the sides loc picks (0: all)
  Probabilities,  // (P1,…,Pn[,loc]): n weights, n the number of choices the view file declares
  Custom,         // any parameters, read into the record by the row's own function
  Action,         // any parameters: an action at the turtle (emits an instance into the Scene)
};

// One organ module as the turtle hands it to its table.
struct OrganModuleCall {
  const float* parameters = nullptr;
  std::size_t count = 0;
  const ModelResources& resources;
  TurtleState& state;
  Scene* scene;  // null in the query pass: nothing is recorded or emitted
  // Warns once per key, at the derived string (Turtle::warnOnce).
  std::function<void(const std::string& key, const std::string& message)> warnOnce;
  // Copy-on-write: the record the organ's last module made, and when. A module right after it
  // (three modules later: `@`, the organ's letter, then the module's) changes that record in
  // place rather than copying it; the turtle keeps one per organ.
  int& scratchRecord;
  std::size_t& scratchModule;
  std::size_t modulesSeen = 0;
};

// A parameter of an organ module that is out of its range: which one (0-based) and what is wrong
// with it ("@Ul: length -1 must be at least 0").
struct ParameterProblem {
  std::size_t index = 0;
  std::string message;
};

// What every organ's table offers the turtle.
class OrganModuleTable {
 public:
  virtual ~OrganModuleTable() = default;
  // The letter after `@` (H for the @H modules).
  virtual char organ() const = 0;
  // Interprets `@` organ() `letter` (letter 0: the organ's letter alone, with parameters).
  virtual void interpret(char letter, OrganModuleCall& call) const = 0;
  // `@` organ() `letter` is one of the organ's modules.
  virtual bool knows(char letter) const = 0;
  // Checks `@` organ() `letter` as the .l file writes it, before the derivation: `parameters`
  // has a value for each parameter that is a constant expression and none for those the
  // derivation computes. The first known value out of its range, if any; a module the table
  // cannot judge without the derivation (or the view file) passes.
  virtual std::optional<ParameterProblem> checkConstants(
      char letter, std::span<const std::optional<float>> parameters) const = 0;
};

// Every organ's table, in the order of hairs/organs/organ_list.h, which defines this at link
// time (organ_models.cpp): the interpreter names no organ.
std::span<const OrganModuleTable* const> organModuleTables();
// The position in organModuleTables() of the organ with letter `organ`, or -1.
int organModuleTableIndex(char organ);

// Checks the organ modules of every axiom and successor (productions, decomposition and
// homomorphism) of `program` whose parameters are constant expressions against their tables:
// a value out of its range (`@Ul(-1)`) throws DiagnosticError at that parameter in the .l file,
// before anything is derived. Values the derivation computes are the turtle's to check: it
// ignores such a module with a warning.
void checkConstantOrganModules(const Program& program);

// The shared readers of the parameter forms (organ_modules.cpp). `name` is the module as the
// user writes it ("@Hd"); each warns once and returns false when the module is to be ignored.
namespace organ_parameters {
// `loc`: 0 (all) or a 1-based side, named after sideNames in the warning.
bool location(const OrganModuleCall& call, const std::string& name, float parameter,
              std::span<const std::string_view> sideNames, int& loc);
// v[,rng[,fun[,loc]]].
bool value(const OrganModuleCall& call, const std::string& name,
           std::span<const std::string_view> sideNames, OrganValue& value, int& loc);
// P1,…,Pn[,loc] for `choices` choices (at most `capacity` are kept): the weights, negative ones
// as 0. `noun` names the choices in the warning ("template hair(s)").
bool probabilities(const OrganModuleCall& call, const std::string& name, std::size_t choices,
                   std::size_t capacity, std::string_view noun,
                   std::span<const std::string_view> sideNames, std::vector<float>& weights,
                   int& loc);
}  // namespace organ_parameters

// A row of an organ's table over its attribute record. Record has sides: `Record::Side`,
// `Record::kSides`, `Record::kSideNames` and `std::array<Side, kSides> sides` (an organ without
// sides has one). Only the members of the row's form are set.
template <class Record>
struct OrganModuleRow {
  using Side = typename Record::Side;
  char letter = 0;  // the module is `@` organ letter
  ParameterForm form = ParameterForm::Custom;
  // Switch: the flag of side `side` (1-based).
  int side = 0;
  bool Side::*flag = nullptr;
  // Value: the attribute on each side.
  OrganValue Side::*value = nullptr;
  // Probabilities: the weights and their count on each side, the number of choices the view
  // file declares, and what they are called in warnings.
  void (*setWeights)(Side&, std::span<const float>) = nullptr;
  std::size_t (*choices)(const ModelResources&) = nullptr;
  std::size_t capacity = 0;
  std::string_view choiceNoun;
  // Custom: reads the parameters into the record; false leaves the record as it was.
  bool (*custom)(Record&, const OrganModuleCall&, const std::string& name) = nullptr;
  // Optional, any form: the check of the parameters known before the derivation
  // (OrganModuleTable::checkConstants).
  std::optional<ParameterProblem> (*checkConstants)(std::span<const std::optional<float>>,
                                                    const std::string& name) = nullptr;
  // Action: acts at the turtle (call.scene is not null).
  void (*action)(const OrganModuleCall&, const std::string& name) = nullptr;
};

// The rows every organ with sides builds the same way: the on/off switch of one side, `@Xf(b)`,
// and a value `@Xd(v[,rng[,fun[,loc]]])` of every side loc picks.
template <class Record>
OrganModuleRow<Record> switchRow(char letter, int side, bool Record::Side::*flag) {
  OrganModuleRow<Record> row;
  row.letter = letter;
  row.form = ParameterForm::Switch;
  row.side = side;
  row.flag = flag;
  return row;
}

template <class Record>
OrganModuleRow<Record> valueRow(char letter, OrganValue Record::Side::*value) {
  OrganModuleRow<Record> row;
  row.letter = letter;
  row.form = ParameterForm::Value;
  row.value = value;
  return row;
}

// An organ's table over its attribute record: the rows, the Scene vector of records and the
// turtle's index into it. Implements the copy-on-write all organs share: a module changes a copy
// of the record unless the record was made by a module of the same organ just before it (runs of
// modules share one new record), and a change that leaves the record as it was makes none.
template <class Record>
class AttributeModuleTable : public OrganModuleTable {
 public:
  using Row = OrganModuleRow<Record>;

  // The organ's records in a Scene (in its part, organ_part.h).
  using Records = std::vector<Record>& (*)(Scene&);

  // The table of the organ with letter Record::kOrgan. `noun` names the organ in the warning for
  // an unknown module ("hair": "@Hx is not a hair module (…)").
  AttributeModuleTable(std::string_view noun, Records records, std::vector<Row> rows)
      : noun_(noun), records_(records), rows_(std::move(rows)) {}

  char organ() const override { return organ_; }
  const std::vector<Row>& rows() const { return rows_; }
  bool knows(char letter) const override { return find(letter) != nullptr; }

  std::optional<ParameterProblem> checkConstants(
      char letter, std::span<const std::optional<float>> parameters) const override {
    const Row* row = find(letter);
    if (row == nullptr || row->checkConstants == nullptr) return std::nullopt;
    return row->checkConstants(parameters, std::string{'@', organ_, letter});
  }

  void interpret(char letter, OrganModuleCall& call) const override {
    if (call.scene == nullptr) return;  // the query pass records nothing
    const std::string name =
        std::string{'@', organ_} + (letter != 0 ? std::string(1, letter) : std::string());
    const Row* row = find(letter);
    if (row == nullptr) {
      call.warnOnce(name,
                    name + " is not a " + std::string(noun_) + " module (" + moduleList() + ")");
      return;
    }
    if (row->form == ParameterForm::Action) {
      row->action(call, name);
      return;
    }
    std::vector<Record>& records = records_(*call.scene);
    int& index = call.state.organs.of<Record>();
    const bool scratch =
        index >= 0 && index == call.scratchRecord && call.modulesSeen == call.scratchModule + 3;
    Record attributes = index >= 0 ? records[static_cast<std::size_t>(index)] : Record{};
    const Record before = attributes;
    if (!apply(*row, attributes, call, name)) return;
    if (scratch) {
      records[static_cast<std::size_t>(index)] = attributes;
    } else if (!(attributes == before) || index < 0) {
      records.push_back(attributes);
      index = static_cast<int>(records.size() - 1);
    } else {
      // Nothing changed and no record was made: the current one may already belong to a
      // control point, so the next module must not take it as its scratch record.
      return;
    }
    call.scratchRecord = index;
    call.scratchModule = call.modulesSeen;
  }

 private:
  const Row* find(char letter) const {
    if (letter == 0) return nullptr;
    for (const Row& row : rows_) {
      if (row.letter == letter) return &row;
    }
    return nullptr;
  }
  std::string moduleList() const {
    std::string list;
    for (const Row& row : rows_) {
      if (!list.empty()) list += ' ';
      list += std::string{'@', organ_, row.letter};
    }
    return list;
  }
  // The sides `loc` picks: all for 0, else the one.
  static std::span<typename Record::Side> sidesOf(Record& record, int loc) {
    if (loc == 0) return record.sides;
    return std::span<typename Record::Side>(&record.sides[static_cast<std::size_t>(loc - 1)], 1);
  }
  static bool apply(const Row& row, Record& record, const OrganModuleCall& call,
                    const std::string& name) {
    switch (row.form) {
      case ParameterForm::Switch:
        record.sides[static_cast<std::size_t>(row.side - 1)].*row.flag =
            call.count == 0 || call.parameters[0] != 0.0f;
        return true;
      case ParameterForm::Value: {
        OrganValue value;
        int loc = 0;
        if (!organ_parameters::value(call, name, Record::kSideNames, value, loc)) return false;
        for (auto& side : sidesOf(record, loc)) side.*row.value = value;
        return true;
      }
      case ParameterForm::Probabilities: {
        std::vector<float> weights;
        int loc = 0;
        if (!organ_parameters::probabilities(call, name, row.choices(call.resources), row.capacity,
                                             row.choiceNoun, Record::kSideNames, weights, loc))
          return false;
        for (auto& side : sidesOf(record, loc)) row.setWeights(side, weights);
        return true;
      }
      case ParameterForm::Custom:
        return row.custom(record, call, name);
      case ParameterForm::Action:
        break;
    }
    return false;
  }

  static constexpr char organ_ = Record::kOrgan;
  std::string_view noun_;
  Records records_;
  std::vector<Row> rows_;
};

}  // namespace hirsute
