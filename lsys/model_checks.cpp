#include "hirsute/lsys/model_checks.h"

#include <cctype>
#include <map>
#include <string>
#include <vector>

namespace hirsute {
namespace {

using ast::Module;
using ast::ModuleList;

std::size_t parameterCount(const Module& m) {
  return m.formals.empty() ? m.arguments.size() : m.formals.size();
}

bool isLetter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

std::string quoted(char symbol) {
  return std::string("'") + symbol + "'";
}

std::string parameters(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " parameter" : " parameters");
}

// The predecessor as the file writes it: `B < A(x,y) > C`.
std::string predecessorText(const ast::Production& p) {
  const auto modules = [](const ModuleList& list) {
    std::string text;
    for (const Module& m : list) {
      text += m.symbol;
      if (m.hasParentheses) {
        text += '(';
        for (std::size_t i = 0; i < m.formals.size(); ++i)
          text += (i > 0 ? "," : "") + m.formals[i].name;
        text += ')';
      }
    }
    return text;
  };
  std::string text;
  if (!p.left.empty()) text += modules(p.left) + " < ";
  text += modules(p.strict);
  if (!p.right.empty()) text += " > " + modules(p.right);
  return text;
}

// Every parameter count each symbol has in a set of module lists, with the first place each
// count is written.
struct ProducedCounts {
  std::array<std::map<std::size_t, SourceLocation>, 128> bySymbol;

  void add(const ModuleList& list) {
    for (const Module& m : list) {
      const auto symbol = static_cast<unsigned char>(m.symbol);
      if (symbol < 128) bySymbol[symbol].emplace(parameterCount(m), m.where);
    }
  }
  const std::map<std::size_t, SourceLocation>& of(char symbol) const {
    return bySymbol[static_cast<unsigned char>(symbol) & 127];
  }
};

// Marks the modules of `list` that the turtle reads as part of a prefixed module: the letters
// after `@` (`@Gs`, `@O`), after `?` (`?P`) and after `~` (`~l`), as Turtle::interpret groups them.
// Warns of each `@` module the turtle does not know.
std::vector<bool> prefixedModules(const ModuleList& list, const ModuleMeanings& meanings,
                                  Diagnostics& diagnostics) {
  std::vector<bool> prefixed(list.size(), false);
  for (std::size_t i = 0; i + 1 < list.size(); ++i) {
    const Module& m = list[i];
    if (parameterCount(m) != 0 || (m.symbol != '@' && m.symbol != '?' && m.symbol != '~')) continue;
    const Module& first = list[i + 1];
    prefixed[i + 1] = true;
    if (m.symbol != '@') {
      ++i;
      continue;
    }
    char second = 0;
    if (parameterCount(first) == 0 && meanings.atFamily(first.symbol)) {
      if (i + 2 >= list.size()) break;
      second = list[i + 2].symbol;
      prefixed[i + 2] = true;
    }
    if (!meanings.atModule(first.symbol, second)) {
      const std::string name =
          std::string("@") + first.symbol + (second ? std::string(1, second) : "");
      diagnostics.warn(m.where, "unknown module '" + name + "': the turtle ignores it",
                       std::string(kUnknownAtModuleWarning));
    }
    i += second ? 2 : 1;
  }
  return prefixed;
}

// `[` and `]` of one axiom or successor: a `]` closing nothing, or `[` left open.
void checkBrackets(const ModuleList& list, const SourceLocation& where, const std::string& what,
                   Diagnostics& diagnostics) {
  int depth = 0, opened = 0, closed = 0;
  for (const Module& m : list) {
    if (m.symbol == '[') ++opened, ++depth;
    if (m.symbol != ']') continue;
    ++closed;
    if (--depth < 0) {
      diagnostics.warn(m.where, "this ']' in " + what + " closes no '['",
                       std::string(kUnbalancedBracketsWarning));
      return;
    }
  }
  if (depth > 0) {
    diagnostics.warn(where,
                     what + " opens " + std::to_string(opened) + " '[' but closes only " +
                         std::to_string(closed) + ": the branches never end",
                     std::string(kUnbalancedBracketsWarning));
  }
}

// Runs of letters written together (`Flower(0.4)`) of which some letter is neither rewritten nor
// interpreted: each letter is a module of its own, and the name means nothing to Hirsute.
void checkLetterRuns(const ModuleList& list, const std::vector<bool>& prefixed,
                     const std::array<bool, 128>& meaningful, Diagnostics& diagnostics) {
  std::size_t i = 0;
  while (i < list.size()) {
    std::size_t end = i;
    while (end < list.size() && !prefixed[end] && isLetter(list[end].symbol)) {
      const Module& m = list[end];
      ++end;
      if (m.hasParentheses || end == list.size()) break;
      const Module& next = list[end];
      if (next.where.line != m.where.line || next.where.column != m.where.column + 1 ||
          next.where.fileName() != m.where.fileName())
        break;
    }
    if (end - i >= 2) {
      std::string name, inert;
      std::size_t inertCount = 0;
      for (std::size_t k = i; k < end; ++k) {
        const char symbol = list[k].symbol;
        name += symbol;
        if (meaningful[static_cast<unsigned char>(symbol) & 127]) continue;
        ++inertCount;
        if (inert.find(symbol) == std::string::npos) inert += symbol;
      }
      // One inert letter beside a meaningful one is a marker (`ZO(4)`, Z a module that only
      // stands in the string); a name (`Flower`, `Apex`, `Bud`) has several.
      if (inertCount >= 2) {
        std::string letters;
        for (std::size_t k = 0; k < inert.size(); ++k)
          letters += (k == 0 ? "" : k + 1 == inert.size() ? " and " : ", ") + quoted(inert[k]);
        diagnostics.warn(list[i].where,
                         "'" + name + "' is read as " + std::to_string(end - i) +
                             " modules of one letter each, and " + letters +
                             (inertCount == 1 ? " is" : " are") +
                             " neither rewritten nor interpreted; module names are one letter",
                         std::string(kMultiLetterNameWarning));
      }
    }
    i = std::max(end, i + 1);
  }
}

// A production whose predecessor the string never holds: a letter no axiom or successor makes,
// or a parameter count it never has (`I(l,w)` while the string holds `I(l)`).
void checkApplies(const ast::Production& p, const ProducedCounts& produced, const char* rules,
                  Diagnostics& diagnostics) {
  const auto check = [&](const Module& m, bool context) {
    if (context && (!isLetter(m.symbol))) return true;
    const auto& counts = produced.of(m.symbol);
    const std::string predecessor = predecessorText(p);
    if (counts.empty()) {
      diagnostics.warn(m.where,
                       std::string(rules) + " `" + predecessor + "` can never apply: no axiom or " +
                           "successor makes the module " + quoted(m.symbol),
                       std::string(kUnusedProductionWarning));
      return false;
    }
    const std::size_t n = parameterCount(m);
    if (counts.count(n)) return true;
    std::string others;
    for (auto k = counts.begin(); k != counts.end(); ++k)
      others += (k == counts.begin()            ? ""
                 : std::next(k) == counts.end() ? " or "
                                                : ", ") +
                std::to_string(k->first);
    diagnostics.warn(
        m.where,
        std::string(rules) + " `" + predecessor + "` can never apply: its " + quoted(m.symbol) +
            " has " + parameters(n) + ", but every " + quoted(m.symbol) + " the string holds has " +
            others +
            (counts.size() == 1 && counts.begin()->first == 1 ? " parameter" : " parameters") +
            " (as made at " + counts.begin()->second.text() + ")",
        std::string(kParameterCountWarning));
    return false;
  };
  for (const Module& m : p.strict)
    if (!check(m, false)) return;
  for (const ModuleList* context : {&p.left, &p.right})
    for (const Module& m : *context)
      if (!check(m, true)) return;
}

}  // namespace

void checkModel(const ast::File& file, const ModuleMeanings& meanings, Diagnostics& diagnostics) {
  // What the string can hold: the axioms, productions and decompositions of every L-system (a
  // sub-L-system's modules go into the same string). The homomorphism's own successors are
  // rewritten by the homomorphism only.
  ProducedCounts inString;
  // A letter is meaningful when the turtle interprets it, a production reads it, or the file
  // names it in `ignore:` or `consider:`.
  std::array<bool, 128> meaningful{};
  for (int c = 0; c < 128; ++c) meaningful[c] = meanings.interpreted(static_cast<char>(c));
  for (const ast::Lsystem& l : file.lsystems) {
    for (const auto& named : {l.ignore, l.consider})
      if (named)
        for (char c : *named) meaningful[static_cast<unsigned char>(c) & 127] = true;
    inString.add(l.axiom);
    for (const ast::Production& p : l.productions) inString.add(p.successor);
    for (const ast::Production& p : l.decomposition.productions) inString.add(p.successor);
    for (const auto* rules :
         {&l.productions, &l.decomposition.productions, &l.homomorphism.productions})
      for (const ast::Production& p : *rules)
        for (const ModuleList* list : {&p.left, &p.strict, &p.right})
          for (const Module& m : *list)
            meaningful[static_cast<unsigned char>(m.symbol) & 127] = true;
  }
  ProducedCounts interpreted = inString;
  for (const ast::Lsystem& l : file.lsystems)
    for (const ast::Production& p : l.homomorphism.productions) interpreted.add(p.successor);

  const auto checkList = [&](const ModuleList& list, const SourceLocation& where,
                             const std::string& what) {
    const std::vector<bool> prefixed = prefixedModules(list, meanings, diagnostics);
    checkBrackets(list, where, what, diagnostics);
    checkLetterRuns(list, prefixed, meaningful, diagnostics);
  };
  for (const ast::Lsystem& l : file.lsystems) {
    if (l.hasAxiom) checkList(l.axiom, l.axiomWhere, "the axiom");
    const auto checkRules = [&](const std::vector<ast::Production>& rules, const char* kind,
                                const ProducedCounts& produced) {
      for (const ast::Production& p : rules) {
        checkList(p.successor, p.where, "the successor of `" + predecessorText(p) + "`");
        checkApplies(p, produced, kind, diagnostics);
      }
    };
    checkRules(l.productions, "the production", inString);
    checkRules(l.decomposition.productions, "the decomposition production", inString);
    checkRules(l.homomorphism.productions, "the homomorphism production", interpreted);
  }
}

}  // namespace hirsute
