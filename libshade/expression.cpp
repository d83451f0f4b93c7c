#include "libshade/expression.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "libcommon/constants.h"

namespace rs {

namespace {
std::atomic<int> gCurrentFrame{0};

// Truncation toward zero into int, or nothing when the value does not fit.
bool TruncateToInt(double v, int& out) {
    if (!(v > -2147483649.0 && v < 2147483648.0)) return false;
    out = static_cast<int>(v);
    return true;
}
}  // namespace

void SetCurrentFrame(int frame) { gCurrentFrame.store(frame, std::memory_order_relaxed); }
int CurrentFrame() { return gCurrentFrame.load(std::memory_order_relaxed); }

double ModuloC(double a, double b) {
    int ia, ib;
    if (!TruncateToInt(a, ia) || !TruncateToInt(b, ib) || ib == 0)
        return std::numeric_limits<double>::quiet_NaN();
    if (ib == -1) return 0;  // INT_MIN % -1 overflows in C; the remainder is 0 anyway
    return ia % ib;
}

double LinearAt(double time, double t0, double v0, double t1, double v1) {
    if (time < t0) return v0;
    if (time > t1) return v1;
    if (std::fabs(t1 - t0) < kEpsilon) return v0;
    return v0 + (v1 - v0) * (time - t0) / (t1 - t0);
}

Expr::Expr(Op op, std::vector<ExprPtr> args) : op_(op), args_(std::move(args)) {
    timeVarying_ = op == Op::Time || op == Op::Frame || op == Op::Linear;
    for (const ExprPtr& a : args_) {
        timeVarying_ = timeVarying_ || a->IsTimeVarying();
        depth_ = std::max(depth_, a->depth_ + 1);
        cost_ = std::min(cost_ + a->cost_, 1099511627776.0);
    }
}

// A node whose operands are all static is replaced by its value.
ExprPtr Expr::Fold(std::shared_ptr<Expr> e) {
    if (e->timeVarying_ || e->op_ == Op::Constant) return e;
    return Number(e->Evaluate(0));
}

ExprPtr Expr::Number(double value) {
    std::shared_ptr<Expr> e(new Expr(Op::Constant, {}));
    e->value_ = value;
    return e;
}

ExprPtr Expr::Time() { return ExprPtr(new Expr(Op::Time, {})); }
ExprPtr Expr::Frame() { return ExprPtr(new Expr(Op::Frame, {})); }

ExprPtr Expr::Negate(ExprPtr a) {
    return Fold(std::shared_ptr<Expr>(new Expr(Op::Negate, {std::move(a)})));
}

ExprPtr Expr::Binary(Op op, ExprPtr a, ExprPtr b) {
    return Fold(std::shared_ptr<Expr>(new Expr(op, {std::move(a), std::move(b)})));
}

ExprPtr Expr::Call(Fn1 fn, ExprPtr a) {
    std::shared_ptr<Expr> e(new Expr(Op::Call1, {std::move(a)}));
    e->fn1_ = fn;
    return Fold(e);
}

ExprPtr Expr::Call(Fn2 fn, ExprPtr a, ExprPtr b) {
    std::shared_ptr<Expr> e(new Expr(Op::Call2, {std::move(a), std::move(b)}));
    e->fn2_ = fn;
    return Fold(e);
}

ExprPtr Expr::Linear(ExprPtr t0, ExprPtr v0, ExprPtr t1, ExprPtr v1) {
    return ExprPtr(
        new Expr(Op::Linear, {std::move(t0), std::move(v0), std::move(t1), std::move(v1)}));
}

std::optional<Expr::Affine> Expr::AffineInTime() const {
    bool unit = false;
    if (const std::optional<double> slope = ScaledTime(unit)) return Affine{-0.0, *slope};
    if (op_ != Op::Add && op_ != Op::Subtract) return std::nullopt;
    for (int constant = 0; constant < 2; ++constant) {
        const Expr& c = *args_[constant];
        const Expr& s = *args_[1 - constant];
        if (c.op_ != Op::Constant) continue;
        const std::optional<double> slope = s.ScaledTime(unit);
        if (!slope) continue;
        // C + S, S + C, S - C: offset ±C, slope S; C - S: offset C, slope -S.
        if (op_ == Op::Add) return Affine{c.value_, *slope};
        return constant == 0 ? Affine{c.value_, -*slope} : Affine{-c.value_, *slope};
    }
    return std::nullopt;
}

std::optional<double> Expr::ScaledTime(bool& unit) const {
    switch (op_) {
        case Op::Time:
            unit = true;
            return 1.0;
        case Op::Negate: {
            const std::optional<double> slope = args_[0]->ScaledTime(unit);
            if (slope) return -*slope;
            return std::nullopt;
        }
        case Op::Multiply:
            for (int constant = 0; constant < 2; ++constant) {
                const Expr& c = *args_[constant];
                bool timeIsUnit = false;
                const std::optional<double> slope = args_[1 - constant]->ScaledTime(timeIsUnit);
                if (c.op_ == Op::Constant && slope && timeIsUnit) {
                    unit = false;
                    return c.value_ * *slope;  // c*(±t) == (±c)*t
                }
            }
            return std::nullopt;
        default:
            return std::nullopt;
    }
}

double Expr::Evaluate(double time) const {
    auto arg = [&](size_t i) { return args_[i]->Evaluate(time); };
    switch (op_) {
        case Op::Constant:
            return value_;
        case Op::Time:
            return time;
        case Op::Frame:
            return CurrentFrame();
        case Op::Negate:
            return -arg(0);
        case Op::Add:
            return arg(0) + arg(1);
        case Op::Subtract:
            return arg(0) - arg(1);
        case Op::Multiply:
            return arg(0) * arg(1);
        case Op::Divide:
            return arg(0) / arg(1);
        case Op::Modulo:
            return ModuloC(arg(0), arg(1));
        case Op::Power:
            return std::pow(arg(0), arg(1));
        case Op::Call1:
            return fn1_(arg(0));
        case Op::Call2:
            return fn2_(arg(0), arg(1));
        case Op::Linear:
            return LinearAt(time, arg(0), arg(1), arg(2), arg(3));
    }
    return 0;
}

}  // namespace rs
