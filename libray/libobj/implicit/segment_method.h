// Layer 6 of the implicit module: segment tracing with local Lipschitz bounds (`method
// segment`; Galin, Guérin, Paris, Peytavie, "Segment Tracing Using Local Lipschitz Bounds",
// Eurographics 2020), a baseline on the plain sum (intersection_method.h).
//
// At t with candidate length σ, K = Field::Bound(box of the segment [t, t + σ]).L·|d|
// bounds |g'| on the segment (the box contains it), so no root lies in [t, t + min(|g|/K, σ)).
// The step is that length (at least the tolerance, as in sphere_method.h), and the next
// candidate is kGrowth times the step (the authors' code grows by 1.5). The first candidate
// is the whole clipped ray. A class change between two samples is bisected to the tolerance.
//
// Guarantee: a returned root lies within `tolerance` of a sign change of g; safe steps skip
// no root. Non-guarantee: as sphere tracing, a contact shorter than the tolerance along the
// ray is stepped over, and a ray that crawls more than kMaxSteps steps is a miss. Each step
// costs one field and one bound evaluation.
#pragma once

#include "libobj/implicit/intersection_method.h"

namespace rs {

class SegmentMethod final : public IntersectionMethod {
  public:
    static constexpr int kMaxSteps = 1000000;
    static constexpr double kGrowth = 1.5;

    SegmentMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;

  private:
    const Field& field_;
    double threshold_, tolerance_;
    Bounds3 box_;
};

}  // namespace rs
