// State shared by the Flex lexer and the Bison parser of `.l` files (private to lsys/).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hirsute/lsys/ast.h"
#include "hirsute/core/diagnostic.h"

namespace hirsute::detail {

struct LexerContext {
  std::shared_ptr<const std::string> file;
  int line = 1;
  int column = 1;
  SourceLocation tokenStart;
  int blockDepth = 0;     // `{` open inside blocks
  int argumentDepth = 0;  // parentheses open inside module arguments
  bool pendingWarnings = true;  // the `warnings` word of the section being read

  // A bracket open in a parameter list, an expression or a block. A syntax error at the end of
  // a line, block or file is reported at the innermost bracket never closed, where the problem is.
  struct OpenBracket {
    char bracket;
    SourceLocation where;
    char module;  // the module whose parameter list it opens; 0 for none
  };
  std::vector<OpenBracket> open;
  char lastSymbol = 0;  // the module symbol read last (a `(` after it opens its parameters)
  // The predecessor being read: whether `<` and `>` were seen, and modules since the last one.
  bool sawLeftContext = false;
  bool sawRightContext = false;
  int predecessorModules = 0;
  bool labelPending = false;  // after `Lsystem:`, until its label
  // The line being read begins with a space: were it meant to continue the production above, it
  // needed a tab (cpfg's continuation line); a syntax error on it says so.
  bool lineIndentedBySpaces = false;
  SourceLocation indentedAt;  // the last line that began so

  // "the '(' of module 'B' is not closed" for the innermost open bracket.
  std::string unclosedMessage() const {
    const OpenBracket& b = open.back();
    std::string what = std::string("the '") + b.bracket + "'";
    if (b.module) what += std::string(" of module '") + b.module + "'";
    if (b.bracket == '{') what += " of the block";
    return what + " is not closed with '" + (b.bracket == '(' ? ')' : b.bracket == '[' ? ']' : '}') + "'";
  }

  // The builder state of the parser.
  ast::File result;
  enum class Section { Productions, Decomposition, Homomorphism } section = Section::Productions;

  SourceLocation here() const { return SourceLocation{file, line, column}; }
  void advance(const char* text, int length) {
    for (int i = 0; i < length; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
  }
  ast::Lsystem& current() { return result.lsystems.back(); }
};

}  // namespace hirsute::detail
