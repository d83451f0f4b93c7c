// Layer 6 of the implicit module: fixed-step marching with bisection refinement (`method
// march [Step]`), a baseline on the plain sum (intersection_method.h).
//
// Algorithm: clip the ray to the box of the positive terms' supports, evaluate g = F − T at
// t0, t0 + h, t0 + 2h, ... (h = Step/|d|, the last sample at the clipped end), and at the
// first pair of consecutive samples whose classes differ (inside: g > 0) bisect to the
// tolerance. A sample with g exactly 0 (other than at tMin) is returned as the root.
//
// Guarantee: a returned root lies within `tolerance` of a sign change of g, and it is the
// first sign change SEEN AT THE SAMPLES.
// Non-guarantee: features thinner than the step along the ray are skipped: an entry and an
// exit between two samples (grazing rays, thin necks, tiny components) are missed, and the
// root returned may then be a later one. Cost is (clipped length)/Step field evaluations
// plus log2(Step/tolerance) for the bisection; there is no cap, so tiny steps are slow.
#pragma once

#include "libobj/implicit/intersection_method.h"

namespace rs {

// The default step: a quarter of the smallest "thickness" of the positive terms (Gascuel
// kernels: e; blob kernel: R/2, about the radius where f falls to half its peak,
// R·sqrt(1 − sqrt(1/2)) = 0.54R), so a lone skeleton's sphere (diameter 2e) gets at least 8
// samples across its diameter; for a moving field, the smallest over the shutter (an
// animated kernel's lowest corner). 1 when there is no positive term.
double DefaultMarchStep(const Field& field);

class MarchMethod final : public IntersectionMethod {
  public:
    MarchMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;
    double Step() const { return step_; }

  private:
    const Field& field_;
    double threshold_, tolerance_, step_;
    Bounds3 box_;
};

}  // namespace rs
