// Layer 7 of the implicit module (compiled into ray_obj, beside the primitive): the
// per-interval polynomial method of Rayshade 4.0's blob primitive (`method polynomial`), a
// baseline on the plain sum (intersection_method.h). It lives at this layer because it uses
// libobj's polynomial solver (libobj/polynomial.h), which the pure-math target ray_implicit
// cannot link.
//
// Terms: point skeletons with the blob kernel s(1 − r²/R²)² only (CheckPolynomialTerms).
// Along the ray, |o + t·d − c|² is a quadratic in t, so each term is a quartic in t between
// the entry and exit of its sphere of radius R; between consecutive entry/exit events the
// set of active terms is fixed and F − T is one quartic. Each interval's quartic is formed
// in the local parameter u = t − t_start with the ray origin moved to the interval start
// (the fix for distant cameras of the research note §8: no O(t⁴) terms cancel), and its
// roots in [0, t_end − t_start] come in ascending order from AscendingRoots; the first one
// in (tMin, tMax) is the hit, whichever interval it is in (the fix of Rayshade's lost exits
// for rays starting just outside, §8 "Defect 2").
//
// Guarantee: the roots of each interval's quartic to the solver's accuracy (about 4 ulp of
// u); a double root (tangency within the solver's rounding bound) is a hit. The `tolerance`
// knob is not used. Non-guarantee: round-off in the quartic's coefficients (sums of terms of
// size s) moves near-tangent roots by about the square root of the relative rounding, and
// can create or remove tangent roots. Cost: one field evaluation is counted per interval.
#pragma once

#include <string>
#include <vector>

#include "libobj/implicit/intersection_method.h"

namespace rs {

// Empty when every term is a point skeleton with the blob kernel; otherwise a message
// naming the first term that is not.
std::string CheckPolynomialTerms(const std::vector<FieldTerm>& terms);

class PolynomialMethod final : public IntersectionMethod {
  public:
    // The terms must pass CheckPolynomialTerms.
    PolynomialMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;

  private:
    const Field& field_;
    double threshold_;
    Bounds3 box_;
};

}  // namespace rs
