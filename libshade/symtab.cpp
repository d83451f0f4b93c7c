#include "libshade/symtab.h"

#include <cmath>

#include "libshade/builtin_functions.h"

namespace rs {

// Wrappers give the overloaded <cmath> functions a single address.
double Sin(double x) { return std::sin(x); }
double Cos(double x) { return std::cos(x); }
double Tan(double x) { return std::tan(x); }
double Asin(double x) { return std::asin(x); }
double Acos(double x) { return std::acos(x); }
double Atan(double x) { return std::atan(x); }
double Sqrt(double x) { return std::sqrt(x); }
double Hypot(double x, double y) { return std::hypot(x, y); }

SymbolTable::SymbolTable() {
    // The original's truncated values (spec §1.4), kept for identical results.
    Define("pi", Expr::Number(3.141592));
    Define("dtor", Expr::Number(0.017453));
    Define("rtod", Expr::Number(57.29578));
    Define("time", Expr::Time());
    Define("frame", Expr::Frame());

    auto fn1 = [this](const char* name, Expr::Fn1 f) {
        Symbol s;
        s.kind = Symbol::Kind::Function;
        s.arity = 1;
        s.fn1 = f;
        symbols_.emplace(name, s);
    };
    fn1("sin", Sin);
    fn1("cos", Cos);
    fn1("tan", Tan);
    fn1("asin", Asin);
    fn1("acos", Acos);
    fn1("atan", Atan);
    fn1("sqrt", Sqrt);

    Symbol hypot;
    hypot.kind = Symbol::Kind::Function;
    hypot.arity = 2;
    hypot.fn2 = Hypot;
    symbols_.emplace("hypot", hypot);

    Symbol linear;
    linear.kind = Symbol::Kind::Function;
    linear.arity = 4;
    linear.isLinear = true;
    symbols_.emplace("linear", linear);
}

const Symbol* SymbolTable::Find(const std::string& name) const {
    auto it = symbols_.find(name);
    return it == symbols_.end() ? nullptr : &it->second;
}

bool SymbolTable::Define(const std::string& name, ExprPtr value) {
    Symbol s;
    s.kind = Symbol::Kind::Variable;
    s.value = std::move(value);
    return symbols_.emplace(name, std::move(s)).second;
}

}  // namespace rs
