// The built-in functions of expressions (spec §1.4: sin cos tan asin acos atan sqrt, hypot),
// one address each so the symbol table and the range evaluation (expression.h) agree on
// which function a Call node holds.
#pragma once

namespace rs {

double Sin(double x);
double Cos(double x);
double Tan(double x);
double Asin(double x);
double Acos(double x);
double Atan(double x);
double Sqrt(double x);
double Hypot(double x, double y);

}  // namespace rs
