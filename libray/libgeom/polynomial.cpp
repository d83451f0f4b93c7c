#include "libgeom/polynomial.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace rs {

namespace {

constexpr double kUnitRoundoff = 1.1102230246251565e-16;  // u = 2⁻⁵³
// Halley/bisection stops when the step or the bracket falls below 4 ulp of the root.
constexpr double kRootRelTolerance = 8 * kUnitRoundoff;
constexpr int kMaxIterations = 100;

// The evaluation routines below take the degree N as a template parameter so that their
// loops unroll; each performs exactly the operations, in exactly the order, of the plain
// loop over i = N−1…0, so every result is bit-identical to a run-time-degree loop.
template <int N>
using Degree = std::integral_constant<int, N>;

// Calls body(Degree<degree>{}) for 0 ≤ degree ≤ 4 (callers guarantee that range).
template <typename Body>
decltype(auto) WithDegree(int degree, Body&& body) {
    switch (degree) {
        case 0: return body(Degree<0>{});
        case 1: return body(Degree<1>{});
        case 2: return body(Degree<2>{});
        case 3: return body(Degree<3>{});
        default: return body(Degree<4>{});
    }
}

template <int N>
double Horner(const double* c, double x) {
    double f = c[N];
    for (int i = N - 1; i >= 0; --i) f = f * x + c[i];
    return f;
}

// Σ|c_i|·|x|^i: the scale of the terms summed when evaluating at x.
template <int N>
double EvaluationScale(const double* c, double x) {
    double ax = std::fabs(x), s = std::fabs(c[N]);
    for (int i = N - 1; i >= 0; --i) s = s * ax + std::fabs(c[i]);
    return s;
}

// Value, first derivative and half the second derivative by Horner's rule.
template <int N>
void EvaluateWithDerivatives(const double* c, double x, double& f, double& df, double& halfD2f) {
    f = c[N];
    df = 0;
    halfD2f = 0;
    for (int i = N - 1; i >= 0; --i) {
        halfD2f = halfD2f * x + df;
        df = df * x + f;
        f = f * x + c[i];
    }
}

// Real roots of c2·x² + c1·x + c0 (c2 ≠ 0), ascending, distinct. A negative discriminant
// within rounding error of zero is taken as zero (a tangent double root).
int QuadraticRoots(double c2, double c1, double c0, double roots[2]) {
    double disc = c1 * c1 - 4 * c2 * c0;
    if (disc < 0) {
        if (-disc > kZeroTolerance * (c1 * c1 + 4 * std::fabs(c2 * c0))) return 0;
        roots[0] = -c1 / (2 * c2);
        return 1;
    }
    if (disc == 0) {
        roots[0] = -c1 / (2 * c2);
        return 1;
    }
    // q has the sign of -c1 so no cancellation happens; q ≠ 0 because disc > 0.
    double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
    double r1 = q / c2, r2 = c0 / q;
    if (r1 > r2) std::swap(r1, r2);
    roots[0] = r1;
    if (r2 == r1) return 1;
    roots[1] = r2;
    return 2;
}

// The root of a polynomial monotonic on [left, right] whose values at the ends, fLeft and
// fRight, have strictly opposite signs: Halley's method kept inside the bracket, bisecting
// whenever Halley would leave it or is not converging fast enough. It stops early at an x
// where |f| is within Horner's rounding-error bound γ_2N·Σ|c_i||x|^i (Higham, Accuracy and
// Stability, §5.1; γ_2N = 2Nu/(1 − 2Nu) < (2N + 1)u): there the computed sign of f, the
// only thing the bracket updates use, carries no information, so further iterations could
// not tell the root's side any better than x does; this loses no root (x lies inside the
// bracket) and no precision the evaluation can resolve. Without this stop, the dozens of
// bisections needed to narrow the bracket to 4 ulp through such a noise band dominated the
// cost at grazing rays.
template <int N>
double RefineRoot(const double* c, double left, double right, double fLeft, double fRight) {
    const bool leftNegative = fLeft < 0;
    // A false-position first guess is usually close for the nearly linear pieces rays give.
    double x = left - fLeft * (right - left) / (fRight - fLeft);
    if (!(x > left && x < right)) x = 0.5 * (left + right);
    double stepBeforeLast = right - left, lastStep = stepBeforeLast;
    for (int i = 0; i < kMaxIterations; ++i) {
        double f, df, halfD2f;
        EvaluateWithDerivatives<N>(c, x, f, df, halfD2f);
        if (std::fabs(f) <= (2 * N + 1) * kUnitRoundoff * EvaluationScale<N>(c, x)) return x;
        if ((f < 0) == leftNegative) {
            left = x;
        } else {
            right = x;
        }
        double tolerance = kRootRelTolerance * std::max(std::fabs(left), std::fabs(right));
        if (right - left <= tolerance) return 0.5 * (left + right);

        // Halley's step x − f·f′ / (f′² − f·f″/2): cubic convergence, so one or two fewer
        // evaluations than Newton's from the same start.
        const double denominator = df * df - f * halfD2f;
        double next = denominator != 0 ? x - f * df / denominator : left;  // `left` bisects
        bool halleyOk = next > left && next < right &&
                        std::fabs(next - x) <= 0.5 * std::fabs(stepBeforeLast);
        if (!halleyOk) next = 0.5 * (left + right);
        stepBeforeLast = lastStep;
        lastStep = next - x;
        if (halleyOk && std::fabs(lastStep) <= kRootRelTolerance * std::fabs(next)) return next;
        x = next;
    }
    return x;
}

}  // namespace

double EvaluatePolynomial(const double* c, int degree, double x) {
    return WithDegree(degree, [&](auto n) { return Horner<n>(c, x); });
}

AscendingRoots::AscendingRoots(const double* coeffs, int degree, double lo, double hi) {
    degree = std::min(degree, 4);
    while (degree > 0 && coeffs[degree] == 0) --degree;
    // Rejected intervals (most rays that miss a quartic surface) stop here, with no levels.
    if (degree >= 3 && lo <= hi && !MayHaveRoot(coeffs, degree, lo, hi)) {
        nLevels_ = 0;
        return;
    }
    // Level k is the k-th derivative; the chain stops at the first of degree ≤ 2.
    Level& top = levels_[0];
    top.degree = std::max(degree, 0);
    for (int i = 0; i <= top.degree; ++i) top.c[i] = coeffs[i];
    nLevels_ = 1;
    while (levels_[nLevels_ - 1].degree > 2) {
        const Level& parent = levels_[nLevels_ - 1];
        Level& child = levels_[nLevels_++];
        child.degree = parent.degree - 1;
        for (int i = 0; i <= child.degree; ++i) child.c[i] = (i + 1) * parent.c[i + 1];
    }
    for (int k = 0; k < nLevels_; ++k) Start(levels_[k], lo, hi);
}

namespace {

template <int N>
bool MayHaveRootOfDegree(const double* c, double lo, double hi) {
    // Taylor-shift to s = x − lo and scale to u = s / (hi − lo) ∈ [0, 1]: a_i = c⁽ⁱ⁾(lo)/i!·wⁱ.
    // Then b_k = Σ_{i≤k} C(k,i)/C(n,i)·a_i are the Bernstein coefficients, and p lies in
    // their convex hull on [lo, hi]. The margin is 10⁻⁹ of S = Σ|c_i|·max(|lo|,|hi|)ⁱ, which
    // bounds |p| term by term over the interval: far above the rounding error of the few
    // operations here (a small multiple of u·S), and far above the solver's own tolerance
    // kZeroTolerance·S for "p(x) is zero", so the answer "no root" never hides a root (or a
    // tangency within rounding error) that the solver would report.
    const double w = hi - lo;
    double a[N + 1];
    for (int i = 0; i <= N; ++i) a[i] = c[i];
    // Repeated synthetic division by (x − lo) gives the coefficients of p(lo + s).
    for (int i = 0; i < N; ++i)
        for (int j = N - 1; j >= i; --j) a[j] += lo * a[j + 1];
    double scale = 1;
    for (int i = 1; i <= N; ++i) {
        scale *= w;
        a[i] *= scale;
    }
    // C(k,i)/C(n,i) for n = degree, rows k = 0…n.
    static constexpr double kRatio[5][5][5] = {
        {},
        {{1}, {1, 1}},
        {{1}, {1, 0.5}, {1, 1, 1}},
        {{1}, {1, 1.0 / 3}, {1, 2.0 / 3, 1.0 / 3}, {1, 1, 1, 1}},
        {{1}, {1, 0.25}, {1, 0.5, 1.0 / 6}, {1, 0.75, 0.5, 0.25}, {1, 1, 1, 1, 1}},
    };
    const double margin = 1e-9 * EvaluationScale<N>(c, std::max(std::fabs(lo), std::fabs(hi)));
    bool allAbove = true, allBelow = true;
    for (int k = 0; k <= N; ++k) {
        double b = 0;
        for (int i = 0; i <= k; ++i) b += kRatio[N][k][i] * a[i];
        allAbove = allAbove && b > margin;
        allBelow = allBelow && b < -margin;
    }
    return !(allAbove || allBelow) || !std::isfinite(margin);
}

}  // namespace

bool MayHaveRoot(const double* c, int degree, double lo, double hi) {
    if (degree < 1 || degree > 4) return true;
    return WithDegree(degree, [&](auto n) { return MayHaveRootOfDegree<n>(c, lo, hi); });
}

void AscendingRoots::Start(Level& level, double lo, double hi) {
    level.hi = hi;
    level.nClosed = level.iClosed = 0;
    level.pendingZero = false;
    level.done = !(lo <= hi);
    if (level.done) return;
    if (level.degree <= 2) {
        double r[2];
        int m = 0;
        if (level.degree == 1) {
            r[m++] = -level.c[0] / level.c[1];
        } else if (level.degree == 2) {
            m = QuadraticRoots(level.c[2], level.c[1], level.c[0], r);
        }
        for (int i = 0; i < m; ++i) {
            if (r[i] >= lo && r[i] <= hi) level.closed[level.nClosed++] = r[i];
        }
        return;
    }
    level.x0 = lo;
    level.v0 = ZeroedValue(level, lo);
    level.pendingZero = level.v0 == 0;
}

double AscendingRoots::ZeroedValue(const Level& level, double x) {
    return WithDegree(level.degree, [&](auto n) {
        const double f = Horner<n>(level.c, x);
        return std::fabs(f) <= kZeroTolerance * EvaluationScale<n>(level.c, x) ? 0 : f;
    });
}

bool AscendingRoots::Next(int k, double& root) {
    if (k >= nLevels_ || k >= kMaxLevels) return false;
    Level& level = levels_[k];
    if (level.degree <= 2) {
        if (level.iClosed >= level.nClosed) return false;
        root = level.closed[level.iClosed++];
        return true;
    }
    for (;;) {
        // A break whose value is within rounding error of zero is a root (a multiple one
        // at an interior critical point) and counts as an exact zero for sign changes.
        if (level.pendingZero) {
            level.pendingZero = false;
            root = level.x0;
            return true;
        }
        if (level.done) return false;
        // The next break: the derivative's next root beyond x0, or the interval's end. The
        // polynomial is monotonic between consecutive breaks, so each piece holds at most
        // one root, present exactly when the end values change sign.
        double x1 = level.hi, critical;
        while (Next(k + 1, critical)) {
            if (critical > level.x0) {
                x1 = std::min(critical, level.hi);
                break;
            }
        }
        if (x1 >= level.hi) level.done = true;
        const double v0 = level.v0, v1 = ZeroedValue(level, x1);
        const bool signChange = (v0 < 0 && v1 > 0) || (v0 > 0 && v1 < 0);
        const double x0 = level.x0;
        level.x0 = x1;
        level.v0 = v1;
        level.pendingZero = v1 == 0 && x1 > x0;
        if (signChange) {
            // Levels walked here have degree 3 or 4 (lower ones use the closed forms).
            root = level.degree == 3 ? RefineRoot<3>(level.c, x0, x1, v0, v1)
                                     : RefineRoot<4>(level.c, x0, x1, v0, v1);
            return true;
        }
    }
}

int SolvePolynomialInInterval(const double* c, int degree, double lo, double hi,
                              double* roots) {
    AscendingRoots walker(c, degree, lo, hi);
    int n = 0;
    double x;
    // A degree-n polynomial has at most n roots; values all within tolerance of zero could
    // otherwise yield more.
    while (n < std::max(degree, 0) && walker.Next(x)) {
        if (n == 0 || x != roots[n - 1]) roots[n++] = x;
    }
    return n;
}

namespace {

// All real roots of Σ c_i x^i: every root lies within Cauchy's bound 1 + max|c_i / c_n|.
int SolveOnLine(const double* c, int degree, double* roots) {
    while (degree > 0 && c[degree] == 0) --degree;
    if (degree <= 0) return 0;
    double bound = 0;
    for (int i = 0; i < degree; ++i) bound = std::max(bound, std::fabs(c[i] / c[degree]));
    bound += 1;
    if (!std::isfinite(bound)) return 0;
    return SolvePolynomialInInterval(c, degree, -bound, bound, roots);
}

}  // namespace

int SolveQuadratic(double a, double b, double c, double roots[2]) {
    const double coeffs[3] = {c, b, a};
    return SolveOnLine(coeffs, 2, roots);
}

int SolveCubic(double a, double b, double c, double d, double roots[3]) {
    const double coeffs[4] = {d, c, b, a};
    return SolveOnLine(coeffs, 3, roots);
}

int SolveQuartic(double a, double b, double c, double d, double e, double roots[4]) {
    const double coeffs[5] = {e, d, c, b, a};
    return SolveOnLine(coeffs, 4, roots);
}

}  // namespace rs
