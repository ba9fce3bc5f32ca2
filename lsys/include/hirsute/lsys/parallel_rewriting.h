// Whether a derivation step may rewrite parts of its string on several threads and give the
// string, the warnings and the errors of one thread rewriting it from left to right.
//
// cpfg rewrites the string module by module, and what one production's code does can reach the
// next: global variables and arrays written in blocks, files, the random streams, stop(), and
// the production's own variables, which keep their values from one use to the next (a block that
// reads `n` before it writes it sees the value the last module left). A program none of whose
// productions can do any of that rewrites each module from the module, its contexts and values
// fixed for the whole step, so that the modules of a step can be rewritten in any order.
#pragma once

#include <string>
#include <vector>

#include "hirsute/lsys/code.h"
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

}  // namespace hirsute
