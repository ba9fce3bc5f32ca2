// The line of the user's file that a diagnostic points at, with a caret under its column, as
// compilers show it beneath the message:
//
//   herb.l:5:11: error: expected a parameter name, found '1'
//       5 | A(n) -> I(LEN*0.6)
//         |           ^
//
// The file is read again when the message is printed, through the model's folder: a name that
// leaves the folder (a `#line` directive may name any file) or is no regular file shows no
// excerpt.
#pragma once

#include <string>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/model_folder.h"

namespace hirsute {

// The two lines above (number, bar, source; bar, caret), each ending in a newline; empty when
// the location has no line or its file cannot be read beneath `folder`. A long line is shown as
// the part around the column. The source's control bytes are shown as printableText shows them.
std::string sourceExcerpt(const SourceLocation& where, const ModelFolder& folder);

// For each macro used on the location's line from its column on (a name the same file
// `#define`s on another line), a note that shows where it is defined, so that a mistake that
// comes from a macro's text points at that text too:
//
//   herb.l:2:9: note: 'SHORT' is a macro, defined here
//    2 | #define SHORT (LEN * 0.6
//      |         ^
//
// For an undefined name (`'STEPZ' is no constant`), instead, the #define of the nearest name
// (`did you mean 'STEPS'?`), if one is a slip of the hand away.
// None when `message` says what it found (`found '->'`) and the source has just that at the
// column: the mistake is in the line as written. At most three; empty when there are none or the
// file cannot be read beneath `folder`.
std::string macroNotes(const SourceLocation& where, const std::string& message,
                       const ModelFolder& folder);

}  // namespace hirsute
