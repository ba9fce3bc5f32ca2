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

}  // namespace hirsute
