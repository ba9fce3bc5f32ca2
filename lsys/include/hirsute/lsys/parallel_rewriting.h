// Whether a derivation step may rewrite parts of its string on several threads and give the
// string, the warnings and the errors of one thread rewriting it from left to right.
//
// cpfg rewrites the string module by module, and what one production's code does can reach the
// next: global variables and arrays written in blocks, files, the random streams, stop(), and
// the production's own variables, which keep their values from one use to the next (a block that
// reads `n` before it writes it sees the value the last module left). A program none of whose
// productions can do any of that rewrites each module from the module, its contexts and values
// fixed for the whole step, so that the modules of a step can be rewritten in any order.
//
// ParallelSteps rewrites such a step in parts, one a thread, each part by a StepPart (a derivation
// of its own: its own evaluator, frames and string), and joins the parts' strings in order. It
// splits a step only where that pays, by the cost of the last steps.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hirsute/lsys/code.h"
#include "hirsute/lsys/context_matching.h"
#include "hirsute/lsys/module_string.h"
#include "hirsute/lsys/program.h"

namespace hirsute {

// A forward must-analysis of `code` (definite assignment over frame slots): true when no
// instruction can read a frame slot that is not written on every path to it. `written`
// holds on entry the slots written before the code runs (a production's formal parameters) and
// on return the slots written on every path to the code's end.
bool readsOnlyWrittenSlots(const Code& code, std::vector<char>& written);

// Whether `program`'s steps can be rewritten in parts; when not, `why` says what prevents it
// (for tests and the benchmark's notes).
bool rewritesModulesIndependently(const Program& program, std::string* why = nullptr);

// A part of a step: rewrites a range of the step's string into a string of its own, on a thread
// of its own.
class StepPart {
 public:
  virtual ~StepPart() = default;
  // On the step's thread, before the parts run: takes the step's variables and its number
  // (`stepsDone` steps done before it), and empties string().
  virtual void prepare(int stepsDone) = 0;
  // Rewrites the modules of `s` from byte `from` up to byte `to` (module starts) into string();
  // `start`: the left neighbours at `from`.
  virtual void rewrite(const ModuleString& s, std::size_t from, std::size_t to,
                       const LeftNeighbours& start) = 0;
  virtual ModuleString& string() = 0;
  // The warnings the part has given so far, those suppressed counted too.
  virtual std::size_t warnings() const = 0;
};

// Which steps are split, and their rewriting in parts.
class ParallelSteps {
 public:
  struct Settings {
    int threads = 0;  // 0: one a processor core (DerivationOptions::threads)
    std::size_t minimumModules = 0;
    double minimumCost = 0;
    std::size_t maxModules = 0;  // a longer string is not joined: one thread fails in order
  };
  using PartFactory = std::function<std::unique_ptr<StepPart>()>;

  ParallelSteps(const Program& program, Settings settings, PartFactory makePart);
  ~ParallelSteps();
  ParallelSteps(const ParallelSteps&) = delete;
  ParallelSteps& operator=(const ParallelSteps&) = delete;

  // Rewrites the step's string `s` in parts into `out` and returns the number of parts; 0, with
  // `out` empty, when the step is not to be split or a part met a warning or an error (the step
  // is then rewritten on one thread, which warns and fails in order). `matcher` indexes the
  // branches of `s` first when the parts' contexts search them; `stepsDone`: the steps before.
  std::size_t rewrite(const ModuleString& s, ModuleString& out, const ContextMatcher& matcher,
                      int stepsDone);
  // The step just rewritten: `modules` modules made `produced`, in `parts` parts (0: on one
  // thread), in `nanoseconds` of wall time: what the next steps' decision weighs.
  void measured(std::size_t modules, std::size_t produced, std::size_t parts, double nanoseconds);
  // Whether the next step, of `modules` modules, is to be split (rewrite() splits it unless a
  // part warns or fails).
  bool splitsNextStep(std::size_t modules) const;
  // Steps rewritten in parts.
  int stepsInParts() const { return stepsInParts_; }

 private:
  const Program& program_;
  Settings settings_;
  PartFactory makePart_;
  std::vector<std::unique_ptr<StepPart>> parts_;
  bool modulesIndependent_ = false;  // rewritesModulesIndependently(program_)
  bool anyContext_ = false;          // a production has a left or right context
  int threads_ = 1;
  int stepsInParts_ = 0;
  // Nanoseconds of rewriting a module: in the last step with a string of minimumModules at
  // least (for a step in parts, its time times the parts), and in the last steady such step on
  // one thread (-1: none yet), whose modules sequentialModules_ holds.
  double stepCost_ = -1;
  double sequentialCost_ = -1;
  std::size_t sequentialModules_ = 0;
  bool remeasure_ = false;  // the last step in parts was not judged: the next is measured alone
  // Steps in parts that did not pay send the next backOff_ steps of minimumModules or more to one
  // thread (stepsAlone_ of them still to come), doubling up to kMaxBackOff while they do not pay
  // and back to none when one does: a busy moment of the machine does not end splitting for
  // good, and a machine whose cores are all busy splits one step in kMaxBackOff.
  static constexpr int kMaxBackOff = 32;
  int backOff_ = 0;
  int stepsAlone_ = 0;
};

}  // namespace hirsute
