#include "libobj/polynomial.h"

#include <algorithm>
#include <cmath>

namespace rs {

namespace {

constexpr double kUnitRoundoff = 1.1102230246251565e-16;  // u = 2⁻⁵³
// Newton/bisection stops when the step or the bracket falls below 4 ulp of the root.
constexpr double kRootRelTolerance = 8 * kUnitRoundoff;
constexpr int kMaxIterations = 100;

// Σ|c_i|·|x|^i: the scale of the terms summed when evaluating at x.
double EvaluationScale(const double* c, int degree, double x) {
    double ax = std::fabs(x), s = std::fabs(c[degree]);
    for (int i = degree - 1; i >= 0; --i) s = s * ax + std::fabs(c[i]);
    return s;
}

// Value and derivative by Horner's rule.
void EvaluateWithDerivative(const double* c, int degree, double x, double& f, double& df) {
    f = c[degree];
    df = 0;
    for (int i = degree - 1; i >= 0; --i) {
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
// fRight, have strictly opposite signs: Newton's method kept inside the bracket, bisecting
// whenever Newton would leave it or is not converging fast enough.
double RefineRoot(const double* c, int degree, double left, double right, double fLeft,
                  double fRight) {
    const bool leftNegative = fLeft < 0;
    // A false-position first guess is usually close for the nearly linear pieces rays give.
    double x = left - fLeft * (right - left) / (fRight - fLeft);
    if (!(x > left && x < right)) x = 0.5 * (left + right);
    double stepBeforeLast = right - left, lastStep = stepBeforeLast;
    for (int i = 0; i < kMaxIterations; ++i) {
        double f, df;
        EvaluateWithDerivative(c, degree, x, f, df);
        if (f == 0) return x;
        if ((f < 0) == leftNegative) {
            left = x;
        } else {
            right = x;
        }
        double tolerance = kRootRelTolerance * std::max(std::fabs(left), std::fabs(right));
        if (right - left <= tolerance) return 0.5 * (left + right);

        double next = df != 0 ? x - f / df : left;  // `left` forces the bisection below
        bool newtonOk = next > left && next < right &&
                        std::fabs(next - x) <= 0.5 * std::fabs(stepBeforeLast);
        if (!newtonOk) next = 0.5 * (left + right);
        stepBeforeLast = lastStep;
        lastStep = next - x;
        if (newtonOk && std::fabs(lastStep) <= kRootRelTolerance * std::fabs(next)) return next;
        x = next;
    }
    return x;
}

// Appends x unless it repeats the previous root or the degree's count is already reached
// (values all within tolerance of zero could otherwise report more roots than exist).
void AppendRoot(double x, int degree, double* roots, int& n) {
    if (n >= degree || (n > 0 && roots[n - 1] == x)) return;
    roots[n++] = x;
}

}  // namespace

double EvaluatePolynomial(const double* c, int degree, double x) {
    double f = c[degree];
    for (int i = degree - 1; i >= 0; --i) f = f * x + c[i];
    return f;
}

int SolvePolynomialInInterval(const double* c, int degree, double lo, double hi,
                              double* roots) {
    while (degree > 0 && c[degree] == 0) --degree;
    if (degree <= 0 || !(lo <= hi)) return 0;
    if (degree == 1) {
        double x = -c[0] / c[1];
        if (!(x >= lo && x <= hi)) return 0;
        roots[0] = x;
        return 1;
    }
    if (degree == 2) {
        double r[2];
        int m = QuadraticRoots(c[2], c[1], c[0], r), n = 0;
        for (int i = 0; i < m; ++i) {
            if (r[i] >= lo && r[i] <= hi) roots[n++] = r[i];
        }
        return n;
    }

    // Critical points split [lo, hi] into pieces on which p is monotonic.
    double derivative[4];
    for (int i = 0; i < degree; ++i) derivative[i] = (i + 1) * c[i + 1];
    double breaks[5];
    int nBreaks = 0;
    breaks[nBreaks++] = lo;
    double critical[3];
    int nCritical = SolvePolynomialInInterval(derivative, degree - 1, lo, hi, critical);
    for (int i = 0; i < nCritical; ++i) {
        if (critical[i] > breaks[nBreaks - 1] && critical[i] < hi) breaks[nBreaks++] = critical[i];
    }
    if (hi > lo) breaks[nBreaks++] = hi;

    // Values at the breaks; those within rounding error of zero are roots (multiple ones at
    // interior critical points) and count as exact zeros when looking for sign changes.
    double values[5];
    for (int k = 0; k < nBreaks; ++k) {
        double f = EvaluatePolynomial(c, degree, breaks[k]);
        if (std::fabs(f) <= kZeroTolerance * EvaluationScale(c, degree, breaks[k])) f = 0;
        values[k] = f;
    }
    int n = 0;
    for (int k = 0; k < nBreaks; ++k) {
        if (values[k] == 0) AppendRoot(breaks[k], degree, roots, n);
        if (k + 1 < nBreaks && ((values[k] < 0 && values[k + 1] > 0) ||
                                (values[k] > 0 && values[k + 1] < 0))) {
            AppendRoot(RefineRoot(c, degree, breaks[k], breaks[k + 1], values[k], values[k + 1]),
                       degree, roots, n);
        }
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
