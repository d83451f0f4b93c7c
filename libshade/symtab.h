// The symbol table of `define`d variables and predefined names (spec §1.4).
//
// Names share one namespace: constants (pi, dtor, rtod), time-varying variables (time,
// frame), functions (sin cos tan asin acos atan sqrt: 1 argument; hypot: 2; linear: 4,
// time-varying) and user variables. Nothing may be redefined.
#pragma once

#include <string>
#include <unordered_map>

#include "libshade/expression.h"

namespace rs {

struct Symbol {
    enum class Kind { Variable, Function };
    Kind kind = Kind::Variable;
    ExprPtr value;  // Variable: its expression (a Constant node when static)
    int arity = 0;  // Function: number of arguments
    Expr::Fn1 fn1 = nullptr;
    Expr::Fn2 fn2 = nullptr;
    bool isLinear = false;  // Function: the time-varying linear()
};

class SymbolTable {
  public:
    SymbolTable();  // holds the predefined symbols

    // Null when `name` is not defined.
    const Symbol* Find(const std::string& name) const;
    // Adds a variable; returns false (and changes nothing) when the name exists.
    bool Define(const std::string& name, ExprPtr value);

  private:
    std::unordered_map<std::string, Symbol> symbols_;
};

}  // namespace rs
