// Layer 8 of the implicit module: the per-interval polynomial method of Rayshade 4.0's
// blob primitive (`method polynomial`), a baseline on the plain sum (intersection_method.h),
// on libgeom's polynomial solver (libgeom/polynomial.h).
//
// Terms: point and segment skeletons with the blob kernel s(1 − r²/R²)² only
// (CheckPolynomialTerms), each a metaball (a capsule for a segment) of strength w·s
// (negative weights carve). The search is MetaballSum's
// (libgeom/metaball_sum.h, shared with the `blob` primitive): one quartic per interval
// between the ray's entries into and exits from the spheres of radius R, formed with the
// origin moved to the interval's start (no cancellation for distant cameras, research note
// §8), the first root in (tMin, tMax) whichever interval it is in (no lost exits for rays
// starting just outside, §8 "Defect 2"); the balls a ray meets come from a grid walked
// front to back, so a ray costs the cells it crosses up to its first root, not O(N).
//
// Guarantee: the roots of each interval's quartic to the solver's accuracy (about 4 ulp of
// u); a double root (tangency within the solver's rounding bound) is a hit. The `tolerance`
// knob is not used. Non-guarantee: round-off in the quartic's coefficients (sums of terms of
// size s) moves near-tangent roots by about the square root of the relative rounding, and
// can create or remove tangent roots. Cost: one field evaluation is counted per quartic.
#pragma once

#include <string>
#include <vector>

#include "libgeom/metaball_sum.h"
#include "libobj/implicit/intersection_method.h"

namespace rs {

// Empty when every term is a point or segment skeleton with the blob kernel; otherwise a
// message naming the first term that is not.
std::string CheckPolynomialTerms(const std::vector<FieldTerm>& terms);

class PolynomialMethod final : public IntersectionMethod {
  public:
    // The terms must pass CheckPolynomialTerms.
    PolynomialMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;
    Vec3 Gradient(const Field& field, const Vec3& p) const override;
    int PredominantTerm(const Vec3& p) const override { return sum_.Predominant(p); }

  private:
    MetaballSum sum_;
};

}  // namespace rs
