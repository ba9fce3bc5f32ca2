/* Grammar of cpfg's `.l` files: L-systems with their header items, axiom, productions,
 * decomposition and homomorphism sections, and the C-like block language. The lexer
 * (lexer.l) already knows which part of a line it is in, so module symbols arrive as SYMBOL
 * tokens and expressions as C tokens. */
%require "3.7"
%language "c++"
%define api.namespace {hirsute::detail}
%define api.parser.class {Parser}
%define api.value.type variant
%define api.token.constructor
%define api.location.type {hirsute::SourceLocation}
%define parse.error custom
%locations

%code requires {
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>
#include "hirsute/lsys/ast.h"
#include "hirsute/core/diagnostic.h"
namespace hirsute::detail { struct LexerContext; }
typedef void* yyscan_t;
}

%param {yyscan_t scanner} {hirsute::detail::LexerContext& ctx}

%code {
#include "lexer_context.h"
hirsute::detail::Parser::symbol_type hirsute_lsys_lex(yyscan_t scanner, hirsute::detail::LexerContext& ctx);
#define yylex hirsute_lsys_lex
#define YYLLOC_DEFAULT(Current, Rhs, N) \
  do { (Current) = (N) ? YYRHSLOC(Rhs, 1) : YYRHSLOC(Rhs, 0); } while (0)

namespace {
using namespace hirsute;
using ast::ExprPtr;

ExprPtr makeExpr(ast::Expr::Kind kind, const SourceLocation& where) {
  auto e = std::make_unique<ast::Expr>();
  e->kind = kind;
  e->where = where;
  return e;
}
// Records the nesting of `e` from its operands; too deep is an error.
ExprPtr nested(ExprPtr e) {
  for (const auto& operand : e->operands) e->depth = std::max(e->depth, operand->depth + 1);
  if (e->depth > ast::kMaxNesting) {
    throw DiagnosticError(e->where, "the expression nests deeper than " + std::to_string(ast::kMaxNesting) + " levels");
  }
  return e;
}
ExprPtr binary(ast::BinaryOp op, ExprPtr a, ExprPtr b, const SourceLocation& where) {
  auto e = makeExpr(ast::Expr::Kind::Binary, where);
  e->binaryOp = op;
  e->operands.push_back(std::move(a));
  e->operands.push_back(std::move(b));
  return nested(std::move(e));
}
ExprPtr unary(ast::UnaryOp op, ExprPtr a, const SourceLocation& where) {
  auto e = makeExpr(ast::Expr::Kind::Unary, where);
  e->unaryOp = op;
  e->operands.push_back(std::move(a));
  return nested(std::move(e));
}
ast::StmtPtr makeStmt(ast::Stmt::Kind kind, const SourceLocation& where) {
  auto s = std::make_unique<ast::Stmt>();
  s->kind = kind;
  s->where = where;
  return s;
}
std::vector<ast::Production>& productionsOf(detail::LexerContext& ctx) {
  switch (ctx.section) {
    case detail::LexerContext::Section::Decomposition: return ctx.current().decomposition.productions;
    case detail::LexerContext::Section::Homomorphism: return ctx.current().homomorphism.productions;
    default: return ctx.current().productions;
  }
}
ast::RuleSet* ruleSetOf(detail::LexerContext& ctx) {
  switch (ctx.section) {
    case detail::LexerContext::Section::Decomposition: return &ctx.current().decomposition;
    case detail::LexerContext::Section::Homomorphism: return &ctx.current().homomorphism;
    default: return nullptr;
  }
}
}  // namespace
}

%token END_OF_FILE 0 "end of file"
%token EOL "end of line"
%token <std::string> LABEL "L-system label"
%token AXIOM "Axiom:" DERIVATION_LENGTH "derivation length:" DEFINE "define:" START "Start:"
%token START_EACH "StartEach:" END_EACH "EndEach:" END "End:" SEED "seed:" RING "ring lsystem"
%token MAXIMUM_DEPTH "maximum depth:" DECOMPOSITION "decomposition" HOMOMORPHISM "homomorphism"
%token END_LSYSTEM "endlsystem" WARNINGS "warnings" NO_WARNINGS "no warnings"
%token <std::string> IGNORE "ignore:" CONSIDER "consider:"
%token <char> SYMBOL "module symbol"
%token ARROW "-->" LPAREN "(" RPAREN ")" LBRACKET "[" RBRACKET "]" LBRACE "{" RBRACE "}"
%token COMMA "," COLON ":" SEMICOLON ";" ASSIGN "=" QUESTION "?"
%token OR "||" AND "&&" EQ "==" NE "!=" LT "<" LE "<=" GT ">" GE ">="
%token PLUS "+" MINUS "-" STAR "*" SLASH "/" PERCENT "%" CARET "^" NOT "!" AMPERSAND "&"
%token IF "if" ELSE "else" WHILE "while" DO "do" ARRAY "array"
%token <double> NUMBER "number"
%token <std::string> IDENT "identifier" STRING "string"

%type <ast::ExprPtr> expr
%type <std::vector<ast::ExprPtr>> expr_list args subscripts dimensions
%type <ast::Block> stmts block
%type <ast::StmtPtr> stmt
%type <std::vector<ast::ArrayDeclaration>> array_decls
%type <ast::ArrayDeclaration> array_decl
%type <ast::ModuleList> patterns modules successor left_context right_context
%type <ast::Module> pattern module
%type <ast::ModuleArguments> module_args module_arg_list
%type <std::vector<ast::Formal>> formals
%type <ast::Production> production predecessor condition_part
%type <ast::ExprPtr> condition probability

%right QUESTION COLON
%left OR
%left AND
%left EQ NE
%left LT LE GT GE
%left PLUS MINUS
%left STAR SLASH PERCENT
%left CARET
%precedence UMINUS NOT AMPERSAND

%start file

%%

file
  : %empty
  | file lsystem
  ;

lsystem
  : lsystem_start EOL header axiom body END_LSYSTEM opt_warnings EOL
  ;

lsystem_start
  : LABEL {
      if ($1.empty()) throw DiagnosticError(@1, "the L-system needs a label after 'Lsystem:' (cpfg: `Lsystem: 1`)");
      ctx.result.lsystems.emplace_back();
      ctx.current().where = @1;
      ctx.current().label = $1;
      ctx.section = LexerContext::Section::Productions;
    }
  ;

header
  : %empty
  | header header_item
  ;

header_item
  : DERIVATION_LENGTH expr EOL { ctx.current().derivationLength = std::move($2); }
  | SEED expr EOL              { ctx.current().seed = std::move($2); }
  | IGNORE                     { ctx.current().ignore = $1; ctx.current().ignoreWhere = @1; }
  | CONSIDER                   { ctx.current().consider = $1; ctx.current().ignoreWhere = @1; }
  | RING EOL                   { ctx.current().ring = true; }
  | DEFINE block               { for (auto& s : $2) ctx.current().define.push_back(std::move(s)); }
  | START block                { for (auto& s : $2) ctx.current().start.push_back(std::move(s)); }
  | START_EACH block           { for (auto& s : $2) ctx.current().startEach.push_back(std::move(s)); }
  | END_EACH block             { for (auto& s : $2) ctx.current().endEach.push_back(std::move(s)); }
  | END block                  { for (auto& s : $2) ctx.current().end.push_back(std::move(s)); }
  ;

axiom
  : AXIOM modules EOL {
      ctx.current().axiom = std::move($2);
      ctx.current().axiomWhere = @1;
      ctx.current().hasAxiom = true;
    }
  | AXIOM EOL { throw DiagnosticError(@1, "the axiom is empty; it needs at least one module"); }
  ;

body
  : %empty
  | body production EOL { productionsOf(ctx).push_back(std::move($2)); }
  | body section_item
  ;

section_item
  : DECOMPOSITION opt_warnings EOL {
      if (ctx.section == LexerContext::Section::Homomorphism)
        throw DiagnosticError(@1, "'decomposition' must come before 'homomorphism'");
      if (ctx.current().decomposition.present)
        throw DiagnosticError(@1, "a second 'decomposition' section in one L-system");
      ctx.section = LexerContext::Section::Decomposition;
      ctx.current().decomposition.present = true;
      ctx.current().decomposition.warnings = ctx.pendingWarnings;
    }
  | HOMOMORPHISM opt_warnings EOL {
      if (ctx.current().homomorphism.present)
        throw DiagnosticError(@1, "a second 'homomorphism' section in one L-system");
      ctx.section = LexerContext::Section::Homomorphism;
      ctx.current().homomorphism.present = true;
      ctx.current().homomorphism.warnings = ctx.pendingWarnings;
    }
  | MAXIMUM_DEPTH expr EOL {
      ast::RuleSet* set = ruleSetOf(ctx);
      if (!set) throw DiagnosticError(@1, "'maximum depth:' belongs after 'decomposition' or 'homomorphism'");
      set->maximumDepth = std::move($2);
    }
  | SEED expr EOL {
      if (ctx.section != LexerContext::Section::Homomorphism)
        throw DiagnosticError(@1, "'seed:' after the axiom is only allowed in the homomorphism section");
      ctx.current().homomorphism.seed = std::move($2);
    }
  | EOL
  ;

opt_warnings
  : %empty      { ctx.pendingWarnings = true; }
  | WARNINGS    { ctx.pendingWarnings = true; }
  | NO_WARNINGS { ctx.pendingWarnings = false; }
  ;

production
  : predecessor condition_part ARROW successor probability {
      $$ = std::move($1);
      $$.before = std::move($2.before);
      $$.condition = std::move($2.condition);
      $$.after = std::move($2.after);
      $$.successor = std::move($4);
      $$.probability = std::move($5);
    }
  | predecessor condition_part ARROW probability {
      throw DiagnosticError(@3, "the successor is missing: write it on the line of '-->' (a line "
                                "that begins with a tab continues it), or '*' for an empty "
                                "successor");
    }
  ;

predecessor
  : patterns                                  { $$.where = @1; $$.strict = std::move($1); }
  | left_context LT patterns                  { $$.where = @1; $$.left = std::move($1); $$.strict = std::move($3); }
  | patterns GT right_context                 { $$.where = @1; $$.strict = std::move($1); $$.right = std::move($3); }
  | left_context LT patterns GT right_context { $$.where = @1; $$.left = std::move($1); $$.strict = std::move($3); $$.right = std::move($5); }
  ;

left_context
  : patterns { $$ = std::move($1); }
  | STAR     { }
  ;

right_context
  : patterns { $$ = std::move($1); }
  | STAR     { }
  ;

patterns
  : pattern          { $$.push_back(std::move($1)); }
  | patterns pattern { $$ = std::move($1); $$.push_back(std::move($2)); }
  ;

pattern
  : SYMBOL                        { $$.symbol = $1; $$.where = @1; }
  | SYMBOL LPAREN formals RPAREN  { $$.symbol = $1; $$.where = @1; $$.hasParentheses = true; $$.formals = std::move($3); }
  | SYMBOL LPAREN RPAREN          { $$.symbol = $1; $$.where = @1; $$.hasParentheses = true; }
  ;

formals
  : IDENT               { $$.push_back(ast::Formal{$1, @1}); }
  | formals COMMA IDENT { $$ = std::move($1); $$.push_back(ast::Formal{$3, @3}); }
  ;

condition_part
  : %empty                        { }
  | COLON                         { }
  | COLON block                   { $$.before = std::move($2); }
  | COLON block condition         { $$.before = std::move($2); $$.condition = std::move($3); }
  | COLON block condition block   { $$.before = std::move($2); $$.condition = std::move($3); $$.after = std::move($4); }
  | COLON condition               { $$.condition = std::move($2); }
  | COLON condition block         { $$.condition = std::move($2); $$.after = std::move($3); }
  ;

condition
  : STAR { $$ = nullptr; }
  | expr { $$ = std::move($1); }
  ;

successor
  : STAR    { }
  | modules { $$ = std::move($1); }
  ;

probability
  : %empty     { $$ = nullptr; }
  | COLON expr { $$ = std::move($2); }
  ;

modules
  : module         { $$.push_back(std::move($1)); }
  | modules module { $$ = std::move($1); $$.push_back(std::move($2)); }
  ;

module
  : SYMBOL                    { $$.symbol = $1; $$.where = @1; }
  | SYMBOL LPAREN module_args RPAREN {
      $$.symbol = $1; $$.where = @1; $$.hasParentheses = true;
      $$.arguments = std::move($3.values); $$.argumentsWhere = std::move($3.where);
    }
  ;

module_args
  : %empty          { }
  | module_arg_list { $$ = std::move($1); }
  ;

/* An expression's location is its operator's; @ of the whole expression is its first token. */
module_arg_list
  : expr                       { $$.values.push_back(std::move($1)); $$.where.push_back(@1); }
  | module_arg_list COMMA expr { $$ = std::move($1); $$.values.push_back(std::move($3)); $$.where.push_back(@3); }
  ;

args
  : %empty    { }
  | expr_list { $$ = std::move($1); }
  ;

expr_list
  : expr                 { $$.push_back(std::move($1)); }
  | expr_list COMMA expr { $$ = std::move($1); $$.push_back(std::move($3)); }
  ;

block
  : LBRACE stmts RBRACE { $$ = std::move($2); }
  ;

stmts
  : %empty     { }
  | stmts stmt { $$ = std::move($1); if ($2) $$.push_back(std::move($2)); }
  ;

stmt
  : IDENT ASSIGN expr SEMICOLON {
      $$ = makeStmt(ast::Stmt::Kind::Assign, @1);
      $$->target = $1;
      $$->value = std::move($3);
    }
  | IDENT subscripts ASSIGN expr SEMICOLON {
      $$ = makeStmt(ast::Stmt::Kind::AssignElement, @1);
      $$->target = $1;
      $$->subscripts = std::move($2);
      $$->value = std::move($4);
    }
  | expr SEMICOLON {
      $$ = makeStmt(ast::Stmt::Kind::Evaluate, @1);
      $$->value = std::move($1);
    }
  | IF LPAREN expr RPAREN block {
      $$ = makeStmt(ast::Stmt::Kind::If, @1);
      $$->value = std::move($3);
      $$->body = std::move($5);
    }
  | IF LPAREN expr RPAREN block ELSE block {
      $$ = makeStmt(ast::Stmt::Kind::If, @1);
      $$->value = std::move($3);
      $$->body = std::move($5);
      $$->otherwise = std::move($7);
    }
  | WHILE LPAREN expr RPAREN block {
      $$ = makeStmt(ast::Stmt::Kind::While, @1);
      $$->value = std::move($3);
      $$->body = std::move($5);
    }
  | DO block WHILE LPAREN expr RPAREN SEMICOLON {
      $$ = makeStmt(ast::Stmt::Kind::DoWhile, @1);
      $$->value = std::move($5);
      $$->body = std::move($2);
    }
  | DO block WHILE LPAREN expr RPAREN {
      $$ = makeStmt(ast::Stmt::Kind::DoWhile, @1);
      $$->value = std::move($5);
      $$->body = std::move($2);
    }
  | ARRAY array_decls SEMICOLON {
      $$ = makeStmt(ast::Stmt::Kind::Arrays, @1);
      $$->arrays = std::move($2);
    }
  ;

array_decls
  : array_decl                   { $$.push_back(std::move($1)); }
  | array_decls COMMA array_decl { $$ = std::move($1); $$.push_back(std::move($3)); }
  ;

array_decl
  : IDENT dimensions {
      $$.where = @1; $$.name = $1; $$.dimensions = std::move($2);
    }
  | IDENT dimensions ASSIGN LBRACE expr_list RBRACE {
      $$.where = @1; $$.name = $1; $$.dimensions = std::move($2); $$.initializer = std::move($5);
    }
  ;

/* `a[3][2]` as cpfg reads it, and the manual's `a[3,2]` */
dimensions
  : LBRACKET expr_list RBRACKET            { $$ = std::move($2); }
  | dimensions LBRACKET expr_list RBRACKET { $$ = std::move($1); for (auto& e : $3) $$.push_back(std::move(e)); }
  ;

subscripts
  : LBRACKET expr RBRACKET            { $$.push_back(std::move($2)); }
  | subscripts LBRACKET expr RBRACKET { $$ = std::move($1); $$.push_back(std::move($3)); }
  ;

expr
  : NUMBER { $$ = makeExpr(ast::Expr::Kind::Number, @1); $$->number = $1; }
  | STRING { $$ = makeExpr(ast::Expr::Kind::String, @1); $$->name = $1; }
  | IDENT  { $$ = makeExpr(ast::Expr::Kind::Variable, @1); $$->name = $1; }
  | IDENT subscripts {
      $$ = makeExpr(ast::Expr::Kind::Element, @1);
      $$->name = $1;
      $$->operands = std::move($2);
      $$ = nested(std::move($$));
    }
  | IDENT LPAREN args RPAREN {
      $$ = makeExpr(ast::Expr::Kind::Call, @1);
      $$->name = $1;
      $$->operands = std::move($3);
      $$ = nested(std::move($$));
    }
  | LPAREN expr RPAREN            { $$ = std::move($2); }
  | MINUS expr %prec UMINUS       { $$ = unary(ast::UnaryOp::Negate, std::move($2), @1); }
  | NOT expr                      { $$ = unary(ast::UnaryOp::Not, std::move($2), @1); }
  | AMPERSAND expr                { $$ = unary(ast::UnaryOp::AddressOf, std::move($2), @1); }
  | expr CARET expr   { $$ = binary(ast::BinaryOp::Power, std::move($1), std::move($3), @2); }
  | expr STAR expr    { $$ = binary(ast::BinaryOp::Multiply, std::move($1), std::move($3), @2); }
  | expr SLASH expr   { $$ = binary(ast::BinaryOp::Divide, std::move($1), std::move($3), @2); }
  | expr PERCENT expr { $$ = binary(ast::BinaryOp::Modulo, std::move($1), std::move($3), @2); }
  | expr PLUS expr    { $$ = binary(ast::BinaryOp::Add, std::move($1), std::move($3), @2); }
  | expr MINUS expr   { $$ = binary(ast::BinaryOp::Subtract, std::move($1), std::move($3), @2); }
  | expr LT expr      { $$ = binary(ast::BinaryOp::Less, std::move($1), std::move($3), @2); }
  | expr LE expr      { $$ = binary(ast::BinaryOp::LessEqual, std::move($1), std::move($3), @2); }
  | expr GT expr      { $$ = binary(ast::BinaryOp::Greater, std::move($1), std::move($3), @2); }
  | expr GE expr      { $$ = binary(ast::BinaryOp::GreaterEqual, std::move($1), std::move($3), @2); }
  | expr EQ expr      { $$ = binary(ast::BinaryOp::Equal, std::move($1), std::move($3), @2); }
  | expr NE expr      { $$ = binary(ast::BinaryOp::NotEqual, std::move($1), std::move($3), @2); }
  | expr AND expr     { $$ = binary(ast::BinaryOp::And, std::move($1), std::move($3), @2); }
  | expr OR expr      { $$ = binary(ast::BinaryOp::Or, std::move($1), std::move($3), @2); }
  | expr QUESTION expr COLON expr {
      $$ = makeExpr(ast::Expr::Kind::Conditional, @2);
      $$->operands.push_back(std::move($1));
      $$->operands.push_back(std::move($3));
      $$->operands.push_back(std::move($5));
      $$ = nested(std::move($$));
    }
  ;

%%

void hirsute::detail::Parser::error(const location_type& where, const std::string& message) {
  throw hirsute::DiagnosticError(where, message);
}

namespace {

using Kind = hirsute::detail::Parser::symbol_kind_type;
using SymbolKind = hirsute::detail::Parser::symbol_kind;

// The token as a user reads it: "'F'", "the end of the line".
std::string describeToken(const hirsute::detail::Parser::context& c) {
  const auto& token = c.lookahead();
  switch (c.token()) {
    case SymbolKind::S_YYEOF: return "the end of the file";
    case SymbolKind::S_EOL: return "the end of the line";
    case SymbolKind::S_SYMBOL: return std::string("module symbol '") + token.value.as<char>() + "'";
    case SymbolKind::S_IDENT: return "identifier '" + token.value.as<std::string>() + "'";
    case SymbolKind::S_STRING: return "a string";
    case SymbolKind::S_NUMBER: {
      char text[32];
      std::snprintf(text, sizeof text, "%g", token.value.as<double>());
      return std::string("number ") + text;
    }
    default: return std::string("'") + hirsute::detail::Parser::symbol_name(c.token()) + "'";
  }
}

// Tokens that end a line, statement, block or section: an open bracket cannot continue past them.
bool endsConstruct(Kind kind) {
  switch (kind) {
    case SymbolKind::S_YYEOF: case SymbolKind::S_EOL: case SymbolKind::S_ARROW:
    case SymbolKind::S_SEMICOLON: case SymbolKind::S_RBRACE: case SymbolKind::S_AXIOM:
    case SymbolKind::S_END_LSYSTEM: case SymbolKind::S_LABEL:
      return true;
    default:
      return false;
  }
}

}  // namespace

// Bison finds where the input stops making sense; the message says what the writer most likely
// missed, at the place where it is missing (an unclosed bracket, the axiom, `-->`, `endlsystem`).
void hirsute::detail::Parser::report_syntax_error(const context& c) const {
  const SourceLocation& where = c.location();
  const Kind kind = c.token();
  const std::string found = describeToken(c);
  // A block's `{` is never blamed here: lines and statements end inside blocks, and the lexer
  // reports a `{` still open at a keyword, `-->` or the end of the file.
  if (!ctx.open.empty() && ctx.open.back().bracket != '{') {
    const SourceLocation& open = ctx.open.back().where;
    bool laterLine = where.line > open.line || where.fileName() != open.fileName();
    if (endsConstruct(kind) || laterLine) throw DiagnosticError(open, ctx.unclosedMessage() + " before " + found);
  }
  Kind expected[YYNTOKENS];
  int count = c.expected_tokens(expected, YYNTOKENS);
  auto expects = [&](Kind k) { return std::find(expected, expected + count, k) != expected + count; };
  if (kind == SymbolKind::S_YYEOF && !ctx.result.lsystems.empty()) {
    const ast::Lsystem& last = ctx.result.lsystems.back();
    throw DiagnosticError(last.where, "L-system '" + last.label + "' has no 'endlsystem' before the end of the file");
  }
  if (expects(SymbolKind::S_LABEL) && expects(SymbolKind::S_YYEOF)) {
    throw DiagnosticError(where, "expected 'Lsystem: label' to start an L-system, found " + found);
  }
  if (expects(SymbolKind::S_AXIOM) && !ctx.result.lsystems.empty()) {
    throw DiagnosticError(where, "L-system '" + ctx.result.lsystems.back().label +
                                     "' has no 'Axiom:' line before this (found " + found + ")");
  }
  if (expects(SymbolKind::S_ARROW)) {
    throw DiagnosticError(where, std::string(expects(SymbolKind::S_PLUS) ? "expected an operator or '-->'" : "expected '-->'") +
                                     ", found " + found);
  }
  if (kind == SymbolKind::S_EOL && expects(SymbolKind::S_SYMBOL) && expects(SymbolKind::S_STAR)) {
    throw DiagnosticError(where, "the successor is missing: write it on the line of '-->' (a line "
                                 "that begins with a tab continues it), or '*' for an empty "
                                 "successor");
  }
  if (expects(SymbolKind::S_SEMICOLON) && kind != SymbolKind::S_RPAREN && kind != SymbolKind::S_RBRACKET) {
    throw DiagnosticError(where, std::string(expects(SymbolKind::S_PLUS) ? "expected an operator or ';'" : "expected ';'") +
                                     " to end the statement, found " + found);
  }
  std::string message = "syntax error, unexpected " + found;
  if (count > 0 && count <= 4) {
    for (int i = 0; i < count; ++i) {
      message += (i == 0 ? ", expecting " : i + 1 == count ? " or " : ", ");
      message += symbol_name(expected[i]);
    }
  }
  throw DiagnosticError(where, message);
}
