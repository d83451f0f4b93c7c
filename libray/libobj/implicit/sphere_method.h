// Layer 6 of the implicit module: sphere tracing with ONE global Lipschitz bound (`method
// sphere`; Hart, "Sphere tracing", The Visual Computer 12(10), 1996), a baseline on the
// plain sum (intersection_method.h).
//
// L is Field::Bound over the box of every term's support (computed once): L >= |∇F|
// everywhere, so |g(t + u) − g(t)| <= L|d|·u and no root lies closer than |g(t)|/(L|d|)
// along the ray. The march steps t += |g|/(L|d|); once that step falls below the tolerance
// it steps by the tolerance instead, and a class change between two samples (inside: g > 0)
// is bisected to the tolerance. (The textbook rule "stop when |g|/L < ε" reports false hits
// beside grazing rays and does not bound the depth error when L ≫ |∇F|; this variant
// keeps the step rule and gives the final answer by a bracket, as every method here.)
//
// Guarantee: a returned root lies within `tolerance` of a sign change of g, and the safe
// steps skip no root. Non-guarantee: a contact shorter than the tolerance along the ray
// (two roots within one minimum step) is stepped over; near-grazing rays crawl at the
// minimum step and give up (miss) after kMaxSteps; with many overlapping terms L is large
// (the sum of all terms' slopes) and every step is small.
#pragma once

#include "libobj/implicit/intersection_method.h"

namespace rs {

class SphereMethod final : public IntersectionMethod {
  public:
    // Steps per ray before giving up (a miss).
    static constexpr int kMaxSteps = 1000000;

    SphereMethod(const Field& field, const MethodParams& params);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;
    double Lipschitz() const { return lipschitz_; }

  private:
    const Field& field_;
    double threshold_, tolerance_;
    Bounds3 box_;
    double lipschitz_ = 0;
};

}  // namespace rs
