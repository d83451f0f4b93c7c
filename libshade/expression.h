// Numeric expressions of the scene language (spec §1.4, §3.15).
//
// An expression is an immutable tree. Builders fold static sub-expressions at once, so a
// static expression is always a single Constant node. Time-varying nodes are `time`,
// `frame` and `linear(...)` and every node above one of them; they are evaluated on demand
// at a given ray time (no caching, so evaluation is thread-safe).
#pragma once

#include <memory>
#include <optional>
#include <vector>

namespace rs {

class Expr;
using ExprPtr = std::shared_ptr<const Expr>;

class Expr {
  public:
    enum class Op {
        Constant,
        Time,
        Frame,
        Negate,
        Add,
        Subtract,
        Multiply,
        Divide,
        Modulo,
        Power,
        Call1,
        Call2,   // built-in functions of one or two arguments
        Linear,  // linear(t0, v0, t1, v1)
    };
    using Fn1 = double (*)(double);
    using Fn2 = double (*)(double, double);

    static ExprPtr Number(double value);
    static ExprPtr Time();
    static ExprPtr Frame();
    static ExprPtr Negate(ExprPtr a);
    // `op` is one of Add … Power.
    static ExprPtr Binary(Op op, ExprPtr a, ExprPtr b);
    static ExprPtr Call(Fn1 fn, ExprPtr a);
    static ExprPtr Call(Fn2 fn, ExprPtr a, ExprPtr b);
    static ExprPtr Linear(ExprPtr t0, ExprPtr v0, ExprPtr t1, ExprPtr v1);

    Op op() const { return op_; }
    bool IsTimeVarying() const { return timeVarying_; }
    // The value of a static expression (requires !IsTimeVarying()).
    double Value() const { return value_; }
    // Height of the tree (1 for a leaf); the parser bounds it so evaluation cannot exhaust
    // the stack.
    int Depth() const { return depth_; }
    // Nodes visited by one evaluation (shared sub-trees counted at every use), saturated
    // at 2^40; bounded by the parser so a chain of `define`s cannot make evaluation
    // exponentially slow.
    double Cost() const { return cost_; }
    // The value at ray time `time` and the frame set by SetCurrentFrame().
    double Evaluate(double time) const;
    // An interval [lo, hi] holding Evaluate(t) for every t in [t0, t1] (t0 <= t1), by
    // interval arithmetic (expression_range.cpp): conservative, every operation's ends
    // rounded outward by one ulp (two for the <cmath> functions), never NaN. Ends are
    // infinite where no finite bound is known: a divisor or a power base whose range holds
    // 0, `%`, tan across a pole, asin/acos beyond [-1, 1], or a function the range
    // evaluation does not know. Not tight: a variable used twice is bounded twice.
    struct Range {
        double lo = 0, hi = 0;
    };
    Range EvaluateRange(double t0, double t1) const;
    // value = offset + slope * time.
    struct Affine {
        double offset = 0, slope = 0;
        double At(double time) const { return offset + slope * time; }
    };
    // The expression as an Affine whose At(t) equals Evaluate(t) bit for bit at every t,
    // read from the tree's shape (no sampling); nothing when the expression is static, not
    // affine in time (time*time, sin(time), frame, linear(...)) or affine in a form whose
    // rounding At does not reproduce (e.g. 2*(1 + time), time/3). Accepted: S, C + S,
    // S + C, C - S, S - C, with C a constant and S a scaled time: time, -S, C*T, T*C (T
    // being time or -time). Exact since b*t, its negation and one addition round the same
    // in both (x - y == x + (-y); -(c*t) == (-c)*t; a bare S has offset -0, as -0 + y == y
    // for every y, zeros included).
    std::optional<Affine> AffineInTime() const;

  private:
    Expr(Op op, std::vector<ExprPtr> args);
    static ExprPtr Fold(std::shared_ptr<Expr> e);
    // The slope when this node is a scaled time (AffineInTime's S), `unit` set when it is
    // time or -time (slope ±1).
    std::optional<double> ScaledTime(bool& unit) const;

    Op op_;
    std::vector<ExprPtr> args_;
    Fn1 fn1_ = nullptr;
    Fn2 fn2_ = nullptr;
    double value_ = 0;
    int depth_ = 1;
    double cost_ = 1;
    bool timeVarying_ = false;
};

// `a % b` with C semantics on the operands truncated to int (spec §1.4): (7 % 3) = 1,
// (-7 % 3) = -1. A zero divisor or an operand outside the int range gives NaN.
double ModuloC(double a, double b);

// `linear(t0,v0,t1,v1)` at `time` (spec §1.4): v0 before t0, v1 after t1, v0 when t0≈t1
// (within kEpsilon), linear in between.
double LinearAt(double time, double t0, double v0, double t1, double v1);

// The frame number the renderer is working on; the value of `frame` in expressions.
void SetCurrentFrame(int frame);
int CurrentFrame();

}  // namespace rs
