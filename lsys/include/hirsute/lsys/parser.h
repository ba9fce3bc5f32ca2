// Reading `.l` text into a syntax tree.
#pragma once

#include <string>

#include "hirsute/lsys/ast.h"

namespace hirsute {

// Parses preprocessed `.l` text (with cpp line markers); `fileName` names the text until the
// first marker. Throws DiagnosticError at the first syntax error.
ast::File parseLsystemText(const std::string& text, const std::string& fileName);

}  // namespace hirsute
