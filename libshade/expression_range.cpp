// Expr::EvaluateRange: interval arithmetic over a time interval (contract in expression.h).
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>

#include "libshade/builtin_functions.h"
#include "libshade/expression.h"

namespace rs {

namespace {

using Range = Expr::Range;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Range kUnbounded{-kInf, kInf};

// [lo, hi] moved outward by `ulps` units in the last place; unbounded when an end is NaN.
Range Outward(double lo, double hi, int ulps) {
    if (std::isnan(lo) || std::isnan(hi)) return kUnbounded;
    for (int i = 0; i < ulps; ++i) {
        lo = std::nextafter(lo, -kInf);
        hi = std::nextafter(hi, kInf);
    }
    return {lo, hi};
}

// The hull of some values (NaN makes it unbounded), widened by `ulps`.
Range Hull(std::initializer_list<double> values, int ulps) {
    double lo = kInf, hi = -kInf;
    for (double v : values) {
        if (std::isnan(v)) return kUnbounded;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    return Outward(lo, hi, ulps);
}

bool Contains(const Range& r, double x) { return r.lo <= x && x <= r.hi; }
double MaxAbs(const Range& r) { return std::max(std::abs(r.lo), std::abs(r.hi)); }
double MinAbs(const Range& r) { return Contains(r, 0) ? 0 : std::min(std::abs(r.lo), std::abs(r.hi)); }

Range Multiply(const Range& a, const Range& b) {
    return Hull({a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi}, 1);
}

Range Divide(const Range& a, const Range& b) {
    if (Contains(b, 0)) return kUnbounded;
    return Hull({a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi}, 1);
}

// ModuloC truncates both operands: |a % b| < |b| and the result has a's sign; a divisor
// that may truncate to 0 gives NaN, so no bound.
Range Modulo(const Range& a, const Range& b) {
    if (b.lo < 1 && b.hi > -1) return kUnbounded;
    const double m = MaxAbs(b);
    return {a.lo >= 0 ? 0 : -m, a.hi <= 0 ? 0 : m};
}

// pow(x, y): for x > 0 (or x >= 0 with y > 0) pow is monotone in each argument for the
// other fixed, so its extremes are at the corners. A negative base needs a constant
// integer exponent: |x|^n with the sign rule of n.
Range Power(const Range& x, const Range& y) {
    if (x.lo > 0 || (x.lo >= 0 && y.lo > 0)) {
        return Hull({std::pow(x.lo, y.lo), std::pow(x.lo, y.hi), std::pow(x.hi, y.lo),
                     std::pow(x.hi, y.hi)},
                    2);
    }
    const double n = y.lo;
    if (y.lo != y.hi || n != std::trunc(n) || std::abs(n) > 1e9) return kUnbounded;
    if (n < 0 && Contains(x, 0)) return kUnbounded;
    const bool even = std::fmod(n, 2) == 0;
    if (!even) return Hull({std::pow(x.lo, n), std::pow(x.hi, n)}, 2);  // monotone
    return Hull({std::pow(MinAbs(x), n), std::pow(MaxAbs(x), n)}, 2);
}

// The range of sin(x + phase) over x in r: the ends, and ±1 where a crest (phase-shifted
// π/2 + 2πk) or trough lies inside. A crest found within a rounding slack of an end is
// counted in: conservative.
Range Sine(const Range& r, double phase) {
    if (!(r.hi - r.lo < 2 * std::numbers::pi)) return {-1, 1};
    const double lo = r.lo + phase, hi = r.hi + phase;
    const double slack = 1e-12 * (1 + std::max(std::abs(lo), std::abs(hi)));
    auto holds = [&](double offset) {
        const double k = std::ceil((lo - slack - offset) / (2 * std::numbers::pi));
        return offset + 2 * std::numbers::pi * k <= hi + slack;
    };
    Range out = Hull({std::sin(lo), std::sin(hi)}, 2);
    // The shifted ends were rounded: widen by the slack (|sin'| <= 1).
    out = {out.lo - slack, out.hi + slack};
    if (holds(std::numbers::pi / 2)) out.hi = 1;
    if (holds(-std::numbers::pi / 2)) out.lo = -1;
    return {std::max(out.lo, -1.0), std::min(out.hi, 1.0)};
}

Range Call1(Expr::Fn1 fn, const Range& a) {
    if (fn == &Sin) return Sine(a, 0);
    if (fn == &Cos) return Sine(a, std::numbers::pi / 2);
    if (fn == &Atan) return Hull({std::atan(a.lo), std::atan(a.hi)}, 2);
    if (fn == &Sqrt) return a.lo < 0 ? kUnbounded : Hull({std::sqrt(a.lo), std::sqrt(a.hi)}, 1);
    if (fn == &Asin || fn == &Acos) {
        if (a.lo < -1 || a.hi > 1) return kUnbounded;
        return Hull({fn(a.lo), fn(a.hi)}, 2);  // both monotone
    }
    if (fn == &Tan) {
        // Monotone between poles π/2 + kπ; unbounded when one may lie inside.
        const double slack = 1e-12 * (1 + MaxAbs(a));
        const double k = std::ceil((a.lo - slack - std::numbers::pi / 2) / std::numbers::pi);
        if (!(a.hi - a.lo < std::numbers::pi) ||
            std::numbers::pi / 2 + std::numbers::pi * k <= a.hi + slack) {
            return kUnbounded;
        }
        return Hull({std::tan(a.lo), std::tan(a.hi)}, 2);
    }
    return kUnbounded;  // a function this evaluation does not know
}

Range Call2(Expr::Fn2 fn, const Range& a, const Range& b) {
    if (fn == &Hypot) return Hull({std::hypot(MinAbs(a), MinAbs(b)), std::hypot(MaxAbs(a), MaxAbs(b))}, 2);
    return kUnbounded;
}

}  // namespace

Expr::Range Expr::EvaluateRange(double t0, double t1) const {
    auto arg = [&](size_t i) { return args_[i]->EvaluateRange(t0, t1); };
    switch (op_) {
        case Op::Constant:
            return {value_, value_};
        case Op::Time:
            return {t0, t1};
        case Op::Frame:
            return {static_cast<double>(CurrentFrame()), static_cast<double>(CurrentFrame())};
        case Op::Negate: {
            const Range a = arg(0);
            return {-a.hi, -a.lo};
        }
        case Op::Add: {
            const Range a = arg(0), b = arg(1);
            return Outward(a.lo + b.lo, a.hi + b.hi, 1);
        }
        case Op::Subtract: {
            const Range a = arg(0), b = arg(1);
            return Outward(a.lo - b.hi, a.hi - b.lo, 1);
        }
        case Op::Multiply: return Multiply(arg(0), arg(1));
        case Op::Divide: return Divide(arg(0), arg(1));
        case Op::Modulo: return Modulo(arg(0), arg(1));
        case Op::Power: return Power(arg(0), arg(1));
        case Op::Call1: return Call1(fn1_, arg(0));
        case Op::Call2: return Call2(fn2_, arg(0), arg(1));
        case Op::Linear: {
            // Static ends: LinearAt is monotone in time (constant, linear, constant), so
            // its range is the hull of its values at t0 and t1, widened by a few ulps of
            // the larger end for the interpolation's rounding. Otherwise every value is a
            // convex combination of v0 and v1: the hull of their ranges.
            const Range v0 = arg(1), v1 = arg(3);
            Range out;
            if (std::none_of(args_.begin(), args_.end(),
                             [](const ExprPtr& e) { return e->IsTimeVarying(); })) {
                const double a = args_[0]->Value(), b = args_[2]->Value();
                out = Hull({LinearAt(t0, a, v0.lo, b, v1.lo), LinearAt(t1, a, v0.lo, b, v1.lo)}, 0);
            } else {
                out = Hull({v0.lo, v0.hi, v1.lo, v1.hi}, 0);
            }
            const double pad = 8 * std::numeric_limits<double>::epsilon() *
                               std::max(MaxAbs(v0), MaxAbs(v1));
            return Outward(out.lo - pad, out.hi + pad, 1);
        }
    }
    return kUnbounded;
}

}  // namespace rs
