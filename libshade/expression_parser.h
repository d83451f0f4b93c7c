// Parsing the numeric argument syntax (spec §1.4) from a token stream into an Expr.
#pragma once

#include "libshade/expression.h"
#include "libshade/lexer.h"
#include "libshade/symtab.h"

namespace rs {

// Limits that keep hostile input from exhausting the stack: parenthesis/unary nesting
// while parsing, the height of the resulting tree (evaluated recursively) and the number
// of nodes one evaluation visits.
inline constexpr int kMaxExprNesting = 200;
inline constexpr int kMaxExprDepth = 2000;
inline constexpr double kMaxExprCost = 1 << 20;

// True when the next tokens start a numeric argument: NUMBER, ±NUMBER or '('.
bool PeekExpression(TokenStream& tokens);

// Consumes a literal, NUMBER, -NUMBER or +NUMBER, storing its value in `value`; returns
// false, consuming nothing, when the next tokens are not one. ParseExpression reads the
// same value for it, as a Constant.
bool ReadLiteral(TokenStream& tokens, double& value);

// Parses `NUMBER | -NUMBER | +NUMBER | ( m )` where inside parentheses
//   m := NUMBER | NAME | FUNC '(' m {',' m} ')' | '(' m ')' | -m | +m
//      | m^m | m*m | m/m | m%m | m+m | m-m
// with precedence ^ (right) > unary ± > * / % > + -. Names resolve in `symbols`. Errors
// (syntax, undefined names, misuse of functions, wrong argument counts) are reported with
// the offending token's location; `usage`, when non-empty, is appended to messages.
ExprPtr ParseExpression(TokenStream& tokens, const SymbolTable& symbols,
                        std::string_view usage = {});

// Reports `message` at `where` (Abort), appending "(usage: ...)" when `usage` is non-empty.
[[noreturn]] void FailAt(const SourceLocation& where, std::string_view usage,
                         const std::string& message);

}  // namespace rs
