// Layer 1 of the implicit module: bracketed 1-D root finding over a functor double(double).
// No geometry types. Both solvers keep a closed bracket [lo, hi] in which the function
// changes sign, and stop when hi - lo <= tolerance, so the returned root is within
// `tolerance` of a true sign change of a continuous function (the guarantee the LG search
// relies on).
//
// Sign convention: a bracket is valid when exactly one end satisfies y > 0 (or an end is an
// exact zero). This is the same classification as "inside F > threshold" used by the
// callers, so adjacent brackets never both claim a boundary root that is not a sign change.
//
// Ridders' method: Ridders, "A new algorithm for computing a single root of a real
// continuous function", IEEE Trans. Circuits Syst. 26 (1979); Press et al., Numerical
// Recipes in C, 2nd ed., §9.2.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "libcommon/constants.h"

namespace rs {

// How accurately every intersection method places a root along a ray (the block's
// `tolerance`), whatever the method: the baselines use `tolerance`, the octree methods all
// of it (OctreeSettings).
struct RootSearchSettings {
    // Root accuracy and splitting floor, as object-space distances.
    double tolerance = 1e-7;
    double minWidth = 1e-7;
    // Automatic accuracy (the scene's `tolerance auto`): on a ray carrying a footprint
    // (ray.h), the tolerance and the splitting floor within a leaf span are
    // footprintFraction × the footprint's width at the span's nearer end (its smaller
    // width), in units of t, but never finer than tolerance and minWidth above; on rays
    // without a footprint, those fixed values. 1/8: the depth error then moves a hit point
    // by at most an eighth of the pixel's width along the ray, invisible after projection
    // (less than one eighth of a pixel on screen), and grazing contacts missed at the floor
    // are narrower than an eighth of a pixel.
    // The automatic values are also capped at autoToleranceCap (in units of t): the
    // renderer starts reflected, refracted and shadow rays at hit points and skips only
    // t < kEpsilon (1e-5) or kShadowEpsilon (4e-5) there, so a hit placed farther than
    // that from the true surface would let those rays meet the surface they leave (shadow
    // acne, doubled refraction). A tenth of kEpsilon keeps every spawned ray clear.
    bool autoTolerance = true;
    double footprintFraction = 0.125;
    double autoToleranceCap = kEpsilon / 10;
    int maxRiddersIterations = 60;
};

struct RootResult {
    double root = 0;
    int iterations = 0;  // loop iterations (Ridders: 2 or 3 evaluations each; bisection: 1)
};

namespace detail {

inline bool IsPositive(double y) { return y > 0; }

// True when [x1, x2] with values y1, y2 brackets a sign change (or has an exact zero end).
inline bool Brackets(double y1, double y2) {
    return y1 == 0 || y2 == 0 || IsPositive(y1) != IsPositive(y2);
}

}  // namespace detail

// Bisection on [x1, x2] (x1 < x2) with known end values y1 = f(x1), y2 = f(x2). Returns
// nothing when the ends do not bracket a sign change or when maxIterations runs out.
template <class F>
std::optional<RootResult> BisectRoot(F&& f, double x1, double y1, double x2, double y2,
                                     double tolerance, int maxIterations) {
    if (!detail::Brackets(y1, y2)) return std::nullopt;
    if (y1 == 0) return RootResult{x1, 0};
    if (y2 == 0) return RootResult{x2, 0};
    for (int it = 1; it <= maxIterations; ++it) {
        double xm = 0.5 * (x1 + x2);
        if (xm <= x1 || xm >= x2) {  // adjacent doubles
            return RootResult{std::abs(y1) <= std::abs(y2) ? x1 : x2, it};
        }
        double ym = f(xm);
        if (ym == 0) return RootResult{xm, it};
        if (detail::IsPositive(ym) == detail::IsPositive(y1)) {
            x1 = xm;
            y1 = ym;
        } else {
            x2 = xm;
            y2 = ym;
        }
        if (x2 - x1 <= tolerance) {
            return RootResult{std::abs(y1) <= std::abs(y2) ? x1 : x2, it};
        }
    }
    return std::nullopt;
}

// Ridders' method on [x1, x2] (x1 < x2) with known end values. Each iteration evaluates
// the midpoint x3 and the Ridders point
//     x4 = x3 + (x3 − x1)·sign(y1 − y2)·y3 / sqrt(y3² − y1·y2),
// which always lies in [x1, x2] (NR §9.2), then keeps the shortest sub-bracket among
// the sorted points {x1, x3, x4, x2}. Since x3 is the midpoint the bracket at least halves
// every iteration, so the method never does worse than bisection; it converges quadratically
// for simple roots. When x4 has converged (moved less than the tolerance) but the bracket is
// still wider, one extra probe at x4 ± tolerance/2 closes it.
template <class F>
std::optional<RootResult> RiddersRoot(F&& f, double x1, double y1, double x2, double y2,
                                      double tolerance, int maxIterations) {
    if (!detail::Brackets(y1, y2)) return std::nullopt;
    if (y1 == 0) return RootResult{x1, 0};
    if (y2 == 0) return RootResult{x2, 0};
    double lastX4 = x1;
    bool haveLast = false;
    for (int it = 1; it <= maxIterations; ++it) {
        double x3 = 0.5 * (x1 + x2);
        if (x3 <= x1 || x3 >= x2) {  // x1, x2 are adjacent doubles: nothing left to split
            return RootResult{std::abs(y1) <= std::abs(y2) ? x1 : x2, it};
        }
        double y3 = f(x3);
        if (y3 == 0) return RootResult{x3, it};
        // y1·y2 < 0 so the radicand is > y3² > 0.
        double s = std::sqrt(y3 * y3 - y1 * y2);
        double x4 = x3 + (x3 - x1) * ((y1 >= y2 ? 1.0 : -1.0) * y3 / s);
        x4 = std::min(std::max(x4, x1), x2);  // round-off guard; exact x4 is inside
        double y4 = f(x4);
        if (y4 == 0) return RootResult{x4, it};
        // Sort the four points and keep the shortest adjacent pair with a sign change.
        double xs[4] = {x1, x3, x4, x2};
        double ys[4] = {y1, y3, y4, y2};
        if (x4 < x3) {
            std::swap(xs[1], xs[2]);
            std::swap(ys[1], ys[2]);
        }
        int best = -1;
        for (int i = 0; i < 3; ++i) {
            if (detail::IsPositive(ys[i]) == detail::IsPositive(ys[i + 1])) continue;
            if (best < 0 || xs[i + 1] - xs[i] < xs[best + 1] - xs[best]) best = i;
        }
        x1 = xs[best];
        y1 = ys[best];
        x2 = xs[best + 1];
        y2 = ys[best + 1];
        if (x2 - x1 > tolerance && haveLast && std::abs(x4 - lastX4) < tolerance) {
            // Close the bracket from the far side of x4.
            double probe = (x4 - x1 < x2 - x4) ? x4 + 0.5 * tolerance : x4 - 0.5 * tolerance;
            if (probe > x1 && probe < x2) {
                double yp = f(probe);
                if (yp == 0) return RootResult{probe, it};
                if (detail::IsPositive(yp) == detail::IsPositive(y1)) {
                    x1 = probe;
                    y1 = yp;
                } else {
                    x2 = probe;
                    y2 = yp;
                }
            }
        }
        lastX4 = x4;
        haveLast = true;
        if (x2 - x1 <= tolerance) {
            return RootResult{std::abs(y1) <= std::abs(y2) ? x1 : x2, it};
        }
    }
    return std::nullopt;
}

}  // namespace rs
