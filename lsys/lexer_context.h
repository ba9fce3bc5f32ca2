// State shared by the Flex lexer and the Bison parser of `.l` files (private to lsys/).
#pragma once

#include <memory>
#include <string>

#include "hirsute/lsys/ast.h"
#include "hirsute/lsys/diagnostic.h"

namespace hirsute::detail {

struct LexerContext {
  std::shared_ptr<const std::string> file;
  int line = 1;
  int column = 1;
  SourceLocation tokenStart;
  int blockDepth = 0;     // `{` open inside blocks
  int argumentDepth = 0;  // parentheses open inside module arguments
  bool pendingWarnings = true;  // the `warnings` word of the section being read

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
