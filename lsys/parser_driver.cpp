#include <limits>
#include <memory>

#include "hirsute/lsys/parser.h"
#include "lexer.hpp"
#include "lexer_context.h"
#include "parser.hpp"

namespace hirsute {
namespace {

// Owns a Flex scanner for the duration of one parse, also when the parse throws.
class Scanner {
 public:
  explicit Scanner(detail::LexerContext& ctx) {
    if (hirsute_lsys_lex_init_extra(&ctx, &scanner_) != 0) throw std::bad_alloc();
  }
  ~Scanner() { hirsute_lsys_lex_destroy(scanner_); }
  Scanner(const Scanner&) = delete;
  Scanner& operator=(const Scanner&) = delete;
  yyscan_t get() const { return scanner_; }

 private:
  yyscan_t scanner_ = nullptr;
};

}  // namespace

ast::File parseLsystemText(const std::string& text, const std::string& fileName) {
  detail::LexerContext ctx;
  ctx.file = std::make_shared<const std::string>(fileName);
  if (text.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2)) {
    throw DiagnosticError(SourceLocation{ctx.file, 0, 0}, "the file is too large to be an L-system");
  }
  Scanner scanner(ctx);
  hirsute_lsys__scan_bytes(text.data(), static_cast<int>(text.size()), scanner.get());
  detail::Parser parser(scanner.get(), ctx);
  try {
    parser.parse();
  } catch (const DiagnosticError& e) {
    // A line that begins with spaces and fails was most likely meant to continue the production
    // above; cpfg continues a line only on one that begins with a tab.
    const Diagnostic& d = e.diagnostic();
    if (!ctx.lineIndentedBySpaces || d.where.line != ctx.indentedAt.line ||
        d.where.fileName() != ctx.indentedAt.fileName())
      throw;
    throw DiagnosticError(d.where, d.message +
                                       "; this line begins with spaces: a line that continues "
                                       "the production above must begin with a tab (cpfg's "
                                       "continuation line)");
  }
  if (ctx.result.lsystems.empty()) {
    // Nothing but comments and blank lines: the file's start is where `Lsystem:` belongs.
    throw DiagnosticError(SourceLocation{std::make_shared<const std::string>(fileName), 1, 1},
                          "no L-system in the file (it must start with `Lsystem: label`)");
  }
  return std::move(ctx.result);
}

}  // namespace hirsute
