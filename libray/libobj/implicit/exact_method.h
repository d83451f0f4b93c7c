// Layer 6 of the implicit module: the ground-truth solver (`method exact`), for measurement
// only (slow). It searches the plain sum (intersection_method.h) in long double, evaluating
// distances and kernels itself (its own code, independent of skeleton.cpp and kernel.cpp's
// double evaluation) and counting each evaluation as a field evaluation.
//
// Splitting. Every term's distance is written through "parts", functions of t that are
// convex along any line: the distance itself for the convex kinds (point, segment,
// triangle, solid box, solid cylinder), the distance to each segment for the polyline
// (d = min of the parts), and for the circle the distance ρ to its axis and the height |z|
// over its plane (d = sqrt((ρ − radius)² + z²)). The ray is split at each part's minimum
// (golden-section search, sound for convex functions; it lands within about
// sqrt(LDBL_EPSILON) of the minimiser, where the part changes by O(LDBL_EPSILON)), and at the
// crossings of each convex distance part with the kernel breakpoints r = e (Gascuel) and
// r = R, and of the circle's ρ with its radius (bisection on the monotone sides). For point
// and segment skeletons these crossings are the sphere and capsule intersections (the
// segment's distance, piecewise a sqrt of a quadratic in t, is convex, so one minimum and at
// most two crossings per level). For the circle the pieces make ρ, |ρ − radius| and |z|
// monotone but the distance may still cross e and R inside a piece (not needed: see below).
//
// Enclosure. Within a piece every part is monotone, so over a sub-interval [a, b] each part
// lies between its end values; that gives an interval of each term's distance (convex kinds:
// [min, max] of the ends; polyline: min over segments of the per-segment ranges; circle:
// from the ranges of |ρ − radius| and |z|), and the kernel being non-increasing, of each
// term and of g = F − T. This is rigorous up to rounding.
//
// Search, left to right, recursive on each piece: an interval whose enclosure excludes zero
// (beyond the tangency tolerance τ) has no root; one with a sign change that Field::Bound's
// G proves monotone (|g'(mid)| > Gλ/2) holds exactly one root, bisected in long double to
// adjacent long doubles; same-sign intervals are also dropped by the chord bound
// min|g_end| > Gλ²/8 + τ and by that monotonicity; others split at the midpoint down to a
// floor width of kFloor times the clipped ray's extent in t, where a sign change is bisected
// and otherwise a golden-section search for the extremum of g toward zero finds either two
// sign changes (the first is bisected) or a TANGENCY: |g| <= τ = 256·LDBL_EPSILON·(T + Σ|w f|)
// there (a double root, reported as a hit at the extremum). Where G is infinite (a linear
// kernel's skeleton, a circle's axis, a polyline's kinks) only the enclosure prunes, and the
// search is bounded by kMaxNodes per ray (then a warning, and the rest of the ray is a miss).
//
// Guarantee (up to long double rounding and the golden-section placement above): the first
// sign change or tangency of g in (tMin, tMax), to long double precision for sign changes;
// tangent points are located to about sqrt(τ/|g''|). The tolerance knob is not used.
#pragma once

#include "libobj/implicit/intersection_method.h"

namespace rs {

class ExactMethod final : public IntersectionMethod {
  public:
    static constexpr long kMaxNodes = 4000000;
    static constexpr long double kFloor = 1e-13L;

    ExactMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;

  private:
    const Field& field_;
    double threshold_;
    Bounds3 box_;
};

}  // namespace rs
